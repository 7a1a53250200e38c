// proxygi render (scene mode): the main job. Loads a scene (or the default:
// the bunny over a plane under the forest map), builds sphere proxies for its
// meshes, shades every vertex with SH soft shadows (vtkPGIGlobalIllumination),
// renders the result offscreen with VTK, and compares the per-vertex radiance
// with the Embree reference of the same scene (computed once and cached).
#include "proxygiBackends.h"
#include "proxygiCommands.h"
#include "proxygiImage.h"
#include "proxygiProgress.h"

#include "pgiAccuracyBudget.h"
#include "pgiEnvironmentMap.h"
#include "pgiOffscreenWindow.h"
#include "pgiSRGB.h"
#include "pgiScene.h"
#include "pgiSceneSetup.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"
#include "vtkPGIOccluder.h"
#include "vtkPGIReferenceImage.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSkybox.h>
#include <vtkStringArray.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

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

bool Given(const Args& args, const std::string& name)
{
  return std::find(args.begin(), args.end(), name) != args.end();
}

struct RenderOptions
{
  std::string Mode = "gpu";
  std::string AutoReason; // why --mode auto chose Mode
  int Order = 4, Spheres = 64, ReferenceSpp = 1024, ReceiverScale = 2, PixelSpp = 256;
  int SelfVisibility = 256; // rays per vertex of the meshes' own visibility; 0: the rules
  std::string BrightLights = "on", BrightShadows = "rays", Background = "map";
  std::string ProxyFit = "occlusion"; // the spheres' radii: fitted for occlusion, or bounding
  int BrightRays = 16;
  int PlaneDirections = 64; // the planes' bounce: look-ups per receiver (0: one point)
  int IndirectOrder = 0;    // the shadowed bounce's SH order (0: --order)
  int ExpMethod = vtkPGIGISettings::EXP_HYB;
  int Blocking = vtkPGIGISettings::BLOCKING_PER_SPHERE; // --blocking sphere|object
  std::string MethodName = "HYB", IndirectName = "shadowed";
  double HierarchyAngle = 25.0, Exposure = 0.0;
  std::string Output, Cache, Vtp, ReferencePNG;
  bool NoError = false, PixelError = false;
  // --error / --time: the budget chooses the knobs (budget::Choose).
  budget::Budget Budget;
  std::string BudgetModel;
  budget::Choice Chosen;
  // What the choice was made from (ChooseForBudget), for the check.
  budget::Model Model;
  budget::SceneFeatures Features;
  std::function<bool(const budget::Knobs&)> Allowed;
  // The routes a budget may choose (filter, mapper) and the GL renderer
  // the GPU mapper would run on.
  std::array<bool, 2> Routes{ { true, false } };
  std::string Renderer;
  int CheckSpp = 0; // --check: Embree samples per vertex of the check (0: none)
  bool Budgeted() const { return this->Budget.Any(); }
  bool Gpu() const { return this->Mode == "gpu"; }
  bool ImageSpace() const { return this->Mode == "image-space"; }
  bool Vertex() const { return this->Mode == "vertex"; }
};

