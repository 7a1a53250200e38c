// LightCloudMapper: a lamp moving through a room on the GPU, its direct
// light from the GI mapper (with soft shadows where the mapper is given
// sphere proxies, SetProxies; none here), its indirect light from a light
// cloud (Kristensen et al. 2005), in one mapper.
//
// 1. The scene (a ProxyGI scene file: meshes, albedo, camera) as one mesh
//    of receivers, and its light cloud (vtkPGILightCloudPrecompute on
//    Embree, compressed, cached in light-cloud-mapper.pgilc).
// 2. vtkPGILightCloudPolyDataMapper in place of vtkPolyDataMapper, with
//    GlobalIllumination on: the lighting's point light is the lamp; each
//    frame the mapper weighs the cloud lights near it and sums the cloud's
//    light per vertex on the GPU, under the GI mapper's direct light.
// 3. Three frames as the lamp moves, each written to a PNG.
//
//   LightCloudMapper scene.json [out-prefix]   (e.g. Testing/Data/cornell-box.json)
#include "pgiOffscreenWindow.h"
#include "pgiScene.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPolyDataMapper.h"
#include "vtkPGILightCloudPrecompute.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkWindowToImageFilter.h"

#include <cstdio>
#include <string>

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s scene.json [out-prefix]\n", argv[0]);
    return 1;
  }
  const std::string prefix = argc > 2 ? argv[2] : "light-cloud-mapper";
  vtkSMPTools::SetBackend("STDThread"); // all cores (Debian's VTK defaults to one)

  // 1. The scene and its cloud.
  proxygi::SceneDescription description;
  proxygi::LoadedScene scene;
  std::string error;
  if (!proxygi::LoadScene(argv[1], description, error) ||
    !proxygi::BuildScene(description, scene, error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  vtkNew<vtkAppendPolyData> append;
  vtkNew<vtkPGIMeshOccluder> occluder; // for the lamp's view of the cloud lights
  for (auto& object : scene.Objects)
  {
    append->AddInputData(object);
    occluder->AddMesh(object);
  }
  append->Update();
  vtkPolyData* room = append->GetOutput();
  vtkNew<vtkPGILightCloudPrecompute> precompute;
  precompute->SetInputData(room);
  precompute->SetGridResolution(4, 4, 4); // over the scene's box
  precompute->SetSamples(64);
  precompute->CompressOn();
  precompute->SetCacheFileName((prefix + ".pgilc").c_str());
  precompute->Update();
  vtkPGILightCloud* cloud = precompute->GetOutput();
  std::printf("cloud: %lld lights, %.1f coefficients per receiver, %.2f s\n",
    static_cast<long long>(cloud->GetNumberOfLights()), cloud->GetCoefficientsPerReceiver(),
    precompute->GetSeconds());

  // 2. The mapper: GI (black sky, the lamp's direct light) under the cloud.
  vtkNew<vtkPGILighting> lighting;
  lighting->SetUniformRadiance(0.0, 0.0, 0.0);
  lighting->AddPointLight(-0.4, -0.3, 1.5, 1.5, 1.4, 1.2); // W/sr
  vtkNew<vtkPGILightCloudPolyDataMapper> mapper;
  mapper->SetInputData(room);
  mapper->SetCloud(cloud);
  mapper->SetLighting(lighting);
  mapper->GlobalIlluminationOn();
  mapper->SetCombineWithVTKLighting(false);
  mapper->GetRelight()->SetOccluder(occluder);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  std::string path;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&path);
  if (!window)
  {
    std::fprintf(stderr, "no offscreen window: %s\n", path.c_str());
    return 1;
  }
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  if (scene.Camera)
  {
    renderer->SetActiveCamera(scene.Camera);
  }
  else
  {
    renderer->ResetCamera();
  }
  std::printf("window: %s\n", path.c_str());

  // 3. The lamp moves; each frame relights and is written.
  for (int frame = 0; frame < 3; ++frame)
  {
    lighting->RemoveAllPointLights();
    lighting->AddPointLight(-0.4 + 0.4 * frame, -0.3 + 0.2 * frame, 1.5, 1.5, 1.4, 1.2);
    mapper->GetRelight()->SetTime(frame / 30.0); // the fade's clock
    window->Render();
    std::printf("frame %d: %s\n", frame, mapper->GetStatus().c_str());
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ShouldRerenderOff();
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputConnection(grab->GetOutputPort());
    const std::string file = prefix + "-" + std::to_string(frame) + ".png";
    writer->SetFileName(file.c_str());
    writer->Write();
    std::printf("wrote %s\n", file.c_str());
  }
  std::printf("GI: %s\n", mapper->GetGIStatus().c_str());
  return 0;
}
