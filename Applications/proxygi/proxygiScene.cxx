// proxygi render (scene mode): the main job. Loads a scene (or the default:
// the bunny over a plane under the forest map), builds sphere proxies for its
// meshes, shades every vertex with SH soft shadows (vtkPGIGlobalIllumination),
// renders the result offscreen with VTK, and compares the per-vertex radiance
// with the Embree reference of the same scene (computed once and cached).
#include "proxygiCommands.h"
#include "proxygiImage.h"

#include "pgiOffscreenWindow.h"
#include "pgiScene.h"
#include "pgiScenePipeline.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"
#include "vtkPGIReferenceImage.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

namespace proxygi
{
namespace cli
{
namespace
{
using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

} // namespace

int RunRenderScene(const Args& args, const std::string& scenePath)
{
  bool ok = true;
  const int order = static_cast<int>(NumberOption(args, "--order", 4, ok));
  const int spheres = static_cast<int>(NumberOption(args, "--spheres", 64, ok));
  const int referenceSpp = static_cast<int>(NumberOption(args, "--reference-spp", 1024, ok));
  const std::string methodName = Option(args, "--method", "HYB");
  const std::string indirectName = Option(args, "--indirect", "shadowed");
  const std::string mode = Option(args, "--mode", "gpu");
  const double hierarchyAngle = NumberOption(args, "--hierarchy", 25.0, ok);
  const int receiverScale = static_cast<int>(NumberOption(args, "--scale", 2, ok));
  const int pixelSpp = static_cast<int>(NumberOption(args, "--pixel-reference-spp", 256, ok));
  if ((mode != "gpu" && mode != "vertex" && mode != "image-space") ||
    (receiverScale != 1 && receiverScale != 2 && receiverScale != 4 && receiverScale != 8) ||
    pixelSpp < 1)
  {
    std::fprintf(stderr,
      "proxygi render: --mode gpu|vertex|image-space, --scale 1|2|4|8, "
      "--pixel-reference-spp >= 1\n");
    return 2;
  }
  const bool imageSpace = mode == "image-space";
  const bool gpu = mode == "gpu";
  const std::map<std::string, int> indirectModes = {
    { "shadowed", vtkPGIGlobalIllumination::INDIRECT_MODE_SHADOWED },
    { "unshadowed", vtkPGIGlobalIllumination::INDIRECT_MODE_UNSHADOWED },
    { "off", vtkPGIGlobalIllumination::INDIRECT_MODE_OFF }
  };
  if (!indirectModes.count(indirectName))
  {
    std::fprintf(stderr, "proxygi render: --indirect shadowed|unshadowed|off\n");
    return 2;
  }
  const std::string output = Option(args, "-o", "proxygi-render.png");
  const std::string cache = Option(args, "--cache", "proxygi-cache");
  if (!ok)
  {
    return 2;
  }
  const std::map<std::string, int> methods = { { "PS", vtkPGIGlobalIllumination::EXP_PS },
    { "PS*", vtkPGIGlobalIllumination::EXP_PS_STAR }, { "OL", vtkPGIGlobalIllumination::EXP_OL },
    { "HYB", vtkPGIGlobalIllumination::EXP_HYB } };
  if (!methods.count(methodName) || order < 2 || order > 8 || spheres < 1 || referenceSpp < 1)
  {
    std::fprintf(stderr,
      "proxygi render: need --method HYB|OL|PS*|PS, 2 <= --order <= 8, "
      "--spheres >= 1, --reference-spp >= 1\n");
    return 2;
  }
  SceneDescription scene = DefaultScene();
  std::string error;
  if (!scenePath.empty() && !LoadScene(scenePath, scene, error))
  {
    std::fprintf(stderr, "proxygi render: %s\n", error.c_str());
    return 1;
  }
  const std::string size = Option(args, "--size", "");
  if (!size.empty() && std::sscanf(size.c_str(), "%dx%d", &scene.Size[0], &scene.Size[1]) != 2)
  {
    std::fprintf(stderr, "proxygi render: --size expects WxH\n");
    return 2;
  }
  LoadedScene loaded;
  if (!BuildScene(scene, loaded, error))
  {
    std::fprintf(stderr, "proxygi render: %s\n", error.c_str());
    return 1;
  }
  std::printf("scene: %s\n", scene.Name.c_str());

  // Proxies (cached), then the SH shading of every object's vertices.
  SceneProxies proxies;
  if (!BuildSceneProxies(scene, loaded, spheres, cache, proxies, error))
  {
    std::fprintf(stderr, "proxygi render: %s\n", error.c_str());
    return 1;
  }
  const auto receiversIn = SceneReceivers(loaded);
  const auto t1 = Clock::now();
  std::vector<vtkSmartPointer<vtkPolyData>> shaded;
  for (auto& receivers : receiversIn)
  {
    if (gpu)
    {
      break; // the GI mapper shades them while rendering
    }
    vtkNew<vtkPGIGlobalIllumination> gi;
    gi->SetInputData(receivers);
    ConfigureGlobalIllumination(gi, scene, loaded, proxies);
    gi->SetOrder(order);
    gi->SetExpMethod(methods.at(methodName));
    gi->SetIndirectMode(indirectModes.at(indirectName));
    gi->SetHierarchyAngle(hierarchyAngle);
    gi->Update();
    shaded.push_back(gi->GetOutput());
    if (shaded.size() == 1)
    {
      for (const std::string& line : gi->GetPlan())
      {
        std::printf("plan: %s\n", line.c_str());
      }
    }
  }
  auto t2 = Clock::now();
  const std::string vtpPrefix = Option(args, "--vtp", "");
  vtkIdType receivers = 0;
  for (auto& s : receiversIn)
  {
    receivers += s->GetNumberOfPoints();
  }

  // Offscreen picture: vertex radiance, tone-mapped, no VTK lighting.
  // Exposure: the 95th percentile of the radiance to 0.8 (GPU: after the
  // first frame, from the radiance read back).
  double exposure = NumberOption(args, "--exposure", 0.0, ok);
  const auto automaticExposure = [&]()
  {
    std::vector<double> luminance;
    for (auto& s : shaded)
    {
      vtkDataArray* r = s->GetPointData()->GetArray("Radiance");
      for (vtkIdType i = 0; i < r->GetNumberOfTuples(); ++i)
      {
        luminance.push_back(
          Luminance(r->GetComponent(i, 0), r->GetComponent(i, 1), r->GetComponent(i, 2)));
      }
    }
    return AutoExposure(luminance);
  };
  if (!(exposure > 0.0) && !gpu)
  {
    exposure = automaticExposure();
  }
  vtkNew<vtkRenderer> renderer;
  // Per vertex on the GPU: the GI mapper set up as the filter would be.
  std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> giMappers;
  for (std::size_t k = 0; gpu && k < loaded.Objects.size(); ++k)
  {
    auto mapper = vtkSmartPointer<vtkPGIGIPolyDataMapper>::New();
    mapper->SetInputData(receiversIn[k]);
    mapper->SetProxies(proxies.Spheres);
    mapper->SetLighting(loaded.Lighting);
    for (const auto& plane : proxies.Planes)
    {
      mapper->AddBlockerPlane(plane.data(), plane.data() + 3, plane.data() + 6);
    }
    mapper->SetOrder(order);
    mapper->SetShadows(scene.Shadows);
    mapper->SetIndirect(scene.Indirect && indirectName != "off");
    mapper->SetIndirectMode(indirectName == "shadowed"
        ? vtkPGIGIPolyDataMapper::INDIRECT_MODE_SHADOWED
        : vtkPGIGIPolyDataMapper::INDIRECT_MODE_UNSHADOWED);
    mapper->SetLocalLights(scene.LocalLights);
    mapper->SetAlbedo(scene.Objects[k].Albedo);
    mapper->SetExposure(exposure > 0.0 ? exposure : 1.0);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    giMappers.push_back(mapper);
  }
  renderer->SetBackground(0.3, 0.3, 0.32);
  vtkNew<vtkPGIImageSpaceGIPass> pass;
  if (imageSpace)
  {
    // Per pixel on the GPU: plain mappers, the albedo as diffuse colour.
    for (std::size_t k = 0; k < loaded.Objects.size(); ++k)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(receiversIn[k]);
      mapper->ScalarVisibilityOff();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(scene.Objects[k].Albedo);
      actor->GetProperty()->SetAmbient(0.0);
      actor->GetProperty()->SetDiffuse(1.0);
      actor->GetProperty()->SetSpecular(0.0);
      renderer->AddActor(actor);
    }
    pass->SetProxies(proxies.Spheres);
    pass->SetLighting(loaded.Lighting);
    for (const auto& plane : proxies.Planes)
    {
      pass->AddBlockerPlane(plane.data(), plane.data() + 3, plane.data() + 6);
    }
    pass->SetShadows(scene.Shadows);
    pass->SetIndirect(scene.Indirect && indirectName != "off");
    pass->SetReceiverScale(receiverScale);
    pass->SetExposure(exposure);
    pass->MeasurePassTimesOn();
    renderer->SetPass(pass);
  }
  for (auto& s : shaded)
  {
    if (imageSpace || gpu)
    {
      break;
    }
    vtkDataArray* r = s->GetPointData()->GetArray("Radiance");
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("DisplayColors");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(r->GetNumberOfTuples());
    for (vtkIdType i = 0; i < r->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        colors->SetValue(3 * i + c, ToSRGB8(exposure * r->GetComponent(i, c)));
      }
    }
    vtkNew<vtkPolyData> display;
    display->ShallowCopy(s);
    display->GetPointData()->SetScalars(colors);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(display);
    mapper->SetColorModeToDirectScalars();
    mapper->ScalarVisibilityOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->LightingOff();
    renderer->AddActor(actor);
  }
  renderer->SetActiveCamera(loaded.Camera);
  renderer->ResetCameraClippingRange();
  // EGL without a display, the X server's window with one (Xvfb included).
  std::string windowPath;
  vtkSmartPointer<vtkRenderWindow> window = NewOffscreenRenderWindow(&windowPath);
  if (!window)
  {
    std::fprintf(stderr, "proxygi render: no offscreen OpenGL: %s\n", windowPath.c_str());
    return 1;
  }
  window->SetSize(scene.Size[0], scene.Size[1]);
  window->AddRenderer(renderer);
  window->Render();
  if (gpu)
  {
    // The first frame compiled the shaders and ran the GI pass; read the
    // per-vertex radiance back (the error and the exposure need it), then
    // time one frame that recomputes GI (as moving proxies would).
    window->WaitForCompletion();
    t2 = Clock::now();
    for (std::size_t k = 0; k < giMappers.size(); ++k)
    {
      vtkNew<vtkFloatArray> radiance;
      if (!giMappers[k]->GetPerVertexResults(radiance))
      {
        std::fprintf(stderr, "proxygi render: the GPU GI pass did not run (%s)\n",
          giMappers[k]->GetGIStatus().c_str());
        return 1;
      }
      radiance->SetName("Radiance");
      auto result = vtkSmartPointer<vtkPolyData>::New();
      result->ShallowCopy(receiversIn[k]);
      result->GetPointData()->AddArray(radiance);
      shaded.push_back(result);
      std::printf("gpu: object %zu (%s): %s\n", k, scene.Objects[k].Name.c_str(),
        giMappers[k]->GetGIStatus().c_str());
    }
    if (!(exposure > 0.0))
    {
      exposure = automaticExposure();
    }
    for (auto& mapper : giMappers)
    {
      mapper->SetExposure(exposure);
      mapper->AlwaysRecomputeOn();
    }
    const auto f0 = Clock::now();
    window->Render();
    window->WaitForCompletion();
    const auto f1 = Clock::now();
    for (auto& mapper : giMappers)
    {
      mapper->AlwaysRecomputeOff();
    }
    std::printf("gpu per-vertex GI: first frame %.3f s (shaders, tables, spherical lights' first "
                "pass, GI pass), a frame that recomputes GI %.1f ms\n",
      Seconds(t1, t2), 1e3 * Seconds(f0, f1));
  }
  if (imageSpace)
  {
    window->Render(); // the first frame builds shaders and tables
    std::printf("image space (receivers at 1/%d, bilateral upsampling): ", receiverScale);
    const char* names[] = { "receiver setup", "splatting", "exponentiation", "indirect",
      "upsampling" };
    double frame = 0.0;
    for (int k = 0; k < 5; ++k)
    {
      const double ms = 1e3 * pass->GetPassTime(k);
      frame += ms;
      std::printf("%s %.1f ms, ", names[k], ms);
    }
    std::printf("frame %.1f ms\n", frame);
  }
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(output.c_str());
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();
  const auto t3 = Clock::now();
  std::printf("window: %s\n", DescribeRenderWindowContext(window).c_str());

