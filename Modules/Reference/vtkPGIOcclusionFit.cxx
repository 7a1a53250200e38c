#include "vtkPGIOcclusionFit.h"

#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPGIOcclusionFit);

vtkPGIOcclusionFit::vtkPGIOcclusionFit()
{
  this->SetNumberOfInputPorts(2);
}

vtkPGIOcclusionFit::~vtkPGIOcclusionFit() = default;

void vtkPGIOcclusionFit::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Directions: " << this->Directions << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "MinimumScale: " << this->MinimumScale << "\n";
  os << indent << "MaximumScale: " << this->MaximumScale << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}

int vtkPGIOcclusionFit::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    // Optional for the pipeline, so that a missing mesh gets our message.
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

namespace
{
// Random numbers by (seed, stream, index), independent of threading.
double Uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
{
  std::uint64_t z =
    seed * 0x9E3779B97F4A7C15ull + stream * 0xD1B54A32D192ED03ull + index + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

void UniformDirection(double u, double v, double d[3])
{
  const double z = 1.0 - 2.0 * u, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * vtkMath::Pi() * v;
  d[0] = rho * std::cos(phi);
  d[1] = rho * std::sin(phi);
  d[2] = z;
}

struct Mesh
{
  std::vector<double> Points;
  std::vector<vtkIdType> Triangles; // 3 per triangle
  std::vector<double> CumulativeArea;
  double Centre[3] = { 0, 0, 0 };
  double Radius = 0.0;
};

// The rays of one sample set and whether the mesh blocks each.
struct RaySet
{
  std::vector<float> Origins, Directions;
  std::vector<unsigned char> MeshBlocked;
  long long MeshBlockedCount = 0;
  std::size_t Size() const { return this->MeshBlocked.size(); }
};

struct Spheres
{
  std::vector<double> Centres; // 3 per sphere
  std::vector<double> Radii;   // input radii
};

bool SamplePoint(const Mesh& mesh, const proxygi::ReferenceTracer& tracer, std::uint64_t seed,
  std::uint64_t point, double p[3])
{
  const std::uint64_t stream = 2 * point;
  if (point % 2 == 1)
  {
    // On a shell around the bounding sphere: 1.05 R to 3 R, denser near.
    double d[3];
    UniformDirection(Uniform(seed, stream, 0), Uniform(seed, stream, 1), d);
    const double u = Uniform(seed, stream, 2);
    const double distance = mesh.Radius * (1.05 + 1.95 * u * u);
    for (int c = 0; c < 3; ++c)
    {
      p[c] = mesh.Centre[c] + distance * d[c];
    }
    return true;
  }
  const double total = mesh.CumulativeArea.back();
  for (int attempt = 0; attempt < 8; ++attempt)
  {
    const std::uint64_t k = 8 * static_cast<std::uint64_t>(attempt);
    const double pick = Uniform(seed, stream, k) * total;
    const std::size_t t = static_cast<std::size_t>(
      std::upper_bound(mesh.CumulativeArea.begin(), mesh.CumulativeArea.end(), pick) -
      mesh.CumulativeArea.begin());
    const std::size_t tri = std::min(t, mesh.CumulativeArea.size() - 1);
    const double* a = &mesh.Points[3 * mesh.Triangles[3 * tri]];
    const double* b = &mesh.Points[3 * mesh.Triangles[3 * tri + 1]];
    const double* c = &mesh.Points[3 * mesh.Triangles[3 * tri + 2]];
    double su = std::sqrt(Uniform(seed, stream, k + 1)), v = Uniform(seed, stream, k + 2);
    const double wa = 1.0 - su, wb = su * (1.0 - v), wc = su * v;
    double e1[3], e2[3], n[3];
    for (int i = 0; i < 3; ++i)
    {
      e1[i] = b[i] - a[i];
      e2[i] = c[i] - a[i];
    }
    vtkMath::Cross(e1, e2, n);
    if (vtkMath::Normalize(n) <= 0.0)
    {
      continue;
    }
    // Log-uniform offsets from 1% to 50% of R.
    const double offset = mesh.Radius * 0.01 * std::pow(50.0, Uniform(seed, stream, k + 3));
    for (int i = 0; i < 3; ++i)
    {
      p[i] = wa * a[i] + wb * b[i] + wc * c[i] + offset * n[i];
    }
    if (!tracer.PlacePoint(p, 32).Inside)
    {
      return true;
    }
  }
  return false;
}

RaySet TraceRays(const Mesh& mesh, const proxygi::ReferenceTracer& tracer, std::uint64_t seed,
  int samples, int directions)
{
  // Spherical Fibonacci directions, turned at random per point.
  std::vector<double> fibonacci(3 * directions);
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  for (int s = 0; s < directions; ++s)
  {
    const double z = 1.0 - (2.0 * s + 1.0) / directions;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    fibonacci[3 * s] = rho * std::cos(golden * s);
    fibonacci[3 * s + 1] = rho * std::sin(golden * s);
    fibonacci[3 * s + 2] = z;
  }
  RaySet set;
  const std::size_t rays = static_cast<std::size_t>(samples) * directions;
  set.Origins.resize(3 * rays);
  set.Directions.resize(3 * rays);
  set.MeshBlocked.assign(rays, 0);
  std::vector<unsigned char> valid(samples, 0);
  vtkSMPTools::For(0, samples,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType s = begin; s < end; ++s)
      {
        double p[3];
        const std::uint64_t point = static_cast<std::uint64_t>(s);
        if (!SamplePoint(mesh, tracer, seed, point, p))
        {
          continue;
        }
        valid[s] = 1;
        // A random rotation (a uniform unit quaternion, Shoemake).
        const std::uint64_t stream = 2 * point + 1;
        const double u1 = Uniform(seed, stream, 0),
                     u2 = 2.0 * vtkMath::Pi() * Uniform(seed, stream, 1),
                     u3 = 2.0 * vtkMath::Pi() * Uniform(seed, stream, 2);
        const double q[4] = { std::sqrt(1.0 - u1) * std::sin(u2),
          std::sqrt(1.0 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3),
          std::sqrt(u1) * std::cos(u3) };
        double m[3][3];
        vtkMath::QuaternionToMatrix3x3(q, m);
        for (int j = 0; j < directions; ++j)
        {
          double d[3];
          vtkMath::Multiply3x3(m, &fibonacci[3 * j], d);
          const std::size_t r = static_cast<std::size_t>(s) * directions + j;
          for (int c = 0; c < 3; ++c)
          {
            set.Origins[3 * r + c] = static_cast<float>(p[c]);
            set.Directions[3 * r + c] = static_cast<float>(d[c]);
          }
        }
        const std::size_t first = static_cast<std::size_t>(s) * directions;
        tracer.OccludedRays(directions, &set.Origins[3 * first], &set.Directions[3 * first], 0.0f,
          nullptr, &set.MeshBlocked[first]);
      }
    });
  // Drop the points that found no place outside the mesh.
  std::size_t kept = 0;
  for (int s = 0; s < samples; ++s)
  {
    if (!valid[s])
    {
      continue;
    }
    const std::size_t from = static_cast<std::size_t>(s) * directions;
    const std::size_t to = kept * directions;
    if (from != to)
    {
      std::copy_n(&set.Origins[3 * from], 3 * directions, &set.Origins[3 * to]);
      std::copy_n(&set.Directions[3 * from], 3 * directions, &set.Directions[3 * to]);
      std::copy_n(&set.MeshBlocked[from], directions, &set.MeshBlocked[to]);
    }
    ++kept;
  }
  const std::size_t size = kept * directions;
  set.Origins.resize(3 * size);
  set.Directions.resize(3 * size);
  set.MeshBlocked.resize(size);
  for (unsigned char b : set.MeshBlocked)
  {
    set.MeshBlockedCount += b ? 1 : 0;
  }
  return set;
}

