#include "vtkPGISphereLightSampler.h"

#include "pgiMaterial.h"
#include "pgiParallel.h"
#include "pgiSHBasis.h"
#include "pgiSHSphericalLight.h"

#include "vtkCellArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTriangleFilter.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkPGISphereLightSampler);

namespace
{
// One object's triangles in an Embree scene of their own (rays see only it).
struct ObjectScene
{
  RTCScene Scene = nullptr;
  std::vector<unsigned> Triangles; // mesh point ids, 3 per primitive
};

struct Mesh
{
  std::vector<float> Points, Albedo; // 3 per point
};

// What one ray from a sphere centre finds under the three rules.
struct Sample
{
  int Rule = 0; // 1, 2 (discarded), 3, 0 (nothing)
  double P[3] = { 0, 0, 0 }, N[3] = { 0, 0, 0 };
  float Albedo[3] = { 0, 0, 0 };
};

// What one rank's piece of the mesh offers for one ray, as doubles so that
// ranks can exchange it: the rule it would apply alone (0 nothing, 1 an
// in-segment forward hit, 2 forward hits none in the segment, 3 an
// in-segment backward hit, looked for only without forward hits), the hit's
// distance along its ray, position, normal and albedo.
constexpr int CandidateSize = 11;
struct Candidate
{
  double V[CandidateSize] = { 0, -1, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  int Rule() const { return static_cast<int>(this->V[0]); }
  double Distance() const { return this->V[1]; }
};

Candidate CandidateOf(const Sample& s, double t)
{
  Candidate c;
  c.V[0] = s.Rule;
  c.V[1] = t;
  for (int k = 0; k < 3; ++k)
  {
    c.V[2 + k] = s.P[k];
    c.V[5 + k] = s.N[k];
    c.V[8 + k] = s.Albedo[k];
  }
  return c;
}

// The three rules over the union of the ranks' pieces: the farthest
// in-segment forward hit of any rank; else none if any rank saw a forward
// hit; else the nearest in-segment backward hit (ties: the lower rank).
Sample Combine(const double* candidates, int ranks, std::size_t stride)
{
  int best = -1, rule = 0;
  for (int r = 0; r < ranks; ++r)
  {
    const double* c = candidates + r * stride;
    const int cr = static_cast<int>(c[0]);
    auto better = [&]
    {
      if (rule != cr)
      {
        // 1 beats 2 beats 3 beats 0.
        const int rank[4] = { 3, 0, 1, 2 };
        return rank[cr] < rank[rule];
      }
      return (cr == 1 && c[1] > candidates[best * stride + 1]) ||
        (cr == 3 && c[1] < candidates[best * stride + 1]);
    };
    if (cr != 0 && (best < 0 || better()))
    {
      best = r;
      rule = cr;
    }
  }
  Sample s;
  s.Rule = rule;
  if (rule == 1 || rule == 3)
  {
    const double* c = candidates + best * stride;
    for (int k = 0; k < 3; ++k)
    {
      s.P[k] = c[2 + k];
      s.N[k] = c[5 + k];
      s.Albedo[k] = static_cast<float>(c[8 + k]);
    }
  }
  return s;
}

struct Sampler
{
  const Mesh* M;
  const ObjectScene* Object;
  const std::vector<double>* Centres; // x, y, z, r per sphere
  std::vector<int> Peers;             // spheres of the same object and level
  double Epsilon;

  bool InSegment(int i, const double p[3]) const
  {
    const std::vector<double>& s = *this->Centres;
    auto d = [&](int k)
    {
      const double dx = p[0] - s[4 * k], dy = p[1] - s[4 * k + 1], dz = p[2] - s[4 * k + 2];
      return std::sqrt(dx * dx + dy * dy + dz * dz) / s[4 * k + 3];
    };
    const double mine = d(i);
    for (int k : this->Peers)
    {
      if (k != i && d(k) < mine * (1.0 - 1e-9))
      {
        return false;
      }
    }
    return true;
  }