  // Per pixel against Embree's image of the same view (cached): both
  // pictures decoded from sRGB, geometry pixels unsaturated in both.
  if ((imageSpace || Flag(args, "--pixel-error")) && !Flag(args, "--no-error"))
  {
    const std::string cachedImage = cache + "/image-" +
      std::to_string(std::hash<std::string>()(
        scene.Name + std::to_string(scene.Size[0]) + "x" + std::to_string(scene.Size[1]))) +
      "-spp" + std::to_string(pixelSpp) + ".vti";
    vtkSmartPointer<vtkImageData> truth;
    if (std::ifstream(cachedImage))
    {
      vtkNew<vtkXMLImageDataReader> reader;
      reader->SetFileName(cachedImage.c_str());
      reader->Update();
      truth = reader->GetOutput();
    }
    else
    {
      vtkNew<vtkPGIReferenceImage> tracer;
      for (auto& object : loaded.Objects)
      {
        tracer->AddInputData(object);
      }
      tracer->SetLighting(loaded.Lighting);
      tracer->SetCamera(loaded.Camera);
      tracer->SetSize(scene.Size);
      tracer->SetSamples(pixelSpp);
      tracer->Update();
      truth = tracer->GetOutput();
      vtkNew<vtkXMLImageDataWriter> writer;
      writer->SetFileName(cachedImage.c_str());
      writer->SetInputData(truth);
      writer->Write();
    }
    const std::string referencePNG = Option(args, "--reference-png", "");
    if (!referencePNG.empty() && WriteTonemappedPNG(truth, exposure, referencePNG))
    {
      std::printf("wrote %s (Embree's image, same exposure)\n", referencePNG.c_str());
    }
    vtkNew<vtkFloatArray> depth;
    window->GetZbufferData(0, 0, scene.Size[0] - 1, scene.Size[1] - 1, depth);
    grab->Modified();
    grab->Update();
    vtkDataArray* picture = grab->GetOutput()->GetPointData()->GetScalars();
    vtkDataArray* radiance = truth->GetPointData()->GetArray("Radiance");
    vtkDataArray* noise = truth->GetPointData()->GetArray("RadianceStdErr");
    double sq = 0.0, ref = 0.0, var = 0.0;
    long used = 0;
    for (vtkIdType i = 0; radiance && i < picture->GetNumberOfTuples(); ++i)
    {
      if (!(depth->GetValue(i) < 1.0f))
      {
        continue;
      }
      double a[3], b[3];
      bool saturated = false;
      for (int c = 0; c < 3; ++c)
      {
        a[c] = FromSRGB8(static_cast<unsigned char>(picture->GetComponent(i, c))) / exposure;
        b[c] = radiance->GetComponent(i, c);
        saturated = saturated || picture->GetComponent(i, c) >= 255.0 || exposure * b[c] >= 1.0;
      }
      if (saturated)
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        sq += (a[c] - b[c]) * (a[c] - b[c]);
        ref += b[c] * b[c];
        var += noise ? std::pow(noise->GetComponent(i, c), 2) : 0.0;
      }
      ++used;
    }
    std::printf("per pixel against the Embree image (%d samples, its own noise %.2f%%): relative "
                "RMSE %.2f%% over %ld geometry pixels (8-bit sRGB picture)\n",
      pixelSpp, ref > 0 ? 100 * std::sqrt(var / ref) : 0.0,
      ref > 0 ? 100 * std::sqrt(sq / ref) : 0.0, used);
  }

  for (std::size_t k = 0; !vtpPrefix.empty() && k < shaded.size(); ++k)
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName((vtpPrefix + "-" + scene.Objects[k].Name + ".vtp").c_str());
    writer->SetInputData(shaded[k]);
    writer->SetDataModeToAppended();
    writer->Write();
  }
  std::printf("settings: SH order %d, exp %s, %lld proxy spheres, %zu planes, %lld receivers\n",
    order, methodName.c_str(), static_cast<long long>(proxies.Leaves), proxies.Planes.size(),
    static_cast<long long>(receivers));
  std::printf("time: proxies %.2f s%s, SH shading %.3f s (%.0f ns per receiver), render %.3f s\n",
    proxies.Seconds, proxies.Cached ? " (cached)" : "", Seconds(t1, t2),
    1e9 * Seconds(t1, t2) / std::max<vtkIdType>(1, receivers), Seconds(t2, t3));

  // Error against the Embree reference (per vertex, cached).
  if (!Flag(args, "--no-error"))
  {
    double seconds = 0.0;
    const auto reference =
      SceneReference(scene, loaded, receiversIn, referenceSpp, cache, nullptr, seconds, error);
    if (reference.empty())
    {
      std::fprintf(stderr, "proxygi render: %s\n", error.c_str());
      return 1;
    }
    // The GPU reads back the total only.
    for (std::size_t k = 0; k < shaded.size(); ++k)
    {
      std::printf(
        "object %zu (%s): relative RMSE against the reference: ", k, scene.Objects[k].Name.c_str());
      if (!gpu)
      {
        std::printf("direct %.2f%%, ",
          100 * RelativeRMSE(shaded, "DirectShadowed", reference, "DirectShadowed", { k }));
      }
      std::printf(
        "total %.2f%%\n", 100 * RelativeRMSE(shaded, "Radiance", reference, "Radiance", { k }));
    }
    std::printf("error against the Embree reference (%d samples, %.1f s to trace, its own noise "
                "%.2f%%): ",
      referenceSpp, seconds, 100 * RelativeRMS(reference, "RadianceStdErr", "Radiance"));
    if (!gpu)
    {
      std::printf("direct light %.2f%%, ",
        100 * RelativeRMSE(shaded, "DirectShadowed", reference, "DirectShadowed"));
    }
    std::printf("total with one-bounce indirect %.2f%% (relative RMSE per vertex over all "
                "objects)\n",
      100 * RelativeRMSE(shaded, "Radiance", reference, "Radiance"));
  }
  std::printf("wrote %s (exposure %.3g)\n", output.c_str(), exposure);
  return 0;
}

} // namespace cli
} // namespace proxygi
