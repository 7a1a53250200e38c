// The Cornell box of Testing/Data/cornell-box.json (the light-cloud tests'
// scene) as one mesh of receivers, its objects also given to an occluder.
// For tests whose module depends on ProxyGI::Scene and ProxyGI::Reference.
#ifndef pgiCornellBox_h
#define pgiCornellBox_h

#include "pgiScene.h"
#include "vtkAppendPolyData.h"
#include "vtkNew.h"
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
} // namespace pgitest

#endif