  // All hits along o + t w (t > 0) whose surface faces `facing`, in order.
  template <typename F>
  void Hits(const double o[3], const double w[3], const double facing[3], F&& visit) const
  {
    float tnear = 0.0f;
    for (int guard = 0; guard < 256; ++guard)
    {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRayHit rh;
      rh.ray.org_x = float(o[0]);
      rh.ray.org_y = float(o[1]);
      rh.ray.org_z = float(o[2]);
      rh.ray.dir_x = float(w[0]);
      rh.ray.dir_y = float(w[1]);
      rh.ray.dir_z = float(w[2]);
      rh.ray.tnear = tnear;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.flags = 0;
      rh.ray.time = 0.0f;
      rh.ray.id = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(this->Object->Scene, &context, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      {
        return;
      }
      const unsigned* t = &this->Object->Triangles[3 * rh.hit.primID];
      const float* a = &this->M->Points[3 * t[0]];
      const float* b = &this->M->Points[3 * t[1]];
      const float* c = &this->M->Points[3 * t[2]];
      // The polygon's own orientation (counter-clockwise = outward), not Embree's Ng.
      const double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
      double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0] };
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double th = rh.ray.tfar;
      if (len > 0.0 && (n[0] * facing[0] + n[1] * facing[1] + n[2] * facing[2]) > 0.0)
      {
        Sample s;
        for (int k = 0; k < 3; ++k)
        {
          s.P[k] = o[k] + th * w[k];
          s.N[k] = n[k] / len;
        }
        const float u = rh.hit.u, v = rh.hit.v;
        for (int k = 0; k < 3; ++k)
        {
          s.Albedo[k] = (1.0f - u - v) * this->M->Albedo[3 * t[0] + k] +
            u * this->M->Albedo[3 * t[1] + k] + v * this->M->Albedo[3 * t[2] + k];
        }
        if (!visit(s))
        {
          return;
        }
      }
      tnear = static_cast<float>(th + this->Epsilon);
    }
  }

  Candidate Find(int i, const double w[3]) const
  {
    const double* x = &(*this->Centres)[4 * i];
    Sample best;
    bool any = false;
    auto distance = [&](const Sample& s)
    {
      return std::sqrt((s.P[0] - x[0]) * (s.P[0] - x[0]) + (s.P[1] - x[1]) * (s.P[1] - x[1]) +
        (s.P[2] - x[2]) * (s.P[2] - x[2]));
    };
    if (this->Object)
    {
      this->Hits(x, w, w,
        [&](const Sample& s)
        {
          any = true;
          if (this->InSegment(i, s.P))
          {
            best = s; // hits come in order: the last one kept is the farthest
            best.Rule = 1;
          }
          return true;
        });
    }
    if (best.Rule == 1)
    {
      return CandidateOf(best, distance(best));
    }
    if (any)
    {
      best.Rule = 2;
      return CandidateOf(best, -1.0);
    }
    const double back[3] = { -w[0], -w[1], -w[2] };
    if (this->Object)
    {
      this->Hits(x, back, w,
        [&](const Sample& s)
        {
          if (this->InSegment(i, s.P))
          {
            best = s;
            best.Rule = 3;
            return false;
          }
          return true;
        });
    }
    return CandidateOf(best, best.Rule == 3 ? distance(best) : -1.0);
  }
};
} // namespace

vtkCxxSetObjectMacro(vtkPGISphereLightSampler, Controller, vtkMultiProcessController);

vtkPGISphereLightSampler::vtkPGISphereLightSampler()
{
  this->SetNumberOfInputPorts(2);
  this->SetAlbedoArrayName("Albedo");
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPGISphereLightSampler::~vtkPGISphereLightSampler()
{
  this->SetAlbedoArrayName(nullptr);
  this->SetController(nullptr);
}

void vtkPGISphereLightSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GeodesicFrequency: " << this->GeodesicFrequency << "\n";
  os << indent << "AlbedoOrder: " << this->AlbedoOrder << "\n";
  os << indent << "AlbedoResolution: " << this->AlbedoResolution << "\n";
  os << indent << "DefaultAlbedo: " << this->DefaultAlbedo[0] << " " << this->DefaultAlbedo[1]
     << " " << this->DefaultAlbedo[2] << "\n";
  os << indent << "AlbedoArrayName: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)")
     << "\n";
  os << indent << "Controller: " << this->Controller << " ("
     << proxygi::parallel::Ranks(this->Controller) << " ranks)\n";
  os << indent << "NumberOfRays: " << this->NumberOfRays << "\n";
  os << indent << "CommunicationBytes: " << this->CommunicationBytes << "\n";
}

int vtkPGISphereLightSampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkPGISphereLightSampler::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkPolyData* input = vtkPolyData::GetData(in[0]);
  vtkPolyData* proxies = vtkPolyData::GetData(in[1]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  // Under MPI each rank holds a piece of the mesh and the global proxies;
  // every rank reaches every collective below.
  vtkMultiProcessController* controller = proxygi::parallel::Active(this->Controller);
  proxygi::parallel::Traffic traffic;
  std::string error;
  const bool emptyPiece = controller && (!input || input->GetNumberOfPoints() == 0);
  vtkDataArray* radius = proxies ? proxies->GetPointData()->GetArray("Radius") : nullptr;
  if ((!emptyPiece && (!input || input->GetNumberOfPoints() == 0)) || !proxies ||
    proxies->GetNumberOfPoints() == 0)
  {
    error = "Need a mesh (input 0) and proxies (input 1), both non-empty.";
  }
  else if (!radius)
  {
    error = "The proxies (input 1) need a \"Radius\" point array.";
  }
  vtkNew<vtkPolyData> nothing;
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(emptyPiece || !input ? nothing.Get() : input);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  if (error.empty() && !emptyPiece)
  {
    triangulate->Update();
  }
  vtkPolyData* tris = triangulate->GetOutput();
  const vtkIdType np = error.empty() ? tris->GetNumberOfPoints() : 0;
  Mesh mesh;
  mesh.Points.resize(3 * np);
  mesh.Albedo.resize(3 * np);
  for (vtkIdType i = 0; i < np && error.empty(); ++i)
  {
    double p[3], a[3];
    tris->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      error = "Mesh point " + std::to_string(i) + " has a NaN or Inf coordinate.";
      break;
    }
    proxygi::AlbedoOf(tris, this->AlbedoArrayName, i, this->DefaultAlbedo, a);
    for (int k = 0; k < 3; ++k)
    {
      mesh.Points[3 * i + k] = static_cast<float>(p[k]);
      mesh.Albedo[3 * i + k] = static_cast<float>(a[k]);
    }
  }
  const vtkIdType ns = error.empty() ? proxies->GetNumberOfPoints() : 0;
  std::vector<double> spheres(4 * ns);
  std::vector<int> sphereObject(ns, 0), sphereLevel(ns, 0);
  vtkDataArray* objectIds = error.empty() ? proxies->GetPointData()->GetArray("ObjectId") : nullptr;
  vtkDataArray* levels = error.empty() ? proxies->GetPointData()->GetArray("Level") : nullptr;
  for (vtkIdType i = 0; i < ns && error.empty(); ++i)
  {
    proxies->GetPoint(i, &spheres[4 * i]);
    spheres[4 * i + 3] = radius->GetTuple1(i);
    for (int k = 0; k < 4; ++k)
    {
      if (!std::isfinite(spheres[4 * i + k]))
      {
        error = "Proxy " + std::to_string(i) + " has a NaN or Inf centre or radius.";
      }
    }
    if (!(spheres[4 * i + 3] > 0.0))
    {
      spheres[4 * i + 3] = 1e-30; // samples nothing useful, but no division by 0
    }
    sphereObject[i] = objectIds ? static_cast<int>(objectIds->GetTuple1(i)) : 0;
    sphereLevel[i] = levels ? static_cast<int>(levels->GetTuple1(i)) : 0;
  }
  // The ranks must sample one global set (Sphere Proxies' output is).
  const std::vector<long long> sets =
    proxygi::parallel::AllGatherCounts(controller, static_cast<long long>(ns), &traffic);
  if (error.empty() && std::any_of(sets.begin(), sets.end(), [&](long long n) { return n != ns; }))
  {
    error = "the ranks hold different proxy sets (" + std::to_string(ns) +
      " spheres here): give every rank the global set (Sphere Proxies or Gather Proxies)";
  }
  std::string agreed;
  if (!proxygi::parallel::AllOk(controller, error.empty(), error, agreed, &traffic))
  {
    vtkErrorMacro(<< agreed);
    return 0;
  }

  // Embree: one scene per object.
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device)
  {
    error = "Embree could not create a device.";
  }
  vtkDataArray* pointObject = tris->GetPointData()->GetArray("ObjectId");
  std::map<int, ObjectScene> objects;
  double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
  vtkCellArray* polys = tris->GetPolys();
  vtkIdType npts;
  const vtkIdType* ids;
  for (polys->InitTraversal(); device && polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    const int object = pointObject ? static_cast<int>(pointObject->GetTuple1(ids[0])) : 0;
    for (int k = 0; k < 3; ++k)
    {
      objects[object].Triangles.push_back(static_cast<unsigned>(ids[k]));
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], double(mesh.Points[3 * ids[k] + c]));
        hi[c] = std::max(hi[c], double(mesh.Points[3 * ids[k] + c]));
      }
    }
  }
  for (auto& entry : objects)
  {
    ObjectScene& o = entry.second;
    o.Scene = rtcNewScene(device);
    // Robust traversal: sample rays often run exactly along mesh edges.
    rtcSetSceneFlags(o.Scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads vertex buffers 16 bytes at a time: pad by one float.
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), np + 1));
    std::copy(mesh.Points.begin(), mesh.Points.end(), v);
    v[3 * np] = v[3 * np + 1] = v[3 * np + 2] = 0.0f;
    const std::size_t nt = o.Triangles.size() / 3;
    unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    std::copy(o.Triangles.begin(), o.Triangles.end(), idx);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(o.Scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(o.Scene);
  }
  // The whole mesh's extent sets the step between hits, on every rank alike.
  proxygi::parallel::GlobalBox(controller, lo, hi);
  const double diagonal =
    std::sqrt(std::pow(hi[0] - lo[0], 2) + std::pow(hi[1] - lo[1], 2) + std::pow(hi[2] - lo[2], 2));

  const std::vector<double> directions = proxygi::sh::GeodesicDirections(this->GeodesicFrequency);
  const int m = static_cast<int>(directions.size() / 3);
  const int ak = this->AlbedoOrder, a2 = ak * ak;
  const proxygi::sh::SphereQuadrature rule(this->AlbedoResolution);
  // Every sphere's rays, geodesic then albedo directions: this piece's candidates.
  const std::size_t rays = static_cast<std::size_t>(m) + rule.Size();
  const std::size_t record = rays * CandidateSize;
  this->NumberOfRays = static_cast<double>(ns) * static_cast<double>(rays);
  std::vector<double> candidates(static_cast<std::size_t>(ns) * record);
  if (device)
  {
    vtkSMPTools::For(0, ns,
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType i = first; i < last; ++i)
        {
          auto object = objects.find(sphereObject[i]);
          Sampler s{ &mesh, object != objects.end() ? &object->second : nullptr, &spheres, {},
            1e-6 * diagonal };
          for (vtkIdType k = 0; k < ns; ++k)
          {
            if (sphereObject[k] == sphereObject[i] && sphereLevel[k] == sphereLevel[i])
            {
              s.Peers.push_back(static_cast<int>(k));
            }
          }
          double* mine = &candidates[static_cast<std::size_t>(i) * record];
          for (std::size_t j = 0; j < rays; ++j)
          {
            const double albedoRay[3] = { j < std::size_t(m) ? 0.0 : rule.X[j - m],
              j < std::size_t(m) ? 0.0 : rule.Y[j - m], j < std::size_t(m) ? 0.0 : rule.Z[j - m] };
            const double* w = j < std::size_t(m) ? &directions[3 * j] : albedoRay;
            const Candidate c = s.Find(static_cast<int>(i), w);
            std::copy(c.V, c.V + CandidateSize, mine + j * CandidateSize);
          }
        }
      });
  }
  for (auto& entry : objects)
  {
    rtcReleaseScene(entry.second.Scene);
  }
  if (device)
  {
    rtcReleaseDevice(device);
  }
  if (!proxygi::parallel::AllOk(controller, error.empty(), error, agreed, &traffic))
  {
    vtkErrorMacro(<< agreed);
    return 0;
  }
  // A sphere whose object has no triangles anywhere samples nothing.
  std::vector<int> present(static_cast<std::size_t>(ns)), presentAnywhere(present.size());
  for (vtkIdType i = 0; i < ns; ++i)
  {
    present[i] = objects.count(sphereObject[i]) ? 1 : 0;
  }
  if (controller && ns > 0)
  {
    controller->AllReduce(present.data(), presentAnywhere.data(), ns, vtkCommunicator::MAX_OP);
    present.swap(presentAnywhere);
  }
  // Every rank's candidates, combined per ray as the serial rules would.
  const int ranks = proxygi::parallel::Ranks(controller);
  std::vector<double> all;
  if (controller)
  {
    all.resize(candidates.size() * static_cast<std::size_t>(ranks));
    controller->AllGather(candidates.data(), all.data(), static_cast<vtkIdType>(candidates.size()));
    traffic.BytesSent += sizeof(double) * candidates.size() * (ranks - 1);
    traffic.BytesReceived += sizeof(double) * candidates.size() * (ranks - 1);
  }
  const std::vector<double>& gathered = controller ? all : candidates;
  this->CommunicationBytes = static_cast<double>(traffic.BytesReceived);
  const std::size_t perRank = candidates.size();

  vtkNew<vtkFloatArray> offsets, normals, albedoSH;
  vtkNew<vtkIntArray> counts;
  offsets->SetName("SampleOffset");
  offsets->SetNumberOfComponents(3 * m);
  offsets->SetNumberOfTuples(ns);
  normals->SetName("SampleNormal");
  normals->SetNumberOfComponents(3 * m);
  normals->SetNumberOfTuples(ns);
  counts->SetName("SampleCount");
  counts->SetNumberOfTuples(ns);
  albedoSH->SetName("AlbedoSH");
  albedoSH->SetNumberOfComponents(3 * a2);
  albedoSH->SetNumberOfTuples(ns);
  std::atomic<long> rules[4] = { { 0 }, { 0 }, { 0 }, { 0 } };

  vtkSMPTools::For(0, ns,
    [&](vtkIdType first, vtkIdType last)
    {
      std::vector<float> off(3 * m), nor(3 * m), sh(3 * a2);
      std::vector<double> found;
      double y[proxygi::sh::MaxCoefficients];
      for (vtkIdType i = first; i < last; ++i)
      {
        std::fill(off.begin(), off.end(), 0.0f);
        std::fill(nor.begin(), nor.end(), 0.0f);
        std::fill(sh.begin(), sh.end(), 0.0f);
        int count = 0;
        const double* base = &gathered[static_cast<std::size_t>(i) * record];
        auto sampleOf = [&](std::size_t j)
        { return Combine(base + j * CandidateSize, ranks, perRank); };
        const double r = spheres[4 * i + 3];
        for (int j = 0; j < m; ++j)
        {
          const Sample sample = sampleOf(static_cast<std::size_t>(j));
          ++rules[sample.Rule == 0 ? 3 : sample.Rule - 1];
          if (sample.Rule == 1 || sample.Rule == 3)
          {
            ++count;
            for (int c = 0; c < 3; ++c)
            {
              off[3 * j + c] = static_cast<float>((sample.P[c] - spheres[4 * i + c]) / r);
              nor[3 * j + c] = static_cast<float>(sample.N[c]);
            }
          }
        }
        // Albedo: the same rules on the quadrature's directions; misses take the mean.
        found.assign(rule.Size() * 4, -1.0);
        double mean[3] = { 0, 0, 0 }, weight = 0.0;
        for (std::size_t q = 0; q < rule.Size(); ++q)
        {
          const Sample sample = sampleOf(static_cast<std::size_t>(m) + q);
          if (sample.Rule == 1 || sample.Rule == 3)
          {
            for (int c = 0; c < 3; ++c)
            {
              found[4 * q + c] = sample.Albedo[c];
              mean[c] += rule.W[q] * sample.Albedo[c];
            }
            found[4 * q + 3] = 1.0;
            weight += rule.W[q];
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          mean[c] = weight > 0.0 ? mean[c] / weight : this->DefaultAlbedo[c];
        }
        if (present[i])
        {
          for (std::size_t q = 0; q < rule.Size(); ++q)
          {
            proxygi::sh::EvaluateBasis(ak, rule.X[q], rule.Y[q], rule.Z[q], y);
            for (int c = 0; c < 3; ++c)
            {
              const double a = found[4 * q + 3] > 0.0 ? found[4 * q + c] : mean[c];
              for (int t = 0; t < a2; ++t)
              {
                sh[c * a2 + t] += static_cast<float>(rule.W[q] * a * y[t]);
              }
            }
          }
        }
        offsets->SetTypedTuple(i, off.data());
        normals->SetTypedTuple(i, nor.data());
        albedoSH->SetTypedTuple(i, sh.data());
        counts->SetValue(i, count);
      }
    });

  output->ShallowCopy(proxies);
  output->GetPointData()->AddArray(offsets);
  output->GetPointData()->AddArray(normals);
  output->GetPointData()->AddArray(counts);
  output->GetPointData()->AddArray(albedoSH);
  vtkNew<vtkDoubleArray> dirs;
  dirs->SetName("SampleDirections");
  dirs->SetNumberOfComponents(3);
  dirs->SetNumberOfTuples(m);
  std::copy(directions.begin(), directions.end(), dirs->GetPointer(0));
  output->GetFieldData()->AddArray(dirs);
  vtkNew<vtkIntArray> ruleCounts;
  ruleCounts->SetName("SampleRules");
  for (auto& count : rules)
  {
    ruleCounts->InsertNextValue(static_cast<int>(count.load()));
  }
  output->GetFieldData()->AddArray(ruleCounts);
  return 1;
}
