// Plain VTK under MPI (no ParaView): the proxy builder and the CPU GI
// filter with a vtkMPIController, against the same pipeline run serially
// on the whole scene. Run with mpiexec -np 2 or 3 (the third rank's piece
// is empty).
//
// Partitions of a ball over a ground (the ground also a reflecting plane):
//  - "objects": rank 0 holds the ground, rank 1 the ball, so the only
//    proxies come from rank 1 and shadow rank 0's receivers. Proxies and
//    per-vertex results must equal the serial run's (same spheres).
//  - "halves": every object cut at x = 0 (cells by centroid); each rank
//    builds spheres of its half-ball. Points on the cut lie on both ranks
//    and must agree exactly; the whole differs from serial only by the
//    proxies (a stated tolerance).
// Arguments: --fail (rank 1 gets a NaN receiver: every rank must report
// the error and return, none may hang), --bunny (the Stanford bunny for the
// ball) and --time (print the stages' seconds: proxy build, gather, shading).
#include "pgiParallel.h"
#include "pgiTesting.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGIReferenceIllumination.h"
#include "vtkPGISphereHierarchy.h"
#include "vtkPGISphereLightSampler.h"
#include "vtkPGISphereSetApproximation.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>

namespace
{
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Triangulated with unsplit normals computed on the whole object, before
// any split: a point on a cut then has one normal on both ranks.
vtkSmartPointer<vtkPolyData> WithNormals(vtkAlgorithmOutput* source)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->Update();
  return normals->GetOutput();
}

vtkSmartPointer<vtkPolyData> Ground(int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -4, 0);
  plane->SetPoint1(4, -4, 0);
  plane->SetPoint2(-4, 4, 0);
  plane->SetResolution(resolution, resolution);
  return WithNormals(plane->GetOutputPort());
}

vtkSmartPointer<vtkPolyData> Ball()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.3, 0.1, 1.2);
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  return WithNormals(sphere->GetOutputPort());
}

vtkSmartPointer<vtkPolyData> Bunny(const std::string& path)
{
  vtkNew<vtkPGIOFFReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkTransform> place;
  place->PostMultiply();
  place->RotateX(90);
  place->Translate(0, 0, 0.494);
  vtkNew<vtkTransformPolyDataFilter> moved;
  moved->SetInputConnection(reader->GetOutputPort());
  moved->SetTransform(place);
  return WithNormals(moved->GetOutputPort());
}

// The cells of `mesh` whose centroid passes `keep`, with only the points
// they use (normals kept).
vtkSmartPointer<vtkPolyData> Piece(vtkPolyData* mesh, const std::function<bool(double)>& keep)
{
  auto piece = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkDataArray* inNormals = mesh->GetPointData()->GetNormals();
  std::map<vtkIdType, vtkIdType> used;
  vtkCellArray* in = mesh->GetPolys();
  in->InitTraversal();
  vtkIdType n;
  const vtkIdType* ids;
  while (in->GetNextCell(n, ids))
  {
    double x = 0.0;
    for (vtkIdType k = 0; k < n; ++k)
    {
      x += mesh->GetPoint(ids[k])[0] / static_cast<double>(n);
    }
    if (!keep(x))
    {
      continue;
    }
    std::vector<vtkIdType> cell(static_cast<std::size_t>(n));
    for (vtkIdType k = 0; k < n; ++k)
    {
      auto it = used.find(ids[k]);
      if (it == used.end())
      {
        it = used.emplace(ids[k], points->InsertNextPoint(mesh->GetPoint(ids[k]))).first;
        normals->InsertNextTuple(inNormals->GetTuple(ids[k]));
      }
      cell[static_cast<std::size_t>(k)] = it->second;
    }
    polys->InsertNextCell(n, cell.data());
  }
  piece->SetPoints(points);
  piece->SetPolys(polys);
  piece->GetPointData()->SetNormals(normals);
  return piece;
}