// Options, checked; the knobs a mode has no use for are said, not dropped.
bool ParseRenderOptions(const Args& args, RenderOptions& o)
{
  bool ok = true;
  // Output names before the renderer probe: a refusal touches no GL.
  o.Output = Option(args, "-o", "proxygi-render.png");
  o.ReferencePNG = Option(args, "--reference-png", "");
  if (!HasExtension("render", "-o", o.Output, { ".png" }) ||
    (!o.ReferencePNG.empty() &&
      !HasExtension("render", "--reference-png", o.ReferencePNG, { ".png" })))
  {
    return false;
  }
  o.Mode = Option(args, "--mode", "auto");
  o.BudgetModel = Option(args, "--budget-model", "");
  o.CheckSpp = static_cast<int>(NumberOption(args, "--check", 0, ok));
  if (o.CheckSpp < 0 || (o.CheckSpp > 0 && !(Given(args, "--error") || Given(args, "--time"))))
  {
    vtkLogF(ERROR,
      "proxygi render: --check N (N > 0 samples per vertex) checks a budget: give "
      "--error or --time with it");
    return false;
  }
  bool budgetOk = true;
  double value = 0.0;
  if (Given(args, "--error"))
  {
    budgetOk = budget::ParseErrorBudget(Option(args, "--error", ""), value);
    o.Budget.SetError(value);
  }
  if (Given(args, "--time"))
  {
    budgetOk = budgetOk && budget::ParseTimeBudget(Option(args, "--time", ""), value);
    o.Budget.SetSeconds(value);
  }
  if (!budgetOk)
  {
    vtkLogF(ERROR,
      "proxygi render: --error takes a fraction or a percentage (0.05, 5%%), "
      "--time seconds or milliseconds (0.2, 0.2s, 200ms)");
    return false;
  }
  if (o.Budgeted() && o.Mode == "image-space")
  {
    vtkLogF(ERROR,
      "proxygi render: --error and --time choose between the CPU filter's and the GPU mapper's "
      "knobs (--mode auto, vertex or gpu): the image-space pass is not a candidate of the "
      "budget model");
    return false;
  }
  std::string gl;
  if (o.Mode == "auto" || (o.Budgeted() && o.Mode == "gpu"))
  {
    vtkSmartPointer<vtkRenderWindow> probe = NewOffscreenRenderWindow();
    gl = probe ? DescribeRenderWindowContext(probe) : std::string();
    o.Renderer = gl.empty() ? std::string("none found") : gl;
  }
  o.Routes = { o.Mode != "gpu", o.Mode == "gpu" || (o.Budgeted() && o.Mode == "auto") };
  if (o.Budgeted() && o.Mode == "auto")
  {
    // The choice sets the mode (ChooseForBudget); the filter's defaults
    // until then.
    o.Mode = "vertex";
    o.AutoReason = "--error/--time: the budget chose the route";
  }
  if (o.Mode == "auto")
  {
    // The fastest route: on a software rasteriser the CPU filter shades
    // several times faster than the GI mapper runs there.
    const bool software = budget::SoftwareRenderer(gl);
    o.Mode = software ? "vertex" : "gpu";
    o.AutoReason = software
      ? "the GL renderer (" + gl + ") is a software one: the CPU filter shades, GL only draws"
      : "the GL renderer (" + o.Renderer + ") is a hardware one: the GI mapper shades on the GPU";
  }
  // The CPU filter's default: order-6 shadows with an order-4 bounce, which
  // costs about what order 4 did (AccuracyTime.md, section 21); the GPU
  // modes run the bounce at the shading order, so they keep 4.
  o.Order = static_cast<int>(NumberOption(args, "--order", o.Mode == "vertex" ? 6 : 4, ok));
  o.Spheres = static_cast<int>(NumberOption(args, "--spheres", 64, ok));
  o.ReferenceSpp = static_cast<int>(NumberOption(args, "--reference-spp", 1024, ok));
  o.MethodName = Option(args, "--method", "HYB");
  // The image-space pass has the unshadowed bounce only: its default.
  o.IndirectName = Option(args, "--indirect", o.Mode == "image-space" ? "unshadowed" : "shadowed");
  // Hierarchy cuts are the CPU filter's: on by default there only.
  o.HierarchyAngle = NumberOption(args, "--hierarchy", o.Mode == "vertex" ? 25.0 : 0.0, ok);
  o.ReceiverScale = static_cast<int>(NumberOption(args, "--scale", 2, ok));
  o.SelfVisibility = static_cast<int>(NumberOption(args, "--self-visibility", 256, ok));
  o.BrightLights = Option(args, "--bright-lights", "on");
  o.Background = Option(args, "--background", "map");
  o.BrightShadows = Option(args, "--bright-shadows", "rays");
  o.BrightRays = static_cast<int>(NumberOption(args, "--bright-rays", 16, ok));
  o.PlaneDirections = static_cast<int>(NumberOption(args, "--plane-directions", 64, ok));
  o.IndirectOrder =
    static_cast<int>(NumberOption(args, "--indirect-order", o.Mode == "vertex" ? 4 : 0, ok));
  o.ProxyFit = Option(args, "--proxy-fit", "occlusion");
  const std::string blocking = Option(args, "--blocking", "sphere");
  o.Blocking = blocking == "object" ? vtkPGIGISettings::BLOCKING_PER_OBJECT
                                    : vtkPGIGISettings::BLOCKING_PER_SPHERE;
  o.PixelSpp = static_cast<int>(NumberOption(args, "--pixel-reference-spp", 256, ok));
  o.Exposure = NumberOption(args, "--exposure", 0.0, ok);
  o.Cache = Option(args, "--cache", "proxygi-cache");
  o.Vtp = Option(args, "--vtp", "");
  o.NoError = Flag(args, "--no-error");
  o.PixelError = o.ImageSpace() || Flag(args, "--pixel-error");
  if (!ok)
  {
    return false;
  }
  if ((!o.Gpu() && !o.Vertex() && !o.ImageSpace()) ||
    (o.ReceiverScale != 1 && o.ReceiverScale != 2 && o.ReceiverScale != 4 &&
      o.ReceiverScale != 8) ||
    o.PixelSpp < 1 || o.SelfVisibility < 0 || o.SelfVisibility > 65536 ||
    (o.BrightLights != "on" && o.BrightLights != "off") ||
    (o.BrightShadows != "rays" && o.BrightShadows != "proxies") ||
    (o.Background != "map" && o.Background != "none") || o.BrightRays < 1 || o.BrightRays > 256 ||
    o.PlaneDirections < 0 || o.PlaneDirections > 1024 || o.IndirectOrder < 0 ||
    o.IndirectOrder > 8 || (o.ProxyFit != "bounding" && o.ProxyFit != "occlusion") ||
    (blocking != "sphere" && blocking != "object"))
  {
    vtkLogF(ERROR,
      "proxygi render: --mode gpu|vertex|image-space, --scale 1|2|4|8, "
      "--pixel-reference-spp >= 1, 0 <= --self-visibility <= 65536, --bright-lights on|off, "
      "--bright-shadows rays|proxies, 1 <= --bright-rays <= 256, --background map|none, "
      "0 <= --plane-directions <= 1024, 0 <= --indirect-order <= 8, "
      "--proxy-fit bounding|occlusion, --blocking sphere|object");
    return false;
  }
  if (o.IndirectName != "shadowed" && o.IndirectName != "unshadowed" && o.IndirectName != "off")
  {
    vtkLogF(ERROR, "proxygi render: --indirect shadowed|unshadowed|off");
    return false;
  }
  const std::map<std::string, int> methods = { { "PS", vtkPGIGISettings::EXP_PS },
    { "PS*", vtkPGIGISettings::EXP_PS_STAR }, { "OL", vtkPGIGISettings::EXP_OL },
    { "HYB", vtkPGIGISettings::EXP_HYB } };
  if (!methods.count(o.MethodName) || o.Order < 2 || o.Order > 8 || o.Spheres < 1 ||
    o.ReferenceSpp < 1 || o.HierarchyAngle < 0.0 || o.HierarchyAngle > 89.0)
  {
    vtkLogF(ERROR,
      "proxygi render: need --method HYB|OL|PS*|PS, 2 <= --order <= 8, "
      "--spheres >= 1, --reference-spp >= 1, 0 <= --hierarchy <= 89");
    return false;
  }
  o.ExpMethod = methods.at(o.MethodName);
  // What does not apply in this mode.
  const auto notFor = [&](const char* option, const char* why)
  {
    if (Given(args, option))
    {
      std::printf("note: %s does not apply to --mode %s (%s)\n", option, o.Mode.c_str(), why);
    }
  };
  if (!o.ImageSpace())
  {
    notFor("--scale", "the receiver buffer is the image-space pass's");
  }
  if (!o.Vertex())
  {
    notFor("--self-visibility", "the GPU backends run the self-shadow rules");
    const char* sh = "the GPU backends keep the whole map in the SH";
    notFor("--bright-lights", sh);
    notFor("--bright-shadows", sh);
    notFor("--bright-rays", sh);
  }
  // Knobs of the shadowed bounce alone.
  const auto shadowedOnly = [&](const char* option, const char* what)
  {
    if (o.ImageSpace())
    {
      notFor(option, "the image-space pass has the unshadowed bounce only");
    }
    else if (o.IndirectName != "shadowed" && Given(args, option))
    {
      std::printf("note: %s does not apply to --indirect %s (it is %s)\n", option,
        o.IndirectName.c_str(), what);
    }
  };
  shadowedOnly("--indirect-order", "the shadowed bounce's order");
  shadowedOnly("--blocking", "how the shadowed bounce's lights block");
  if (o.ImageSpace())
  {
    notFor("--plane-directions", "the image-space pass samples the planes' light at one point");
    notFor("--reference-spp", "image-space is compared per pixel: --pixel-reference-spp");
    notFor("--vtp", "image-space has no per-vertex results");
  }
  if (!o.PixelError)
  {
    notFor("--pixel-reference-spp", "no per-pixel error without --pixel-error");
    notFor("--reference-png", "no Embree image without --pixel-error");
  }
  if (o.NoError)
  {
    notFor("--reference-spp", "--no-error");
    notFor("--pixel-reference-spp", "--no-error");
  }
  return true;
}

