// proxygi view: an interactive window on a scene with GI live. Single keys
// switch the effects, the backend, the SH order and the sphere count; a
// handle drags a local light; an overlay shows the plan, the frame and GI
// times and, when a reference of the scene is cached, the error against it.
#include "proxygiBackends.h"
#include "proxygiCommands.h"
#include "proxygiImage.h"
#include "proxygiProgress.h"

#include "pgiScene.h"
#include "pgiSceneSetup.h"
#include "vtkPGIGIBake.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkCoordinate.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkHandleWidget.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereHandleRepresentation.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <sstream>

namespace proxygi
{
namespace cli
{
namespace
{
const char* Usage = R"(usage: proxygi view [scene.json] [options]

Opens a window (X; under xvfb-run without a screen) on a scene (default: the
bunny over a ground plane under the forest map) with global illumination
live: trackball camera, single keys for the effects and knobs, a handle that
drags a local light, and an overlay with the plan, the frame and GI times and
the error against the scene's Embree reference when one is cached (proxygi
render caches it in the same --cache folder).

Keys:
  b        backend: gpu (GI mapper) -> vertex (CPU filter) -> image-space pass
  s        soft shadows on/off
  i        indirect light: shadowed -> unshadowed -> off
  l        local lights on/off (a scene without lights gets the viewer's lamp)
  o / O    SH order up / down (2..8; what a backend cannot run it says)
  n / N    proxy spheres per mesh doubled / halved (4..1024)
  g        proxies shown as glyphs on/off
  h        overlay on/off
  x, F12   screenshot (PREFIX-N.png)
  r        reset the camera
  q, e     quit
  drag the yellow sphere (left button) to move the local light

Options:
  --mode M            backend to start with: gpu (default), vertex, image-space
  --order N           SH order (default 4)
  --spheres N         proxy spheres per mesh (default 64)
  --scale N           image-space receiver buffer at 1/N (1, 2, 4, 8; 2)
  --exposure E        tone-mapping scale (default: automatic, from the first frame)
  --cache DIR         proxies and references are cached here (proxygi-cache)
  --reference-spp N   the cached reference's samples per vertex (default 1024)
  --size WxH          window size (default: the scene's)
  --screenshot PREFIX screenshots are PREFIX-1.png, PREFIX-2.png, ... (proxygi-view)
  --no-overlay        start with the overlay hidden
  --play FILE         replay recorded interaction (vtkInteractorEventRecorder), then exit
  --record FILE       record the interaction to FILE
)";

enum class Backend
{
  Gpu = 0,
  Vertex,
  ImageSpace
};

const char* BackendName(Backend b)
{
  return b == Backend::Gpu ? "gpu" : b == Backend::Vertex ? "vertex" : "image-space";
}

const char* BackendDescription(Backend b)
{
  return b == Backend::Gpu ? "GI mapper, per vertex on the GPU"
    : b == Backend::Vertex ? "CPU filter, per vertex"
                           : "image-space pass, per pixel on the GPU";
}

using Clock = std::chrono::steady_clock;
double Milliseconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Trackball camera; the viewer's keys first. VTK's own keys other than
// r (reset), q and e (quit) are swallowed: w, s, 3, f, p... would change
// the representation or the style behind the viewer's back.
class ViewerStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static ViewerStyle* New();
  vtkTypeMacro(ViewerStyle, vtkInteractorStyleTrackballCamera);

  std::function<bool(const std::string&)> KeyHandler;

  void OnKeyPress() override
  {
    const char* sym = this->Interactor->GetKeySym();
    if (sym && this->KeyHandler)
    {
      this->KeyHandler(sym);
    }
  }
  void OnChar() override
  {
    const char key = this->Interactor->GetKeyCode();
    if (key == 'r' || key == 'R' || key == 'q' || key == 'Q' || key == 'e' || key == 'E')
    {
      this->Superclass::OnChar();
    }
  }
};
vtkStandardNewMacro(ViewerStyle);

struct ViewOptions
{
  Backend Start = Backend::Gpu;
  int Order = 4, Spheres = 64, ReceiverScale = 2, ReferenceSpp = 1024;
  double Exposure = 0.0;
  std::string Cache = "proxygi-cache", Screenshot = "proxygi-view", Play, Record;
  bool Overlay = true;
};

class Viewer
{
public:
  Viewer(const SceneDescription& scene, const ViewOptions& options)
    : Scene(scene)
    , Options(options)
    , Order(options.Order)
    , Spheres(options.Spheres)
    , Mode(options.Start)
    , OverlayShown(options.Overlay)
  {
  }

