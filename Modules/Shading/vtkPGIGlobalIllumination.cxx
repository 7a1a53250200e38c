#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILocalLightTransfer.h"

#include "pgiAccuracyBudget.h"

#include "pgiBrightLightShadows.h"
#include "pgiEnvironmentMap.h"
#include "pgiEnvironmentShading.h"
#include "pgiIndirectLight.h"
#include "pgiMaterial.h"
#include "pgiParallel.h"
#include "pgiPlaneLightMap.h"
#include "pgiSHBatch.h"
#include "pgiSHLightTables.h"
#include "pgiSHRotation.h"
#include "pgiSHSphericalLight.h"
#include "pgiSHZonal.h"
#include "pgiSRGB.h"
#include "pgiSoftShadows.h"
#include "pgiSphereTree.h"
#include "pgiSphericalLights.h"
#include "vtkPGILighting.h"
#include "vtkPGIOccluder.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

vtkStandardNewMacro(vtkPGIGlobalIllumination);

namespace
{
/**
 * The spherical lights of one cluster's cut (hierarchy indices `cut` into
 * `nodes`), each parent with the reflection ratio (Guerrero 2008, eq. 25)
 * that scales its share at the cluster's central receiver (p, n) to the sum
 * of its leaves' shares there.
 */
void CutSphericalLights(const proxygi::SphericalLights& nodes,
  const proxygi::SphericalLights& leaves, const std::map<std::size_t, int>& leafOfNode,
  const proxygi::ProxyHierarchy& hierarchy, const std::vector<int>& cut,
  const proxygi::Blockers& planes, const proxygi::ShadowedIndirect& kernel, const float p[3],
  const float n[3], proxygi::SphericalLights& out)
{
  const std::size_t n2 = static_cast<std::size_t>(nodes.Order) * nodes.Order;
  out = proxygi::SphericalLights();
  out.Order = nodes.Order;
  for (int node : cut)
  {
    out.Add(nodes.X[node], nodes.Y[node], nodes.Z[node], nodes.R[node], nodes.Object[node]);
    out.Radiance.insert(out.Radiance.end(), nodes.Radiance.begin() + node * 3 * n2,
      nodes.Radiance.begin() + (node + 1) * 3 * n2);
  }
  out.Finish();
  proxygi::SphericalLightScratch scratch;
  std::vector<float> leafShare(leaves.Count()), cutShare(out.Count());
  float rgb[3];
  kernel.ExitRadiance(leaves, true, nullptr, &planes, p, n, rgb, scratch, leafShare.data());
  kernel.ExitRadiance(out, true, nullptr, &planes, p, n, rgb, scratch, cutShare.data());
  out.ReflectionRatio.assign(out.Count(), 1.0f);
  for (std::size_t k = 0; k < cut.size(); ++k)
  {
    if (hierarchy.Children[cut[k]].empty())
    {
      continue; // a leaf: ratio 1
    }
    float sum = 0.0f;
    std::vector<int> below(hierarchy.Children[cut[k]]);
    while (!below.empty())
    {
      const int j = below.back();
      below.pop_back();
      if (!hierarchy.Children[j].empty())
      {
        below.insert(below.end(), hierarchy.Children[j].begin(), hierarchy.Children[j].end());
        continue;
      }
      const auto leaf = leafOfNode.find(static_cast<std::size_t>(j));
      sum += leaf != leafOfNode.end() ? leafShare[leaf->second] : 0.0f;
    }
    // Nothing to scale where the parent is hidden or unlit at the centre: 1.
    out.ReflectionRatio[k] = cutShare[k] > 1e-12f ? std::min(4.0f, sum / cutShare[k]) : 1.0f;
  }
}
// 3-component tuples as doubles, read straight from a float array (the
// usual points and normals): no virtual call per receiver.
class Tuples3
{
public:
  explicit Tuples3(vtkDataArray* array)
    : Array(array)
  {
    auto* floats = vtkFloatArray::SafeDownCast(array);
    this->Floats = floats && floats->GetNumberOfComponents() == 3 ? floats->GetPointer(0) : nullptr;
  }
  void Get(vtkIdType i, double x[3]) const
  {
    if (this->Floats)
    {
      for (int c = 0; c < 3; ++c)
      {
        x[c] = this->Floats[3 * i + c];
      }
    }
    else
    {
      this->Array->GetTuple(i, x);
    }
  }

private:
  vtkDataArray* Array;
  const float* Floats;
};

// A receiver's unit normal; a zero, NaN or Inf one (vtkPolyDataNormals
// gives NaN on degenerate triangles) faces +z rather than poisoning the
// shading: (Inf, 0, 0) normalizes to (NaN, 0, 0) in vtkMath::Normalize.
void UnitNormal(const Tuples3& normals, vtkIdType i, double n[3])
{
  normals.Get(i, n);
  const double length = vtkMath::Normalize(n);
  if (!(length > 0.0) || !std::isfinite(n[0] + n[1] + n[2]))
  {
    n[0] = n[1] = 0.0;
    n[2] = 1.0;
  }
}
} // namespace
vtkCxxSetObjectMacro(vtkPGIGlobalIllumination, Lighting, vtkPGILighting);
vtkCxxSetObjectMacro(vtkPGIGlobalIllumination, Controller, vtkMultiProcessController);
vtkCxxSetObjectMacro(vtkPGIGlobalIllumination, Occluder, vtkPGIOccluder);
vtkCxxSetObjectMacro(vtkPGIGlobalIllumination, LocalLightTransfer, vtkPGILocalLightTransfer);

namespace
{
struct ClusterFrames
{
  std::vector<int> Of;
  std::vector<std::array<double, 3>> Centres, At, Facing;
  std::vector<double> Radius;
  std::string How;
};

// What a clustering depended on: reused while the receivers stand still.
struct ClusterKey
{
  const void* Receivers = nullptr;
  vtkMTimeType Time = 0;
  vtkIdType Count = -1;
  int PerCluster = 0;
  bool Distributed = false;
  bool operator==(const ClusterKey& o) const
  {
    return this->Receivers == o.Receivers && this->Time == o.Time && this->Count == o.Count &&
      this->PerCluster == o.PerCluster && this->Distributed == o.Distributed;
  }
};

// One thread's buffers for shading a range of receivers.
struct ShadeScratch
{
  std::vector<std::vector<proxygi::SeenBlocker>> Seen, BatchSeen;
  proxygi::SphericalLightScratch Lights;
  std::vector<float> Points, Facing, BatchPoints, BatchFacing, Visibilities, BatchVisibilities,
    PlaneScales, PlaneGaps;
  std::vector<proxygi::sh::Status> Statuses, BatchStatuses;
  std::vector<int> Used, BatchUsed;
  std::vector<vtkIdType> ByBlockers, Who;
  std::vector<long long> Key;
  std::vector<float> BatchSelfLogs;
  proxygi::BrightLightScratch Bright;
};

// The objects the proxies stand for, sorted and unique.
std::vector<int> ProxyObjectsOf(const proxygi::Blockers& blockers)
{
  std::vector<int> objects(blockers.Object.begin(), blockers.Object.end());
  std::sort(objects.begin(), objects.end());
  objects.erase(std::unique(objects.begin(), objects.end()), objects.end());
  return objects;
}

// Whether a receiver's ObjectId names an object no proxy stands for (a
// ground plane): it owns no spheres.
bool NamesNoProxies(double id, const std::vector<int>& proxyObjects)
{
  return id >= 0.0 && id < (1 << 24) &&
    !std::binary_search(proxyObjects.begin(), proxyObjects.end(), static_cast<int>(id));
}

// The receivers' precomputed own visibility (vtkPGISelfVisibility), where
// it still holds; Line says why it runs or not (empty: no such array).
struct SelfVisibilityInput
{
  const float* Logs = nullptr;     // rows of accumulation order^2 (may point into Rotated)
  std::vector<float> Rotated;      // the logs turned with receivers moved rigidly
  vtkDataArray* Objects = nullptr; // the receivers' ObjectId (with or without Logs)
  // The bounce off the object onto itself: receiver i gathers the exit
  // radiance of Targets[Offsets[i] .. Offsets[i + 1]) with their Weights.
  vtkIdTypeArray* Offsets = nullptr;
  vtkIdTypeArray* Targets = nullptr;
  vtkFloatArray* Weights = nullptr;
  // Where each entry's largest hit lies, at the trace (optional), and the
  // rigid motion since: a hit now lies at Turn h + Shift.
  vtkFloatArray* HitPoints = nullptr;
  double Turn[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  double Shift[3] = { 0, 0, 0 };
  std::string Line;
  // The receiver's own object (-1: none, the rules run).
  int OwnObject(vtkIdType i) const
  {
    if (!this->Logs)
    {
      return -1;
    }
    const double id = this->Objects->GetTuple1(i);
    return id >= 0.0 && id < (1 << 24) ? static_cast<int>(id) : -1;
  }
  // Without traced arrays: the objects the proxies stand for, sorted.
  std::vector<int> ProxyObjects;
  // A receiver whose object has no proxies: no self-shadow rules for it.
  bool OwnsNoSpheres(vtkIdType i) const
  {
    if (this->Logs || !this->Objects)
    {
      return false;
    }
    return NamesNoProxies(this->Objects->GetTuple1(i), this->ProxyObjects);
  }
};

// The bounce arrays (field data), checked once: every target a receiver.
bool ValidBounce(vtkPolyData* receivers, SelfVisibilityInput& self)
{
  vtkFieldData* fd = receivers->GetFieldData();
  auto* offsets = vtkIdTypeArray::SafeDownCast(fd->GetArray("SelfBounceOffsets"));
  auto* targets = vtkIdTypeArray::SafeDownCast(fd->GetArray("SelfBounceTargets"));
  auto* weights = vtkFloatArray::SafeDownCast(fd->GetArray("SelfBounceWeights"));
  const vtkIdType n = receivers->GetNumberOfPoints();
  if (!offsets || !targets || !weights || offsets->GetNumberOfTuples() != n + 1 ||
    targets->GetNumberOfTuples() != weights->GetNumberOfTuples() || offsets->GetValue(0) != 0 ||
    offsets->GetValue(n) != targets->GetNumberOfTuples())
  {
    return false;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (offsets->GetValue(i + 1) < offsets->GetValue(i))
    {
      return false;
    }
  }
  for (vtkIdType e = 0; e < targets->GetNumberOfTuples(); ++e)
  {
    const vtkIdType t = targets->GetValue(e);
    if (t < 0 || t >= n || !(weights->GetValue(e) >= 0.0f) || !std::isfinite(weights->GetValue(e)))
    {
      return false;
    }
  }
  self.Offsets = offsets;
  self.Targets = targets;
  self.Weights = weights;
  // Older traces have no hit points: their gather takes the corners' light.
  auto* points = vtkFloatArray::SafeDownCast(fd->GetArray("SelfBounceHitPoints"));
  self.HitPoints = points && points->GetNumberOfComponents() == 3 &&
      points->GetNumberOfTuples() == targets->GetNumberOfTuples()
    ? points
    : nullptr;
  if (self.HitPoints)
  {
    const float* values = points->GetPointer(0);
    self.HitPoints = std::all_of(values, values + points->GetNumberOfValues(),
                       [](float v) { return std::isfinite(v); })
      ? points
      : nullptr;
  }
  return true;
}

// The rotation R, the shift t = pc - R qc and the largest residual
// |R q + t - p| of the best rigid fit of the rest points q onto the points p
// (Kabsch, by SVD).
double RigidFit(vtkPolyData* receivers, vtkDataArray* rest, double R[9], double t[3])
{
  const vtkIdType n = receivers->GetNumberOfPoints();
  double pc[3] = { 0, 0, 0 }, qc[3] = { 0, 0, 0 };
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], q[3];
    receivers->GetPoint(i, p);
    rest->GetTuple(i, q);
    for (int c = 0; c < 3; ++c)
    {
      pc[c] += p[c] / n;
      qc[c] += q[c] / n;
    }
  }
  double H[3][3] = {};
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], q[3];
    receivers->GetPoint(i, p);
    rest->GetTuple(i, q);
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        H[a][b] += (q[a] - qc[a]) * (p[b] - pc[b]);
      }
    }
  }
  double U[3][3], w[3], VT[3][3];
  vtkMath::SingularValueDecomposition3x3(H, U, w, VT); // U, VT proper rotations
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      R[3 * i + j] = VT[0][i] * U[j][0] + VT[1][i] * U[j][1] + VT[2][i] * U[j][2];
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    t[a] = pc[a] - (R[3 * a] * qc[0] + R[3 * a + 1] * qc[1] + R[3 * a + 2] * qc[2]);
  }
  double residual = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], q[3], d2 = 0.0;
    receivers->GetPoint(i, p);
    rest->GetTuple(i, q);
    for (int a = 0; a < 3; ++a)
    {
      const double fitted = R[3 * a] * q[0] + R[3 * a + 1] * q[1] + R[3 * a + 2] * q[2] + t[a];
      d2 += (fitted - p[a]) * (fitted - p[a]);
    }
    residual = std::max(residual, std::sqrt(d2));
  }
  return std::isfinite(residual) ? residual : VTK_DOUBLE_MAX;
}

