// Scene files: the default scene loads; a JSON scene parses into what it
// says; bad files fail with a message that names the problem.
#include "pgiScene.h"

#include "pgiTesting.h"
#include "vtkCamera.h"
#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPGILighting.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"

#include <cstring>

using namespace proxygi;

int TestScene(int, char*[])
{
  // The built-in default: bunny (z-up, feet on z = 0) over a plane, forest map.
  LoadedScene loaded;
  std::string error;
  PGI_CHECK(BuildScene(DefaultScene(), loaded, error));
  std::printf("default scene: %zu objects; %s\n", loaded.Objects.size(), error.c_str());
  PGI_CHECK(loaded.Objects.size() == 2);
  if (loaded.Objects.size() == 2)
  {
    double b[6];
    loaded.Objects[0]->GetBounds(b);
    std::printf("bunny bounds z: %.4f .. %.4f\n", b[4], b[5]);
    PGI_NEAR(b[4], 0.0, 0.01);
    PGI_CHECK(loaded.Objects[0]->GetNumberOfPoints() == 37706);
    PGI_CHECK(loaded.Objects[0]->GetPointData()->GetArray("Albedo") != nullptr);
  }
  PGI_CHECK(loaded.Lighting && loaded.Lighting->GetEnvironmentImage() != nullptr);

  const char* json = R"({
    "name": "test",
    "objects": [ { "sphere": { "center": [0, 0, 1.5], "radius": 1, "resolution": 16 },
                   "albedo": [0.2, 0.4, 0.6], "translate": [1, 0, 0] },
                 { "plane": { "center": [0, 0, 0], "size": 4 } } ],
    "environment": { "uniform": [2, 2, 2], "rotation": 30 },
    "lights": [ { "type": "sphere", "center": [0, 0, 5], "radius": 0.5, "radiance": [9, 9, 9] },
                { "type": "point", "position": [1, 1, 1], "intensity": [3, 3, 3] } ],
    "camera": { "position": [0, -5, 2], "focal_point": [0, 0, 0], "view_angle": 40, "size": [320, 200] },
    "effects": { "indirect": false }
  })";
  SceneDescription scene;
  PGI_CHECK(ParseScene(json, ".", scene, error));
  PGI_CHECK(scene.Objects.size() == 2 && scene.Lights.size() == 2);
  PGI_CHECK(!scene.Indirect && scene.Shadows);
  PGI_CHECK(scene.Size[0] == 320 && scene.Size[1] == 200);
  PGI_CHECK(BuildScene(scene, loaded, error));
  PGI_CHECK(loaded.Objects.size() == 2);
  if (loaded.Objects.size() == 2)
  {
    double b[6];
    loaded.Objects[0]->GetBounds(b);
    PGI_NEAR(0.5 * (b[0] + b[1]), 1.0, 1e-6); // translated
    PGI_NEAR(loaded.Objects[0]->GetPointData()->GetArray("Albedo")->GetComponent(0, 2), 0.6, 1e-6);
    PGI_NEAR(loaded.Lighting->GetUniformRadiance()[0], 2.0, 0.0);
    PGI_NEAR(loaded.Lighting->GetEnvironmentRotation(), 30.0, 0.0);
    PGI_CHECK(loaded.Lighting->GetSphereLights().size() == 1);
    PGI_CHECK(loaded.Lighting->GetPointLights().size() == 1);
    if (loaded.Lighting->GetSphereLights().size() == 1)
    {
      const vtkPGILighting::SphereLight& light = loaded.Lighting->GetSphereLights()[0];
      PGI_NEAR(light.Center[2], 5.0, 0.0);
      PGI_NEAR(light.Radius, 0.5, 0.0);
      PGI_NEAR(light.Radiance[1], 9.0, 0.0);
    }
    PGI_NEAR(loaded.Camera->GetViewAngle(), 40.0, 0.0);
  }

  // Bad files: each gives a message naming the problem.
  struct
  {
    const char* Json;
    const char* Expect;
  } bad[] = { { "{", "JSON" }, { "[]", "object" }, { "{\"objects\": []}", "objects" },
    { "{\"objects\": [{\"cube\": 1}]}", "mesh" },
    { "{\"objects\": [{\"plane\": {}, \"albedo\": [2, 0, 0]}]}", "albedo" },
    { "{\"objects\": [{\"plane\": {}, \"albedo\": [0.1, 0.2]}]}", "albedo" },
    { "{\"objects\": [{\"plane\": {}}], \"lights\": [{\"type\": \"laser\"}]}", "type" },
    { "{\"objects\": [{\"plane\": {}}], \"camera\": {\"size\": [0, 10]}}", "size" },
    { "{\"objects\": [{\"quad\": {\"origin\": [0, 0, 0], \"point1\": [1, 1, 1], "
      "\"point2\": [2, 2, 2]}}]}",
      "collinear" },
    { "{\"objects\": [{\"quad\": {\"resolution\": [0, 4]}}]}", "resolution" },
    { "{\"objects\": [{\"box\": {\"size\": [1, 0, 1]}}]}", "positive" },
    { "{\"objects\": [{\"box\": {\"resolution\": 1e9}}]}", "resolution" },
    { "{\"objects\": [{\"plane\": {}}], \"light_cloud\": {\"region\": [1, 0, 0, 1, 0, 1]}}",
      "region" },
    { "{\"objects\": [{\"plane\": {}}], \"light_cloud\": {\"path\": [[0, 0, 0]]}}", "path" },
    { "{\"objects\": [{\"plane\": {}}], \"light_cloud\": {\"path\": [[0, 0, 0], [1, 0]]}}",
      "path" } };
  for (const auto& b : bad)
  {
    std::string message;
    const bool ok = ParseScene(b.Json, ".", scene, message);
    PGI_CHECK(!ok && message.find(b.Expect) != std::string::npos);
    if (ok || message.find(b.Expect) == std::string::npos)
    {
      std::printf("  for %s got '%s'\n", b.Json, message.c_str());
    }
  }
  // The light cloud's region and path.
  PGI_CHECK(ParseScene("{\"objects\": [{\"plane\": {}}], \"light_cloud\": {\"region\": "
                       "[-1, 1, -2, 2, 0, 3], \"path\": [[0, 0, 1], [1, 0, 1], [1, 1, 2]]}}",
    ".", scene, error));
  PGI_CHECK(scene.HasCloudRegion && scene.CloudRegion[3] == 2.0 && scene.LightPath.size() == 9 &&
    scene.LightPath[8] == 2.0);
  // Walls and boxes: a quad faces (point1 - origin) x (point2 - origin); a
  // box's faces face out; each face has its own points.
  PGI_CHECK(ParseScene("{\"objects\": [{\"quad\": {\"origin\": [1, -1, 0], \"point1\": [1, -1, 2], "
                       "\"point2\": [1, 1, 0], \"resolution\": [4, 2]}}, "
                       "{\"box\": {\"center\": [0, 0, 1], \"size\": [0.5, 1, 2], "
                       "\"resolution\": 3}}]}",
    ".", scene, error));
  if (PGI_CHECK(BuildScene(scene, loaded, error) && loaded.Objects.size() == 2))
  {
    vtkPolyData* wall = loaded.Objects[0];
    PGI_CHECK(wall->GetNumberOfPoints() == 15 && wall->GetNumberOfPolys() == 16);
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(wall);
    normals->ComputeCellNormalsOn();
    normals->AutoOrientNormalsOff();
    normals->ConsistencyOff();
    normals->Update();
    double n[3];
    normals->GetOutput()->GetCellData()->GetNormals()->GetTuple(0, n);
    PGI_NEAR(n[0], -1.0, 1e-12);
    vtkPolyData* block = loaded.Objects[1];
    PGI_CHECK(block->GetNumberOfPoints() == 6 * 16 && block->GetNumberOfPolys() == 6 * 18);
    double b[6];
    block->GetBounds(b);
    PGI_NEAR(b[1] - b[0], 0.5, 1e-12);
    PGI_NEAR(b[5] - b[4], 2.0, 1e-12);
    normals->SetInputData(block);
    normals->Update();
    vtkDataArray* cellNormals = normals->GetOutput()->GetCellData()->GetNormals();
    int outward = 0;
    for (vtkIdType c = 0; c < block->GetNumberOfCells(); ++c)
    {
      double centre[3] = { 0, 0, 0 }, pt[3];
      vtkCell* cell = block->GetCell(c);
      for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k)
      {
        block->GetPoint(cell->GetPointId(k), pt);
        for (int a = 0; a < 3; ++a)
        {
          centre[a] += pt[a] / cell->GetNumberOfPoints();
        }
      }
      cellNormals->GetTuple(c, n);
      outward += (centre[0] * n[0] + centre[1] * n[1] + (centre[2] - 1.0) * n[2]) > 0.0 ? 1 : 0;
    }
    PGI_CHECK(outward == block->GetNumberOfCells());
  }
  // Missing mesh and missing map: found at build time, with a hint.
  PGI_CHECK(ParseScene("{\"objects\": [{\"mesh\": \"nope.off\"}]}", ".", scene, error));
  PGI_CHECK(!BuildScene(scene, loaded, error) && error.find("not found") != std::string::npos);
  PGI_CHECK(ParseScene("{\"objects\": [{\"plane\": {}}], \"environment\": {\"map\": \"none.exr\"}}",
    ".", scene, error));
  PGI_CHECK(!BuildScene(scene, loaded, error) && error.find("not found") != std::string::npos);
  PGI_CHECK(!LoadScene("/nonexistent/scene.json", scene, error));
  return pgitest::Result();
}
