// proxygi proxies: the bounding sphere proxies of a mesh, written as .vtp,
// with their outside-volume ratio E and the time the build took.
#include "proxygiCommands.h"
#include "proxygiProgress.h"

#include "vtkPGIOFFReader.h"
#include "vtkPGIOcclusionFit.h"
#include "vtkPGISphereHierarchy.h"
#include "vtkPGISphereSetApproximation.h"

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

namespace proxygi
{
namespace cli
{
namespace
{
const char* Usage = R"(usage: proxygi proxies MESH [options]

Bounds a closed triangle mesh with spheres of minimal outside volume and
writes them as a .vtp (points = centres; Radius, ObjectId, Level, Parent
arrays: in ParaView, Glyph with a Sphere of scale factor 2, scaled by Radius).
Prints E = (volume in the spheres but outside the mesh) / (mesh volume), the
paper's sum over spheres, and the build time.

  MESH              .off (OFF, COFF, NOFF) or .vtp polygon mesh
  -o FILE           output .vtp (default: MESH's name + -proxies.vtp, here)
  -n, --spheres N   spheres per object (default 64)
  --method NAME     variational (default) | octree | kmeans
  --target-e E      instead: the fewest spheres (from N up) with E <= E
  --seed S          random seed (default 1); same seed, same spheres
  --components      one object per connected component
  --fit F           bounding (default: every point inside a sphere) or
                    occlusion (then the radii scaled so that the spheres block
                    what the mesh blocks, by Embree rays: vtkPGIOcclusionFit;
                    all the spheres stand for the whole mesh)
  --hierarchy       add the bounding hierarchy (branching 4) above the leaves
  --iterations N    variational: at most N clustering rounds (default 100)
  --resolution N    rows along the longest side for E (default 256)
)";

const std::set<std::string> ValueOptions = { "-o", "-n", "--spheres", "--method", "--target-e",
  "--seed", "--iterations", "--resolution", "--fit" };
const std::set<std::string> FlagOptions = { "--components", "--hierarchy", "--help" };

bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Errors and warnings of the pipeline go to stderr in one line each.
class Reporter : public vtkCommand
{
public:
  static Reporter* New() { return new Reporter; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    std::string message = data ? static_cast<const char*>(data) : "";
    const std::size_t from = message.find("): ");
    message = from == std::string::npos ? message : message.substr(from + 3);
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
    {
      message.pop_back();
    }
    vtkLogF(ERROR, "proxygi proxies: %s: %s", event == vtkCommand::ErrorEvent ? "error" : "warning",
      message.c_str());
    this->Errors += event == vtkCommand::ErrorEvent;
  }
  int Errors = 0;
};
} // namespace

int RunProxies(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  std::string mesh;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    if (ValueOptions.count(args[i]))
    {
      ++i;
      continue;
    }
    if (FlagOptions.count(args[i]))
    {
      continue;
    }
    if (!args[i].empty() && args[i][0] == '-')
    {
      vtkLogF(ERROR, "proxygi proxies: unknown option '%s'", args[i].c_str());
      return 2;
    }
    if (!mesh.empty())
    {
      std::fprintf(
        stderr, "proxygi proxies: one mesh only ('%s' and '%s')\n", mesh.c_str(), args[i].c_str());
      return 2;
    }
    mesh = args[i];
  }
  if (mesh.empty())
  {
    vtkLogF(ERROR, "proxygi proxies: no mesh given");
    std::fputs(Usage, stderr);
    return 2;
  }
  bool ok = true;
  const double spheres = NumberOption(args, "--spheres", NumberOption(args, "-n", 64, ok), ok);
  const double target = NumberOption(args, "--target-e", 0.0, ok);
  const double seed = NumberOption(args, "--seed", 1, ok);
  const double iterations = NumberOption(args, "--iterations", 100, ok);
  const double resolution = NumberOption(args, "--resolution", 256, ok);
  const std::string methodName = Option(args, "--method", "variational");
  const std::string fit = Option(args, "--fit", "bounding");
  if (!ok)
  {
    return 2;
  }
  if (fit != "bounding" && fit != "occlusion")
  {
    vtkLogF(ERROR, "proxygi proxies: --fit is bounding or occlusion, not '%s'", fit.c_str());
    return 2;
  }
  int method = -1;
  if (methodName == "variational")
  {
    method = vtkPGISphereSetApproximation::VARIATIONAL;
  }
  else if (methodName == "octree")
  {
    method = vtkPGISphereSetApproximation::OCTREE;
  }
  else if (methodName == "kmeans" || methodName == "k-means")
  {
    method = vtkPGISphereSetApproximation::KMEANS;
  }
  if (method < 0)
  {
    vtkLogF(ERROR, "proxygi proxies: --method is variational, octree or kmeans, not '%s'",
      methodName.c_str());
    return 2;
  }
  if (!(spheres >= 1 && spheres <= 1e6 && std::floor(spheres) == spheres) || !(target >= 0.0) ||
    !(seed >= 0 && seed <= 4294967295.0 && std::floor(seed) == seed) ||
    !(iterations >= 1 && iterations <= 1e6) || !(resolution >= 8 && resolution <= 4096))
  {
    vtkLogF(ERROR,
      "proxygi proxies: need 1 <= N, E >= 0, 0 <= seed < 2^32, "
      "1 <= iterations, 8 <= resolution <= 4096");
    return 2;
  }
  std::string output = Option(args, "-o", "");
  if (output.empty())
  {
    std::string stem =
      mesh.substr(mesh.find_last_of('/') == std::string::npos ? 0 : mesh.find_last_of('/') + 1);
    stem = stem.substr(0, stem.find_last_of('.'));
    output = stem + "-proxies.vtp";
  }
  if (!HasExtension("proxies", "-o", output, { ".vtp" }))
  {
    return 2;
  }