vtkSmartPointer<vtkPolyData> Append(vtkPolyData* a, vtkPolyData* b)
{
  auto both = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (vtkPolyData* part : { a, b })
  {
    const vtkIdType offset = points->GetNumberOfPoints();
    for (vtkIdType i = 0; i < part->GetNumberOfPoints(); ++i)
    {
      points->InsertNextPoint(part->GetPoint(i));
      normals->InsertNextTuple(part->GetPointData()->GetNormals()->GetTuple(i));
    }
    vtkCellArray* in = part->GetPolys();
    in->InitTraversal();
    vtkIdType n;
    const vtkIdType* ids;
    while (in->GetNextCell(n, ids))
    {
      std::vector<vtkIdType> cell(ids, ids + n);
      for (vtkIdType& id : cell)
      {
        id += offset;
      }
      polys->InsertNextCell(n, cell.data());
    }
  }
  both->SetPoints(points);
  both->SetPolys(polys);
  both->GetPointData()->SetNormals(normals);
  return both;
}

struct Stages
{
  double Proxies = 0, Gather = 0, Shading = 0, GatherBytes = 0, FilterBytes = 0;
};

// The pipeline every rank runs: proxies of its occluder piece, GI of its
// receivers (ground and occluder pieces) under a sky with a reflecting ground.
// With `localProxies` each rank builds spheres of its piece alone (an empty
// piece none) and the GI filter gathers them. A hierarchy angle above 0 adds
// a sphere hierarchy and cuts it per receiver cluster at that angle.
vtkSmartPointer<vtkPolyData> Shade(vtkMultiProcessController* controller, vtkPolyData* ground,
  vtkPolyData* occluder, int spheres, Stages& stages, int& errors, vtkPolyData** proxiesOut,
  bool localProxies = false, double hierarchyAngle = 0.0)
{
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  vtkNew<vtkPGISphereSetApproximation> proxies;
  proxies->SetController(localProxies ? nullptr : controller);
  proxies->AddObserver(vtkCommand::ErrorEvent, onError);
  proxies->SetInputData(occluder);
  proxies->SetMethodToKMeans();
  proxies->SetNumberOfSpheres(spheres);
  proxies->ComputeOutsideVolumeOff();
  auto start = Clock::now();
  vtkNew<vtkPolyData> none;
  if (localProxies && occluder->GetNumberOfPoints() == 0)
  {
    proxies->SetInputData(none);
  }
  else
  {
    proxies->Update();
  }
  stages.Proxies = Since(start) - proxies->GetGatherTime();
  stages.Gather = proxies->GetGatherTime();
  stages.GatherBytes = proxies->GetGatheredBytes();
  vtkNew<vtkPGISphereHierarchy> hierarchy;
  hierarchy->SetInputConnection(proxies->GetOutputPort());

  vtkNew<vtkPGILighting> sky;
  const double blueSky[3] = { 0.6, 0.8, 1.2 };
  sky->SetUniformRadiance(blueSky);
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetController(controller);
  gi->AddObserver(vtkCommand::ErrorEvent, onError);
  gi->SetInputData(Append(ground, occluder));
  if (localProxies && occluder->GetNumberOfPoints() == 0)
  {
    gi->SetProxiesData(none);
  }
  else
  {
    gi->SetProxiesConnection(
      hierarchyAngle > 0.0 ? hierarchy->GetOutputPort() : proxies->GetOutputPort());
  }
  gi->GetSettings()->SetHierarchyAngle(hierarchyAngle);
  gi->GetSettings()->SetReceiversPerCluster(64);
  gi->SetLighting(sky);
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, albedo[3] = { 0.6, 0.5, 0.4 };
  gi->AddBlockerPlane(origin, up, albedo);
  gi->GetSettings()->SetDefaultProxyAlbedo(0.8, 0.8, 0.8);
  start = Clock::now();
  gi->Update();
  stages.Shading = Since(start) - gi->GetCommunicationTime();
  stages.Gather += gi->GetCommunicationTime();
  stages.FilterBytes = gi->GetCommunicationBytes();
  if (hierarchyAngle > 0.0 && gi->GetOutput()->GetNumberOfPoints() > 0)
  {
    // The cuts ran (a test of them that shaded without would prove nothing).
    bool cut = false;
    for (const std::string& line : gi->GetPlan())
    {
      cut = cut || line.find("receiver clusters, cuts of") != std::string::npos;
    }
    pgitest::Check(cut, "hierarchy cuts used", __FILE__, __LINE__);
  }
  if (proxiesOut)
  {
    // The set the filter shaded with: its bake's spheres.
    auto* used = vtkPolyData::New();
    used->SetPoints(vtkSmartPointer<vtkPoints>::New());
    used->GetPoints()->SetNumberOfPoints(
      static_cast<vtkIdType>(gi->GetBake()->GetScene().SceneBlockers.Spheres()));
    *proxiesOut = used;
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(gi->GetOutput());
  return result;
}

using Key = std::array<double, 3>;

// Radiance by point position (points on a cut appear once per rank).
std::multimap<Key, std::array<float, 3>> ByPosition(vtkPolyData* shaded)
{
  std::multimap<Key, std::array<float, 3>> map;
  auto* radiance = vtkFloatArray::SafeDownCast(shaded->GetPointData()->GetArray("Radiance"));
  for (vtkIdType i = 0; radiance && i < shaded->GetNumberOfPoints(); ++i)
  {
    const double* p = shaded->GetPoint(i);
    std::array<float, 3> v;
    radiance->GetTypedTuple(i, v.data());
    map.emplace(Key{ p[0], p[1], p[2] }, v);
  }
  return map;
}

int CheckPartition(vtkMultiProcessController* controller, const char* name, vtkPolyData* ground,
  vtkPolyData* occluder, int spheres, const std::function<int(double x, bool isGround)>& rankOf,
  double tolerance, bool time, bool localProxies = false, double hierarchyAngle = 0.0)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  // Ranks 0 and 1 share the scene; any further rank is empty (one rank: all).
  auto mine = [&](bool isGround)
  { return [&, isGround](double x) { return rankOf(x, isGround) % ranks == rank; }; };
  vtkSmartPointer<vtkPolyData> groundPiece = Piece(ground, mine(true));
  vtkSmartPointer<vtkPolyData> occluderPiece = Piece(occluder, mine(false));
  Stages stages;
  int errors = 0;
  vtkPolyData* proxies = nullptr;
  // Rank 0 ran the serial check of the previous case alone: start together,
  // so that no stage counts that wait.
  controller->Barrier();
  auto start = Clock::now();
  vtkSmartPointer<vtkPolyData> shaded = Shade(controller, groundPiece, occluderPiece, spheres,
    stages, errors, &proxies, localProxies, hierarchyAngle);
  const double total = Since(start);
  pgitest::Check(errors == 0, "no errors on this rank", __FILE__, __LINE__);
  pgitest::Check(shaded->GetNumberOfPoints() ==
      groundPiece->GetNumberOfPoints() + occluderPiece->GetNumberOfPoints(),
    "every receiver of the piece shaded", __FILE__, __LINE__);

  // Everything on rank 0, in rank order.
  vtkSmartPointer<vtkPolyData> all = proxygi::parallel::AllGatherPolyData(controller, shaded);
  const double slowest = proxygi::parallel::Max(controller, total);
  if (time)
  {
    const double p = proxygi::parallel::Max(controller, stages.Proxies);
    const double g = proxygi::parallel::Max(controller, stages.Gather);
    const double s = proxygi::parallel::Max(controller, stages.Shading);
    if (rank == 0)
    {
      std::printf("%s np=%d: total %.3f s (slowest rank): proxy build %.3f, all-gather (with the "
                  "wait for the slowest rank) %.4f, "
                  "shading %.3f; %d global spheres; bytes received per rank: proxies %.0f, "
                  "filter %.0f\n",
        name, ranks, slowest, p, g, s, static_cast<int>(proxies->GetNumberOfPoints()),
        stages.GatherBytes, stages.FilterBytes);
    }
  }
  const vtkIdType globalSpheres = proxies->GetNumberOfPoints();
  proxies->UnRegister(nullptr);
  if (rank != 0)
  {
    return pgitest::Result();
  }

  // Seams: a point held by two ranks has one result.
  const auto distributed = ByPosition(all);
  long boundary = 0, seams = 0;
  for (auto it = distributed.begin(); it != distributed.end();)
  {
    auto range = distributed.equal_range(it->first);
    for (auto other = std::next(range.first); other != range.second; ++other)
    {
      ++boundary;
      seams += other->second != range.first->second ? 1 : 0;
    }
    it = range.second;
  }
  std::printf(
    "%s np=%d: %ld points on partition boundaries, %ld differ\n", name, ranks, boundary, seams);
  pgitest::Check(seams == 0, "boundary points agree exactly across ranks", __FILE__, __LINE__);

  // The serial run of the whole scene on this rank alone.
  Stages serialStages;
  int serialErrors = 0;
  vtkPolyData* serialProxies = nullptr;
  vtkSmartPointer<vtkPolyData> serial = Shade(nullptr, ground, occluder, spheres, serialStages,
    serialErrors, &serialProxies, false, hierarchyAngle);
  const vtkIdType serialSpheres = serialProxies->GetNumberOfPoints();
  serialProxies->UnRegister(nullptr);
  if (time)
  {
    std::printf("%s serial: proxy build %.3f s, shading %.3f s\n", name, serialStages.Proxies,
      serialStages.Shading);
  }
  pgitest::Check(
    globalSpheres == serialSpheres, "as many global spheres as serial", __FILE__, __LINE__);
  pgitest::ErrorSum error;
  long matched = 0;
  for (const auto& s : ByPosition(serial))
  {
    auto it = distributed.find(s.first);
    if (it == distributed.end())
    {
      continue;
    }
    ++matched;
    for (int c = 0; c < 3; ++c)
    {
      error.Add(it->second[c], s.second[c]);
    }
  }
  pgitest::Check(matched == serial->GetNumberOfPoints(), "every serial point found distributed",
    __FILE__, __LINE__);
  std::printf("%s np=%d: Radiance against serial: relative RMSE %.3g, worst %.3g (tolerance "
              "%.3g)\n",
    name, ranks, error.RelativeRMSE(), error.Worst, tolerance);
  pgitest::Below(error.RelativeRMSE(), tolerance, "distributed against serial", __FILE__, __LINE__);
  return pgitest::Result();
}
// The Embree reference: each rank traces its receivers against the whole
// (gathered) scene; with position seeds every point equals the serial run's.
int CheckReference(
  vtkMultiProcessController* controller, vtkPolyData* ground, vtkPolyData* occluder)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  auto mine = [&](double x) { return (x < 0.0 ? 0 : 1) % ranks == rank; };
  vtkNew<vtkPGILighting> sky;
  auto trace = [&](vtkMultiProcessController* c, vtkPolyData* receivers, vtkPolyData* object)
  {
    vtkNew<vtkPGIReferenceIllumination> reference;
    reference->SetController(c);
    reference->PositionSeedsOn();
    reference->SetSamples(8);
    reference->SetLighting(sky);
    reference->SetInputData(receivers);
    reference->AddSceneObjectData(object);
    reference->Update();
    auto result = vtkSmartPointer<vtkPolyData>::New();
    result->ShallowCopy(reference->GetOutput());
    return std::make_pair(result, reference->GetCommunicationBytes());
  };
  // Receivers: the ground; scene object: the occluder, both split.
  auto distributed = trace(controller, Piece(ground, mine), Piece(occluder, mine));
  vtkSmartPointer<vtkPolyData> all =
    proxygi::parallel::AllGatherPolyData(controller, distributed.first);
  if (rank != 0)
  {
    return pgitest::Result();
  }
  vtkSmartPointer<vtkPolyData> serial = trace(nullptr, ground, occluder).first;
  const auto gathered = ByPosition(all);
  long compared = 0, differing = 0;
  for (const auto& s : ByPosition(serial))
  {
    auto range = gathered.equal_range(s.first);
    for (auto it = range.first; it != range.second; ++it, ++compared)
    {
      differing += it->second != s.second ? 1 : 0;
    }
  }
  std::printf("reference np=%d: %ld receiver results compared with serial, %ld differ; %.0f "
              "bytes of scene received by rank 0\n",
    ranks, compared, differing, distributed.second);
  pgitest::Check(
    compared >= serial->GetNumberOfPoints(), "every receiver traced", __FILE__, __LINE__);
  pgitest::Check(
    differing == 0, "the distributed reference equals the serial one", __FILE__, __LINE__);
  return pgitest::Result();
}