SelfVisibilityInput FindSelfVisibility(vtkPolyData* receivers, bool wanted, int accOrder)
{
  SelfVisibilityInput self;
  vtkPointData* pd = receivers->GetPointData();
  vtkDataArray* logs = pd->GetArray("SelfLogVisibility");
  if (!logs)
  {
    return self;
  }
  const int a2 = accOrder * accOrder;
  auto* floats = vtkFloatArray::SafeDownCast(logs);
  vtkDataArray* rest = pd->GetArray("SelfVisibilityRest");
  vtkDataArray* objects = pd->GetArray("ObjectId");
  const vtkIdType n = receivers->GetNumberOfPoints();
  std::ostringstream line;
  line << "self-visibility: ";
  if (!wanted)
  {
    line
      << "SelfVisibility off: the SelfLogVisibility array is not used; the self-shadow rules run";
  }
  else if (!floats || logs->GetNumberOfComponents() != a2 || logs->GetNumberOfTuples() != n)
  {
    line << "SelfLogVisibility has " << logs->GetNumberOfComponents()
         << " components (float: " << (floats ? "yes" : "no") << "), the accumulation order "
         << accOrder << " needs " << a2 << " floats: the self-shadow rules run";
  }
  else if (!objects || !rest || rest->GetNumberOfComponents() != 3)
  {
    line << "no ObjectId or SelfVisibilityRest array beside SelfLogVisibility: the self-shadow "
            "rules run";
  }
  else if (!ValidBounce(receivers, self))
  {
    line << "SelfBounceOffsets, SelfBounceTargets and SelfBounceWeights (field data) are missing "
            "or do not index these receivers: the self-shadow rules run";
  }
  else
  {
    // Moved or deformed since the trace: the stored visibility no longer holds.
    double bounds[6];
    receivers->GetBounds(bounds);
    const double diagonal = std::sqrt(vtkMath::Distance2BetweenPoints(
      std::array<double, 3>{ bounds[0], bounds[2], bounds[4] }.data(),
      std::array<double, 3>{ bounds[1], bounds[3], bounds[5] }.data()));
    const double tolerance = 1e-5 * std::max(diagonal, 1e-30);
    double moved = 0.0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3], q[3];
      receivers->GetPoint(i, p);
      rest->GetTuple(i, q);
      moved = std::max(moved, std::sqrt(vtkMath::Distance2BetweenPoints(p, q)));
    }
    double R[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    double shift[3] = { 0, 0, 0 };
    const double residual = moved <= tolerance ? 0.0 : RigidFit(receivers, rest, R, shift);
    if (!(residual <= tolerance))
    {
      line << "the receivers moved or deformed since their visibility was traced (up to " << moved
           << ", " << residual << " from the best rigid motion): the self-shadow rules run";
    }
    else
    {
      self.Logs = floats->GetPointer(0);
      std::copy_n(R, 9, self.Turn);
      std::copy_n(shift, 3, self.Shift);
      if (moved > tolerance)
      {
        // Moved rigidly: every log turns by R, one a2 x a2 matrix for all.
        std::vector<double> M(static_cast<std::size_t>(a2) * a2), e(a2), column(a2);
        for (int j = 0; j < a2; ++j)
        {
          std::fill(e.begin(), e.end(), 0.0);
          e[j] = 1.0;
          proxygi::sh::RotateSH(accOrder, R, e.data(), column.data());
          for (int i = 0; i < a2; ++i)
          {
            M[i * a2 + j] = column[i];
          }
        }
        self.Rotated.resize(static_cast<std::size_t>(a2) * n);
        const float* logs0 = self.Logs;
        float* out = self.Rotated.data();
        vtkSMPTools::For(0, n,
          [&](vtkIdType first, vtkIdType last)
          {
            for (vtkIdType v = first; v < last; ++v)
            {
              for (int i = 0; i < a2; ++i)
              {
                // Bands do not mix: only the row's own band is nonzero.
                const int l = proxygi::sh::BandOf(i);
                double sum = 0.0;
                for (int j = l * l; j < (l + 1) * (l + 1); ++j)
                {
                  sum += M[i * a2 + j] * logs0[a2 * v + j];
                }
                out[a2 * v + i] = static_cast<float>(sum);
              }
            }
          });
        self.Logs = self.Rotated.data();
        const double angle =
          std::acos(std::max(-1.0, std::min(1.0, 0.5 * (R[0] + R[4] + R[8] - 1.0))));
        line << "the receivers moved rigidly since the trace (turned "
             << vtkMath::DegreesFromRadians(angle) << " degrees): their logs turned with them; ";
      }
      self.Objects = objects;
      line << "precomputed (vtkPGISelfVisibility) on " << n
           << " receivers: their own object's shadows and bounce onto itself (IndirectSelf) "
              "from the traced mesh, their own proxies left out of both";
    }
  }
  self.Line = line.str();
  return self; // moved, so Logs still points into Rotated
}

// Gather entries lit by the bright lights where their hits lie carry at
// least this weight (four rays' of 256 at 60 degrees): the heavy ones are
// near hits, where a shadow finer than the triangles (a tail's on the rump)
// lies between a hit and the corners it was gathered from. The lighter ones
// barely count (the cow alone under sunrise 20.64% against 20.62% with
// every entry lit there, for 27 times the rays).
constexpr float MinHitWeight = 1.0f / 64.0f;

// Where gather entry e hits the receivers now.
void HitPointNow(const SelfVisibilityInput& self, vtkIdType e, float h[3])
{
  const float* hit = self.HitPoints->GetPointer(3 * e);
  for (int c = 0; c < 3; ++c)
  {
    h[c] = static_cast<float>(self.Turn[3 * c] * hit[0] + self.Turn[3 * c + 1] * hit[1] +
      self.Turn[3 * c + 2] * hit[2] + self.Shift[c]);
  }
}

} // namespace

struct vtkPGIGlobalIllumination::ShadeBuffers
{
  vtkSMPThreadLocal<ShadeScratch> PerThread;
  std::vector<proxygi::PlaneLightMap> PlaneMaps; // one per blocker plane
  // What PlaneMaps were built from: the bake's build, the occluder and its
  // MTime, the effective settings' MTime. A new receiver mesh alone (the
  // next object of a scene) reuses them.
  struct MapKey
  {
    int Builds = -1;
    const vtkObject* Occluder = nullptr;
    vtkMTimeType OccluderTime = 0, SettingsTime = 0;
    bool operator==(const MapKey& o) const
    {
      return Builds == o.Builds && Occluder == o.Occluder && OccluderTime == o.OccluderTime &&
        SettingsTime == o.SettingsTime;
    }
  } PlaneMapsKey;
  std::string PlaneMapsLine;
};