  int Run();

private:
  bool Setup(std::string& error);
  bool UseProxies(int spheres, std::string& error);
  void ApplySettings();
  void BuildBackend();
  void RunCPUFilter();
  void Refresh();
  void ComputeError();
  void UpdateOverlay();
  void UpdateGlyphs();
  void PlaceLamp();
  void ApplyLights();
  bool OnKey(const std::string& key);
  void Screenshot();
  void OnRenderStart(vtkObject*, unsigned long, void*);
  void OnRenderEnd(vtkObject*, unsigned long, void*);
  void OnLampMoved(vtkObject*, unsigned long, void*);
  void OnLampReleased(vtkObject*, unsigned long, void*);
  double InitialExposure();
  bool PerVertexRadiance(
    std::vector<vtkSmartPointer<vtkPolyData>>& shaded, std::string& error) const;
  void SetExposure(double exposure);

  SceneDescription Scene;
  ViewOptions Options;
  LoadedScene Loaded;
  std::vector<vtkSmartPointer<vtkPolyData>> Receivers;
  std::map<int, SceneProxies> ProxiesBySpheres;
  SceneProxies* Proxies = nullptr;
  vtkNew<vtkPGIGISettings> Settings;
  vtkNew<vtkPGIGISettings> Effective;
  std::vector<std::string> NotHonoured;

  int Order, Spheres;
  Backend Mode;
  bool Shadows = true, LocalLights = true, ProxiesShown = false, OverlayShown = true;
  int Indirect = 0; // 0 shadowed, 1 unshadowed, 2 off
  double Exposure = 1.0;

  // The viewer's own lamp, for a scene without local lights.
  bool ViewerLamp = false;
  SceneLight Lamp;

  vtkNew<vtkRenderer> SceneRenderer, OverlayRenderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderWindowInteractor> Interactor;
  vtkNew<ViewerStyle> Style;
  vtkNew<vtkTextActor> Text, PlanText;
  vtkNew<vtkHandleWidget> LampWidget;
  vtkNew<vtkSphereHandleRepresentation> LampHandle;
  vtkNew<vtkPolyData> GlyphCentres;
  vtkNew<vtkActor> Glyphs;

  std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> Mappers;
  std::vector<vtkSmartPointer<vtkPGIGlobalIllumination>> Filters;
  std::vector<vtkSmartPointer<vtkPolyData>> Displayed;
  vtkSmartPointer<vtkPGIImageSpaceGIPass> Pass;