void UseKnobs(const budget::Knobs& k, RenderOptions& o)
{
  o.Order = k.Order;
  o.IndirectOrder = k.IndirectOrder;
  o.Spheres = k.Spheres;
  o.SelfVisibility = k.SelfVisibility;
  o.HierarchyAngle = k.HierarchyAngle;
  o.ExpMethod = k.ExpMethod;
  o.MethodName = vtkPGIGISettings::ExpMethodName(k.ExpMethod);
  o.Blocking = k.Blocking;
  o.BrightRays = k.BrightLightRays;
  if (o.IndirectName != "off")
  {
    o.IndirectName = k.ShadowedIndirect ? "shadowed" : "unshadowed";
  }
}

// --error / --time: the knobs from the budget model (the one that ships, or
// --budget-model), among the candidates that agree with the knobs given.
bool ChooseForBudget(
  const Args& args, RenderOptions& o, const SceneDescription& scene, const LoadedScene& loaded)
{
  o.Model = budget::Model::Default();
  budget::Model& model = o.Model;
  std::string error;
  if (!o.BudgetModel.empty() && !model.Load(o.BudgetModel, error))
  {
    vtkLogF(ERROR, "proxygi render: %s", error.c_str());
    return false;
  }
  budget::SceneFeatures& features = o.Features;
  if (!SceneBudgetFeatures(scene, loaded, features, error))
  {
    vtkLogF(ERROR, "proxygi render: %s", error.c_str());
    return false;
  }
  // The knobs given on the command line, as given.
  const bool order = Given(args, "--order"), spheres = Given(args, "--spheres"),
             self = Given(args, "--self-visibility"), indirect = Given(args, "--indirect"),
             indirectOrder = Given(args, "--indirect-order"),
             hierarchy = Given(args, "--hierarchy"), method = Given(args, "--method"),
             brightRays = Given(args, "--bright-rays"), blocking = Given(args, "--blocking");
  budget::Knobs asGiven = { o.Order, o.IndirectOrder, o.Spheres, o.SelfVisibility,
    o.IndirectName == "shadowed", o.HierarchyAngle };
  asGiven.ExpMethod = o.ExpMethod;
  asGiven.BrightLightRays = o.BrightRays;
  asGiven.Blocking = o.Blocking;
  o.Allowed = [=](const budget::Knobs& k)
  {
    return (!order || k.Order == asGiven.Order) && (!spheres || k.Spheres == asGiven.Spheres) &&
      (!self || k.SelfVisibility == asGiven.SelfVisibility) &&
      (!indirect || k.ShadowedIndirect == asGiven.ShadowedIndirect) &&
      (!indirectOrder || k.IndirectOrder == asGiven.IndirectOrder) &&
      (!hierarchy || k.HierarchyAngle == asGiven.HierarchyAngle) &&
      (!method || k.ExpMethod == asGiven.ExpMethod) &&
      (!brightRays || k.BrightLightRays == asGiven.BrightLightRays) &&
      (!blocking || k.Blocking == asGiven.Blocking);
  };
  // The GPU mapper's candidates where the model has them, with times of
  // this kind of renderer (auto); --mode gpu takes them in any case, said.
  std::string why;
  const bool mapperTimes = budget::MapperTimesApply(model, o.Renderer, why);
  if (o.Routes[1] && !o.Routes[0] && !model.HasRoute(budget::Route::Mapper))
  {
    vtkLogF(ERROR, "proxygi render: budget with --mode gpu: %s", why.c_str());
    return false;
  }
  if (o.Routes[1] && !mapperTimes)
  {
    std::printf(
      "budget: %s%s\n", o.Routes[0] ? "the CPU filter's candidates only: " : "note: ", why.c_str());
  }
  const bool filterRoute = o.Routes[0], mapperRoute = o.Routes[1] && (mapperTimes || !o.Routes[0]);
  const auto given = o.Allowed;
  o.Allowed = [=](const budget::Knobs& k)
  { return (k.Backend == budget::Route::Filter ? filterRoute : mapperRoute) && given(k); };
  const auto& allowed = o.Allowed;
  const budget::Budget& b = o.Budget;
  o.Chosen = budget::Choose(model, features, b, allowed);
  if (o.Chosen.Candidate < 0)
  {
    vtkLogF(ERROR, "proxygi render: budget: %s", o.Chosen.Reason.c_str());
    return false;
  }
  const budget::Knobs& k = o.Chosen.Settings;
  UseKnobs(k, o);
  if (filterRoute && mapperRoute)
  {
    o.Mode = k.Backend == budget::Route::Mapper ? "gpu" : "vertex";
    o.AutoReason = std::string("--error/--time: the budget chose the ") +
      (k.Backend == budget::Route::Mapper ? "GPU mapper" : "CPU filter") + " on " + o.Renderer;
  }
  std::string asked;
  char text[64];
  if (b.HasError)
  {
    std::snprintf(text, sizeof(text), "error %g%%", 100.0 * b.Error);
    asked = text;
  }
  if (b.HasTime)
  {
    std::snprintf(text, sizeof(text), "%stime %g ms", asked.empty() ? "" : ", ", 1e3 * b.Seconds);
    asked += text;
  }
  std::printf("budget: %s -> %s\n", asked.c_str(), k.Describe().c_str());
  const bool gpu = k.Backend == budget::Route::Mapper;
  std::printf("budget: predicted error %.1f%% (x/%.2f), %s %.3f s on %s; %s\n",
    100.0 * o.Chosen.PredictedError, std::exp(model.ErrorSpread), gpu ? "a GI frame" : "SH shading",
    o.Chosen.PredictedSeconds, (gpu ? model.MapperRenderer : model.Machine).c_str(),
    o.Chosen.Reason.c_str());
  if (!o.Chosen.Met)
  {
    std::printf("budget: %s\n",
      o.Chosen.Valid ? "cannot be met; running the closest reachable settings"
                     : "not a usable budget; running the closest reachable settings");
  }
  return true;
}

