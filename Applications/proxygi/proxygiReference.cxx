// proxygi reference: Embree path-traced ground truth of a scene, per pixel
// (EXR + tone-mapped PNG) or per vertex (.vtp with the radiance arrays).
#include "proxygiCommands.h"
#include "proxygiImage.h"
#include "proxygiProgress.h"

#include "pgiScene.h"
#include "vtkPGIEXRWriter.h"
#include "vtkPGILighting.h"
#include "vtkPGIReferenceIllumination.h"
#include "vtkPGIReferenceImage.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace proxygi
{
namespace cli
{
namespace
{
const char* Usage = R"(usage: proxygi reference [scene.json] [options]

Monte Carlo ground truth (Embree) of a scene file, or of the built-in default
scene (the bunny over a plane under the forest map) when none is given.

Per pixel (default):
  -o FILE.exr        radiance image, OpenEXR (default reference.exr)
  --png FILE.png     also a tone-mapped sRGB PNG (exposure: --exposure E, or auto)
  --size WxH         image size (default: the scene camera's)
Per vertex:
  --per-vertex FILE.vtp  write object K's vertices with DirectShadowed,
                     IndirectOneBounce, Radiance and *StdErr arrays (.vtp);
                     the other objects shadow and reflect
  --object K         the receiving object (default 0)
Both:
  --spp N            samples per pixel or vertex (default 64)
  --bounces B        0 direct only, 1 one-bounce indirect (default), more for tests
  --seed S           random seed (default 1)
  --proxies FILE     sphere proxies (.vtp with a Radius array) replace the
                     non-receiving objects (per vertex) or all objects (per pixel)

Progress is shown on standard error (a bar on a terminal, else a line each
10%). Ctrl-C stops the tracing and writes nothing. Files are written under a
temporary name and renamed, never left half-written. Exit codes: 0 done,
1 failed (scene, data or writing), 2 bad arguments (an output name must end
in its format's extension), 130 interrupted.
)";

double ElapsedSeconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

int RunReference(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  bool ok = true;
  const int spp = static_cast<int>(NumberOption(args, "--spp", 64, ok));
  const int bounces = static_cast<int>(NumberOption(args, "--bounces", 1, ok));
  const int seed = static_cast<int>(NumberOption(args, "--seed", 1, ok));
  const int objectIndex = static_cast<int>(NumberOption(args, "--object", 0, ok));
  const double exposureOption = NumberOption(args, "--exposure", 0.0, ok);
  if (!ok)
  {
    return 2;
  }
  if (spp < 1 || bounces < 0 || bounces > 64)
  {
    vtkLogF(ERROR, "proxygi reference: need --spp >= 1 and 0 <= --bounces <= 64");
    return 2;
  }
  // The output names first: a wrong extension is refused before the work.
  const std::string perVertex = Option(args, "--per-vertex", "");
  const std::string exr = Option(args, "-o", "reference.exr");
  const std::string png = Option(args, "--png", "");
  if ((!perVertex.empty() && !HasExtension("reference", "--per-vertex", perVertex, { ".vtp" })) ||
    (perVertex.empty() && !HasExtension("reference", "-o", exr, { ".exr" })) ||
    (!png.empty() && !HasExtension("reference", "--png", png, { ".png" })))
  {
    return 2;
  }
  // The scene: the first argument that is not an option or an option's value.
  const std::string scenePath = Positional(args, {});
  SceneDescription scene = DefaultScene();
  std::string error;
  if (!scenePath.empty() && !LoadScene(scenePath, scene, error))
  {
    vtkLogF(ERROR, "proxygi reference: %s", error.c_str());
    return 1;
  }
  const std::string size = Option(args, "--size", "");
  if (!size.empty() && std::sscanf(size.c_str(), "%dx%d", &scene.Size[0], &scene.Size[1]) != 2)
  {
    vtkLogF(ERROR, "proxygi reference: --size expects WxH, e.g. 512x512");
    return 2;
  }
  LoadedScene loaded;
  if (!BuildScene(scene, loaded, error))
  {
    vtkLogF(ERROR, "proxygi reference: %s", error.c_str());
    return 1;
  }
  vtkSmartPointer<vtkPolyData> proxies;
  const std::string proxiesPath = Option(args, "--proxies", "");
  if (!proxiesPath.empty())
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(proxiesPath.c_str());
    reader->Update();
    proxies = reader->GetOutput();
    if (!proxies || proxies->GetNumberOfPoints() == 0)
    {
      vtkLogF(ERROR, "proxygi reference: no proxies in '%s'", proxiesPath.c_str());
      return 1;
    }
  }
  std::printf("scene: %s (%zu objects)\n", scene.Name.c_str(), loaded.Objects.size());
  const auto start = std::chrono::steady_clock::now();

  if (!perVertex.empty())
  {
    if (objectIndex < 0 || objectIndex >= static_cast<int>(loaded.Objects.size()))
    {
      std::fprintf(
        stderr, "proxygi reference: --object must lie in 0..%zu\n", loaded.Objects.size() - 1);
      return 2;
    }
    vtkNew<vtkPGIReferenceIllumination> reference;
    reference->SetInputData(loaded.Objects[objectIndex]);
    for (std::size_t k = 0; k < loaded.Objects.size(); ++k)
    {
      if (static_cast<int>(k) != objectIndex)
      {
        reference->AddSceneObjectData(loaded.Objects[k]);
      }
    }
    if (proxies)
    {
      reference->SetProxiesData(proxies);
      reference->UseProxiesOn();
    }
    reference->SetLighting(loaded.Lighting);
    reference->SetSamples(spp);
    reference->SetMaxBounces(bounces);
    reference->SetSeed(static_cast<unsigned>(seed));
    bool interrupted = false;
    {
      Progress progress(reference, "proxygi reference");
      reference->Update();
      interrupted = progress.Interrupted();
    }
    if (interrupted)
    {
      return InterruptedExitCode;
    }
    vtkPolyData* out = reference->GetOutput();
    if (out->GetNumberOfPoints() == 0)
    {
      vtkLogF(ERROR, "proxygi reference: the reference failed (see the errors above)");
      return 1;
    }
    const double seconds = ElapsedSeconds(start);
    const double rays = out->GetFieldData()->GetArray("Rays")->GetTuple1(0);
    const double meanRel = out->GetFieldData()->GetArray("MeanRelativeStdErr")->GetTuple1(0);
    const double rel = out->GetFieldData()->GetArray("RelativeRMSStdErr")->GetTuple1(0);
    if (!WritePolyData(out, perVertex))
    {
      vtkLogF(ERROR, "proxygi reference: cannot write %s", perVertex.c_str());
      return 1;
    }
    std::printf("per vertex: %lld receivers, %d samples, %d bounce(s), %d threads\n",
      static_cast<long long>(out->GetNumberOfPoints()), spp, bounces,
      vtkSMPTools::GetEstimatedNumberOfThreads());
    std::printf("time %.2f s, %.2f Mrays/s; standard error: relative RMS %.3f%%, mean of "
                "per-vertex relative %.3f%%\n",
      seconds, rays / seconds / 1e6, 100 * rel, 100 * meanRel);
    // Noise falls as 1/sqrt(samples): what 1% would take, extrapolated.
    const double sppFor1 = spp * (rel / 0.01) * (rel / 0.01);
    std::printf("extrapolated to 1%% relative RMS standard error: %.0f samples, %.1f s\n", sppFor1,
      seconds * sppFor1 / spp);
    std::printf("wrote %s\n", perVertex.c_str());
    return 0;
  }

  vtkNew<vtkPGIReferenceImage> image;
  if (proxies)
  {
    image->SetInputData(0, loaded.Objects[0]);
    image->SetInputData(1, proxies);
    image->UseProxiesOn();
  }
  else
  {
    for (const auto& object : loaded.Objects)
    {
      image->AddInputData(0, object);
    }
  }
  image->SetLighting(loaded.Lighting);
  image->SetCamera(loaded.Camera);
  image->SetSize(scene.Size);
  image->SetSamples(spp);
  image->SetMaxBounces(bounces);
  image->SetSeed(static_cast<unsigned>(seed));
  bool interrupted = false;
  {
    Progress progress(image, "proxygi reference");
    image->Update();
    interrupted = progress.Interrupted();
  }
  if (interrupted)
  {
    return InterruptedExitCode;
  }
  vtkImageData* radiance = image->GetOutput();
  if (radiance->GetNumberOfPoints() == 0)
  {
    vtkLogF(ERROR, "proxygi reference: the reference failed (see the errors above)");
    return 1;
  }
  const double seconds = ElapsedSeconds(start);
  vtkDataArray* rgb = radiance->GetPointData()->GetScalars();
  vtkDataArray* err = radiance->GetPointData()->GetArray("RadianceStdErr");
  double rel = 0.0;
  vtkIdType counted = 0;
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    const double e = err->GetComponent(i, 1), v = rgb->GetComponent(i, 1);
    if (e > 0.0 && v > 0.0)
    {
      rel += e / v;
      ++counted;
    }
  }
  const bool written = WriteThenRename(exr,
    [&](const std::string& file)
    {
      vtkNew<vtkPGIEXRWriter> writer;
      writer->SetFileName(file.c_str());
      writer->SetInputData(radiance);
      return writer->Write() == 1;
    });
  if (!written)
  {
    vtkLogF(ERROR, "proxygi reference: cannot write %s", exr.c_str());
    return 1;
  }
  std::printf("per pixel: %dx%d, %d samples, %d bounce(s), %d threads\n", scene.Size[0],
    scene.Size[1], spp, bounces, vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("time %.2f s, mean relative standard error of lit pixels %.3f%%\n", seconds,
    counted ? 100 * rel / counted : 0.0);
  std::printf("wrote %s\n", exr.c_str());
  if (!png.empty())
  {
    const double exposure = exposureOption > 0.0 ? exposureOption : AutoExposure(radiance);
    if (!WriteTonemappedPNG(radiance, exposure, png))
    {
      vtkLogF(ERROR, "proxygi reference: cannot write %s", png.c_str());
      return 1;
    }
    std::printf("wrote %s (exposure %.3g)\n", png.c_str(), exposure);
  }
  return 0;
}

} // namespace cli
} // namespace proxygi
