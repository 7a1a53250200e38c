#include "vtkPGISelfVisibility.h"

#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"
#include "pgiSHBasis.h"
#include "pgiSHLog.h"
#include "vtkPGIGIBake.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPGISelfVisibility);

vtkPGISelfVisibility::vtkPGISelfVisibility() = default;
vtkPGISelfVisibility::~vtkPGISelfVisibility() = default;

void vtkPGISelfVisibility::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Order: " << this->Order << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ObjectId: " << this->ObjectId << "\n";
}

namespace
{
// A turn in [0, 1) per vertex and seed (splitmix64), independent of threading.
double Turn(std::uint64_t seed, std::uint64_t vertex)
{
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + vertex + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

// One mesh point a vertex's rays hit: its weight in the gather, summed over
// the rays, and the largest single ray's share with where that ray hit.
struct BounceHit
{
  unsigned Target = 0;
  float Weight = 0.0f;
  float Largest = 0.0f;
  float Point[3] = { 0.0f, 0.0f, 0.0f };
};

void TangentFrame(const double n[3], double t[3], double b[3])
{
  const double a[3] = { std::abs(n[0]) < 0.9 ? 1.0 : 0.0, std::abs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0 };
  vtkMath::Cross(n, a, t);
  vtkMath::Normalize(t);
  vtkMath::Cross(n, t, b);
}
} // namespace

int vtkPGISelfVisibility::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< "No input points.");
    return 0;
  }
  if (input->GetNumberOfPolys() == 0 && input->GetNumberOfStrips() == 0)
  {
    vtkErrorMacro(<< "The input has no polygons to trace against.");
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (!std::isfinite(p[0] + p[1] + p[2]))
    {
      vtkErrorMacro(<< "Point " << i << " is not finite.");
      return 0;
    }
  }
  // The input's, or computed as the GI filter computes them.
  vtkSmartPointer<vtkDataArray> normals = proxygi::ReceiverNormals(input);
  if (!normals)
  {
    vtkErrorMacro(<< "Could not compute point normals; give them.");
    return 0;
  }

  proxygi::ReferenceTracer tracer;
  std::string error;
  const double albedo[3] = { 0.0, 0.0, 0.0 };
  if (!proxygi::AddPolyData(tracer, input, albedo, nullptr, error) || !tracer.Commit(error))
  {
    vtkErrorMacro(<< "Cannot build the mesh for tracing: " << error);
    return 0;
  }

  const int order = this->Order, n2 = order * order, samples = this->Samples;
  // Directions in the normal's frame: uniform in z over the hemisphere
  // (equal solid angle each), golden-angle azimuths.
  std::vector<double> local(3 * samples);
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  for (int s = 0; s < samples; ++s)
  {
    const double z = 1.0 - (s + 0.5) / samples, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    local[3 * s] = rho * std::cos(golden * s);
    local[3 * s + 1] = rho * std::sin(golden * s);
    local[3 * s + 2] = z;
  }
  const double weight = 2.0 * vtkMath::Pi() / samples;

  vtkNew<vtkFloatArray> logs, rest;
  logs->SetName("SelfLogVisibility");
  logs->SetNumberOfComponents(n2);
  logs->SetNumberOfTuples(n);
  rest->SetName("SelfVisibilityRest");
  rest->SetNumberOfComponents(3);
  rest->SetNumberOfTuples(n);
  // The bounce off the mesh onto itself: per vertex, the mesh points its
  // blocked rays hit (the hit triangle's nearest corner: a third of the
  // memory of all three), each with weight 2 cos(theta) / Samples
  // (irradiance / pi per unit exit radiance there), and where the largest
  // of those hits lies: near hits see shadows finer than the triangles,
  // where the corner's light does not hold, and the GI filter lights that
  // point instead (barycentric weights over all three corners did not help
  // more, for 2.5 times the entries).
  std::vector<std::vector<BounceHit>> bounce(n);
  std::atomic<long long> blockedRays(0);
  std::atomic<vtkIdType> failures(0);
  const vtkIdType blocks = std::min<vtkIdType>(100, n);
  for (vtkIdType block = 0; block < blocks && !this->GetAbortExecute(); ++block)
  {
    vtkSMPTools::For(n * block / blocks, n * (block + 1) / blocks,
      [&](vtkIdType first, vtkIdType last)
      {
        double v[proxygi::sh::MaxCoefficients], f[proxygi::sh::MaxCoefficients],
          y[proxygi::sh::MaxCoefficients];
        float out[proxygi::sh::MaxCoefficients];
        long long localBlocked = 0;
        for (vtkIdType i = first; i < last; ++i)
        {
          double x[3], nrm[3], t[3], b[3];
          input->GetPoint(i, x);
          normals->GetTuple(i, nrm);
          if (!(vtkMath::Normalize(nrm) > 0.0) || !std::isfinite(nrm[0] + nrm[1] + nrm[2]))
          {
            nrm[0] = nrm[1] = 0.0;
            nrm[2] = 1.0;
          }
          TangentFrame(nrm, t, b);
          const double turn = 2.0 * vtkMath::Pi() * Turn(this->Seed, static_cast<std::uint64_t>(i));
          const double c = std::cos(turn), s = std::sin(turn);
          proxygi::sh::SetConstant(order, 1.0, v);
          int blocked = 0;
          for (int k = 0; k < samples; ++k)
          {
            const double lx = c * local[3 * k] - s * local[3 * k + 1];
            const double ly = s * local[3 * k] + c * local[3 * k + 1];
            const double lz = local[3 * k + 2];
            const double d[3] = { lx * t[0] + ly * b[0] + lz * nrm[0],
              lx * t[1] + ly * b[1] + lz * nrm[1], lx * t[2] + ly * b[2] + lz * nrm[2] };
            unsigned ids[3];
            double bary[3];
            if (tracer.HitVertices(x, nrm, d, ids, bary))
            {
              ++blocked;
              // A hit from behind sees the unlit inside (or the far side of
              // a sheet, whose light is not the front's): it blocks, no bounce.
              // (The triangle's own normal, turned to its corners' side.)
              double p0[3], p1[3], p2[3], e1[3], e2[3], ng[3], corners[3] = { 0, 0, 0 };
              input->GetPoint(ids[0], p0);
              input->GetPoint(ids[1], p1);
              input->GetPoint(ids[2], p2);
              for (int c3 = 0; c3 < 3; ++c3)
              {
                e1[c3] = p1[c3] - p0[c3];
                e2[c3] = p2[c3] - p0[c3];
                double m[3];
                normals->GetTuple(ids[c3], m);
                corners[0] += m[0];
                corners[1] += m[1];
                corners[2] += m[2];
              }
              vtkMath::Cross(e1, e2, ng);
              const double side = vtkMath::Dot(ng, corners) < 0.0 ? -1.0 : 1.0;
              if (side * vtkMath::Dot(ng, d) < 0.0)
              {
                BounceHit hit;
                for (int c3 = 0; c3 < 3; ++c3)
                {
                  hit.Point[c3] =
                    static_cast<float>(bary[0] * p0[c3] + bary[1] * p1[c3] + bary[2] * p2[c3]);
                }
                const int q =
                  bary[0] >= bary[1] ? (bary[0] >= bary[2] ? 0 : 2) : (bary[1] >= bary[2] ? 1 : 2);
                hit.Target = ids[q];
                hit.Weight = hit.Largest = static_cast<float>(2.0 * lz / samples);
                bounce[i].push_back(hit);
              }
              proxygi::sh::EvaluateBasis(order, d[0], d[1], d[2], y);
              for (int j = 0; j < n2; ++j)
              {
                v[j] -= weight * y[j];
              }
            }
          }
          localBlocked += blocked;
          // One entry per point hit.
          std::vector<BounceHit>& hits = bounce[i];
          std::sort(hits.begin(), hits.end(),
            [](const BounceHit& a, const BounceHit& b) { return a.Target < b.Target; });
          std::size_t kept = 0;
          for (std::size_t h = 0; h < hits.size(); ++h)
          {
            if (kept > 0 && hits[kept - 1].Target == hits[h].Target)
            {
              BounceHit& into = hits[kept - 1];
              into.Weight += hits[h].Weight;
              if (hits[h].Largest > into.Largest)
              {
                into.Largest = hits[h].Largest;
                std::copy_n(hits[h].Point, 3, into.Point);
              }
            }
            else
            {
              hits[kept++] = hits[h];
            }
          }
          hits.resize(kept);
          hits.shrink_to_fit();
          if (blocked == 0)
          {
            proxygi::sh::Fill(out, n2, 0.0f);
          }
          else if (proxygi::sh::Log(order, v, f) != proxygi::sh::Status::Ok)
          {
            ++failures;
            proxygi::sh::Fill(out, n2, 0.0f);
          }
          else
          {
            for (int j = 0; j < n2; ++j)
            {
              out[j] = static_cast<float>(f[j]);
            }
          }
          logs->SetTypedTuple(i, out);
          const float xf[3] = { static_cast<float>(x[0]), static_cast<float>(x[1]),
            static_cast<float>(x[2]) };
          rest->SetTypedTuple(i, xf);
        }
        blockedRays += localBlocked;
      });
    this->UpdateProgress(static_cast<double>(block + 1) / blocks);
  }
  if (this->GetAbortExecute())
  {
    return 1;
  }
  if (failures > 0)
  {
    vtkWarningMacro(<< failures << " vertices' visibility had no finite log; left unshadowed.");
  }

  output->ShallowCopy(input);
  vtkNew<vtkIdTypeArray> offsets, targets;
  vtkNew<vtkFloatArray> weights, hitPoints;
  hitPoints->SetName("SelfBounceHitPoints");
  hitPoints->SetNumberOfComponents(3);
  offsets->SetName("SelfBounceOffsets");
  targets->SetName("SelfBounceTargets");
  weights->SetName("SelfBounceWeights");
  offsets->SetNumberOfTuples(n + 1);
  vtkIdType entries = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    offsets->SetValue(i, entries);
    entries += static_cast<vtkIdType>(bounce[i].size());
  }
  offsets->SetValue(n, entries);
  targets->SetNumberOfTuples(entries);
  weights->SetNumberOfTuples(entries);
  hitPoints->SetNumberOfTuples(entries);
  for (vtkIdType i = 0, e = 0; i < n; ++i)
  {
    for (const BounceHit& hit : bounce[i])
    {
      targets->SetValue(e, hit.Target);
      hitPoints->SetTypedTuple(e, hit.Point);
      weights->SetValue(e++, hit.Weight);
    }
  }
  output->GetFieldData()->AddArray(offsets);
  output->GetFieldData()->AddArray(targets);
  output->GetFieldData()->AddArray(weights);
  output->GetFieldData()->AddArray(hitPoints);
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(logs);
  pd->AddArray(rest);
  if (!input->GetPointData()->GetNormals())
  {
    pd->SetNormals(normals);
  }
  if (!pd->GetArray("ObjectId"))
  {
    vtkNew<vtkIntArray> id;
    id->SetName("ObjectId");
    id->SetNumberOfTuples(n);
    id->FillValue(this->ObjectId);
    pd->AddArray(id);
  }
  auto field = [&](const char* name, double value)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    output->GetFieldData()->AddArray(a);
  };
  field("SelfVisibilitySamples", samples);
  field("SelfVisibilityBlockedFraction",
    static_cast<double>(blockedRays.load()) / (static_cast<double>(n) * samples));
  return 1;
}