// The shadowed bounce's first pass: each rank casts the spheres' rays at its
// piece of the occluder; the combined samples must be the serial ones.
int CheckSampler(vtkMultiProcessController* controller, vtkPolyData* occluder, bool time)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  // The same global spheres on every rank (built alone from the whole object).
  vtkNew<vtkPGISphereSetApproximation> fit;
  fit->SetController(nullptr);
  fit->SetInputData(occluder);
  fit->SetMethodToKMeans();
  fit->SetNumberOfSpheres(32);
  fit->ComputeOutsideVolumeOff();
  fit->Update();
  vtkSmartPointer<vtkPolyData> piece =
    Piece(occluder, [&](double x) { return (x < 0.0 ? 0 : 1) % ranks == rank; });
  vtkNew<vtkPGISphereLightSampler> distributed;
  distributed->SetController(controller);
  distributed->SetInputData(piece);
  distributed->SetProxiesConnection(fit->GetOutputPort());
  controller->Barrier();
  auto start = Clock::now();
  distributed->Update();
  const double seconds = proxygi::parallel::Max(controller, Since(start));
  if (rank != 0)
  {
    return pgitest::Result();
  }
  vtkNew<vtkPGISphereLightSampler> serial;
  serial->SetController(nullptr);
  serial->SetInputData(occluder);
  serial->SetProxiesConnection(fit->GetOutputPort());
  start = Clock::now();
  serial->Update();
  const double serialSeconds = Since(start);
  long differing = 0, values = 0;
  double worst = 0.0;
  for (const char* name : { "SampleOffset", "SampleNormal", "SampleCount", "AlbedoSH" })
  {
    vtkDataArray* a = distributed->GetOutput()->GetPointData()->GetArray(name);
    vtkDataArray* b = serial->GetOutput()->GetPointData()->GetArray(name);
    if (!pgitest::Check(a && b && a->GetNumberOfValues() == b->GetNumberOfValues(),
          "sampler arrays present and equal in size", __FILE__, __LINE__))
    {
      continue;
    }
    for (vtkIdType v = 0; v < a->GetNumberOfValues(); ++v)
    {
      const double d = std::fabs(a->GetComponent(v / a->GetNumberOfComponents(),
                                   static_cast<int>(v % a->GetNumberOfComponents())) -
        b->GetComponent(
          v / b->GetNumberOfComponents(), static_cast<int>(v % b->GetNumberOfComponents())));
      differing += d > 0.0 ? 1 : 0;
      worst = std::max(worst, d);
      ++values;
    }
  }
  std::printf("sampler np=%d: %ld of %ld values differ from serial (largest %.3g); %d bytes "
              "received by rank 0; %.3f s distributed, %.3f s serial\n",
    ranks, differing, values, worst, static_cast<int>(distributed->GetCommunicationBytes()),
    seconds, serialSeconds);
  if (time)
  {
    std::printf("sampler np=%d: %.3g rays; %.0f bytes received per ray per other rank\n", ranks,
      serial->GetNumberOfRays(),
      ranks > 1 ? distributed->GetCommunicationBytes() / (serial->GetNumberOfRays() * (ranks - 1))
                : 0.0);
  }
  pgitest::Check(
    differing == 0, "the distributed first pass equals the serial one", __FILE__, __LINE__);
  return pgitest::Result();
}
// The cost of one all-gather of B bytes per rank, the cost model's basis:
// t = alpha + beta * (P - 1) * B ((P - 1) B bytes go into each rank). Ranks
// start together; the median of 15 calls per size.
void CollectiveCost(vtkMultiProcessController* controller)
{
  const int ranks = controller->GetNumberOfProcesses();
  if (ranks < 2)
  {
    return;
  }
  // alpha: the smallest message's time; beta: the slope between the two largest.
  const std::vector<vtkIdType> sizes = { 256, 4096, 65536, 1 << 20, 1 << 24 };
  std::vector<double> medians;
  for (const vtkIdType bytes : sizes)
  {
    std::vector<char> mine(static_cast<size_t>(bytes), 1);
    std::vector<char> all(static_cast<size_t>(bytes) * ranks);
    std::vector<double> times;
    for (int r = 0; r < 15; ++r)
    {
      controller->Barrier();
      const auto start = Clock::now();
      controller->AllGather(mine.data(), all.data(), bytes);
      times.push_back(proxygi::parallel::Max(controller, Since(start)));
    }
    std::nth_element(times.begin(), times.begin() + 7, times.end());
    medians.push_back(times[7]);
    if (controller->GetLocalProcessId() == 0)
    {
      std::printf("all-gather np=%d: %lld bytes per rank: %.3g s (median of 15)\n", ranks,
        static_cast<long long>(bytes), times[7]);
    }
  }
  const size_t last = sizes.size() - 1;
  const double beta = (medians[last] - medians[last - 1]) /
    (static_cast<double>(sizes[last] - sizes[last - 1]) * (ranks - 1));
  if (controller->GetLocalProcessId() == 0)
  {
    std::printf("all-gather np=%d: alpha %.3g s, beta %.3g s/byte (%.2f GB/s into each rank)\n",
      ranks, medians[0], beta, 1e-9 / beta);
  }
}
} // namespace

