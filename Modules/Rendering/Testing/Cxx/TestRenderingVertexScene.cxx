// Per-vertex GI on the GPU on a whole scene with colour bleeding: the
// default scene's bunny (its committed 32 proxies) with a red and a green
// ball on a ground plane under the forest map, every object drawn by a
// vtkPGIGIPolyDataMapper with soft shadows and the one-bounce light (both
// models). Checks colour bleeding on the ground vertices next to each ball
// (read back: the nearby ball's hue gains most), finite radiance, then the
// image (shadowed bounce) against its baseline. The same scene as
// TestRenderingImageSpaceScene, per vertex. Needs the data set-up fetches
// (skipped without it).
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"
#include "vtkPGIEXRReader.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTesting.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

int TestRenderingVertexScene(int argc, char* argv[])
{
  const std::string bunnyPath = std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
  const std::string forestPath = std::string(PROXYGI_DATA_DIR) + "/environments/forest.exr";
  if (!vtksys::SystemTools::FileExists(bunnyPath) || !vtksys::SystemTools::FileExists(forestPath))
  {
    std::printf("skipped: %s or %s missing (run Utilities/setup.sh --data)\n", bunnyPath.c_str(),
      forestPath.c_str());
    return VTK_SKIP_RETURN_CODE;
  }
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("window: %s\n", description.c_str());
  if (!PGI_CHECK(window != nullptr))
  {
    return EXIT_FAILURE;
  }

  vtkNew<vtkPGIOFFReader> reader;
  reader->SetFileName(bunnyPath.c_str());
  vtkNew<vtkTransform> place;
  place->PostMultiply();
  place->RotateX(90);
  place->Translate(0, 0, 0.494);
  vtkNew<vtkTransformPolyDataFilter> bunny;
  bunny->SetInputConnection(reader->GetOutputPort());
  bunny->SetTransform(place);
  vtkNew<vtkPolyDataNormals> bunnyNormals;
  bunnyNormals->SetInputConnection(bunny->GetOutputPort());
  bunnyNormals->SplittingOff();
  bunnyNormals->Update();

  // Proxies: the bunny's committed 32 (object 0, grey), the balls exactly
  // (objects 1 and 2, coloured).
  vtkNew<vtkXMLPolyDataReader> proxiesReader;
  const std::string proxiesPath = std::string(PGI_RENDERING_TEST_DATA) + "/bunny-proxies-32.vtp";
  proxiesReader->SetFileName(proxiesPath.c_str());
  proxiesReader->Update();
  vtkPolyData* bunnyProxies = proxiesReader->GetOutput();
  vtkNew<vtkPoints> centres;
  vtkNew<vtkFloatArray> radii, albedos, objects;
  radii->SetName("Radius");
  albedos->SetName("Albedo");
  albedos->SetNumberOfComponents(3);
  objects->SetName("ObjectId");
  vtkDataArray* bunnyRadii = bunnyProxies->GetPointData()->GetArray("Radius");
  for (vtkIdType i = 0; i < bunnyProxies->GetNumberOfPoints(); ++i)
  {
    centres->InsertNextPoint(bunnyProxies->GetPoint(i));
    radii->InsertNextValue(static_cast<float>(bunnyRadii->GetTuple1(i)));
    albedos->InsertNextTuple3(0.8, 0.8, 0.8);
    objects->InsertNextValue(0);
  }
  struct Ball
  {
    double Centre[3], Radius, Albedo[3];
  };
  const Ball balls[2] = { { { -0.95, 0.35, 0.35 }, 0.35, { 0.9, 0.1, 0.1 } },
    { { 0.85, 0.45, 0.35 }, 0.35, { 0.1, 0.8, 0.15 } } };
  struct Object
  {
    vtkSmartPointer<vtkPolyData> Mesh;
    double Albedo[3];
  };
  std::vector<Object> scene;
  scene.push_back({ bunnyNormals->GetOutput(), { 0.8, 0.8, 0.8 } });
  for (int k = 0; k < 2; ++k)
  {
    const Ball& b = balls[k];
    centres->InsertNextPoint(b.Centre);
    radii->InsertNextValue(static_cast<float>(b.Radius));
    albedos->InsertNextTuple3(b.Albedo[0], b.Albedo[1], b.Albedo[2]);
    objects->InsertNextValue(static_cast<float>(k + 1));
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(b.Centre);
    sphere->SetRadius(b.Radius);
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(32);
    sphere->Update();
    scene.push_back({ sphere->GetOutput(), { b.Albedo[0], b.Albedo[1], b.Albedo[2] } });
  }
  vtkNew<vtkPolyData> proxies;
  proxies->SetPoints(centres);
  proxies->GetPointData()->AddArray(radii);
  proxies->GetPointData()->AddArray(albedos);
  proxies->GetPointData()->AddArray(objects);
  vtkNew<vtkPlaneSource> ground;
  ground->SetOrigin(-3, -3, 0);
  ground->SetPoint1(3, -3, 0);
  ground->SetPoint2(-3, 3, 0);
  ground->SetResolution(60, 60);
  ground->Update();
  scene.push_back({ ground->GetOutput(), { 0.8, 0.8, 0.8 } });

  vtkNew<vtkPGIEXRReader> forest;
  forest->SetFileName(forestPath.c_str());
  forest->Update();
  vtkNew<vtkPGILighting> lighting;
  lighting->SetEnvironmentImage(forest->GetOutput());
  vtkNew<vtkRenderer> renderer;
  std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> mappers;
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, grey[3] = { 0.8, 0.8, 0.8 };
  for (const Object& o : scene)
  {
    auto mapper = vtkSmartPointer<vtkPGIGIPolyDataMapper>::New();
    mapper->SetInputData(o.Mesh);
    mapper->SetProxies(proxies);
    mapper->SetLighting(lighting);
    mapper->AddBlockerPlane(origin, up, grey);
    mapper->SetAlbedo(o.Albedo[0], o.Albedo[1], o.Albedo[2]);
    mapper->SetExposure(0.6);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    mappers.push_back(mapper);
  }
  renderer->SetBackground(0.1, 0.1, 0.12);
  window->AddRenderer(renderer);
  window->SetSize(300, 300);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.3, -3.4, 2.2);
  camera->SetFocalPoint(0, 0.2, 0.3);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(35);
  renderer->ResetCameraClippingRange();

  // The ground's vertex next to each ball (on the camera side), read back.
  vtkPolyData* plane = ground->GetOutput();
  const auto nearest = [&](const double* at)
  {
    vtkIdType best = 0;
    double bestD = 1e30;
    for (vtkIdType i = 0; i < plane->GetNumberOfPoints(); ++i)
    {
      double x[3];
      plane->GetPoint(i, x);
      const double d = (x[0] - at[0]) * (x[0] - at[0]) + (x[1] - at[1]) * (x[1] - at[1]);
      if (d < bestD)
      {
        bestD = d;
        best = i;
      }
    }
    return best;
  };
  const double nearRedAt[3] = { -0.95, -0.05, 0.0 }, nearGreenAt[3] = { 0.85, 0.05, 0.0 };
  const vtkIdType nearRed = nearest(nearRedAt), nearGreen = nearest(nearGreenAt);
  const auto groundRadiance = [&](vtkIdType i, double rgb[3])
  {
    vtkNew<vtkFloatArray> radiance;
    PGI_CHECK(mappers.back()->GetPerVertexResults(radiance));
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = radiance->GetNumberOfTuples() > i ? radiance->GetComponent(i, c) : 0.0;
    }
  };
  window->Render();
  double redOff[3], greenOff[3];
  groundRadiance(nearRed, redOff);
  groundRadiance(nearGreen, greenOff);
  int image = vtkTesting::PASSED;
  for (int mode : { vtkPGIGIPolyDataMapper::INDIRECT_MODE_UNSHADOWED,
         vtkPGIGIPolyDataMapper::INDIRECT_MODE_SHADOWED })
  {
    for (auto& mapper : mappers)
    {
      mapper->IndirectOn();
      mapper->SetIndirectMode(mode);
    }
    window->Render();
    std::printf("%s\n", mappers.back()->GetGIStatus().c_str());
    double redOn[3], greenOn[3];
    groundRadiance(nearRed, redOn);
    groundRadiance(nearGreen, greenOn);
    const char* name =
      mode == vtkPGIGIPolyDataMapper::INDIRECT_MODE_SHADOWED ? "shadowed" : "unshadowed";
    std::printf("%s bounce: ground by the red ball %.4f %.4f %.4f -> %.4f %.4f %.4f; by the "
                "green ball %.4f %.4f %.4f -> %.4f %.4f %.4f\n",
      name, redOff[0], redOff[1], redOff[2], redOn[0], redOn[1], redOn[2], greenOff[0], greenOff[1],
      greenOff[2], greenOn[0], greenOn[1], greenOn[2]);
    std::printf("  red gain / green gain by the red ball %.2f, green / red by the green ball "
                "%.2f\n",
      (redOn[0] - redOff[0]) / std::max(1e-9, redOn[1] - redOff[1]),
      (greenOn[1] - greenOff[1]) / std::max(1e-9, greenOn[0] - greenOff[0]));
    // The bounce adds more of the nearby ball's colour than of the other's.
    PGI_CHECK(redOn[0] - redOff[0] > 1.2 * (redOn[1] - redOff[1]));
    PGI_CHECK(greenOn[1] - greenOff[1] > 1.5 * (greenOn[0] - greenOff[0]));
    PGI_CHECK(redOn[0] > redOff[0] && greenOn[1] > greenOff[1]);
    for (auto& mapper : mappers)
    {
      vtkNew<vtkFloatArray> radiance;
      PGI_CHECK(mapper->GetPerVertexResults(radiance));
      double low = 0.0;
      for (vtkIdType i = 0; i < radiance->GetNumberOfValues(); ++i)
      {
        const double v = radiance->GetValue(i);
        low = std::isfinite(v) ? std::min(low, v) : -1e30;
      }
      PGI_CHECK(low >= 0.0);
    }
  }
  image = vtkRegressionTestImage(window);
  return (image == vtkTesting::FAILED || pgitest::Result() != EXIT_SUCCESS) ? EXIT_FAILURE
                                                                            : EXIT_SUCCESS;
}