  Clock::time_point FrameStart;
  double FrameMs = 0.0, GIMs = 0.0, ProxiesSeconds = 0.0;
  bool GIChanged = true, ProxiesCached = false;
  // Per backend: frames that only drew, and GI runs (for the summary at exit).
  std::map<Backend, std::vector<double>> DrawMs, GIRunMs;
  void PrintFrameTimes() const;
  std::string ErrorLine = "error: not computed yet";
  int Shots = 0;
};

bool Viewer::UseProxies(int spheres, std::string& error)
{
  auto found = this->ProxiesBySpheres.find(spheres);
  if (found == this->ProxiesBySpheres.end())
  {
    SetupProgress progress("proxygi view");
    SceneProxies proxies;
    // The radii fitted for occlusion, as proxygi render's default.
    if (!BuildSceneProxies(this->Scene, this->Loaded, spheres, this->Options.Cache, proxies, error,
          &progress, ProxyFit::Occlusion))
    {
      return false;
    }
    found = this->ProxiesBySpheres.emplace(spheres, proxies).first;
  }
  this->Proxies = &found->second;
  this->Spheres = spheres;
  this->ProxiesSeconds = this->Proxies->Seconds;
  this->ProxiesCached = this->Proxies->Cached;
  return true;
}

// The viewer's state as the run's one settings object, resolved for the backend.
void Viewer::ApplySettings()
{
  ConfigureSettings(this->Settings, this->Scene);
  this->Settings->SetOrder(this->Order);
  this->Settings->SetExpMethod(vtkPGIGISettings::EXP_HYB);
  this->Settings->SetShadows(this->Shadows);
  this->Settings->SetIndirect(this->Scene.Indirect && this->Indirect != 2);
  this->Settings->SetIndirectMode(this->Indirect == 0 ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
                                                      : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  this->Settings->SetLocalLights(this->LocalLights);
  // The CPU filter's hierarchy cuts as in proxygi render --mode vertex.
  this->Settings->SetHierarchyAngle(this->Mode == Backend::Vertex ? 25.0 : 0.0);
  SetBackendPlaneDefaults(this->Settings, BackendName(this->Mode));
  const vtkPGIGISettings::Support& support = BackendSupport(BackendName(this->Mode));
  this->NotHonoured.clear();
  vtkPGILighting* lighting = this->Loaded.Lighting;
  this->Settings->Resolve(support, static_cast<int>(this->Proxies->Planes.size()), this->Effective,
    this->NotHonoured,
    static_cast<int>(lighting->GetSphereLights().size() + lighting->GetPointLights().size()));
  this->GIChanged = true;
}

// The scene drawn by the current backend, on the shared settings.
void Viewer::BuildBackend()
{
  this->SceneRenderer->RemoveAllViewProps();
  this->SceneRenderer->SetPass(nullptr);
  this->Mappers.clear();
  this->Filters.clear();
  this->Displayed.clear();
  this->Pass = nullptr;
  this->ApplySettings();
  if (this->Mode == Backend::Gpu)
  {
    this->Mappers = AddGPUMappers(this->SceneRenderer, this->Receivers, this->Settings,
      this->Loaded, *this->Proxies, this->Exposure);
  }
  else if (this->Mode == Backend::ImageSpace)
  {
    this->Pass = vtkSmartPointer<vtkPGIImageSpaceGIPass>::New();
    AddImageSpacePass(this->SceneRenderer, this->Pass, this->Scene, this->Receivers, this->Settings,
      this->Loaded, *this->Proxies, this->Options.ReceiverScale, this->Exposure);
    this->Pass->MeasurePassTimesOn();
  }
  else
  {
    for (auto& receiver : this->Receivers)
    {
      auto gi = vtkSmartPointer<vtkPGIGlobalIllumination>::New();
      gi->SetInputData(receiver);
      ConfigureGlobalIllumination(gi, this->Scene, this->Loaded, *this->Proxies);
      gi->SetSettings(this->Settings);
      this->Filters.push_back(gi);
    }
    this->RunCPUFilter();
    std::vector<vtkSmartPointer<vtkPolyData>> shaded;
    for (auto& gi : this->Filters)
    {
      shaded.push_back(gi->GetOutput());
    }
    this->Displayed = AddVertexColourActors(this->SceneRenderer, shaded, this->Exposure);
  }
  this->SceneRenderer->SetActiveCamera(this->Loaded.Camera);
}

// The CPU filter re-executes when its settings, proxies or light changed.
void Viewer::RunCPUFilter()
{
  if (this->Filters.empty())
  {
    return;
  }
  const auto t0 = Clock::now();
  vtkMTimeType before = 0, after = 0;
  for (auto& gi : this->Filters)
  {
    before += gi->GetOutput()->GetMTime();
    gi->Update();
    after += gi->GetOutput()->GetMTime();
  }
  if (after != before)
  {
    this->GIMs = Milliseconds(t0, Clock::now());
    this->GIRunMs[Backend::Vertex].push_back(this->GIMs);
    for (std::size_t k = 0; k < this->Displayed.size(); ++k)
    {
      ColourByRadiance(this->Filters[k]->GetOutput(), this->Exposure, this->Displayed[k]);
    }
  }
}

// After a key or a finished drag: GI brought up to date, the error against
// the cached reference, the overlay.
void Viewer::Refresh()
{
  this->RunCPUFilter();
  this->Window->Render();
  this->ComputeError();
  vtkLog(INFO, "proxygi view: " << this->ErrorLine);
  this->UpdateOverlay();
  this->Window->Render();
}

void Viewer::ComputeError()
{
  if (this->Mode == Backend::ImageSpace)
  {
    this->ErrorLine = "error: per vertex (gpu and vertex backends)";
    return;
  }
  double seconds = 0.0;
  std::string error;
  const auto reference = SceneReference(this->Scene, this->Loaded, this->Receivers,
    this->Options.ReferenceSpp, this->Options.Cache, nullptr, seconds, error, 1, false);
  if (reference.empty())
  {
    this->ErrorLine = "error: no cached reference of this scene and light (" +
      std::to_string(this->Options.ReferenceSpp) + " spp)";
    return;
  }
  std::vector<vtkSmartPointer<vtkPolyData>> shaded;
  if (!this->PerVertexRadiance(shaded, error))
  {
    this->ErrorLine = "error: " + error;
    return;
  }
  char line[160];
  std::snprintf(line, sizeof(line), "error vs Embree reference (%d spp): %.2f%% per vertex",
    this->Options.ReferenceSpp, 100.0 * RelativeRMSE(shaded, "Radiance", reference, "Radiance"));
  this->ErrorLine = line;
}

void Viewer::UpdateOverlay()
{
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << "ProxyGI  " << this->Scene.Name << "\n";
  s << "[b] " << BackendName(this->Mode) << ": " << BackendDescription(this->Mode)
    << "\n[o/O] SH order " << this->Effective->GetOrder() << "   [n/N] " << this->Spheres
    << " spheres per mesh (" << this->Proxies->Leaves << " leaves)\n";
  s << "[s] shadows " << (this->Shadows ? "on" : "off") << "  [i] indirect "
    << (this->Indirect == 2      ? "off"
           : this->Indirect == 0 ? "shadowed"
                                 : "unshadowed")
    << "  [l] lights " << (this->LocalLights ? (this->ViewerLamp ? "on (lamp)" : "on") : "off")
    << "  [g] proxies " << (this->ProxiesShown ? "on" : "off") << "\n";
  s << "frame " << this->FrameMs << " ms  GI " << this->GIMs << " ms "
    << (this->Mode == Backend::ImageSpace ? "(every frame)" : "(when it last ran)") << "  proxies "
    << this->ProxiesSeconds << " s" << (this->ProxiesCached ? " (cached)" : "") << "\n";
  s << this->ErrorLine;
  this->Text->SetInput(s.str().c_str());
  this->Text->SetVisibility(this->OverlayShown);

  std::ostringstream p;
  vtkPGIGIBake* bake = this->Mode == Backend::Gpu
    ? (this->Mappers.empty() ? nullptr : this->Mappers[0]->GetBake())
    : this->Mode == Backend::ImageSpace ? this->Pass->GetBake()
    : this->Filters.empty()             ? nullptr
                                        : this->Filters[0]->GetBake();
  for (const std::string& line : bake ? bake->GetScene().Plan : std::vector<std::string>())
  {
    p << "plan: " << line << "\n";
  }
  for (const std::string& note : this->NotHonoured)
  {
    p << "not honoured: " << note << "\n";
  }
  p << "[h] overlay [x] screenshot [r] reset camera [q] quit; drag the yellow ball: light";
  this->PlanText->SetInput(p.str().c_str());
  this->PlanText->SetVisibility(this->OverlayShown);
}

void Viewer::UpdateGlyphs()
{
  vtkNew<vtkPoints> centres;
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  vtkPolyData* spheres = this->Proxies->Spheres;
  vtkDataArray* r = spheres ? spheres->GetPointData()->GetArray("Radius") : nullptr;
  for (vtkIdType i = 0; r && i < this->Proxies->Leaves; ++i)
  {
    centres->InsertNextPoint(spheres->GetPoint(i));
    radii->InsertNextValue(static_cast<float>(r->GetTuple1(i)));
  }
  this->GlyphCentres->SetPoints(centres);
  this->GlyphCentres->GetPointData()->AddArray(radii);
  this->GlyphCentres->Modified();
  this->Glyphs->SetVisibility(this->ProxiesShown);
}

// The lamp of a scene without local lights: above and to the left of the
// view, a tenth of the view distance across, bright enough to be seen
// against the environment at the chosen exposure.
void Viewer::PlaceLamp()
{
  vtkCamera* camera = this->Loaded.Camera;
  double eye[3], focal[3], up[3], dir[3], right[3];
  camera->GetPosition(eye);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  for (int k = 0; k < 3; ++k)
  {
    dir[k] = focal[k] - eye[k];
  }
  const double distance = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  right[0] = dir[1] * up[2] - dir[2] * up[1];
  right[1] = dir[2] * up[0] - dir[0] * up[2];
  right[2] = dir[0] * up[1] - dir[1] * up[0];
  const double rn = std::sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
  for (int k = 0; k < 3; ++k)
  {
    this->Lamp.Position[k] =
      focal[k] - 0.25 * distance * right[k] / std::max(rn, 1e-300) + 0.15 * distance * up[k];
  }
  this->Lamp.Sphere = true;
  this->Lamp.Radius = 0.05 * distance;
  // Diffuse exit radiance at the focal point ~ albedo L (r/d)^2: aim at 0.5
  // of the display range.
  const double d2 = 0.085 * distance * distance, r2 = this->Lamp.Radius * this->Lamp.Radius;
  const double radiance = 0.5 / (this->Exposure * 0.8 * r2 / d2);
  this->Lamp.Value[0] = this->Lamp.Value[1] = this->Lamp.Value[2] = radiance;
}

// The scene's lights (with the lamp while it is on) into the lighting.
void Viewer::ApplyLights()
{
  SetSceneLights(this->Scene, this->Loaded.Lighting);
  this->GIChanged = true;
}

double Viewer::InitialExposure()
{
  if (this->Options.Exposure > 0.0)
  {
    return this->Options.Exposure;
  }
  if (this->Mode == Backend::ImageSpace)
  {
    return ExposureFromPicture(this->Window, this->Pass);
  }
  std::vector<vtkSmartPointer<vtkPolyData>> shaded;
  std::string error;
  return this->PerVertexRadiance(shaded, error) ? AutomaticExposure(shaded) : 1.0;
}

// The per-vertex "Radiance" of every object: the CPU filter's outputs, or
// the GI mappers' read back. False (with why) when there is none.
bool Viewer::PerVertexRadiance(
  std::vector<vtkSmartPointer<vtkPolyData>>& shaded, std::string& error) const
{
  shaded.clear();
  for (auto& gi : this->Filters)
  {
    shaded.emplace_back(gi->GetOutput());
  }
  if (!ReadBackRadiance(this->Mappers, shaded, error))
  {
    return false;
  }
  if (shaded.empty())
  {
    error = "no per-vertex radiance in this backend";
    return false;
  }
  return true;
}

void Viewer::SetExposure(double exposure)
{
  for (auto& mapper : this->Mappers)
  {
    mapper->SetExposure(exposure);
  }
  if (this->Pass)
  {
    this->Pass->SetExposure(exposure);
  }
  for (std::size_t k = 0; k < this->Displayed.size(); ++k)
  {
    ColourByRadiance(this->Filters[k]->GetOutput(), exposure, this->Displayed[k]);
  }
}

bool Viewer::Setup(std::string& error)
{
  if (!BuildScene(this->Scene, this->Loaded, error))
  {
    return false;
  }
  this->LocalLights = this->Scene.LocalLights;
  if (!this->UseProxies(this->Spheres, error))
  {
    return false;
  }
  this->Receivers = SceneReceivers(this->Loaded);
  this->Shadows = this->Scene.Shadows;
  this->Indirect = this->Scene.Indirect ? 0 : 2;
  if (this->Scene.Lights.empty())
  {
    // The lamp starts off: the scene as given first (its cached reference applies).
    this->ViewerLamp = true;
    this->LocalLights = false;
  }

  this->SceneRenderer->SetBackground(0.3, 0.3, 0.32);
  this->SceneRenderer->SetLayer(0);
  this->OverlayRenderer->SetLayer(1);
  this->OverlayRenderer->InteractiveOff();
  this->OverlayRenderer->SetActiveCamera(this->Loaded.Camera);
  this->Window->SetNumberOfLayers(2);
  this->Window->AddRenderer(this->SceneRenderer);
  this->Window->AddRenderer(this->OverlayRenderer);
  this->Window->SetSize(this->Scene.Size[0], this->Scene.Size[1]);
  this->Window->SetWindowName("ProxyGI");
  this->Window->SetMultiSamples(0);
  this->Interactor->SetRenderWindow(this->Window);
  this->Style->KeyHandler = [this](const std::string& key) { return this->OnKey(key); };
  this->Interactor->SetInteractorStyle(this->Style);
  this->Window->AddObserver(vtkCommand::StartEvent, this, &Viewer::OnRenderStart);
  this->Window->AddObserver(vtkCommand::EndEvent, this, &Viewer::OnRenderEnd);

  this->Text->GetTextProperty()->SetFontFamilyToCourier();
  this->Text->GetTextProperty()->SetFontSize(12);
  this->Text->GetTextProperty()->SetColor(1.0, 1.0, 0.9);
  this->Text->GetTextProperty()->ShadowOn();
  this->Text->GetTextProperty()->SetVerticalJustificationToTop();
  this->Text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->Text->GetPositionCoordinate()->SetValue(0.01, 0.99);
  this->OverlayRenderer->AddActor2D(this->Text);
  this->PlanText->GetTextProperty()->ShallowCopy(this->Text->GetTextProperty());
  this->PlanText->GetTextProperty()->SetFontSize(10);
  this->PlanText->GetTextProperty()->SetVerticalJustificationToBottom();
  this->PlanText->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->PlanText->GetPositionCoordinate()->SetValue(0.01, 0.01);
  this->OverlayRenderer->AddActor2D(this->PlanText);

  vtkNew<vtkSphereSource> unit;
  unit->SetRadius(1.0);
  unit->SetThetaResolution(20);
  unit->SetPhiResolution(12);
  vtkNew<vtkGlyph3DMapper> glyphMapper;
  glyphMapper->SetInputData(this->GlyphCentres);
  glyphMapper->SetSourceConnection(unit->GetOutputPort());
  glyphMapper->SetScaleArray("Radius");
  glyphMapper->SetScaleModeToScaleByMagnitude();
  glyphMapper->ScalingOn();
  glyphMapper->ScalarVisibilityOff();
  this->Glyphs->SetMapper(glyphMapper);
  this->Glyphs->GetProperty()->SetColor(1.0, 0.55, 0.15);
  this->Glyphs->GetProperty()->SetOpacity(0.45);
  this->OverlayRenderer->AddActor(this->Glyphs);
  this->UpdateGlyphs();

  // The first frame, then the exposure every backend keeps.
  this->BuildBackend();
  this->SceneRenderer->ResetCameraClippingRange();
  this->OverlayRenderer->DrawOff(); // its depth clear would hide the geometry from the probe
  this->Window->Render();
  this->Exposure = this->InitialExposure();
  this->OverlayRenderer->DrawOn();
  this->SetExposure(this->Exposure);
  if (this->ViewerLamp)
  {
    this->PlaceLamp();
  }

  const SceneLight& light = this->ViewerLamp ? this->Lamp : this->Scene.Lights[0];
  this->LampHandle->SetWorldPosition(const_cast<double*>(light.Position));
  this->LampHandle->SetSphereRadius(std::max(light.Radius, 0.01));
  this->LampHandle->GetProperty()->SetColor(1.0, 0.9, 0.2);
  this->LampWidget->SetInteractor(this->Interactor);
  this->LampWidget->SetRepresentation(this->LampHandle);
  this->LampWidget->SetCurrentRenderer(this->OverlayRenderer);
  this->LampWidget->AddObserver(vtkCommand::InteractionEvent, this, &Viewer::OnLampMoved);
  this->LampWidget->AddObserver(vtkCommand::EndInteractionEvent, this, &Viewer::OnLampReleased);
  this->LampWidget->SetEnabled(this->LocalLights);
  return true;
}

bool Viewer::OnKey(const std::string& key)
{
  std::string error;
  if (key == "b")
  {
    this->Mode = static_cast<Backend>((static_cast<int>(this->Mode) + 1) % 3);
    this->BuildBackend();
  }
  else if (key == "s")
  {
    this->Shadows = !this->Shadows;
    this->ApplySettings();
  }
  else if (key == "i")
  {
    this->Indirect = (this->Indirect + 1) % 3;
    this->ApplySettings();
  }
  else if (key == "l")
  {
    this->LocalLights = !this->LocalLights;
    if (this->ViewerLamp)
    {
      // The lamp is part of the scene while it is on (the reference key too).
      if (this->LocalLights)
      {
        this->Scene.Lights.push_back(this->Lamp);
      }
      else
      {
        this->Scene.Lights.clear();
      }
      this->ApplyLights();
    }
    this->LampWidget->SetEnabled(this->LocalLights);
    this->ApplySettings();
  }
  else if (key == "o" || key == "O")
  {
    this->Order = std::max(2, std::min(8, this->Order + (key == "o" ? 1 : -1)));
    this->ApplySettings();
  }
  else if (key == "n" || key == "N")
  {
    const int spheres =
      std::max(4, std::min(1024, key == "n" ? 2 * this->Spheres : this->Spheres / 2));
    if (!this->UseProxies(spheres, error))
    {
      vtkLog(ERROR, "proxygi view: " << error);
      return true;
    }
    this->UpdateGlyphs();
    this->BuildBackend();
  }
  else if (key == "g")
  {
    this->ProxiesShown = !this->ProxiesShown;
    this->Glyphs->SetVisibility(this->ProxiesShown);
  }
  else if (key == "h")
  {
    this->OverlayShown = !this->OverlayShown;
  }
  else if (key == "x" || key == "F12")
  {
    this->Screenshot();
    return true;
  }
  else
  {
    return false;
  }
  vtkLog(INFO,
    "proxygi view: key '" << key << "': backend " << BackendName(this->Mode) << ", order "
                          << this->Effective->GetOrder() << ", " << this->Spheres
                          << " spheres, shadows " << (this->Shadows ? "on" : "off") << ", indirect "
                          << this->Indirect << ", local lights "
                          << (this->LocalLights ? "on" : "off"));
  this->Refresh();
  return true;
}

void Viewer::Screenshot()
{
  this->Window->Render();
  const std::string path = this->Options.Screenshot + "-" + std::to_string(++this->Shots) + ".png";
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(this->Window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  if (WritePNG(grab->GetOutput(), path))
  {
    std::printf("wrote %s\n", path.c_str());
    std::fflush(stdout);
  }
  else
  {
    vtkLog(ERROR, "proxygi view: could not write " << path);
  }
}

void Viewer::OnRenderStart(vtkObject*, unsigned long, void*)
{
  // The overlay shows the previous frame's times.
  if (this->OverlayShown && this->Proxies)
  {
    this->UpdateOverlay();
  }
  this->FrameStart = Clock::now();
}

void Viewer::OnRenderEnd(vtkObject*, unsigned long, void*)
{
  this->Window->WaitForCompletion();
  this->FrameMs = Milliseconds(this->FrameStart, Clock::now());
  if (this->Mode == Backend::ImageSpace && this->Pass)
  {
    double ms = 0.0;
    for (int k = 0; k < vtkPGIImageSpaceGIPass::NumberOfPasses; ++k)
    {
      ms += 1e3 * this->Pass->GetPassTime(k);
    }
    this->GIMs = ms;
    this->GIRunMs[Backend::ImageSpace].push_back(ms);
    this->DrawMs[Backend::ImageSpace].push_back(this->FrameMs);
  }
  else if (this->Mode == Backend::Gpu && this->GIChanged)
  {
    this->GIMs = this->FrameMs;
    this->GIRunMs[Backend::Gpu].push_back(this->FrameMs);
  }
  else
  {
    this->DrawMs[this->Mode].push_back(this->FrameMs);
  }
  this->GIChanged = false;
}

void Viewer::OnLampMoved(vtkObject*, unsigned long, void*)
{
  const double* p = this->LampHandle->GetWorldPosition();
  SceneLight& light = this->ViewerLamp ? this->Scene.Lights.back() : this->Scene.Lights[0];
  std::copy(p, p + 3, light.Position);
  if (this->ViewerLamp)
  {
    std::copy(p, p + 3, this->Lamp.Position);
  }
  this->ApplyLights();
  this->ErrorLine = "error: updated when the drag ends";
  if (this->Mode != Backend::Vertex)
  {
    this->UpdateOverlay();
  }
}

void Viewer::OnLampReleased(vtkObject*, unsigned long, void*)
{
  const double* p = this->LampHandle->GetWorldPosition();
  vtkLog(INFO, "proxygi view: light moved to " << p[0] << " " << p[1] << " " << p[2]);
  this->Refresh();
}

// Medians per backend: what a frame costs when only the camera moved, and
// what GI costs when it runs (the image-space pass runs it every frame).
void Viewer::PrintFrameTimes() const
{
  const auto median = [](std::vector<double> v)
  {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  for (Backend b : { Backend::Gpu, Backend::Vertex, Backend::ImageSpace })
  {
    const auto draws = this->DrawMs.find(b);
    const auto runs = this->GIRunMs.find(b);
    if (draws == this->DrawMs.end() && runs == this->GIRunMs.end())
    {
      continue;
    }
    const std::vector<double> none;
    const std::vector<double>& d = draws != this->DrawMs.end() ? draws->second : none;
    const std::vector<double>& g = runs != this->GIRunMs.end() ? runs->second : none;
    std::printf("frame times, %s: %s %.1f ms median over %zu frames; GI %.1f ms median over %zu "
                "runs%s\n",
      BackendName(b), b == Backend::ImageSpace ? "every frame (GI included)" : "drawing only",
      median(d), d.size(), median(g), g.size(),
      b == Backend::Gpu        ? " (the frames that recomputed it)"
        : b == Backend::Vertex ? " (the CPU filter)"
                               : " (the pass's own GPU time)");
  }
}

int Viewer::Run()
{
  std::string error;
  if (!this->Setup(error))
  {
    vtkLog(ERROR, "proxygi view: " << error);
    return 1;
  }
  this->Interactor->Initialize();
  this->Refresh();
  {
    // Where the lamp's handle is on screen (for recording interaction by hand).
    double display[3];
    vtkNew<vtkCoordinate> at;
    at->SetCoordinateSystemToWorld();
    at->SetValue(this->LampHandle->GetWorldPosition());
    int* d = at->GetComputedDisplayValue(this->SceneRenderer);
    display[0] = d[0];
    display[1] = d[1];
    vtkLog(INFO, "proxygi view: light handle at display " << display[0] << " " << display[1]);
  }
  std::printf("proxygi view: %s, backend %s, %dx%d window (%s)\n", this->Scene.Name.c_str(),
    BackendName(this->Mode), this->Window->GetSize()[0], this->Window->GetSize()[1],
    this->Window->GetClassName());
  std::fflush(stdout);
  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(this->Interactor);
  if (!this->Options.Play.empty())
  {
    recorder->SetFileName(this->Options.Play.c_str());
    recorder->On();
    recorder->Play();
    recorder->Off();
    std::printf("proxygi view: played %s\n", this->Options.Play.c_str());
    this->PrintFrameTimes();
    return 0;
  }
  if (!this->Options.Record.empty())
  {
    recorder->SetFileName(this->Options.Record.c_str());
    recorder->On();
    recorder->Record();
  }
  this->Interactor->Start();
  this->PrintFrameTimes();
  return 0;
}

bool ParseViewOptions(const Args& args, ViewOptions& o, SceneDescription& scene)
{
  bool ok = true;
  const std::string mode = Option(args, "--mode", "gpu");
  o.Order = static_cast<int>(NumberOption(args, "--order", 4, ok));
  o.Spheres = static_cast<int>(NumberOption(args, "--spheres", 64, ok));
  o.ReceiverScale = static_cast<int>(NumberOption(args, "--scale", 2, ok));
  o.ReferenceSpp = static_cast<int>(NumberOption(args, "--reference-spp", 1024, ok));
  o.Exposure = NumberOption(args, "--exposure", 0.0, ok);
  o.Cache = Option(args, "--cache", o.Cache);
  o.Screenshot = Option(args, "--screenshot", o.Screenshot);
  o.Play = Option(args, "--play", "");
  o.Record = Option(args, "--record", "");
  o.Overlay = !Flag(args, "--no-overlay");
  if (!ok)
  {
    return false;
  }
  if (mode == "gpu" || mode == "vertex" || mode == "image-space")
  {
    o.Start = mode == "gpu" ? Backend::Gpu
      : mode == "vertex"    ? Backend::Vertex
                            : Backend::ImageSpace;
  }
  else
  {
    vtkLogF(ERROR, "proxygi view: --mode gpu|vertex|image-space");
    return false;
  }
  if (o.Order < 2 || o.Order > 8 || o.Spheres < 4 || o.Spheres > 1024 || o.ReferenceSpp < 1 ||
    (o.ReceiverScale != 1 && o.ReceiverScale != 2 && o.ReceiverScale != 4 &&
      o.ReceiverScale != 8) ||
    o.Exposure < 0.0)
  {
    vtkLogF(ERROR,
      "proxygi view: need 2 <= --order <= 8, 4 <= --spheres <= 1024, --reference-spp >= 1, "
      "--scale 1|2|4|8, --exposure >= 0");
    return false;
  }
  const std::string size = Option(args, "--size", "");
  if (!size.empty() &&
    (std::sscanf(size.c_str(), "%dx%d", &scene.Size[0], &scene.Size[1]) != 2 ||
      scene.Size[0] < 16 || scene.Size[1] < 16))
  {
    vtkLogF(ERROR, "proxygi view: --size expects WxH (at least 16x16)");
    return false;
  }
  return true;
}

} // namespace

int RunView(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  SceneDescription scene = DefaultScene();
  const std::string scenePath = Positional(args, { "--no-overlay", "--help" });
  std::string error;
  if (!scenePath.empty() && !LoadScene(scenePath, scene, error))
  {
    vtkLogF(ERROR, "proxygi view: %s", error.c_str());
    return 1;
  }
  ViewOptions options;
  if (!ParseViewOptions(args, options, scene))
  {
    return 2;
  }
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    vtkLogF(ERROR,
      "proxygi view: needs an X display (DISPLAY is not set); run it under xvfb-run for "
      "an offscreen one, or use 'proxygi render' for a picture");
    return 1;
  }
  Viewer viewer(scene, options);
  return viewer.Run();
}

} // namespace cli
} // namespace proxygi