// What the spheres at `scales` make of a ray set: counts, and per sphere the
// votes of the update (rightly blocked, wrongly blocked, missed nearest).
struct Tally
{
  long long Disagree = 0;
  long long SpheresBlocked = 0;
  std::vector<double> Right, Wrong, Missed;
};

Tally Evaluate(
  const Spheres& spheres, const std::vector<double>& scales, const RaySet& rays, bool votes)
{
  const std::size_t count = spheres.Radii.size();
  const std::size_t blockSize = 4096;
  const std::size_t blocks = (rays.Size() + blockSize - 1) / blockSize;
  std::vector<Tally> partial(blocks);
  std::vector<double> radius2(count), radius(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    radius[i] = spheres.Radii[i] * scales[i];
    radius2[i] = radius[i] * radius[i];
  }
  vtkSMPTools::For(0, static_cast<vtkIdType>(blocks),
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<std::size_t> hits;
      for (vtkIdType b = begin; b < end; ++b)
      {
        Tally& t = partial[b];
        if (votes)
        {
          t.Right.assign(count, 0.0);
          t.Wrong.assign(count, 0.0);
          t.Missed.assign(count, 0.0);
        }
        const std::size_t first = static_cast<std::size_t>(b) * blockSize;
        const std::size_t last = std::min(rays.Size(), first + blockSize);
        for (std::size_t r = first; r < last; ++r)
        {
          const float* o = &rays.Origins[3 * r];
          const float* d = &rays.Directions[3 * r];
          hits.clear();
          double nearestGap = std::numeric_limits<double>::infinity();
          std::size_t nearest = count;
          for (std::size_t i = 0; i < count; ++i)
          {
            const double* c = &spheres.Centres[3 * i];
            const double oc[3] = { c[0] - o[0], c[1] - o[1], c[2] - o[2] };
            const double oc2 = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2];
            const double along = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
            const double off2 = std::max(0.0, oc2 - along * along);
            if (oc2 <= radius2[i] || (along > 0.0 && off2 <= radius2[i]))
            {
              hits.push_back(i);
            }
            else if (votes && along > 0.0)
            {
              const double gap = (std::sqrt(off2) - radius[i]) / radius[i];
              if (gap < nearestGap)
              {
                nearestGap = gap;
                nearest = i;
              }
            }
          }
          const bool meshBlocked = rays.MeshBlocked[r] != 0, blocked = !hits.empty();
          t.SpheresBlocked += blocked ? 1 : 0;
          t.Disagree += meshBlocked != blocked ? 1 : 0;
          if (!votes)
          {
            continue;
          }
          const double share = blocked ? 1.0 / static_cast<double>(hits.size()) : 0.0;
          for (std::size_t i : hits)
          {
            (meshBlocked ? t.Right : t.Wrong)[i] += share;
          }
          if (meshBlocked && !blocked && nearest < count)
          {
            t.Missed[nearest] += 1.0;
          }
        }
      }
    });
  // Summed in block order: the same result on any thread count.
  Tally total;
  if (votes)
  {
    total.Right.assign(count, 0.0);
    total.Wrong.assign(count, 0.0);
    total.Missed.assign(count, 0.0);
  }
  for (const Tally& t : partial)
  {
    total.Disagree += t.Disagree;
    total.SpheresBlocked += t.SpheresBlocked;
    for (std::size_t i = 0; votes && i < count; ++i)
    {
      total.Right[i] += t.Right[i];
      total.Wrong[i] += t.Wrong[i];
      total.Missed[i] += t.Missed[i];
    }
  }
  return total;
}

