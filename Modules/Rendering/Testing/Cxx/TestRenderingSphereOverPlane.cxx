// The GI mapper on the canonical scene: a unit sphere 1.5 above a plane,
// per-vertex SHEXP soft shadows on the GPU for the plane (shadowed by the
// sphere proxy) and the sphere (shadowed by the ground as a blocker plane,
// and by itself through the self-shadow rules). Under a uniform white sky
// the plane must match the closed form (the CPU filter's bound); the GI pass
// runs once and is reused while only the camera moves, and reruns when the
// proxy or the light changes. The image, under a coloured sky with a sun, is
// compared with the baseline.
#include "pgiOffscreenWindow.h"
#include "pgiRenderingTestScenes.h"
#include "pgiTesting.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

int TestRenderingSphereOverPlane(int argc, char* argv[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("window: %s\n", description.c_str());
  if (!PGI_CHECK(window != nullptr))
  {
    return EXIT_FAILURE;
  }

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -4, 0);
  plane->SetPoint1(4, -4, 0);
  plane->SetPoint2(-4, 4, 0);
  plane->SetResolution(64, 64);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0, 1.5);
  ball->SetRadius(1.0);
  ball->SetThetaResolution(64);
  ball->SetPhiResolution(32);

  vtkNew<vtkPolyData> proxies;
  vtkNew<vtkPoints> centres;
  centres->InsertNextPoint(0, 0, 1.5);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  radius->InsertNextValue(1.0);
  proxies->SetPoints(centres);
  proxies->GetPointData()->AddArray(radius);
  vtkNew<vtkPGILighting> lighting; // uniform white sky

  vtkNew<vtkPGIGIPolyDataMapper> planeMapper, ballMapper;
  planeMapper->GetSettings()->IndirectOff(); // the GPU default before the shared settings
  ballMapper->GetSettings()->IndirectOff();  // the GPU default before the shared settings
  planeMapper->SetInputConnection(plane->GetOutputPort());
  ballMapper->SetInputConnection(ball->GetOutputPort());
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
  for (vtkPGIGIPolyDataMapper* m : { planeMapper.Get(), ballMapper.Get() })
  {
    m->SetProxies(proxies);
    m->SetLighting(lighting);
    m->GetSettings()->SetOrder(4);
  }
  ballMapper->AddBlockerPlane(origin, up);
  vtkNew<vtkActor> planeActor, ballActor;
  planeActor->SetMapper(planeMapper);
  ballActor->SetMapper(ballMapper);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(planeActor);
  renderer->AddActor(ballActor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);
  window->SetSize(300, 300);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.5, -7.0, 5.0);
  camera->SetFocalPoint(-0.3, 0.5, 0.5);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  renderer->ResetCameraClippingRange();
  window->Render();
  std::printf(
    "plane: %s\nball: %s\n", planeMapper->GetGIStatus().c_str(), ballMapper->GetGIStatus().c_str());

  // The plane against the closed form of a sphere over a plane (white sky).
  vtkNew<vtkFloatArray> radiance;
  PGI_CHECK(planeMapper->GetPerVertexResults(radiance));
  vtkPolyData* planeData = plane->GetOutput();
  // A failed read-back leaves an empty array; std::max below drops NaN.
  const bool planeRead = radiance->GetNumberOfTuples() == planeData->GetNumberOfPoints() &&
    radiance->GetNumberOfComponents() == 3;
  PGI_CHECK(planeRead && planeData->GetNumberOfPoints() == 65 * 65);
  PGI_CHECK(pgitest::NonFiniteValues(radiance.Get()) == 0);
  // White sky, grey albedo: every channel has the same closed form.
  for (int c = 0; planeRead && c < 3; ++c)
  {
    pgitest::ErrorSum errors;
    for (vtkIdType i = 0; i < planeData->GetNumberOfPoints(); ++i)
    {
      double x[3];
      planeData->GetPoint(i, x);
      const double d2 = x[0] * x[0] + x[1] * x[1] + 1.5 * 1.5;
      const double exact = 0.8 * (1.0 - 1.0 / d2 * 1.5 / std::sqrt(d2));
      errors.Add(radiance->GetComponent(i, c), exact);
    }
    std::printf("GPU soft shadow vs closed form, channel %d: relative RMSE %.3f%%, "
                "max error %.4f\n",
      c, 100 * errors.RelativeRMSE(), errors.Worst);
    PGI_BELOW(errors.RelativeRMSE(), 0.006); // the CPU filter's bound on this scene
    PGI_BELOW(errors.Worst, 0.012);          // measured 0.0062 (channel 0, llvmpipe), 2x margin
  }

  // The ball's bottom faces the ground: far darker than its top.
  vtkNew<vtkFloatArray> ballRadiance;
  PGI_CHECK(ballMapper->GetPerVertexResults(ballRadiance));
  double top = 0.0, bottom = 1.0;
  vtkPolyData* ballData = ball->GetOutput();
  const bool ballRead = ballRadiance->GetNumberOfTuples() == ballData->GetNumberOfPoints() &&
    ballRadiance->GetNumberOfComponents() == 3;
  PGI_CHECK(ballRead && ballData->GetNumberOfPoints() > 0);
  PGI_CHECK(pgitest::NonFiniteValues(ballRadiance.Get()) == 0);
  for (vtkIdType i = 0; ballRead && i < ballData->GetNumberOfPoints(); ++i)
  {
    double x[3];
    ballData->GetPoint(i, x);
    if (x[2] > 2.49)
    {
      top = std::max(top, static_cast<double>(ballRadiance->GetComponent(i, 0)));
    }
    if (x[2] < 0.51)
    {
      bottom = std::min(bottom, static_cast<double>(ballRadiance->GetComponent(i, 0)));
    }
  }
  std::printf("ball: top %.4f, bottom %.4f\n", top, bottom);
  PGI_BELOW(bottom, 0.1);
  PGI_BELOW(0.6, top);

  // Camera moves reuse the GI results; a moved proxy recomputes them.
  camera->Azimuth(10);
  window->Render();
  PGI_CHECK(planeMapper->GetNumberOfGIUpdates() == 1);
  PGI_CHECK(ballMapper->GetNumberOfGIUpdates() == 1);
  camera->Azimuth(-10);
  centres->SetPoint(0, 0, 0, 1.6);
  proxies->Modified();
  window->Render();
  PGI_CHECK(planeMapper->GetNumberOfGIUpdates() == 2);
  centres->SetPoint(0, 0, 0, 1.5);
  proxies->Modified();
  window->Render();
  PGI_CHECK(planeMapper->GetNumberOfGIUpdates() == 3);

  // Display knobs change no GI.
  planeMapper->SetExposure(0.3);
  ballMapper->SetExposure(0.3);
  window->Render();
  PGI_CHECK(planeMapper->GetNumberOfGIUpdates() == 3);

  // The picture: a coloured sky with a sun (a new light recomputes GI).
  lighting->SetEnvironmentImage(pgitest::Sky());
  window->Render();
  PGI_CHECK(planeMapper->GetNumberOfGIUpdates() == 4);
  std::printf("with the sky: %s\n", planeMapper->GetGIStatus().c_str());

  const int image = vtkRegressionTestImage(window);

  // VTK's own lighting added to GI brightens the ball; GI off is VTK alone.
  auto centre = [&]()
  {
    vtkNew<vtkUnsignedCharArray> pixels;
    window->GetPixelData(150, 150, 150, 150, 0, pixels);
    return pixels->GetValue(0) + pixels->GetValue(1) + pixels->GetValue(2);
  };
  const int gi = centre();
  ballMapper->CombineWithVTKLightingOn();
  window->Render();
  const int combined = centre();
  ballMapper->GlobalIlluminationOff();
  window->Render();
  const int vtkOnly = centre();
  std::printf("ball centre (sum of RGB): GI %d, GI + VTK lighting %d, VTK lighting %d\n", gi,
    combined, vtkOnly);
  PGI_CHECK(combined > gi);
  PGI_CHECK(vtkOnly != gi && ballMapper->GetNumberOfGIUpdates() == 4);
  return (image == vtkTesting::FAILED || pgitest::Result() != EXIT_SUCCESS) ? EXIT_FAILURE
                                                                            : EXIT_SUCCESS;
}