// One settings object for every consumer of this run.
vtkSmartPointer<vtkPGIGISettings> MakeSettings(
  const RenderOptions& o, const SceneDescription& scene)
{
  auto settings = vtkSmartPointer<vtkPGIGISettings>::New();
  ConfigureSettings(settings, scene);
  settings->SetOrder(o.Order);
  settings->SetExpMethod(o.ExpMethod);
  settings->SetIndirect(scene.Indirect && o.IndirectName != "off");
  settings->SetIndirectMode(o.IndirectName == "shadowed"
      ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
      : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  settings->SetHierarchyAngle(o.HierarchyAngle);
  settings->SetBrightLights(o.BrightLights == "on");
  settings->SetBrightLightRays(o.BrightRays);
  settings->SetSphericalLightBlocking(o.Blocking);
  settings->SetPlaneBounceDirections(o.PlaneDirections);
  settings->SetIndirectOrder(o.IndirectOrder);
  SetBackendPlaneDefaults(settings, o.Mode);
  return settings;
}

// What the chosen backend runs of the settings: every replacement said.
vtkSmartPointer<vtkPGIGISettings> ReportSettings(vtkPGIGISettings* settings, const RenderOptions& o,
  const SceneProxies& proxies, const LoadedScene& loaded)
{
  const vtkPGIGISettings::Support& support = BackendSupport(o.Mode);
  auto effective = vtkSmartPointer<vtkPGIGISettings>::New();
  std::vector<std::string> notes;
  vtkPGILighting* lighting = loaded.Lighting;
  settings->Resolve(support, static_cast<int>(proxies.Planes.size()), effective, notes,
    static_cast<int>(lighting->GetSphereLights().size() + lighting->GetPointLights().size()));
  for (const std::string& note : notes)
  {
    std::printf("not honoured: %s\n", note.c_str());
  }
  return effective;
}

// The CPU filter on every object (--mode vertex).
std::vector<vtkSmartPointer<vtkPolyData>> ShadeOnCPU(
  const std::vector<vtkSmartPointer<vtkPolyData>>& receivers, vtkPGIGISettings* settings,
  const SceneDescription& scene, const LoadedScene& loaded, const SceneProxies& proxies,
  vtkPGIOccluder* occluder)
{
  // One filter for every object: its bake (the light in SH, its tables, the
  // spherical lights' first pass) is built once; each new receiver mesh only
  // costs its own shading.
  vtkNew<vtkPGIGlobalIllumination> gi;
  ConfigureGlobalIllumination(gi, scene, loaded, proxies);
  gi->SetSettings(settings);
  gi->SetOccluder(occluder);
  std::vector<vtkSmartPointer<vtkPolyData>> shaded = ShadeEach(gi, receivers);
  // The first object's plan whole, then each other object's lines that
  // differ from it under its name (a ground's clusters scaled to the union,
  // its own stages).
  std::vector<std::string> first;
  for (std::size_t k = 0; k < shaded.size(); ++k)
  {
    auto* plan = vtkStringArray::SafeDownCast(shaded[k]->GetFieldData()->GetAbstractArray("Plan"));
    for (vtkIdType i = 0; plan && i < plan->GetNumberOfValues(); ++i)
    {
      const std::string& line = plan->GetValue(i);
      if (k == 0)
      {
        first.push_back(line);
        std::printf("plan: %s\n", line.c_str());
      }
      else if (std::find(first.begin(), first.end(), line) == first.end())
      {
        std::printf("plan (%s): %s\n",
          k < scene.Objects.size() ? scene.Objects[k].Name.c_str() : "object", line.c_str());
      }
    }
  }
  return shaded;
}

// The environment behind the scene, drawn as the pictures are: exposure
// times radiance, sRGB bytes (Embree's image shows the same). Null for a
// uniform sky (the grey background stays).
vtkSmartPointer<vtkImageData> EnvironmentBackground(vtkPGILighting* lighting, double exposure)
{
  const proxygi::EnvironmentMap* map = nullptr;
  std::string error;
  if (!lighting->GetEnvironmentImage() && !lighting->GetEnvironmentFileName())
  {
    return nullptr;
  }
  if (!lighting->GetEnvironment(map, error) || map->GetWidth() < 4)
  {
    return nullptr;
  }
  const int w = map->GetWidth(), h = map->GetHeight();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* bytes = static_cast<unsigned char*>(image->GetScalarPointer());
  const std::vector<float>& rgb = map->GetRGB();
  const double scale = exposure * lighting->GetEnvironmentScale();
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      // VTK's rows run bottom-up, the map's top-down; its columns run the
      // other way round the sky from the skybox's.
      const float* texel = &rgb[3 * (static_cast<std::size_t>(j) * w + i)];
      unsigned char* out = &bytes[3 * (static_cast<std::size_t>(h - 1 - j) * w + (w - 1 - i))];
      for (int c = 0; c < 3; ++c)
      {
        out[c] = proxygi::ToSRGB8(std::min(1.0, scale * texel[c]));
      }
    }
  }
  return image;
}