int TestParallelGlobalIllumination(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv, 0);
  vtkMultiProcessController::SetGlobalController(controller);
  bool fail = false, bunny = false, time = false;
  for (int i = 1; i < argc; ++i)
  {
    fail = fail || !std::strcmp(argv[i], "--fail");
    bunny = bunny || !std::strcmp(argv[i], "--bunny");
    time = time || !std::strcmp(argv[i], "--time");
  }
  const int rank = controller->GetLocalProcessId();
  int result = EXIT_SUCCESS;
  if (controller->GetNumberOfProcesses() < 2 && !time)
  {
    std::printf("needs at least 2 ranks (mpiexec -np 2)\n");
    result = EXIT_FAILURE;
  }
  else if (fail)
  {
    // Rank 1's receivers hold a NaN: every rank must fail with its reason.
    vtkSmartPointer<vtkPolyData> ground = Ground(8);
    vtkSmartPointer<vtkPolyData> ball = Ball();
    vtkSmartPointer<vtkPolyData> groundPiece = Piece(ground, [&](double) { return rank == 0; });
    vtkSmartPointer<vtkPolyData> ballPiece = Piece(ball, [&](double) { return rank == 1; });
    if (rank == 1)
    {
      ballPiece->GetPoints()->SetPoint(0, std::nan(""), 0, 0);
      ballPiece->GetPoints()->Modified();
    }
    Stages stages;
    int errors = 0;
    vtkSmartPointer<vtkPolyData> shaded =
      Shade(controller, groundPiece, ballPiece, 16, stages, errors, nullptr);
    std::printf("rank %d: %d error(s) reported, %lld points out\n", rank, errors,
      static_cast<long long>(shaded->GetNumberOfPoints()));
    pgitest::Check(errors > 0, "every rank reports the error", __FILE__, __LINE__);
    pgitest::Check(shaded->GetNumberOfPoints() == 0, "no output on failure", __FILE__, __LINE__);
    result = pgitest::Result();
  }
  else
  {
    vtkSmartPointer<vtkPolyData> ground = Ground(bunny ? 128 : 48);
    vtkSmartPointer<vtkPolyData> occluder;
    if (bunny)
    {
      const std::string path = std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
      if (!vtksys::SystemTools::FileExists(path))
      {
        std::printf("%s missing (run Utilities/setup.sh --data)\n", path.c_str());
        controller->Finalize();
        return EXIT_FAILURE;
      }
      occluder = Bunny(path);
    }
    else
    {
      occluder = Ball();
    }
    // Ground on rank 0, occluder on rank 1: one rank's geometry shadows the other's.
    result |= CheckPartition(
      controller, "objects", ground, occluder, 32,
      [](double, bool isGround) { return isGround ? 0 : 1; }, 1e-6, time);
    // The same with per-rank proxies that the GI filter gathers itself.
    result |= CheckPartition(
      controller, "objects, gathered by the filter", ground, occluder, 32,
      [](double, bool isGround) { return isGround ? 0 : 1; }, 1e-6, time, true);
    result |= CheckSampler(controller, occluder, time);
    if (!bunny)
    {
      result |= CheckReference(controller, Ground(16), occluder);
    }
    // Both cut at x = 0: seams, and per-piece proxies (measured: 1.04% on
    // the ball, 3.3% on the bunny, whose halves' spheres differ more).
    result |= CheckPartition(
      controller, "halves", ground, occluder, 32, [](double x, bool) { return x < 0.0 ? 0 : 1; },
      bunny ? 0.08 : 0.03, time);
    // Hierarchy cuts: the receiver clusters must not follow the partition
    // (seams); against the serial run (clustered otherwise) they differ by
    // the cuts' error.
    result |= CheckPartition(
      controller, "halves, hierarchy cut at 25 degrees", ground, occluder, 32,
      [](double x, bool) { return x < 0.0 ? 0 : 1; }, bunny ? 0.08 : 0.03, time, false, 25.0);
    if (time)
    {
      CollectiveCost(controller);
    }
  }
  controller->Finalize();
  return result;
}