void AddValue(vtkPolyData* output, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  output->GetFieldData()->AddArray(a);
}
} // namespace

int vtkPGIOcclusionFit::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* proxies = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* input = vtkPolyData::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!proxies || proxies->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< "No proxies (input 0).");
    return 0;
  }
  vtkDataArray* radii = proxies->GetPointData()->GetArray("Radius");
  if (!radii)
  {
    vtkErrorMacro(<< "The proxies have no \"Radius\" point array.");
    return 0;
  }
  if (vtkDataArray* level = proxies->GetPointData()->GetArray("Level"))
  {
    for (vtkIdType i = 0; i < level->GetNumberOfTuples(); ++i)
    {
      if (level->GetTuple1(i) != 0.0)
      {
        vtkErrorMacro(<< "The proxies hold a hierarchy: fit the leaves, then build it.");
        return 0;
      }
    }
  }
  Spheres spheres;
  const vtkIdType count = proxies->GetNumberOfPoints();
  for (vtkIdType i = 0; i < count; ++i)
  {
    double c[3];
    proxies->GetPoint(i, c);
    const double r = radii->GetTuple1(i);
    if (!std::isfinite(c[0] + c[1] + c[2]) || !std::isfinite(r) || r <= 0.0)
    {
      vtkErrorMacro(<< "Proxy " << i << " has a non-finite centre or a non-positive radius.");
      return 0;
    }
    spheres.Centres.insert(spheres.Centres.end(), c, c + 3);
    spheres.Radii.push_back(r);
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< "No mesh (input 1): give the mesh the proxies stand for.");
    return 0;
  }
  if (input->GetNumberOfPolys() == 0 && input->GetNumberOfStrips() == 0)
  {
    vtkErrorMacro(<< "The mesh has no polygons to trace against.");
    return 0;
  }

  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(input);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  vtkPolyData* triangulated = triangles->GetOutput();
  Mesh mesh;
  const vtkIdType points = triangulated->GetNumberOfPoints();
  mesh.Points.resize(3 * points);
  double bounds[6];
  triangulated->GetBounds(bounds);
  for (int c = 0; c < 3; ++c)
  {
    mesh.Centre[c] = 0.5 * (bounds[2 * c] + bounds[2 * c + 1]);
  }
  for (vtkIdType i = 0; i < points; ++i)
  {
    triangulated->GetPoint(i, &mesh.Points[3 * i]);
    if (!std::isfinite(mesh.Points[3 * i] + mesh.Points[3 * i + 1] + mesh.Points[3 * i + 2]))
    {
      vtkErrorMacro(<< "Mesh point " << i << " is not finite.");
      return 0;
    }
    mesh.Radius = std::max(
      mesh.Radius, std::sqrt(vtkMath::Distance2BetweenPoints(&mesh.Points[3 * i], mesh.Centre)));
  }
  vtkNew<vtkIdList> ids;
  double area = 0.0;
  for (vtkIdType t = 0; t < triangulated->GetNumberOfCells(); ++t)
  {
    triangulated->GetCellPoints(t, ids);
    if (ids->GetNumberOfIds() != 3)
    {
      continue;
    }
    double e1[3], e2[3], n[3];
    const double* a = &mesh.Points[3 * ids->GetId(0)];
    for (int c = 0; c < 3; ++c)
    {
      e1[c] = mesh.Points[3 * ids->GetId(1) + c] - a[c];
      e2[c] = mesh.Points[3 * ids->GetId(2) + c] - a[c];
    }
    vtkMath::Cross(e1, e2, n);
    area += 0.5 * vtkMath::Norm(n);
    mesh.CumulativeArea.push_back(area);
    for (int k = 0; k < 3; ++k)
    {
      mesh.Triangles.push_back(ids->GetId(k));
    }
  }
  if (mesh.CumulativeArea.empty() || !(area > 0.0) || !(mesh.Radius > 0.0))
  {
    vtkErrorMacro(<< "The mesh has no triangle of positive area.");
    return 0;
  }

  proxygi::ReferenceTracer tracer;
  std::string error;
  const double albedo[3] = { 0.0, 0.0, 0.0 };
  if (!proxygi::AddPolyData(tracer, triangulated, albedo, nullptr, error) || !tracer.Commit(error))
  {
    vtkErrorMacro(<< "Cannot build the mesh for tracing: " << error);
    return 0;
  }
  // One set to fit on, an independent one to report on.
  const RaySet fitting =
    TraceRays(mesh, tracer, 2ull * this->Seed, this->Samples, this->Directions);
  this->UpdateProgress(0.3);
  const RaySet testing =
    TraceRays(mesh, tracer, 2ull * this->Seed + 1, this->Samples, this->Directions);
  this->UpdateProgress(0.5);
  if (fitting.Size() == 0 || testing.Size() == 0 || fitting.MeshBlockedCount == 0)
  {
    vtkErrorMacro(<< "No sample point found outside the mesh.");
    return 0;
  }

  const std::size_t n = spheres.Radii.size();
  const double lo = this->MinimumScale, hi = this->MaximumScale;
  auto disagree = [&](const std::vector<double>& s)
  { return Evaluate(spheres, s, fitting, false).Disagree; };
  // One common scale first (golden section on the disagreeing rays).
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  long long f1 = disagree(std::vector<double>(n, x1)), f2 = disagree(std::vector<double>(n, x2));
  for (int step = 0; step < 16; ++step)
  {
    if (f1 <= f2)
    {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - phi * (b - a);
      f1 = disagree(std::vector<double>(n, x1));
    }
    else
    {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + phi * (b - a);
      f2 = disagree(std::vector<double>(n, x2));
    }
  }
  const double common = f1 <= f2 ? x1 : x2;
  std::vector<double> scales(n, common), best = scales;
  long long bestDisagree = std::min(f1, f2);
  const long long unscaled = disagree(std::vector<double>(n, 1.0));
  if (unscaled <= bestDisagree)
  {
    best.assign(n, 1.0);
    scales = best;
    bestDisagree = unscaled;
  }
  // Per-sphere rounds from the best scales so far: radius ~ sqrt(solid
  // angle), hence the square root; a round that does worse is undone and
  // the steps halved.
  double exponent = 0.5;
  Tally votes = Evaluate(spheres, best, fitting, true);
  for (int round = 0; round < this->Iterations && !this->GetAbortExecute(); ++round)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const double ratio =
        (votes.Right[i] + votes.Missed[i] + 1.0) / (votes.Right[i] + votes.Wrong[i] + 1.0);
      const double step = std::min(1.25, std::max(0.8, std::pow(ratio, exponent)));
      scales[i] = std::min(hi, std::max(lo, best[i] * step));
    }
    Tally t = Evaluate(spheres, scales, fitting, true);
    if (t.Disagree < bestDisagree)
    {
      bestDisagree = t.Disagree;
      best = scales;
      votes = std::move(t);
    }
    else if ((exponent *= 0.5) < 1.0 / 64.0)
    {
      break;
    }
    this->UpdateProgress(0.5 + 0.5 * (round + 1) / std::max(1, this->Iterations));
  }

  output->ShallowCopy(proxies);
  vtkSmartPointer<vtkDataArray> fitted;
  fitted.TakeReference(radii->NewInstance());
  fitted->DeepCopy(radii);
  fitted->SetName("Radius");
  vtkNew<vtkDoubleArray> bounding, scaleArray;
  bounding->SetName("BoundingRadius");
  bounding->SetNumberOfTuples(count);
  scaleArray->SetName("RadiusScale");
  scaleArray->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    bounding->SetValue(i, spheres.Radii[i]);
    scaleArray->SetValue(i, best[i]);
    fitted->SetTuple1(i, spheres.Radii[i] * best[i]);
  }
  vtkNew<vtkPointData> pointData;
  pointData->ShallowCopy(proxies->GetPointData());
  const bool activeScalars = proxies->GetPointData()->GetScalars() == radii;
  pointData->RemoveArray("Radius");
  pointData->AddArray(fitted);
  if (activeScalars)
  {
    pointData->SetActiveScalars("Radius");
  }
  pointData->AddArray(bounding);
  pointData->AddArray(scaleArray);
  output->GetPointData()->ShallowCopy(pointData);

  const Tally before = Evaluate(spheres, std::vector<double>(n, 1.0), testing, false);
  const Tally after = Evaluate(spheres, best, testing, false);
  const double blocked = static_cast<double>(std::max(1LL, testing.MeshBlockedCount));
  AddValue(output, "OcclusionErrorBefore", before.Disagree / blocked);
  AddValue(output, "OcclusionErrorAfter", after.Disagree / blocked);
  AddValue(
    output, "OcclusionBiasBefore", (before.SpheresBlocked - testing.MeshBlockedCount) / blocked);
  AddValue(
    output, "OcclusionBiasAfter", (after.SpheresBlocked - testing.MeshBlockedCount) / blocked);
  AddValue(output, "CommonScale", common);
  this->UpdateProgress(1.0);
  return 1;
}