// Receiver clusters and their hierarchy cuts (one blocker list each), and
// the clustering they came from.
struct vtkPGIGlobalIllumination::Clusters
{
  std::vector<int> Of;
  std::vector<proxygi::Blockers> Blockers;
  std::vector<proxygi::SphericalLights> Lights;
  ClusterFrames Frames;
  ClusterKey Key;
};

vtkPGIGlobalIllumination::vtkPGIGlobalIllumination()
  : Scratch(new ShadeBuffers)
  , Budget(new proxygi::budget::Planner)
{
  this->SetNumberOfInputPorts(2);
  this->Settings = vtkPGIGISettings::New();
  this->Bake->SetSettings(this->Effective);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPGIGlobalIllumination::~vtkPGIGlobalIllumination()
{
  this->SetLighting(nullptr);
  this->SetOccluder(nullptr);
  this->SetLocalLightTransfer(nullptr);
  this->SetController(nullptr);
  this->SetBudgetModelFileName(nullptr);
  this->Settings->UnRegister(this);
}

void vtkPGIGlobalIllumination::SetSettings(vtkPGIGISettings* settings)
{
  if (vtkPGIGISettings::Share(this, this->Settings, settings))
  {
    this->Modified();
  }
}

const vtkPGIGISettings::Support& vtkPGIGlobalIllumination::GetSupport()
{
  static const vtkPGIGISettings::Support support = []
  {
    vtkPGIGISettings::Support s;
    s.Backend = "CPU filter";
    return s;
  }();
  return support;
}

vtkMTimeType vtkPGIGlobalIllumination::GetMTime()
{
  vtkMTimeType t = std::max(this->Superclass::GetMTime(), this->Settings->GetMTime());
  if (this->Lighting)
  {
    t = std::max(t, this->Lighting->GetMTime());
  }
  if (this->Occluder)
  {
    t = std::max(t, this->Occluder->GetMTime());
  }
  if (this->LocalLightTransfer)
  {
    t = std::max(t, this->LocalLightTransfer->GetMTime());
  }
  return std::max(t, this->Bake->vtkObject::GetMTime());
}

void vtkPGIGlobalIllumination::AddBlockerPlane(const double origin[3], const double normal[3])
{
  const double black[3] = { 0, 0, 0 };
  this->AddBlockerPlane(origin, normal, black);
}

void vtkPGIGlobalIllumination::AddBlockerPlane(
  const double origin[3], const double normal[3], const double albedo[3])
{
  this->Bake->AddBlockerPlane(origin, normal, albedo);
  this->Modified();
}

void vtkPGIGlobalIllumination::AddBlockerPlane(const double origin[3], const double normal[3],
  const double albedo[3], const double halfEdge1[3], const double halfEdge2[3])
{
  const double halfEdges[6] = { halfEdge1[0], halfEdge1[1], halfEdge1[2], halfEdge2[0],
    halfEdge2[1], halfEdge2[2] };
  this->Bake->AddBlockerPlane(origin, normal, albedo, halfEdges);
  this->Modified();
}

void vtkPGIGlobalIllumination::AddBlockerPlane(
  double ox, double oy, double oz, double nx, double ny, double nz, double ar, double ag, double ab)
{
  const double origin[3] = { ox, oy, oz }, normal[3] = { nx, ny, nz }, albedo[3] = { ar, ag, ab };
  this->AddBlockerPlane(origin, normal, albedo);
}

void vtkPGIGlobalIllumination::RemoveAllBlockerPlanes()
{
  this->Bake->RemoveAllBlockerPlanes();
  this->Modified();
}

void vtkPGIGlobalIllumination::AddTransferredLight(
  vtkPolyData* receivers, vtkFloatArray* cloud, vtkFloatArray* total)
{
  cloud->FillValue(0.0f);
  const std::vector<vtkPGILighting::PointLight> none;
  const auto& points = this->Lighting ? this->Lighting->GetPointLights() : none;
  if (!this->Effective->GetLightCloud())
  {
    this->Plan.push_back("light cloud: off (switched off)");
    return;
  }
  if (points.empty())
  {
    this->Plan.push_back(this->LocalLightTransfer
        ? "light cloud: skipped (no point lights in the lighting)"
        : "light cloud: skipped (no point lights, no cloud)");
    return;
  }
  if (!this->LocalLightTransfer)
  {
    this->Plan.push_back("light cloud: skipped (no cloud given: the " +
      std::to_string(points.size()) + " point lights' indirect light is not drawn)");
    return;
  }
  if (this->LocalLightTransfer->CarriesDirectLight())
  {
    vtkWarningMacro(<< "The light cloud carries direct light too, which LocalLights already "
                       "draws with soft shadows: precompute it with IncludeDirect off.");
    this->Plan.push_back("light cloud: skipped (it carries direct light too, which the local "
                         "lights' soft shadows draw; precompute it with IncludeDirect off)");
    return;
  }
  std::string why;
  std::vector<std::string> lines;
  if (!this->LocalLightTransfer->AddLight(receivers, points, cloud->GetPointer(0), lines, why))
  {
    vtkErrorMacro(<< "The light cloud cannot light these receivers: " << why);
    cloud->FillValue(0.0f);
    this->Plan.push_back("light cloud: failed (" + why + ")");
    return;
  }
  float* all = total->GetPointer(0);
  const float* add = cloud->GetPointer(0);
  for (vtkIdType k = 0; k < cloud->GetNumberOfValues(); ++k)
  {
    all[k] += add[k];
  }
  for (const std::string& line : lines)
  {
    this->Plan.push_back(line);
  }
}

void vtkPGIGlobalIllumination::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "Occluder: " << this->Occluder << "\n";
  os << indent << "LocalLightTransfer: " << this->LocalLightTransfer << "\n";
  os << indent << "Settings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
  os << indent << "BlockerPlanes: " << this->Bake->GetNumberOfBlockerPlanes() << "\n";
  os << indent << "Bake builds: " << this->Bake->GetNumberOfBuilds() << "\n";
  os << indent << "ColorExposure: " << this->ColorExposure << "\n";
  os << indent << "ErrorBudget: " << this->ErrorBudget << "\n";
  os << indent << "TimeBudget: " << this->TimeBudget << "\n";
  os << indent << "BudgetModelFileName: "
     << (this->BudgetModelFileName ? this->BudgetModelFileName : "(the model that ships)") << "\n";
  os << indent << "Controller: " << this->Controller << " ("
     << proxygi::parallel::Ranks(this->Controller) << " ranks)\n";
}

int vtkPGIGlobalIllumination::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

std::string vtkPGIGlobalIllumination::CheckReceivers(vtkPolyData* receivers)
{
  if (!receivers || receivers->GetNumberOfPoints() == 0)
  {
    return "No receivers: input 0 is empty.";
  }
  const Tuples3 points(receivers->GetPoints()->GetData());
  for (vtkIdType i = 0; i < receivers->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points.Get(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      return "Receiver " + std::to_string(i) + " has a NaN or Inf coordinate.";
    }
  }
  return std::string();
}

std::string vtkPGIGlobalIllumination::ApplyBudget(vtkPolyData* proxies, vtkPolyData* receivers)
{
  namespace budget = proxygi::budget;
  // The frame is every rank's receivers: all ranks choose alike.
  const double points = proxygi::parallel::Sum(proxygi::parallel::Active(this->Controller),
    receivers ? static_cast<double>(receivers->GetNumberOfPoints()) : 0.0);
  const bool traced = this->Effective->GetSelfVisibility() && receivers &&
    receivers->GetPointData()->GetArray("SelfLogVisibility");
  const auto b = budget::Budget::FromSetters(this->ErrorBudget, this->TimeBudget);
  budget::Choice choice;
  std::string error;
  // Orders 2..8 (Model::Read checks), all within this filter's support.
  if (!this->Budget->Plan(this->BudgetModelFileName ? this->BudgetModelFileName : "",
        budget::Route::Filter, proxies, points, traced, this->Lighting, b, this->Effective, choice,
        this->BudgetPlan, error))
  {
    return error + ".";
  }
  if (!choice.Valid)
  {
    vtkWarningMacro(<< "Budget: " << choice.Reason << ".");
  }
  return std::string();
}

std::string vtkPGIGlobalIllumination::PrepareBake(vtkPolyData* proxies, vtkPolyData* receivers)
{
  std::vector<std::string> notes;
  this->Settings->Resolve(
    GetSupport(), this->Bake->GetNumberOfBlockerPlanes(), this->Effective, notes);
  this->BudgetPlan.clear();
  if (this->ErrorBudget != 0.0 || this->TimeBudget != 0.0)
  {
    std::string error = this->ApplyBudget(proxies, receivers);
    if (!error.empty())
    {
      return error;
    }
  }
  this->Bake->SetProxies(proxies);
  this->Bake->SetLighting(this->Lighting);
  if (!this->Bake->Update())
  {
    const std::string& proxyError = this->Bake->GetProxyError();
    if (!proxyError.empty())
    {
      std::string m = proxyError;
      m[0] = static_cast<char>(std::toupper(m[0]));
      return m + " (the proxies, input 1).";
    }
    return this->Bake->GetError();
  }
  this->Plan = this->Bake->GetScene().Plan;
  if (!this->BudgetPlan.empty())
  {
    this->Plan.insert(this->Plan.begin(), this->BudgetPlan);
  }
  if (this->Effective->GetHierarchyAngle() > 0.0 && !this->Bake->GetScene().UseHierarchy)
  {
    this->Plan.push_back("hierarchy: not used (the proxies have no Level/Parent arrays)");
  }
  return std::string();
}