void AddEnvironmentBackground(vtkRenderer* renderer, vtkImageData* image, double rotationDegrees)
{
  vtkNew<vtkTexture> texture;
  texture->SetInputData(image);
  texture->InterpolateOn();
  texture->RepeatOn();
  vtkNew<vtkSkybox> sky;
  sky->SetTexture(texture);
  sky->SetProjectionToSphere();
  sky->SetFloorPlane(0.0f, 0.0f, 1.0f, 0.0f);
  // Checked against Embree's image of the same view (city map, turned and
  // not): the skybox's azimuth starts half a turn from the map's.
  const double a = vtkMath::RadiansFromDegrees(rotationDegrees);
  sky->SetFloorRight(static_cast<float>(-std::sin(a)), static_cast<float>(std::cos(a)), 0.0f);
  renderer->AddActor(sky);
}

// GPU mode after the first frame: the per-vertex radiance read back (the
// error and the exposure need it), then one frame that recomputes GI timed.
bool ReadBackGPU(vtkRenderWindow* window,
  const std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>>& mappers,
  const SceneDescription& scene, std::vector<vtkSmartPointer<vtkPolyData>>& shaded,
  double& exposure, double& frameSeconds)
{
  std::string error;
  if (!ReadBackRadiance(mappers, shaded, error))
  {
    vtkLogF(ERROR, "proxygi render: %s", error.c_str());
    return false;
  }
  for (std::size_t k = 0; k < mappers.size(); ++k)
  {
    std::printf("gpu: object %zu (%s): %s\n", k, scene.Objects[k].Name.c_str(),
      mappers[k]->GetGIStatus().c_str());
  }
  if (!(exposure > 0.0))
  {
    exposure = AutomaticExposure(shaded);
  }
  for (auto& mapper : mappers)
  {
    mapper->SetExposure(exposure);
  }
  frameSeconds = TimeGIFrame(window, mappers);
  return true;
}

// Image-space mode: the first frame built shaders and tables; the second is timed per pass.
double TimeImageSpace(vtkRenderWindow* window, vtkPGIImageSpaceGIPass* pass, int scale)
{
  window->Render();
  std::printf("image space (receivers at 1/%d, bilateral upsampling): ", scale);
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
  std::printf("image space: %s\n", pass->GetStatus().c_str());
  return 1e-3 * frame;
}

} // namespace

