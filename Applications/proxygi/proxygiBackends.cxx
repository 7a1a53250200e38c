// The three ways proxygi draws a scene with GI (see proxygiBackends.h).
#include "proxygiBackends.h"
#include "proxygiImage.h"

#include "pgiOffscreenWindow.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <chrono>

namespace proxygi
{
namespace cli
{
const vtkPGIGISettings::Support& BackendSupport(const std::string& mode)
{
  return mode == "gpu"      ? vtkPGIGIPolyDataMapper::GetSupport()
    : mode == "image-space" ? vtkPGIImageSpaceGIPass::GetSupport()
                            : vtkPGIGlobalIllumination::GetSupport();
}

void SetBackendPlaneDefaults(vtkPGIGISettings* settings, const std::string& mode)
{
  const bool imageSpace = mode == "image-space";
  settings->SetPlaneBlocking(
    imageSpace ? vtkPGIGISettings::PLANES_IN_LOG_SPACE : vtkPGIGISettings::PLANES_IN_LIGHT);
  settings->SetPlaneBounceShadows(!imageSpace);
}

// Exposure: the 95th percentile of the per-vertex radiance to 0.8.
double AutomaticExposure(const std::vector<vtkSmartPointer<vtkPolyData>>& shaded)
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
}

void ColourByRadiance(vtkPolyData* shaded, double exposure, vtkPolyData* display)
{
  vtkDataArray* r = shaded->GetPointData()->GetArray("Radiance");
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("DisplayColors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(r ? r->GetNumberOfTuples() : 0);
  for (vtkIdType i = 0; r && i < r->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      colors->SetValue(3 * i + c, ToSRGB8(exposure * r->GetComponent(i, c)));
    }
  }
  display->ShallowCopy(shaded);
  display->GetPointData()->SetScalars(colors);
}

// The CPU filter's radiance as vertex colours, no VTK lighting.
std::vector<vtkSmartPointer<vtkPolyData>> AddVertexColourActors(
  vtkRenderer* renderer, const std::vector<vtkSmartPointer<vtkPolyData>>& shaded, double exposure)
{
  std::vector<vtkSmartPointer<vtkPolyData>> displayed;
  for (auto& s : shaded)
  {
    auto display = vtkSmartPointer<vtkPolyData>::New();
    ColourByRadiance(s, exposure, display);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(display);
    mapper->SetColorModeToDirectScalars();
    mapper->ScalarVisibilityOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->LightingOff();
    renderer->AddActor(actor);
    displayed.push_back(display);
  }
  return displayed;
}

// Per vertex on the GPU: one GI mapper per object, all on the run's settings.
std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> AddGPUMappers(vtkRenderer* renderer,
  const std::vector<vtkSmartPointer<vtkPolyData>>& receivers, vtkPGIGISettings* settings,
  const LoadedScene& loaded, const SceneProxies& proxies, double exposure)
{
  std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> mappers;
  for (auto& object : receivers)
  {
    auto mapper = vtkSmartPointer<vtkPGIGIPolyDataMapper>::New();
    mapper->SetInputData(object);
    mapper->SetProxies(proxies.Spheres);
    mapper->SetLighting(loaded.Lighting);
    for (const auto& plane : proxies.Planes)
    {
      mapper->AddBlockerPlane(
        plane.data(), plane.data() + 3, plane.data() + 6, plane.data() + 9, plane.data() + 12);
    }
    mapper->SetSettings(settings);
    mapper->SetExposure(exposure > 0.0 ? exposure : 1.0);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    mappers.push_back(mapper);
  }
  return mappers;
}

double TimeGIFrame(
  vtkRenderWindow* window, const std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>>& mappers)
{
  for (auto& mapper : mappers)
  {
    mapper->AlwaysRecomputeOn();
  }
  const auto t0 = std::chrono::steady_clock::now();
  window->Render();
  window->WaitForCompletion();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (auto& mapper : mappers)
  {
    mapper->AlwaysRecomputeOff();
  }
  return seconds;
}

bool ReadBackRadiance(const std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>>& mappers,
  std::vector<vtkSmartPointer<vtkPolyData>>& shaded, std::string& error)
{
  for (auto& mapper : mappers)
  {
    vtkNew<vtkFloatArray> radiance;
    if (!mapper->GetPerVertexResults(radiance))
    {
      error = "the GPU GI pass did not run (" + mapper->GetGIStatus() + ")";
      return false;
    }
    radiance->SetName("Radiance");
    auto result = vtkSmartPointer<vtkPolyData>::New();
    result->ShallowCopy(mapper->GetInput());
    result->GetPointData()->AddArray(radiance);
    shaded.push_back(result);
  }
  return true;
}

bool ShadeOnGPU(const std::vector<vtkSmartPointer<vtkPolyData>>& receivers,
  vtkPGIGISettings* settings, const LoadedScene& loaded, const SceneProxies& proxies,
  const int size[2], std::vector<vtkSmartPointer<vtkPolyData>>& shaded, double& frameSeconds,
  bool& cutShort, std::string& renderer, std::string& error)
{
  shaded.clear();
  cutShort = false;
  vtkNew<vtkRenderer> scene;
  const auto mappers = AddGPUMappers(scene, receivers, settings, loaded, proxies, 1.0);
  scene->SetActiveCamera(loaded.Camera);
  std::string windowPath;
  vtkSmartPointer<vtkRenderWindow> window = NewOffscreenRenderWindow(&windowPath);
  if (!window)
  {
    error = "no offscreen OpenGL: " + windowPath;
    return false;
  }
  window->SetSize(size[0], size[1]);
  window->AddRenderer(scene);
  // The first frame builds the shaders and tables; the timed one recomputes
  // GI, as a frame that changes the scene does.
  window->Render();
  if (!ReadBackRadiance(mappers, shaded, error))
  {
    return false;
  }
  for (auto& mapper : mappers)
  {
    cutShort = cutShort || mapper->GetGICutShort();
  }
  frameSeconds = TimeGIFrame(window, mappers);
  renderer = DescribeRenderWindowContext(window);
  return true;
}

// Per pixel on the GPU: plain mappers (the albedo as diffuse colour) under the pass.
void AddImageSpacePass(vtkRenderer* renderer, vtkPGIImageSpaceGIPass* pass,
  const SceneDescription& scene, const std::vector<vtkSmartPointer<vtkPolyData>>& receivers,
  vtkPGIGISettings* settings, const LoadedScene& loaded, const SceneProxies& proxies,
  int receiverScale, double exposure)
{
  for (std::size_t k = 0; k < receivers.size(); ++k)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(receivers[k]);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    const double* albedo = scene.Objects[k].Albedo;
    actor->GetProperty()->SetColor(albedo[0], albedo[1], albedo[2]);
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
  pass->SetSettings(settings);
  pass->SetReceiverScale(receiverScale);
  pass->SetExposure(exposure > 0.0 ? exposure : 1.0);
  renderer->SetPass(pass);
}

// Image-space mode has no per-vertex radiance: the automatic exposure reads
// the geometry pixels of a frame drawn at a low exposure (radiance up to 32
// unclipped) back to radiance.
double ExposureFromPicture(vtkRenderWindow* window, vtkPGIImageSpaceGIPass* pass)
{
  const double probe = 1.0 / 32.0;
  pass->SetExposure(probe);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  int* size = window->GetSize();
  vtkNew<vtkFloatArray> depth;
  window->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, depth);
  vtkDataArray* picture = grab->GetOutput()->GetPointData()->GetScalars();
  std::vector<double> luminance;
  for (vtkIdType i = 0; i < picture->GetNumberOfTuples() && i < depth->GetNumberOfTuples(); ++i)
  {
    if (depth->GetValue(i) < 1.0f)
    {
      double rgb[3];
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = FromSRGB8(static_cast<unsigned char>(picture->GetComponent(i, c))) / probe;
      }
      luminance.push_back(Luminance(rgb[0], rgb[1], rgb[2]));
    }
  }
  const double exposure = AutoExposure(luminance);
  pass->SetExposure(exposure);
  return exposure;
}

} // namespace cli
} // namespace proxygi