namespace
{
// What each receiver cluster's hierarchy cut is made from: bounding sphere
// (centre, radius; negative: an empty cluster, no cut) and the receiver
// position and normal the cut's ratios are fitted at.
// Under MPI the clusters must not depend on the partition, or a point
// on a partition boundary would get another cut, hence a seam, on each
// rank: cells of a grid over all ranks' receivers (the cell size a
// power-of-two fraction of the global diagonal, so near-equal receiver
// counts give the same grid), split by the normal's dominant axis; the
// cut is taken from the cell's sphere, its centre and that axis.
// Collective.
ClusterFrames GridClusters(vtkMultiProcessController* controller, vtkPolyData* receivers,
  const std::vector<double>& points, vtkIdType n, vtkDataArray* normals, int perCluster)
{
  ClusterFrames f;
  double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX },
         hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], points[3 * i + c]);
      hi[c] = std::max(hi[c], points[3 * i + c]);
    }
  }
  proxygi::parallel::GlobalBox(controller, lo, hi);
  double totals[2] = { static_cast<double>(n), 0.0 };
  vtkCellArray* polys = receivers ? receivers->GetPolys() : nullptr;
  if (polys && n > 0)
  {
    // Surface area: with ~perCluster receivers per cell, cells are about
    // sqrt(area * perCluster / receivers) wide on a surface.
    vtkUnsignedCharArray* ghosts = receivers->GetCellGhostArray();
    const vtkIdType verts = receivers->GetNumberOfVerts() + receivers->GetNumberOfLines();
    vtkIdType cellId = verts, count = 0;
    const vtkIdType* ids = nullptr;
    for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cellId)
    {
      if (ghosts && ghosts->GetValue(cellId) != 0)
      {
        continue;
      }
      for (vtkIdType k = 2; k < count; ++k)
      {
        const double* a = &points[3 * ids[0]];
        const double* p1 = &points[3 * ids[k - 1]];
        const double* p2 = &points[3 * ids[k]];
        const double u[3] = { p1[0] - a[0], p1[1] - a[1], p1[2] - a[2] };
        const double v[3] = { p2[0] - a[0], p2[1] - a[1], p2[2] - a[2] };
        double w[3];
        vtkMath::Cross(u, v, w);
        totals[1] += 0.5 * vtkMath::Norm(w);
      }
    }
  }
  proxygi::parallel::SumEach(controller, totals, 2);
  const double diagonal = std::sqrt(vtkMath::Distance2BetweenPoints(lo, hi));
  if (n == 0 || !(diagonal > 0.0) || !std::isfinite(diagonal))
  {
    return f;
  }
  double size = totals[1] > 0.0 ? std::sqrt(totals[1] * perCluster / totals[0])
                                : diagonal * std::cbrt(perCluster / totals[0]);
  size = diagonal * std::exp2(std::round(std::log2(std::min(1.0, size / diagonal))));
  const Tuples3 normalTuples(normals);
  std::map<std::array<long long, 4>, int> cellOf;
  f.Of.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double nd[3];
    UnitNormal(normalTuples, i, nd);
    int axis = 0;
    for (int c = 1; c < 3; ++c)
    {
      axis = std::abs(nd[c]) > std::abs(nd[axis]) ? c : axis;
    }
    std::array<long long, 4> key;
    for (int c = 0; c < 3; ++c)
    {
      key[c] = static_cast<long long>(std::floor((points[3 * i + c] - lo[c]) / size));
    }
    key[3] = 2 * axis + (nd[axis] < 0.0 ? 1 : 0);
    auto inserted = cellOf.emplace(key, static_cast<int>(f.Centres.size()));
    if (inserted.second)
    {
      std::array<double, 3> centre, axisNormal = { 0.0, 0.0, 0.0 };
      for (int c = 0; c < 3; ++c)
      {
        centre[c] = lo[c] + (static_cast<double>(key[c]) + 0.5) * size;
      }
      axisNormal[axis] = key[3] % 2 ? -1.0 : 1.0;
      f.Centres.push_back(centre);
      f.At.push_back(centre);
      f.Facing.push_back(axisNormal);
      f.Radius.push_back(0.5 * std::sqrt(3.0) * size);
    }
    f.Of[i] = inserted.first->second;
  }
  std::ostringstream line;
  line << "grid cells of " << size << " by normal axis, the same on every rank";
  f.How = line.str();
  return f;
}

// Serially: Lloyd clusters of the receivers, each cut from its bounding
// sphere and the receiver nearest its centre.
ClusterFrames LloydFrames(
  const std::vector<double>& points, vtkIdType n, vtkDataArray* normals, int perCluster)
{
  ClusterFrames f;
  if (n == 0)
  {
    return f;
  }
  const int clusters = static_cast<int>(std::max<vtkIdType>(1, (n + perCluster - 1) / perCluster));
  // Seeds evenly along the point order, then Lloyd (the sphere tree's).
  f.Centres.resize(clusters);
  for (int k = 0; k < clusters; ++k)
  {
    std::copy_n(&points[3 * (n * k / clusters)], 3, f.Centres[k].data());
  }
  f.Of = proxygi::LloydClusters(points.data(), n, f.Centres, 4);
  // Per cluster: bounding sphere and the receiver nearest its centre.
  f.Radius.assign(clusters, 0.0);
  std::vector<vtkIdType> central(clusters, -1);
  std::vector<double> centralDistance(clusters, VTK_DOUBLE_MAX);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int k = f.Of[i];
    const double d2 = vtkMath::Distance2BetweenPoints(&points[3 * i], f.Centres[k].data());
    f.Radius[k] = std::max(f.Radius[k], std::sqrt(d2));
    if (d2 < centralDistance[k])
    {
      centralDistance[k] = d2;
      central[k] = i;
    }
  }
  const Tuples3 normalTuples(normals);
  f.At.resize(clusters);
  f.Facing.resize(clusters);
  for (int k = 0; k < clusters; ++k)
  {
    if (central[k] < 0)
    {
      f.Radius[k] = -1.0; // empty: no cut
      continue;
    }
    std::copy_n(&points[3 * central[k]], 3, f.At[k].data());
    UnitNormal(normalTuples, central[k], f.Facing[k].data());
  }
  f.How = "Lloyd clusters of this piece";
  return f;
}
} // namespace

bool vtkPGIGlobalIllumination::ClusterReceivers(vtkPolyData* receivers, vtkDataArray* normals)
{
  Clusters& cl = *this->ReceiverClusters;
  cl.Of.clear();
  cl.Blockers.clear();
  cl.Lights.clear();
  const proxygi::BakedScene& b = this->Bake->GetScene();
  if (!b.NeedVisibility || !b.UseHierarchy)
  {
    return true;
  }
  vtkMultiProcessController* controller = proxygi::parallel::Active(this->Controller);
  const vtkIdType n = receivers ? receivers->GetNumberOfPoints() : 0;
  const int perCluster = this->Effective->GetReceiversPerCluster();
  // Clusters depend on the receivers only: when just the proxies or the
  // light changed, the last ones stand and only the cuts are taken again.
  ClusterKey key;
  key.Receivers = receivers;
  key.Time = receivers ? std::max(receivers->GetMTime(), normals ? normals->GetMTime() : 0) : 0;
  key.Count = n;
  key.PerCluster = perCluster;
  key.Distributed = controller != nullptr;
  const bool reuse = !controller && key == cl.Key; // collective under MPI: always
  if (!reuse)
  {
    std::vector<double> points(3 * static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      receivers->GetPoint(i, &points[3 * i]);
    }
    cl.Frames = controller ? GridClusters(controller, receivers, points, n, normals, perCluster)
                           : LloydFrames(points, n, normals, perCluster);
    cl.Key = key;
  }
  const ClusterFrames& f = cl.Frames;
  if (f.Centres.empty())
  {
    return true;
  }
  cl.Of = f.Of;
  const int clusters = static_cast<int>(f.Centres.size());
  const proxygi::ShadowedIndirect shadowedIndirect(b.IndirectKernel,
    this->Effective->GetSphericalLightBlocking() == vtkPGIGISettings::BLOCKING_PER_OBJECT
      ? proxygi::SphericalLightBlocking::PerObject
      : proxygi::SphericalLightBlocking::PerSphere);
  cl.Blockers.resize(clusters);
  if (b.RunShadowed)
  {
    cl.Lights.resize(clusters);
  }
  const double angle = this->Effective->GetHierarchyAngle();
  const float maxAngle = static_cast<float>(vtkMath::RadiansFromDegrees(angle));
  // Clusters whose receivers own no spheres (a ground): their cut is scaled
  // to block what the leaves' union blocks (ScaleCutToUnion).
  std::vector<char> ownsNone(clusters, 0);
  vtkDataArray* receiverIds = receivers->GetPointData()->GetArray("ObjectId");
  const proxygi::Blockers& leaves = b.SceneBlockers;
  if (receiverIds && leaves.Object.size() == leaves.Spheres())
  {
    const std::vector<int> objects = ProxyObjectsOf(leaves);
    std::vector<double> first(clusters, std::numeric_limits<double>::quiet_NaN());
    std::vector<char> mixed(clusters, 0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      const int k = f.Of[i];
      const double id = receiverIds->GetTuple1(i);
      if (k < 0)
      {
        continue;
      }
      if (std::isnan(first[k]))
      {
        first[k] = id;
      }
      mixed[k] = mixed[k] || id != first[k];
    }
    for (int k = 0; k < clusters; ++k)
    {
      ownsNone[k] = !mixed[k] && NamesNoProxies(first[k], objects);
    }
  }
  const proxygi::SoftShadows kernel(b.Kernel);
  std::vector<float> scales(clusters, 0.0f);
  // The clusters' cuts are independent: one thread each.
  const bool rules = this->Effective->GetSelfShadowRules();
  vtkSMPTools::For(0, clusters,
    [&](int begin, int end)
    {
      std::vector<int> nodes;
      for (int k = begin; k < end; ++k)
      {
        if (f.Radius[k] < 0.0)
        {
          continue;
        }
        const float pR[3] = { float(f.Centres[k][0]), float(f.Centres[k][1]),
          float(f.Centres[k][2]) };
        const float pf[3] = { float(f.At[k][0]), float(f.At[k][1]), float(f.At[k][2]) };
        const float nf[3] = { float(f.Facing[k][0]), float(f.Facing[k][1]), float(f.Facing[k][2]) };
        cl.Blockers[k] = proxygi::CutHierarchy(b.Hierarchy, pR, float(f.Radius[k]), pf, nf,
          maxAngle, b.Order, rules, b.RunShadowed ? &nodes : nullptr);
        if (ownsNone[k])
        {
          scales[k] = proxygi::ScaleCutToUnion(cl.Blockers[k], leaves, kernel, pf, nf);
        }
        if (b.RunShadowed)
        {
          CutSphericalLights(b.Lights, b.LeafLights, b.LeafOfNode, b.Hierarchy, nodes,
            b.SceneBlockers, shadowedIndirect, pf, nf, cl.Lights[k]);
        }
        cl.Blockers[k].PlaneOrigin = b.SceneBlockers.PlaneOrigin;
        cl.Blockers[k].PlaneNormal = b.SceneBlockers.PlaneNormal;
        cl.Blockers[k].PlaneAlbedo = b.SceneBlockers.PlaneAlbedo;
      }
    });
  std::size_t cutTotal = 0;
  int used = 0, scaled = 0;
  double scaleSum = 0.0;
  for (int k = 0; k < clusters; ++k)
  {
    if (f.Radius[k] >= 0.0)
    {
      cutTotal += cl.Blockers[k].Spheres();
      ++used;
    }
    if (scales[k] > 0.0f && scales[k] < 1.0f)
    {
      ++scaled;
      scaleSum += scales[k];
    }
  }
  std::ostringstream line;
  line << "hierarchy: " << used << " receiver clusters, cuts of "
       << (used ? static_cast<double>(cutTotal) / used : 0.0) << " spheres on average (of "
       << b.SceneBlockers.Spheres() << " leaves) at " << angle
       << " degrees, each node blocking its leaves' union (" << f.How
       << (reuse ? ", reused: the receivers did not change" : "") << ")"
       << (b.RunShadowed ? "; spherical lights cut alike, with reflection ratios" : "");
  if (scaled > 0)
  {
    line << "; " << scaled << " clusters of receivers without proxies scaled to their blockers' "
         << "union (logs x " << scaleSum / scaled << " on average)";
  }
  this->Plan.push_back(line.str());
  return true;
}