int RunRenderScene(const Args& args, const std::string& scenePath)
{
  // The scene first: a refusal touches no GL (the options probe the
  // renderer for --mode auto).
  SceneDescription scene = DefaultScene();
  std::string error;
  if (!scenePath.empty() && !LoadScene(scenePath, scene, error))
  {
    vtkLogF(ERROR, "proxygi render: %s", error.c_str());
    return 1;
  }
  RenderOptions o;
  if (!ParseRenderOptions(args, o))
  {
    return 2;
  }
  const std::string size = Option(args, "--size", "");
  if (!size.empty() && std::sscanf(size.c_str(), "%dx%d", &scene.Size[0], &scene.Size[1]) != 2)
  {
    vtkLogF(ERROR, "proxygi render: --size expects WxH");
    return 2;
  }
  LoadedScene loaded;
  if (!BuildScene(scene, loaded, error))
  {
    vtkLogF(ERROR, "proxygi render: %s", error.c_str());
    return 1;
  }
  std::printf("scene: %s\n", scene.Name.c_str());
  if (o.Budgeted() && !ChooseForBudget(args, o, scene, loaded))
  {
    return 2;
  }
  if (!o.AutoReason.empty())
  {
    std::printf("mode: %s (auto: %s; --mode gpu|vertex|image-space to choose)\n", o.Mode.c_str(),
      o.AutoReason.c_str());
  }

  SceneProxies proxies;
  SetupProgress progress("proxygi render");
  std::vector<vtkSmartPointer<vtkPolyData>> receiversIn, shaded;
  vtkIdType receivers = 0;
  vtkSmartPointer<vtkPGIGISettings> settings, effective;
  Clock::time_point t1, t2;
  double occluderSeconds = 0.0;
  // --check N: the choice's error estimated against Embree at N samples
  // per vertex (EstimatedRelativeRMSE, against a reference of
  // --reference-spp) and its time measured (the GPU mapper's: run once in
  // a window of its own, a GI frame timed); the model's predictions for
  // this scene scaled by measured / predicted and the choice made again
  // among the routes the budget chose from (budget::Recheck). A new choice
  // is prepared, shaded and checked too, and the one of the two that
  // serves the budget better is kept.
  std::vector<vtkSmartPointer<vtkPolyData>> cheap;
  struct Attempt
  {
    SceneProxies Proxies;
    std::vector<vtkSmartPointer<vtkPolyData>> Receivers, Shaded;
    vtkIdType Count = 0;
    vtkSmartPointer<vtkPGIGISettings> Settings, Effective;
    Clock::time_point T1, T2;
    budget::Choice Chosen;
    std::string Mode;
    double Estimated = 0.0, Seconds = 0.0;
  } first;
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    proxies = SceneProxies();
    if (!BuildSceneProxies(scene, loaded, o.Spheres, o.Cache, proxies, error, &progress,
          o.ProxyFit == "occlusion" ? ProxyFit::Occlusion : ProxyFit::Bounding))
    {
      vtkLogF(ERROR, "proxygi render: %s%s", error.c_str(),
        progress.Interrupted() ? "; nothing written, nothing cached" : "");
      return progress.Interrupted() ? InterruptedExitCode : 1;
    }
    for (const auto& fit : proxies.Fits)
    {
      std::printf("proxies of %s fitted for occlusion: rays where spheres and mesh disagree "
                  "%.1f%% -> %.1f%% of those the mesh blocks (bias %+.1f%% -> %+.1f%%)\n",
        fit.Object.c_str(), 100.0 * fit.ErrorBefore, 100.0 * fit.ErrorAfter, 100.0 * fit.BiasBefore,
        100.0 * fit.BiasAfter);
    }
    receiversIn = SceneReceivers(loaded);
    if (o.Vertex() && o.SelfVisibility > 0)
    {
      double seconds = 0.0;
      if (!AddSelfVisibility(
            scene, receiversIn, o.Order, o.SelfVisibility, o.Cache, seconds, error, &progress))
      {
        vtkLogF(ERROR, "proxygi render: %s", error.c_str());
        return progress.Interrupted() ? InterruptedExitCode : 1;
      }
      std::printf("self-visibility: %d rays per vertex, %s\n", o.SelfVisibility,
        seconds > 0.0 ? ("traced in " + std::to_string(seconds) + " s").c_str() : "cached");
    }
    receivers = 0;
    for (auto& s : receiversIn)
    {
      receivers += s->GetNumberOfPoints();
    }
    settings = MakeSettings(o, scene);
    effective = ReportSettings(settings, o, proxies, loaded);

    // The bright lights' shadows from the real meshes, as the reference's:
    // their Embree scene is built once, before the shading is timed.
    const auto t0 = Clock::now();
    vtkSmartPointer<vtkPGIOccluder> occluder =
      o.Vertex() && o.BrightShadows == "rays" ? SceneOccluder(receiversIn) : nullptr;
    std::string occluderError;
    if (occluder && !occluder->Prepare(occluderError))
    {
      vtkLogF(ERROR, "proxygi render: occluder: %s", occluderError.c_str());
      return 1;
    }
    occluderSeconds = occluder ? Seconds(t0, Clock::now()) : 0.0;
    // Shading: the CPU filter before rendering (vertex), or the GPU while rendering.
    t1 = Clock::now();
    if (o.Vertex())
    {
      shaded = ShadeOnCPU(receiversIn, settings, scene, loaded, proxies, occluder);
    }
    t2 = Clock::now();
    if (!o.Budgeted() || o.CheckSpp <= 0 || !(o.Vertex() || o.Gpu()))
    {
      break;
    }
    double seconds = Seconds(t1, t2);
    if (o.Gpu())
    {
      bool cutShort = false;
      std::string renderer;
      if (!ShadeOnGPU(receiversIn, settings, loaded, proxies, scene.Size, shaded, seconds, cutShort,
            renderer, error))
      {
        vtkLogF(ERROR, "proxygi render: budget check: %s", error.c_str());
        return 1;
      }
    }
    double cheapSeconds = 0.0;
    if (cheap.empty())
    {
      cheap = SceneReference(scene, loaded, SceneReceivers(loaded), o.CheckSpp, o.Cache, nullptr,
        cheapSeconds, error, 7, true, &progress);
      if (cheap.empty())
      {
        vtkLogF(ERROR, "proxygi render: budget check: %s", error.c_str());
        return progress.Interrupted() ? InterruptedExitCode : 1;
      }
    }
    const double estimated = EstimatedRelativeRMSE(shaded, cheap, o.CheckSpp, o.ReferenceSpp);
    std::printf("budget check: Embree at %d samples per vertex estimates %.2f%% against %d "
                "samples (predicted %.2f%%), %s %.3f s (predicted %.3f s)\n",
      o.CheckSpp, 100.0 * estimated, o.ReferenceSpp, 100.0 * o.Chosen.PredictedError,
      o.Gpu() ? "a GI frame" : "SH shading", seconds, o.Chosen.PredictedSeconds);
    if (attempt == 1)
    {
      // An estimate just under the budget may be the check's own error.
      char margin[96] = "";
      if (o.Budget.HasError && o.Model.CheckMargin > 1.0)
      {
        std::snprintf(margin, sizeof(margin),
          " (an estimate meets it when %.2f times it does: the check's margin)",
          o.Model.CheckMargin);
      }
      if (budget::FirstServesBetter(
            o.Budget, first.Estimated, first.Seconds, estimated, seconds, o.Model.CheckMargin))
      {
        std::printf("budget check: the first choice serves the budget better%s: kept (%s)\n",
          margin, first.Chosen.Settings.Describe().c_str());
        proxies = first.Proxies;
        receiversIn = first.Receivers;
        shaded = first.Shaded;
        receivers = first.Count;
        settings = first.Settings;
        effective = first.Effective;
        t1 = first.T1;
        t2 = first.T2;
        o.Chosen = first.Chosen;
        o.Mode = first.Mode;
        UseKnobs(o.Chosen.Settings, o);
      }
      else
      {
        std::printf("budget check: the new choice serves the budget better%s: kept\n", margin);
      }
      break;
    }
    // Among the candidates the budget chose from: both routes under --mode
    // auto where the mapper's times hold, else the mode's own.
    const budget::Choice again =
      budget::Recheck(o.Model, o.Features, o.Budget, o.Chosen, estimated, seconds, o.Allowed);
    std::printf("budget check: this scene's errors scaled by %.2f (candidates %s; the others "
                "by %.2f), its times by %.2f\n",
      o.Features.ErrorScale, budget::CheckFamilyName(o.Chosen.Settings).c_str(),
      o.Features.OtherErrorScale, o.Features.TimeScale);
    if (again.Candidate == o.Chosen.Candidate)
    {
      std::printf("budget check: the choice stands (%s)\n", again.Settings.Describe().c_str());
      o.Chosen = again;
      break;
    }
    first = { proxies, receiversIn, shaded, receivers, settings, effective, t1, t2, o.Chosen,
      o.Mode, estimated, seconds };
    o.Chosen = again;
    UseKnobs(again.Settings, o);
    const std::string mode = again.Settings.Backend == budget::Route::Mapper ? "gpu" : "vertex";
    std::printf("budget check: chose again -> %s, predicted %.1f%% in %.3f s; %s%s\n",
      again.Settings.Describe().c_str(), 100.0 * again.PredictedError, again.PredictedSeconds,
      again.Reason.c_str(), mode == o.Mode ? "" : ("; mode " + mode).c_str());
    o.Mode = mode;
  }
  // The GPU mapper shades again while rendering: the check's read-back goes.
  if (o.Gpu())
  {
    shaded.clear();
    t1 = Clock::now();
  }
  double exposure = o.Exposure;
  if (!(exposure > 0.0) && o.Vertex())
  {
    exposure = AutomaticExposure(shaded);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.3, 0.3, 0.32);
  std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> giMappers;
  vtkNew<vtkPGIImageSpaceGIPass> pass;
  if (o.Gpu())
  {
    giMappers = AddGPUMappers(renderer, receiversIn, settings, loaded, proxies, exposure);
  }
  else if (o.ImageSpace())
  {
    AddImageSpacePass(
      renderer, pass, scene, receiversIn, settings, loaded, proxies, o.ReceiverScale, o.Exposure);
    pass->MeasurePassTimesOn();
  }
  else
  {
    AddVertexColourActors(renderer, shaded, exposure);
  }
  renderer->SetActiveCamera(loaded.Camera);
  renderer->ResetCameraClippingRange();
  // The map behind the scene (--background none: grey). The GPU mode knows
  // its exposure after the first frame: the picture is then redrawn.
  vtkSmartPointer<vtkImageData> background = o.Background == "map"
    ? EnvironmentBackground(loaded.Lighting, exposure > 0.0 ? exposure : 1.0)
    : nullptr;
  if (background)
  {
    AddEnvironmentBackground(renderer, background, loaded.Lighting->GetEnvironmentRotation());
  }
  // EGL without a display, the X server's window with one (Xvfb included).
  std::string windowPath;
  vtkSmartPointer<vtkRenderWindow> window = NewOffscreenRenderWindow(&windowPath);
  if (!window)
  {
    vtkLogF(ERROR, "proxygi render: no offscreen OpenGL: %s", windowPath.c_str());
    return 1;
  }
  window->SetSize(scene.Size[0], scene.Size[1]);
  window->AddRenderer(renderer);
  window->Render();
  double giFrame = 0.0;
  if (o.Gpu())
  {
    window->WaitForCompletion();
    t2 = Clock::now();
    if (!ReadBackGPU(window, giMappers, scene, shaded, exposure, giFrame))
    {
      return 1;
    }
    std::printf("gpu per-vertex GI: first frame %.3f s (shaders, tables, spherical lights' first "
                "pass, GI pass), a frame that recomputes GI %.1f ms\n",
      Seconds(t1, t2), 1e3 * giFrame);
  }
  if (o.ImageSpace())
  {
    if (!(exposure > 0.0))
    {
      exposure = ExposureFromPicture(window, pass);
    }
    giFrame = TimeImageSpace(window, pass, o.ReceiverScale);
    t2 = Clock::now();
  }
  if (background && !o.Vertex())
  {
    background->DeepCopy(EnvironmentBackground(loaded.Lighting, exposure));
    background->Modified();
  }
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  if (!WritePNG(grab->GetOutput(), o.Output))
  {
    vtkLogF(ERROR, "proxygi render: cannot write %s", o.Output.c_str());
    return 1;
  }
  const auto t3 = Clock::now();
  std::printf("window: %s\n", windowPath.c_str());
  const int pixelSpp = o.PixelSpp;
  const std::string& cache = o.Cache;

  // Per pixel against Embree's image of the same view (cached): both
  // pictures decoded from sRGB, geometry pixels unsaturated in both.
  if (o.PixelError && !o.NoError)
  {
    // Keyed by all the image depends on: the scene, the view and the size.
    std::ostringstream view;
    view.precision(17);
    view << DescribeScene(scene) << '|' << scene.Size[0] << 'x' << scene.Size[1];
    for (int c = 0; c < 3; ++c)
    {
      view << '|' << scene.CameraPosition[c] << '|' << scene.FocalPoint[c] << '|'
           << scene.ViewUp[c];
    }
    view << '|' << scene.ViewAngle;
    const std::string cachedImage = cache + "/image-" +
      std::to_string(std::hash<std::string>()(view.str())) + "-spp" + std::to_string(pixelSpp) +
      ".vti";
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
      {
        Progress traced(tracer, "proxygi render: tracing Embree's image");
        tracer->Update();
        if (traced.Interrupted())
        {
          vtkLogF(ERROR, "proxygi render: interrupted; Embree's image was not cached");
          return InterruptedExitCode;
        }
      }
      truth = tracer->GetOutput();
      WriteThenRename(cachedImage,
        [&](const std::string& path)
        {
          vtkNew<vtkXMLImageDataWriter> writer;
          writer->SetFileName(path.c_str());
          writer->SetInputData(truth);
          return writer->Write() == 1;
        });
    }
    if (!o.ReferencePNG.empty() && WriteTonemappedPNG(truth, exposure, o.ReferencePNG))
    {
      std::printf("wrote %s (Embree's image, same exposure)\n", o.ReferencePNG.c_str());
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

  for (std::size_t k = 0; !o.Vtp.empty() && k < shaded.size(); ++k)
  {
    const std::string path = o.Vtp + "-" + scene.Objects[k].Name + ".vtp";
    if (!WritePolyData(shaded[k], path))
    {
      vtkLogF(ERROR, "proxygi render: cannot write %s", path.c_str());
      return 1;
    }
  }
  // What ran (the effective settings of this mode's backend).
  const bool shadowedBounce = effective->GetIndirect() &&
    effective->GetIndirectMode() == vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
  std::string bounceOrder;
  if (shadowedBounce && effective->GetEffectiveIndirectOrder() != effective->GetOrder())
  {
    bounceOrder = "SH order " + std::to_string(effective->GetEffectiveIndirectOrder());
  }
  if (shadowedBounce &&
    effective->GetSphericalLightBlocking() == vtkPGIGISettings::BLOCKING_PER_OBJECT)
  {
    bounceOrder += std::string(bounceOrder.empty() ? "" : ", ") + "per-object blocking";
  }
  if (!bounceOrder.empty())
  {
    bounceOrder = " (" + bounceOrder + ")";
  }
  std::printf("settings: mode %s, SH order %d, exp %s, indirect %s%s, %lld proxy spheres, %zu "
              "planes, %lld receivers\n",
    o.Mode.c_str(), effective->GetOrder(),
    vtkPGIGISettings::ExpMethodName(effective->GetExpMethod()),
    !effective->GetIndirect() ? "off"
                              : vtkPGIGISettings::IndirectModeName(effective->GetIndirectMode()),
    bounceOrder.c_str(), static_cast<long long>(proxies.Leaves), proxies.Planes.size(),
    static_cast<long long>(receivers));
  if (o.ImageSpace())
  {
    std::printf("time: proxies %.2f s%s, image-space GI frame %.1f ms, first frame and picture "
                "%.3f s\n",
      proxies.Seconds, proxies.Cached ? " (cached)" : "", 1e3 * giFrame, Seconds(t1, t3));
  }
  else
  {
    std::printf("time: proxies %.2f s%s, SH shading %.3f s (%.0f ns per receiver), render %.3f s"
                "%s\n",
      proxies.Seconds, proxies.Cached ? " (cached)" : "", Seconds(t1, t2),
      1e9 * Seconds(t1, t2) / std::max<vtkIdType>(1, receivers), Seconds(t2, t3),
      occluderSeconds > 0.0 ? (", the meshes' Embree scene for the bright lights' rays " +
                                std::to_string(occluderSeconds).substr(0, 5) + " s")
                                .c_str()
                            : "");
  }

  // Error against the Embree reference (per vertex, cached).
  const bool gpu = o.Gpu();
  const int referenceSpp = o.ReferenceSpp;
  if (!o.NoError && !o.ImageSpace())
  {
    double seconds = 0.0;
    const auto reference = SceneReference(
      scene, loaded, receiversIn, referenceSpp, cache, nullptr, seconds, error, 1, true, &progress);
    if (reference.empty())
    {
      vtkLogF(ERROR, "proxygi render: %s%s", error.c_str(),
        progress.Interrupted() ? "; the reference was not cached" : "");
      return progress.Interrupted() ? InterruptedExitCode : 1;
    }
    // The indirect light: Radiance - DirectShadowed - LocalLights against
    // Embree's IndirectOneBounce (on copies; the GPU reads back the total only).
    std::vector<vtkSmartPointer<vtkPolyData>> bounce;
    for (std::size_t k = 0; !gpu && k < shaded.size(); ++k)
    {
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->ShallowCopy(shaded[k]);
      vtkDataArray* radiance = copy->GetPointData()->GetArray("Radiance");
      vtkDataArray* direct = copy->GetPointData()->GetArray("DirectShadowed");
      vtkDataArray* local = copy->GetPointData()->GetArray("LocalLights");
      vtkNew<vtkFloatArray> indirect;
      indirect->SetName("IndirectOneBounce");
      indirect->SetNumberOfComponents(3);
      indirect->SetNumberOfTuples(copy->GetNumberOfPoints());
      for (vtkIdType i = 0; radiance && direct && i < copy->GetNumberOfPoints(); ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          indirect->SetTypedComponent(i, c,
            static_cast<float>(radiance->GetComponent(i, c) - direct->GetComponent(i, c) -
              (local ? local->GetComponent(i, c) : 0.0)));
        }
      }
      copy->GetPointData()->AddArray(indirect);
      bounce.push_back(copy);
    }
    for (std::size_t k = 0; k < shaded.size(); ++k)
    {
      std::printf(
        "object %zu (%s): relative RMSE against the reference: ", k, scene.Objects[k].Name.c_str());
      if (!gpu)
      {
        std::printf("direct %.2f%%, indirect %.2f%%, ",
          100 * RelativeRMSE(shaded, "DirectShadowed", reference, "DirectShadowed", { k }),
          100 * RelativeRMSE(bounce, "IndirectOneBounce", reference, "IndirectOneBounce", { k }));
      }
      std::printf(
        "total %.2f%%\n", 100 * RelativeRMSE(shaded, "Radiance", reference, "Radiance", { k }));
    }
    std::printf("error against the Embree reference (%d samples, %.1f s to trace, its own noise "
                "%.2f%%): ",
      referenceSpp, seconds, 100 * RelativeRMS(reference, "RadianceStdErr", "Radiance"));
    if (!gpu)
    {
      std::printf("direct light %.2f%%, indirect %.2f%%, ",
        100 * RelativeRMSE(shaded, "DirectShadowed", reference, "DirectShadowed"),
        100 * RelativeRMSE(bounce, "IndirectOneBounce", reference, "IndirectOneBounce"));
    }
    std::printf("total with one-bounce indirect %.2f%% (relative RMSE per vertex over all "
                "objects)\n",
      100 * RelativeRMSE(shaded, "Radiance", reference, "Radiance"));
    if (o.Budgeted())
    {
      // The GPU mapper's time is a frame that recomputes GI, as calibrated.
      const double measured = RelativeRMSE(shaded, "Radiance", reference, "Radiance");
      const double took = o.Gpu() ? giFrame : Seconds(t1, t2);
      std::printf("budget: predicted %.2f%% in %.3f s, measured %.2f%% in %.3f s: %s\n",
        100.0 * o.Chosen.PredictedError, o.Chosen.PredictedSeconds, 100.0 * measured, took,
        (o.Budget.HasError && measured > o.Budget.Error) ||
            (o.Budget.HasTime && took > o.Budget.Seconds)
          ? "the budget was not met"
          : "within the budget");
    }
  }
  std::printf("wrote %s (exposure %.3g)\n", o.Output.c_str(), exposure);
  return 0;
}

} // namespace cli
} // namespace proxygi