  vtkNew<Reporter> reporter;
  vtkSmartPointer<vtkAlgorithm> reader;
  if (EndsWith(mesh, ".off") || EndsWith(mesh, ".OFF"))
  {
    auto off = vtkSmartPointer<vtkPGIOFFReader>::New();
    off->SetFileName(mesh.c_str());
    reader = off;
  }
  else if (EndsWith(mesh, ".vtp"))
  {
    auto vtp = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    vtp->SetFileName(mesh.c_str());
    reader = vtp;
  }
  else
  {
    vtkLogF(ERROR, "proxygi proxies: '%s' is neither .off nor .vtp", mesh.c_str());
    return 2;
  }
  reader->AddObserver(vtkCommand::ErrorEvent, reporter);
  reader->Update();
  vtkPolyData* input = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (reporter->Errors || !input || input->GetNumberOfPoints() == 0)
  {
    vtkLogF(ERROR, "proxygi proxies: cannot read a mesh from '%s'", mesh.c_str());
    return 1;
  }

  vtkNew<vtkPGISphereSetApproximation> approx;
  approx->AddObserver(vtkCommand::ErrorEvent, reporter);
  approx->AddObserver(vtkCommand::WarningEvent, reporter);
  approx->SetInputData(input);
  approx->SetMethod(method);
  approx->SetNumberOfSpheres(static_cast<int>(spheres));
  approx->SetTargetOutsideVolumeRatio(target);
  approx->SetSeed(static_cast<unsigned>(seed));
  approx->SetMaximumIterations(static_cast<int>(iterations));
  approx->SetMetricResolution(static_cast<int>(resolution));
  approx->SetSplitConnectedComponents(Flag(args, "--components"));
  const auto start = std::chrono::steady_clock::now();
  bool interrupted = false;
  {
    Progress progress(approx, "proxygi proxies");
    approx->Update();
    interrupted = progress.Interrupted();
  }
  if (interrupted)
  {
    return InterruptedExitCode;
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (reporter->Errors || approx->GetOutput()->GetNumberOfPoints() == 0)
  {
    return 1;
  }
  vtkSmartPointer<vtkPolyData> proxies = approx->GetOutput();
  vtkSmartPointer<vtkPolyData> fitted;
  if (fit == "occlusion")
  {
    vtkNew<vtkPGIOcclusionFit> occlusion;
    occlusion->AddObserver(vtkCommand::ErrorEvent, reporter);
    occlusion->SetInputData(proxies);
    occlusion->SetMeshData(input);
    occlusion->SetSeed(static_cast<unsigned>(seed));
    {
      Progress progress(occlusion, "proxygi proxies");
      occlusion->Update();
      interrupted = progress.Interrupted();
    }
    if (interrupted)
    {
      return InterruptedExitCode;
    }
    if (reporter->Errors)
    {
      return 1;
    }
    fitted = occlusion->GetOutput();
    proxies = fitted;
  }
  if (Flag(args, "--hierarchy"))
  {
    vtkNew<vtkPGISphereHierarchy> hierarchy;
    hierarchy->SetInputData(proxies);
    hierarchy->Update();
    proxies = hierarchy->GetOutput();
  }

  std::printf("mesh %s: %lld points, %lld polygons\n", mesh.c_str(),
    static_cast<long long>(input->GetNumberOfPoints()),
    static_cast<long long>(input->GetNumberOfPolys() + input->GetNumberOfStrips()));
  vtkDataArray* counts = approx->GetOutput()->GetFieldData()->GetArray("SphereCount");
  for (int o = 0; o < approx->GetNumberOfObjects(); ++o)
  {
    std::printf("object %d: %s, %d spheres, E = %.4f (the paper's sum over spheres: %.4f), "
                "built in %.2f s\n",
      o, vtkPGISphereSetApproximation::GetMethodName(method),
      counts ? static_cast<int>(counts->GetTuple1(o)) : -1, approx->GetOutsideVolumeRatio(o),
      approx->GetOutsideVolumeRatioSum(o), approx->GetBuildTime(o));
  }
  std::printf("total %.2f s (build %.2f s, E at resolution %d)\n", seconds,
    approx->GetTotalBuildTime(), static_cast<int>(resolution));
  if (fitted)
  {
    vtkFieldData* field = fitted->GetFieldData();
    std::printf("fitted for occlusion: rays where spheres and mesh disagree %.1f%% -> %.1f%% of "
                "those the mesh blocks (bias %+.1f%% -> %+.1f%%; held-out points)\n",
      100.0 * field->GetArray("OcclusionErrorBefore")->GetTuple1(0),
      100.0 * field->GetArray("OcclusionErrorAfter")->GetTuple1(0),
      100.0 * field->GetArray("OcclusionBiasBefore")->GetTuple1(0),
      100.0 * field->GetArray("OcclusionBiasAfter")->GetTuple1(0));
  }

  const bool written = WriteThenRename(output,
    [&](const std::string& file)
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->AddObserver(vtkCommand::ErrorEvent, reporter);
      writer->SetInputData(proxies);
      writer->SetFileName(file.c_str());
      return writer->Write() == 1 && !reporter->Errors;
    });
  if (!written)
  {
    vtkLogF(ERROR, "proxygi proxies: cannot write '%s'", output.c_str());
    return 1;
  }
  std::printf("wrote %lld spheres to %s\n", static_cast<long long>(proxies->GetNumberOfPoints()),
    output.c_str());
  return 0;
}

} // namespace cli
} // namespace proxygi