void vtkPGIGlobalIllumination::ShadeReceivers(
  vtkPolyData* receivers, vtkDataArray* normals, vtkPolyData* output)
{
  const proxygi::BakedScene& b = this->Bake->GetScene();
  const Clusters& cl = *this->ReceiverClusters;
  vtkPGIGISettings* settings = this->Effective;
  const vtkIdType n = receivers->GetNumberOfPoints();
  const int order = b.Order, n2 = order * order;
  const proxygi::Blockers& blockers = b.SceneBlockers;
  const proxygi::EnvironmentShading& shading = *b.Shading;
  const proxygi::EnvironmentShading& openShading = *b.OpenShading;
  const proxygi::SecondaryLights& secondary = *b.Secondary;
  const bool planesInLight = b.PlanesInLight;
  const bool runShadows = b.RunShadows, runIndirect = b.RunIndirect,
             runPlaneBounce = b.RunPlaneBounce, runShadowed = b.RunShadowed,
             needVisibility = b.NeedVisibility;
  const proxygi::sh::AnalyticLightTables* lightTables =
    b.RunLocal ? &proxygi::sh::AnalyticLightTables::Get(order) : nullptr;
  const auto indirectOperator =
    static_cast<proxygi::IndirectOperator>(settings->GetIndirectOperator());
  const bool planeBounceShadows = settings->GetPlaneBounceShadows();
  const bool shadowsOn = settings->GetShadows();
  const char* albedoArray = settings->GetAlbedoArrayName();
  const proxygi::AlbedoReader albedoOf(receivers, albedoArray, settings->GetDefaultAlbedo());
  const proxygi::ShadowedIndirect shadowedIndirect(b.IndirectKernel,
    settings->GetSphericalLightBlocking() == vtkPGIGISettings::BLOCKING_PER_OBJECT
      ? proxygi::SphericalLightBlocking::PerObject
      : proxygi::SphericalLightBlocking::PerSphere);
  const proxygi::SphericalLights& shadowedLeaves = b.ShadowedLeaves();
  const proxygi::SoftShadows shadows(b.Kernel);
  proxygi::BrightLightSet bright;
  const bool brightRays = b.RunBrightLights && shadowsOn && this->Occluder;
  const float rayOffset =
    brightRays ? static_cast<float>(1e-5 * this->Occluder->GetSceneSize()) : 0.0f;
  if (b.RunBrightLights)
  {
    bright.Set(b.BrightLights, settings->GetBrightLightRays());
  }
  std::atomic<long long> brightNs(0);
  // The planes' unshadowed light from the residual, and the directions the
  // receivers look at them along.
  std::vector<float> planeResidual(3 * blockers.Planes()), planeHemisphere(3 * 16);
  for (std::size_t k = 0; k < blockers.Planes(); ++k)
  {
    openShading.ShadeUnshadowed(&blockers.PlaneNormal[3 * k], &planeResidual[3 * k]);
  }
  proxygi::CosineHemisphere(16, planeHemisphere.data());
  // Receivers on or below a plane keep the planes in log space (they see
  // under the ones they are below, and skip those).
  proxygi::SoftShadowSettings logSettings = b.Kernel;
  logSettings.PlanesInLogSpace = true;
  const proxygi::SoftShadows shadowsLog(logSettings);
  const int a2 = shadows.GetAccumulationOrder() * shadows.GetAccumulationOrder();
  SelfVisibilityInput self = needVisibility
    ? FindSelfVisibility(receivers, settings->GetSelfVisibility(), shadows.GetAccumulationOrder())
    : SelfVisibilityInput();
  // The bright lights' share of each receiver's light, for the own bounce
  // to light its heavy hits where they lie instead.
  std::vector<float> brightOf(
    self.Logs && self.HitPoints && brightRays && settings->GetIndirect() && !b.Dark
      ? 3 * static_cast<std::size_t>(n)
      : 0);
  proxygi::BrightLightSet brightAtHits; // fewer rays: a receiver averages many hits
  if (!brightOf.empty())
  {
    brightAtHits.Set(b.BrightLights, std::max(1, settings->GetBrightLightRays() / 16));
  }
  // Without traced arrays, receivers that name an object with no proxies
  // (a ground plane) own no spheres: the rules do not run for them. In the
  // batch keys their object slot holds noSpheres (own objects: id + 1).
  constexpr long long noSpheres = (1LL << 24) + 1;
  const std::vector<int>& sphereObjects = b.SceneBlockers.Object;
  vtkDataArray* receiverObjects = receivers->GetPointData()->GetArray("ObjectId");
  if (!self.Logs && receiverObjects && sphereObjects.size() == b.SceneBlockers.Spheres())
  {
    self.Objects = receiverObjects;
    self.ProxyObjects = ProxyObjectsOf(b.SceneBlockers);
  }
  if (!self.Line.empty())
  {
    this->Plan.push_back(self.Line);
  }

  // Last update's arrays when nobody else holds them: a repeated update
  // (proxies moving) allocates, and faults in, no new memory.
  const auto reuse = [n](vtkSmartPointer<vtkFloatArray>& slot, const char* name, int components)
  {
    if (!slot || slot->GetReferenceCount() > 1)
    {
      slot = vtkSmartPointer<vtkFloatArray>::New();
    }
    slot->SetName(name);
    slot->SetNumberOfComponents(components);
    slot->SetNumberOfTuples(n);
    return slot.Get();
  };
  vtkFloatArray* direct = reuse(this->OutputArrays[0], "DirectShadowed", 3);
  vtkFloatArray* indirect = reuse(this->OutputArrays[1], "IndirectProxy", 3);
  vtkFloatArray* indirectShadowed = reuse(this->OutputArrays[2], "IndirectShadowed", 3);
  vtkFloatArray* local = reuse(this->OutputArrays[3], "LocalLights", 3);
  vtkFloatArray* total = reuse(this->OutputArrays[4], "Radiance", 3);
  vtkFloatArray* visibility = reuse(this->OutputArrays[5], "Visibility", n2);
  vtkFloatArray* indirectSelf = reuse(this->OutputArrays[6], "IndirectSelf", 3);

  // The planes' shadowed light on grids, once per update, which each
  // receiver then averages over its view of the plane (pgiPlaneLightMap.h);
  // PlaneBounceDirections 0: one plane point per receiver below.
  const int planes = static_cast<int>(blockers.Planes());
  const bool scalePlanes =
    (runIndirect || runPlaneBounce) && planeBounceShadows && planes > 0 && planes <= 8;
  const int planeDirections = settings->GetPlaneBounceDirections();
  const bool planeMaps = scalePlanes && needVisibility && planeDirections > 0;
  std::vector<proxygi::PlaneLightMap>& maps = this->Scratch->PlaneMaps;
  ShadeBuffers::MapKey mapKey;
  mapKey.Builds = this->Bake->GetNumberOfBuilds();
  mapKey.Occluder = this->Occluder;
  mapKey.OccluderTime = this->Occluder ? this->Occluder->GetMTime() : 0;
  mapKey.SettingsTime = settings->GetMTime();
  if (planeMaps && mapKey == this->Scratch->PlaneMapsKey)
  {
    this->Plan.push_back(this->Scratch->PlaneMapsLine +
      ", reused: same proxies, light, occluder and settings as the last update");
  }
  else if (planeMaps)
  {
    const auto start = std::chrono::steady_clock::now();
    proxygi::PlaneLightMapShading how;
    how.Shadows = &shadows;
    how.Bright = b.RunBrightLights ? &bright : nullptr;
    how.Occluder = brightRays ? this->Occluder : nullptr;
    how.RayOffset = rayOffset;
    how.MinAngle = static_cast<float>(settings->GetMinBlockerAngle());
    how.ShadowsOn = shadowsOn;
    const int points = proxygi::BuildPlaneLightMaps(b, how, planeDirections, maps);
    std::ostringstream line;
    line << "planes' bounce: the shadowed light of " << planes << " plane(s) on " << points
         << " grid points" << (how.Bright ? " (bright lights included)" : "") << ", averaged over "
         << planeDirections << " directions per receiver"
         << (std::any_of(maps.begin(), maps.end(),
               [](const proxygi::PlaneLightMap& m) { return m.GetBounded(); })
                ? ", the sky past bounded planes' edges over " +
                  std::to_string(proxygi::PlaneLightMap::SkyBins) + " azimuths"
                : std::string())
         << " ("
         << 1e-6 *
        static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(
          std::chrono::steady_clock::now() - start)
                              .count())
         << " ms)";
    this->Plan.push_back(line.str());
    this->Scratch->PlaneMapsKey = mapKey;
    this->Scratch->PlaneMapsLine = line.str();
  }
  else if (scalePlanes && needVisibility)
  {
    this->Plan.push_back("planes' bounce: the shadowed light at one plane point per receiver "
                         "(PlaneBounceDirections 0)");
  }

  std::atomic<vtkIdType> shadowed(0), failures(0), shadowedFailures(0);
  std::atomic<long long> secondPassNs(0), visibilityNs(0);
  // Progress and abort between blocks; a block of at least 4096 receivers
  // keeps the fork-join of each block small beside its work.
  const Tuples3 pointTuples(receivers->GetPoints()->GetData()), normalTuples(normals);
  const vtkIdType blocks = std::max<vtkIdType>(1, std::min<vtkIdType>(50, n / 4096));
  for (vtkIdType block = 0; block < blocks && !this->GetAbortExecute(); ++block)
  {
    vtkSMPTools::For(n * block / blocks, n * (block + 1) / blocks,
      [&](vtkIdType first, vtkIdType last)
      {
        float g[proxygi::sh::MaxCoefficients], unshadowed[proxygi::sh::MaxCoefficients];
        proxygi::sh::SetConstant(order, 1.0f, unshadowed);
        // This thread's buffers, kept from range to range and update to update.
        ShadeScratch& buffers = this->Scratch->PerThread.Local();
        proxygi::SphericalLightScratch& scratch = buffers.Lights;
        vtkIdType localShadowed = 0, localFailures = 0, localShadowedFailures = 0;
        long long localSecondPassNs = 0, localBrightNs = 0;
        // The visibility of the whole range first, in batches of receivers
        // that share their blockers (cluster) and kernel (planes in the light
        // or in log space), so the batched kernels run full lanes.
        const vtkIdType count = last - first;
        std::vector<float>&points = buffers.Points, &facing = buffers.Facing,
        &batchPoints = buffers.BatchPoints, &batchFacing = buffers.BatchFacing,
        &visibilities = buffers.Visibilities, &batchVisibilities = buffers.BatchVisibilities,
        &planeScales = buffers.PlaneScales, &planeGaps = buffers.PlaneGaps;
        std::vector<proxygi::sh::Status>&statuses = buffers.Statuses,
        &batchStatuses = buffers.BatchStatuses;
        std::vector<int>&used = buffers.Used, &batchUsed = buffers.BatchUsed;
        std::vector<vtkIdType>&byBlockers = buffers.ByBlockers, &who = buffers.Who;
        std::vector<long long>& key = buffers.Key;
        points.resize(3 * count);
        facing.resize(3 * count);
        statuses.resize(count);
        used.resize(count);
        byBlockers.resize(count);
        key.resize(count);
        // The blockers each receiver sees, for the indirect light.
        const bool wantSeen = runIndirect || runPlaneBounce;
        std::vector<std::vector<proxygi::SeenBlocker>>&seens = buffers.Seen,
        &batchSeens = buffers.BatchSeen;
        seens.resize(count);
        batchSeens.resize(count);
        for (vtkIdType j = 0; j < count; ++j)
        {
          double pd[3], nd[3];
          pointTuples.Get(first + j, pd);
          UnitNormal(normalTuples, first + j, nd);
          for (int c = 0; c < 3; ++c)
          {
            points[3 * j + c] = static_cast<float>(pd[c]);
            facing[3 * j + c] = static_cast<float>(nd[c]);
          }
          const bool carries = planesInLight && blockers.AboveEveryPlane(&points[3 * j]);
          // Batches share the cluster, the receivers' own object (or that
          // they own no spheres) and the kernel.
          const long long object =
            self.OwnsNoSpheres(first + j) ? noSpheres : self.OwnObject(first + j) + 1;
          key[j] = 2 *
              ((cl.Of.empty() ? 0LL : static_cast<long long>(cl.Of[first + j])) * (1LL << 25) +
                object) +
            (carries ? 1 : 0);
          byBlockers[j] = j;
          seens[j].clear();
        }
        const auto visibilityStart = std::chrono::steady_clock::now();
        if (needVisibility)
        {
          std::stable_sort(byBlockers.begin(), byBlockers.end(),
            [&](vtkIdType a, vtkIdType b) { return key[a] < key[b]; });
          visibilities.resize(n2 * count);
          batchPoints.resize(3 * count);
          batchFacing.resize(3 * count);
          batchVisibilities.resize(n2 * count);
          batchUsed.resize(count);
          batchStatuses.resize(count);
          for (vtkIdType j = 0; j < count; ++j)
          {
            std::copy_n(&points[3 * byBlockers[j]], 3, &batchPoints[3 * j]);
            std::copy_n(&facing[3 * byBlockers[j]], 3, &batchFacing[3 * j]);
          }
          std::vector<float>& batchSelfLogs = buffers.BatchSelfLogs;
          if (self.Logs)
          {
            batchSelfLogs.resize(static_cast<std::size_t>(a2) * count);
            for (vtkIdType j = 0; j < count; ++j)
            {
              std::copy_n(&self.Logs[a2 * (first + byBlockers[j])], a2, &batchSelfLogs[a2 * j]);
            }
          }
          for (vtkIdType start = 0; start < count;)
          {
            vtkIdType end = start + 1;
            while (end < count && key[byBlockers[end]] == key[byBlockers[start]])
            {
              ++end;
            }
            const vtkIdType i = first + byBlockers[start];
            const proxygi::Blockers& mine = cl.Of.empty() ? blockers : cl.Blockers[cl.Of[i]];
            const proxygi::SoftShadows& kernel = key[byBlockers[start]] % 2 ? shadows : shadowsLog;
            proxygi::SelfVisibility own;
            const long long object = (key[byBlockers[start]] / 2) % (1LL << 25);
            if (object == noSpheres)
            {
              own.OwnsNoSpheres = true;
            }
            else if (object > 0)
            {
              own.Object = static_cast<int>(object - 1);
              own.Log = &batchSelfLogs[a2 * start];
            }
            kernel.VisibilityBatch(static_cast<int>(end - start), &batchPoints[3 * start],
              &batchFacing[3 * start], mine, &batchVisibilities[n2 * start], &batchStatuses[start],
              &batchUsed[start], wantSeen ? &batchSeens[start] : nullptr, own);
            start = end;
          }
          for (vtkIdType j = 0; j < count; ++j)
          {
            const vtkIdType to = byBlockers[j];
            std::copy_n(&batchVisibilities[n2 * j], n2, &visibilities[n2 * to]);
            statuses[to] = batchStatuses[j];
            used[to] = batchUsed[j];
            if (wantSeen)
            {
              seens[to].swap(batchSeens[j]);
            }
          }
        }
        // The planes' shadow scales: averaged over the planes' light maps,
        // or (PlaneShadowScale) one plane point per receiver and plane, their
        // visibilities batched the same way.
        planeScales.clear();
        if (planeMaps)
        {
          // Receivers whose light carries the one plane have a visibility
          // without it: the plane is seen past it (planesSeenPast), and the
          // sky past its edges is theirs (PlaneGaps, added to the direct light).
          planeScales.resize(3 * static_cast<std::size_t>(planes) * count);
          planeGaps.assign(3 * static_cast<std::size_t>(count), 0.0f);
          for (vtkIdType j = 0; j < count; ++j)
          {
            const bool past = planes == 1 && key[j] % 2 == 1;
            const bool failed = statuses[j] != proxygi::sh::Status::Ok;
            const float* g = past && used[j] > 0 && !failed ? &visibilities[n2 * j] : nullptr;
            for (int k = 0; k < planes; ++k)
            {
              maps[k].Scale(&points[3 * j], &facing[3 * j], &planeScales[3 * (j * planes + k)], g,
                past && runShadows ? &planeGaps[3 * j] : nullptr);
            }
          }
        }
        else if (scalePlanes && needVisibility)
        {
          planeScales.assign(3 * static_cast<std::size_t>(planes) * count, 1.0f);
          for (int k = 0; k < planes; ++k)
          {
            const float* m = &blockers.PlaneNormal[3 * k];
            who.clear();
            for (vtkIdType j = 0; j < count; ++j)
            {
              const vtkIdType r = byBlockers[j];
              if (proxygi::PlaneShadowPoint(
                    blockers, k, &points[3 * r], &facing[3 * r], &batchPoints[3 * who.size()]))
              {
                std::copy_n(m, 3, &batchFacing[3 * who.size()]);
                who.push_back(r);
              }
            }
            const vtkIdType seeing = static_cast<vtkIdType>(who.size());
            for (vtkIdType start = 0; start < seeing;)
            {
              vtkIdType end = start + 1;
              while (end < seeing && key[who[end]] / 2 == key[who[start]] / 2)
              {
                ++end;
              }
              const vtkIdType i = first + who[start];
              const proxygi::Blockers& mine = cl.Of.empty() ? blockers : cl.Blockers[cl.Of[i]];
              shadows.VisibilityBatch(static_cast<int>(end - start), &batchPoints[3 * start],
                &batchFacing[3 * start], mine, &batchVisibilities[n2 * start],
                &batchStatuses[start], &batchUsed[start]);
              start = end;
            }
            for (vtkIdType j = 0; j < seeing; ++j)
            {
              proxygi::PlaneShadowScaleAt(openShading, m, &batchVisibilities[n2 * j], batchUsed[j],
                batchStatuses[j], &planeScales[3 * (who[j] * planes + k)]);
            }
          }
        }
        // The bright lights' part of the planes' light, sampled where each
        // receiver sees the plane: the residual's scale and theirs, blended
        // by their shares of the plane's light.
        if (scalePlanes && b.RunBrightLights && !planeMaps)
        {
          if (planeScales.empty())
          {
            planeScales.assign(3 * static_cast<std::size_t>(planes) * count, 1.0f);
          }
          for (vtkIdType j = 0; j < count; ++j)
          {
            for (int k = 0; k < planes; ++k)
            {
              float lit[3], open[3];
              if (!proxygi::BrightLightsOnPlane(bright,
                    cl.Of.empty() ? blockers : cl.Blockers[cl.Of[first + j]], k,
                    brightRays ? this->Occluder : nullptr, rayOffset,
                    static_cast<float>(settings->GetMinBlockerAngle()), &points[3 * j],
                    &facing[3 * j], planeHemisphere, buffers.Bright, lit, open))
              {
                continue;
              }
              float* scale = &planeScales[3 * (j * planes + k)];
              const float* residual = &planeResidual[3 * k];
              for (int c = 0; c < 3; ++c)
              {
                const float whole = residual[c] + open[c];
                if (whole > 0.0f)
                {
                  scale[c] = std::min(1.0f, (residual[c] * scale[c] + lit[c]) / whole);
                }
              }
            }
          }
        }
        visibilityNs += std::chrono::duration_cast<std::chrono::nanoseconds>(
          std::chrono::steady_clock::now() - visibilityStart)
                          .count();
        for (vtkIdType i = first; i < last; ++i)
        {
          const vtkIdType j = i - first;
          double albedo[3];
          const float* p = &points[3 * j];
          const float* nf = &facing[3 * j];
          float rgb[3], bounce[3] = { 0, 0, 0 }, lit[3] = { 0, 0, 0 },
                        bounceShadowed[3] = { 0, 0, 0 };
          const proxygi::Blockers& mine = cl.Of.empty() ? blockers : cl.Blockers[cl.Of[i]];
          const bool lightCarriesPlanes = key[j] % 2 == 1;
          std::vector<proxygi::SeenBlocker>& seen = seens[j];
          if (needVisibility)
          {
            std::copy_n(&visibilities[n2 * j], n2, g);
            if (used[j] > 0)
            {
              ++localShadowed;
            }
            if (statuses[j] != proxygi::sh::Status::Ok)
            {
              ++localFailures;
              proxygi::sh::SetConstant(order, 1.0f, g);
              seen.clear();
            }
          }
          else
          {
            proxygi::sh::SetConstant(order, 1.0f, g);
          }
          if (runShadows)
          {
            (lightCarriesPlanes ? shading : openShading).Shade(nf, g, rgb);
            if (planeMaps)
            {
              // The environment past a bounded plane's edges (PlaneLightMap::Scale).
              for (int c = 0; c < 3; ++c)
              {
                rgb[c] += planeGaps[3 * j + c];
              }
            }
          }
          else
          {
            openShading.ShadeUnshadowed(nf, rgb);
          }
          if (b.RunBrightLights)
          {
            const auto start = std::chrono::steady_clock::now();
            const float before[3] = { rgb[0], rgb[1], rgb[2] };
            if (brightRays)
            {
              proxygi::BrightLightsFromRays(
                bright, mine, *this->Occluder, p, nf, rayOffset, buffers.Bright, rgb);
            }
            else
            {
              proxygi::BrightLightsFromProxies(bright, mine, p, nf,
                static_cast<float>(settings->GetMinBlockerAngle()), shadowsOn, rgb);
            }
            if (!brightOf.empty())
            {
              for (int c = 0; c < 3; ++c)
              {
                brightOf[3 * i + c] = rgb[c] - before[c];
              }
            }
            localBrightNs += std::chrono::duration_cast<std::chrono::nanoseconds>(
              std::chrono::steady_clock::now() - start)
                               .count();
          }
          float planeBounce[3] = { 0, 0, 0 };
          if (runIndirect || runPlaneBounce)
          {
            // xi needs the coverage of everything seen, planes included.
            // With the plane seen past the visibility, xi is the spheres' alone.
            const bool seenPast = planeMaps && planes == 1 && lightCarriesPlanes;
            float dc = g[0];
            if (lightCarriesPlanes && !seenPast)
            {
              double sum = 0.0;
              for (int k = 0; k < n2; ++k)
              {
                sum += g[k] * b.PlaneVisibility[k];
              }
              dc = static_cast<float>(sum / proxygi::sh::SqrtFourPi);
            }
            // Planes reflect less where the proxies shadow them.
            const bool scaled = scalePlanes && !planeScales.empty();
            proxygi::IndirectExitRadiance(indirectOperator, secondary, mine, seen, dc, nf,
              runIndirect ? bounce : planeBounce, scaled ? &planeScales[3 * j * planes] : nullptr,
              !runIndirect, self.OwnObject(i), // the own object's bounce: IndirectSelf
              seenPast);
          }
          const proxygi::SphericalLights& myLights =
            cl.Lights.empty() ? shadowedLeaves : cl.Lights[cl.Of[i]];
          if (runShadowed)
          {
            const auto start = std::chrono::steady_clock::now();
            if (!shadowedIndirect.ExitRadiance(myLights, true, nullptr, &blockers, p, nf,
                  bounceShadowed, scratch, nullptr, self.OwnObject(i)))
            {
              ++localShadowedFailures;
            }
            localSecondPassNs += std::chrono::duration_cast<std::chrono::nanoseconds>(
              std::chrono::steady_clock::now() - start)
                                   .count();
          }
          for (int c = 0; c < 3; ++c)
          {
            bounceShadowed[c] += planeBounce[c];
          }
          if (lightTables)
          {
            double pd[3];
            pointTuples.Get(i, pd);
            proxygi::LocalLightsRadiance(
              b.Locals, *lightTables, pd, nf, shadowsOn ? g : unshadowed, lit);
          }
          albedoOf.Get(i, albedo);
          float sum[3];
          for (int k = 0; k < 3; ++k)
          {
            rgb[k] = static_cast<float>(rgb[k] * albedo[k]);
            bounce[k] = static_cast<float>(bounce[k] * albedo[k]);
            bounceShadowed[k] = static_cast<float>(bounceShadowed[k] * albedo[k]);
            lit[k] = static_cast<float>(lit[k] * albedo[k]);
            sum[k] = rgb[k] + bounce[k] + bounceShadowed[k] + lit[k]; // one of the two is 0
          }
          direct->SetTypedTuple(i, rgb);
          indirect->SetTypedTuple(i, bounce);
          indirectShadowed->SetTypedTuple(i, bounceShadowed);
          local->SetTypedTuple(i, lit);
          total->SetTypedTuple(i, sum);
          visibility->SetTypedTuple(i, g);
        }
        shadowed += localShadowed;
        failures += localFailures;
        shadowedFailures += localShadowedFailures;
        secondPassNs += localSecondPassNs;
        brightNs += localBrightNs;
      });
    this->UpdateProgress(static_cast<double>(block + 1) / blocks);
  }
  this->StageMs[4] = 1e-6 * static_cast<double>(visibilityNs.load());
  this->StageMs[5] = 1e-6 * static_cast<double>(secondPassNs.load());
  if (runShadowed)
  {
    const double seconds = 1e-9 * static_cast<double>(secondPassNs.load());
    std::ostringstream line;
    line << "indirect light (shadowed): second pass over " << n << " receivers, "
         << (settings->GetSphericalLightBlocking() == vtkPGIGISettings::BLOCKING_PER_OBJECT
                ? "per-object"
                : "per-sphere")
         << " blocking, " << seconds << " s summed over threads ("
         << (n ? 1e6 * seconds / static_cast<double>(n) : 0.0) << " us per receiver)";
    this->Plan.push_back(line.str());
  }
  if (b.RunBrightLights)
  {
    const double seconds = 1e-9 * static_cast<double>(brightNs.load());
    std::ostringstream line;
    line << "bright lights: " << b.BrightLights.size() << " shaded on " << n << " receivers, ";
    if (brightRays)
    {
      line << "shadowed by " << bright.Rays << " rays per light against the occluder ("
           << this->Occluder->Describe() << ")";
    }
    else if (shadowsOn)
    {
      line << "shadowed by the proxies (the light's cone against each sphere, analytic; "
              "an occluder gives the meshes' own shadows)";
    }
    else
    {
      line << "unshadowed (shadows switched off)";
    }
    line << ", " << seconds << " s summed over threads";
    this->Plan.push_back(line.str());
  }
  if (shadowedFailures > 0)
  {
    vtkWarningMacro(<< shadowedFailures
                    << " receivers met non-finite SH values in the shadowed indirect light; "
                       "those spherical lights were left out.");
  }
  if (failures > 0)
  {
    vtkWarningMacro(<< failures
                    << " receivers met non-finite SH values; they were left unshadowed.");
  }
  // The bounce off each object onto itself, from its traced mesh: its direct
  // and local light where its rays hit it, once that is known everywhere.
  indirectSelf->FillValue(0.0f);
  if (self.Logs && settings->GetIndirect() && !b.Dark && !this->GetAbortExecute())
  {
    const vtkIdType* offsets = self.Offsets->GetPointer(0);
    const vtkIdType* targets = self.Targets->GetPointer(0);
    const float* weights = self.Weights->GetPointer(0);
    const float* lit = direct->GetPointer(0);
    const float* locals = local->GetPointer(0);
    std::atomic<vtkIdType> litAtHits(0);
    std::atomic<long long> hitNs(0);
    const Tuples3 normalTuples(normals);
    vtkSMPTools::For(0, n,
      [&](vtkIdType first, vtkIdType last)
      {
        proxygi::BrightLightScratch& scratch = this->Scratch->PerThread.Local().Bright;
        std::vector<float> hitPoints, hitNormals, hitLight;
        std::vector<vtkIdType> hitEntries;
        vtkIdType localLitAtHits = 0;
        long long localHitNs = 0;
        for (vtkIdType i = first; i < last; ++i)
        {
          if (self.OwnObject(i) < 0)
          {
            continue;
          }
          double sum[3] = { 0, 0, 0 }, albedo[3];
          hitEntries.clear();
          for (vtkIdType e = offsets[i]; e < offsets[i + 1]; ++e)
          {
            const vtkIdType t = targets[e];
            for (int c = 0; c < 3; ++c)
            {
              sum[c] += weights[e] * (lit[3 * t + c] + locals[3 * t + c]);
            }
            if (!brightOf.empty() && weights[e] >= MinHitWeight)
            {
              hitEntries.push_back(e);
            }
          }
          if (!hitEntries.empty())
          {
            // The corners' bright light, interpolated, need not hold where
            // near rays hit: the bright lights' share is taken there instead.
            const auto start = std::chrono::steady_clock::now();
            const std::size_t count = hitEntries.size();
            hitPoints.resize(3 * count);
            hitNormals.resize(3 * count);
            hitLight.assign(3 * count, 0.0f);
            for (std::size_t k = 0; k < count; ++k)
            {
              const vtkIdType e = hitEntries[k], t = targets[e];
              HitPointNow(self, e, &hitPoints[3 * k]);
              double nd[3];
              UnitNormal(normalTuples, t, nd);
              for (int c = 0; c < 3; ++c)
              {
                hitNormals[3 * k + c] = static_cast<float>(nd[c]);
              }
            }
            proxygi::BrightLightsFromRays(brightAtHits, blockers, *this->Occluder,
              static_cast<int>(count), hitPoints.data(), hitNormals.data(), rayOffset, scratch,
              hitLight.data());
            for (std::size_t k = 0; k < count; ++k)
            {
              const vtkIdType e = hitEntries[k], t = targets[e];
              double albedoT[3];
              albedoOf.Get(t, albedoT);
              for (int c = 0; c < 3; ++c)
              {
                sum[c] += weights[e] * albedoT[c] * (hitLight[3 * k + c] - brightOf[3 * t + c]);
              }
            }
            localLitAtHits += static_cast<vtkIdType>(count);
            localHitNs += std::chrono::duration_cast<std::chrono::nanoseconds>(
              std::chrono::steady_clock::now() - start)
                            .count();
          }
          albedoOf.Get(i, albedo);
          float* out = indirectSelf->GetPointer(3 * i);
          float* all = total->GetPointer(3 * i);
          for (int c = 0; c < 3; ++c)
          {
            out[c] = static_cast<float>(albedo[c] * sum[c]);
            all[c] += out[c];
          }
        }
        litAtHits += localLitAtHits;
        hitNs += localHitNs;
      });
    std::ostringstream line;
    line << "indirect light (self): each object's bounce onto itself gathered from "
         << self.Targets->GetNumberOfTuples() << " traced hits ("
         << (n ? static_cast<double>(self.Targets->GetNumberOfTuples()) / n : 0.0)
         << " per receiver)";
    if (!brightOf.empty())
    {
      line << "; " << litAtHits.load()
           << " of them (the entries of at least 1/64 of a receiver's rays) lit by the bright "
              "lights where they lie ("
           << brightAtHits.Rays << (brightAtHits.Rays == 1 ? " ray" : " rays") << " per light, "
           << 1e-9 * hitNs.load() << " s summed over threads)";
    }
    else if (self.Logs && !self.HitPoints)
    {
      line << "; no SelfBounceHitPoints: every hit takes its corners' light";
    }
    this->Plan.push_back(line.str());
  }
  if (needVisibility)
  {
    std::ostringstream line;
    line << (runShadows ? "shadows: " : "visibility (for indirect/local lights): ")
         << blockers.Spheres() << " proxy spheres, " << blockers.Planes()
         << (planesInLight ? " planes (carried by the light)" : " planes (log space)") << ", exp "
         << proxygi::sh::ExpMethodName(b.Kernel.Exp.Method) << ", kernels "
         << proxygi::sh::BatchTargetName() << "; " << shadowed.load() << " of " << n
         << " receivers had blockers in view (the others skipped the exp)";
    this->Plan.push_back(line.str());
  }

  vtkFloatArray* transferred = reuse(this->OutputArrays[7], "IndirectLocal", 3);
  this->AddTransferredLight(receivers, transferred, total);

  output->ShallowCopy(receivers);
  output->GetPointData()->AddArray(transferred);
  output->GetPointData()->AddArray(direct);
  output->GetPointData()->AddArray(indirect);
  output->GetPointData()->AddArray(indirectShadowed);
  output->GetPointData()->AddArray(local);
  output->GetPointData()->AddArray(total);
  output->GetPointData()->AddArray(indirectSelf);
  // The picture the GPU paths draw, for colouring with Map Scalars off.
  if (!this->ColorArray || this->ColorArray->GetReferenceCount() > 1)
  {
    this->ColorArray = vtkSmartPointer<vtkUnsignedCharArray>::New();
  }
  vtkUnsignedCharArray* colors = this->ColorArray;
  colors->SetName("RadianceSRGB");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(n);
  const double exposure = this->ColorExposure;
  vtkSMPTools::For(0, n,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          colors->SetTypedComponent(
            i, c, proxygi::ToSRGB8(exposure * total->GetTypedComponent(i, c)));
        }
      }
    });
  output->GetPointData()->AddArray(colors);
  output->GetPointData()->AddArray(visibility);
  if (!receivers->GetPointData()->GetNormals())
  {
    output->GetPointData()->SetNormals(normals);
  }
}

