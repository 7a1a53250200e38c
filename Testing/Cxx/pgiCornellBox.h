// The Cornell box of Testing/Data/cornell-box.json (the light-cloud tests'
// scene) as one mesh of receivers, its objects also given to an occluder.
// For tests whose module depends on ProxyGI::Scene, ProxyGI::Reference and
// ProxyGI::LightCloud.
#ifndef pgiCornellBox_h
#define pgiCornellBox_h

#include "pgiScene.h"
#include "vtkAppendPolyData.h"
#include "vtkNew.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPrecompute.h"
#include "vtkPGILightCloudTransfer.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdio>
#include <string>

namespace pgitest
{
/// The box's objects appended (null, with the error printed, on failure).
inline vtkSmartPointer<vtkPolyData> LoadCornellBox(
  const char* path, vtkPGIMeshOccluder* occluder = nullptr)
{
  proxygi::SceneDescription description;
  proxygi::LoadedScene scene;
  std::string error;
  if (!proxygi::LoadScene(path, description, error) ||
    !proxygi::BuildScene(description, scene, error))
  {
    std::printf("%s: %s\n", path, error.c_str());
    return nullptr;
  }
  vtkNew<vtkAppendPolyData> append;
  for (auto& object : scene.Objects)
  {
    append->AddInputData(object);
    if (occluder)
    {
      occluder->AddMesh(object);
    }
  }
  append->Update();
  vtkSmartPointer<vtkPolyData> box = append->GetOutput();
  return box;
}

/// A quick cloud over the box's inside: `cells` across, 32 gather rays;
/// glossy for specular > 0 (Phong exponent 12, SH order `order`).
inline vtkSmartPointer<vtkPGILightCloud> CornellCloud(
  vtkPolyData* box, int cells, bool compress, double specular = 0.0, int order = 4)
{
  vtkNew<vtkPGILightCloudPrecompute> precompute;
  precompute->SetInputData(box);
  precompute->SetRegionOfInterest(-1.0, 1.0, -1.0, 1.0, 0.0, 2.0);
  precompute->SetGridResolution(cells, cells, cells);
  precompute->SetSamples(32);
  precompute->SetSpecularAlbedo(specular);
  precompute->SetPhongExponent(12.0);
  precompute->SetGlossyOrder(order);
  precompute->SetCompress(compress);
  precompute->Update();
  auto cloud = vtkSmartPointer<vtkPGILightCloud>::New();
  cloud->DeepCopy(precompute->GetOutput());
  return cloud;
}

/// The CPU GI filter on the box with `cloud` as its point lights' transfer
/// (GetLocalLightTransfer()), lit by `lighting`.
inline vtkSmartPointer<vtkPGIGlobalIllumination> CloudGI(
  vtkPolyData* box, vtkPGILightCloud* cloud, vtkPGILighting* lighting, vtkPGIOccluder* occluder)
{
  vtkNew<vtkPGILightCloudTransfer> transfer;
  transfer->SetCloud(cloud);
  transfer->GetRelight()->SetOccluder(occluder);
  auto gi = vtkSmartPointer<vtkPGIGlobalIllumination>::New();
  gi->SetInputData(box);
  gi->SetLighting(lighting);
  gi->SetLocalLightTransfer(transfer);
  return gi;
}
} // namespace pgitest

#endif