int vtkPGIGlobalIllumination::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  this->Plan.clear();
  this->CommunicationTime = this->CommunicationBytes = 0.0;
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point from)
  { return 1e3 * std::chrono::duration<double>(Clock::now() - from).count(); };
  const Clock::time_point started = Clock::now();
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  vtkPolyData* proxies =
    this->GetNumberOfInputConnections(1) ? vtkPolyData::GetData(in[1]) : nullptr;
  // Under MPI every rank reaches every collective below, whatever its
  // piece: a rank that fails says so in the agreement and all stop there.
  vtkMultiProcessController* controller = proxygi::parallel::Active(this->Controller);
  const bool emptyPiece = controller && (!receivers || receivers->GetNumberOfPoints() == 0);
  std::string error = emptyPiece ? std::string() : this->CheckReceivers(receivers);
  vtkSmartPointer<vtkDataArray> normals;
  if (emptyPiece)
  {
    normals = vtkSmartPointer<vtkFloatArray>::New();
    normals->SetNumberOfComponents(3);
  }
  else if (error.empty())
  {
    normals = proxygi::ReceiverNormals(receivers);
    this->StageMs[0] = since(started);
    if (!normals)
    {
      error = "Could not compute receiver normals (no polygons?); give point normals.";
    }
  }
  proxygi::parallel::Traffic traffic;
  std::string agreed;
  if (!proxygi::parallel::AllOk(controller, error.empty(), error, agreed, &traffic))
  {
    vtkErrorMacro(<< agreed);
    return 0;
  }
  vtkSmartPointer<vtkPolyData> globalProxies = proxies;
  const bool gathered = controller && !proxygi::parallel::IsGlobal(proxies);
  if (controller)
  {
    globalProxies = proxygi::parallel::GatherProxies(controller, proxies, error, &traffic);
    if (!globalProxies)
    {
      vtkErrorMacro(<< "Proxies: " << error << ".");
      return 0;
    }
  }
  Clock::time_point stage = Clock::now();
  error = this->PrepareBake(globalProxies, receivers);
  if (error.empty() && this->Occluder && this->Bake->GetScene().RunBrightLights &&
    this->Effective->GetShadows() && !this->Occluder->Prepare(error))
  {
    error = "Occluder: " + error + ".";
  }
  this->StageMs[1] = since(stage);
  if (!proxygi::parallel::AllOk(controller, error.empty(), error, agreed, &traffic))
  {
    vtkErrorMacro(<< agreed);
    return 0;
  }
  this->CommunicationTime = traffic.Seconds;
  this->CommunicationBytes = static_cast<double>(traffic.BytesReceived);
  if (controller)
  {
    std::ostringstream line;
    line << "distributed: rank " << controller->GetLocalProcessId() << " of "
         << controller->GetNumberOfProcesses() << ", "
         << (receivers ? receivers->GetNumberOfPoints() : 0) << " receivers in this piece; "
         << (globalProxies ? globalProxies->GetNumberOfPoints() : 0) << " proxies, "
         << (gathered ? "all-gathered here" : "global already (gathered upstream)") << "; "
         << traffic.BytesReceived << " bytes received in " << 1e3 * traffic.Seconds << " ms";
    this->Plan.push_back(line.str());
    if (!emptyPiece && !receivers->GetPointData()->GetNormals() && !receivers->GetCellGhostArray())
    {
      this->Plan.push_back("normals: computed on this rank's piece without ghost cells, so "
                           "points on a partition boundary may get other normals (and "
                           "results) than on the neighbouring rank; give normals computed "
                           "before the split, or a ghost layer");
    }
  }
  if (!this->ReceiverClusters)
  {
    this->ReceiverClusters.reset(new Clusters);
  }
  stage = Clock::now();
  this->ClusterReceivers(receivers, normals);
  this->StageMs[2] = since(stage);
  stage = Clock::now();
  this->ShadeReceivers(receivers, normals, output);
  this->StageMs[3] = since(stage);
  {
    std::ostringstream line;
    line << "stages (ms): normals " << this->StageMs[0] << ", precompute " << this->StageMs[1]
         << (this->Bake->GetNumberOfBuilds() != this->BuildsSeen ? " (built)" : " (reused)")
         << ", receiver clusters and cuts " << this->StageMs[2] << ", shading " << this->StageMs[3]
         << " (visibility " << this->StageMs[4] << ", spherical lights " << this->StageMs[5]
         << ", summed over threads), total " << since(started);
    this->BuildsSeen = this->Bake->GetNumberOfBuilds();
    this->Plan.push_back(line.str());
  }
  vtkNew<vtkStringArray> plan;
  plan->SetName("Plan");
  for (const std::string& line : this->Plan)
  {
    plan->InsertNextValue(line);
  }
  output->GetFieldData()->AddArray(plan);
  return 1;
}
