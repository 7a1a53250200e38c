// Image-space GI on a whole scene: the default scene's bunny (its committed
// 32 proxies) with a red and a green ball on a ground plane under the forest
// map, soft shadows and one-bounce light at a 1/2 receiver buffer with
// bilateral upsampling. Checks colour bleeding (the ground next to each ball
// takes its hue), no NaN pixel (all pixels finite in the visibility buffer),
// then the image against its baseline. Needs the data set-up fetches
// (skipped without it).
#include "pgiBunnyScene.h"
#include "pgiOffscreenWindow.h"
#include "pgiSRGB.h"
#include "pgiTesting.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTesting.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdio>
#include <string>

using proxygi::FromSRGB8;

int TestRenderingImageSpaceScene(int argc, char* argv[])
{
  if (!pgitest::BunnyDataPresent())
  {
    return pgitest::MissingDataResult();
  }
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("window: %s\n", description.c_str());
  if (!PGI_CHECK(window != nullptr))
  {
    return EXIT_FAILURE;
  }

  // Proxies: the bunny's committed 32, grey, and the balls exactly, coloured.
  const pgitest::BallScene scene;
  vtkSmartPointer<vtkPolyData> proxies = scene.Proxies(false);
  vtkNew<vtkRenderer> renderer;
  for (const auto& b : scene.Balls)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(b.Centre);
    sphere->SetRadius(b.Radius);
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(32);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(b.Albedo[0], b.Albedo[1], b.Albedo[2]);
    renderer->AddActor(actor);
  }

  vtkNew<vtkPlaneSource> ground;
  ground->SetOrigin(-3, -3, 0);
  ground->SetPoint1(3, -3, 0);
  ground->SetPoint2(-3, 3, 0);
  ground->SetResolution(32, 32);
  ground->Update();
  vtkSmartPointer<vtkPolyData> bunny = pgitest::PlacedBunny();
  for (vtkPolyData* mesh : { bunny.Get(), ground->GetOutput() })
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(mesh);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
    renderer->AddActor(actor);
  }

  vtkSmartPointer<vtkPGILighting> lighting = pgitest::ForestLighting();
  vtkNew<vtkPGIImageSpaceGIPass> pass;
  pass->GetSettings()->IndirectOff(); // the GPU default before the shared settings
  pass->SetProxies(proxies);
  pass->SetLighting(lighting);
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, grey[3] = { 0.8, 0.8, 0.8 };
  pass->AddBlockerPlane(origin, up, grey);
  pass->SetReceiverScale(2);
  pass->SetExposure(0.6);
  renderer->SetPass(pass);
  renderer->SetBackground(0.1, 0.1, 0.12);
  window->AddRenderer(renderer);
  window->SetSize(300, 300);
  pgitest::BallScene::SetCamera(renderer->GetActiveCamera());
  renderer->ResetCameraClippingRange();

  // Ground points next to each ball (on the camera side), with and without
  // the bounce: the red ball reddens its neighbourhood, the green one greens.
  auto groundColour = [&](const double* at, double rgb[3])
  {
    renderer->SetWorldPoint(at[0], at[1], at[2], 1.0);
    renderer->WorldToDisplay();
    const double* d = renderer->GetDisplayPoint();
    unsigned char* pixel = window->GetPixelData(static_cast<int>(d[0]), static_cast<int>(d[1]),
      static_cast<int>(d[0]), static_cast<int>(d[1]), 0);
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = FromSRGB8(pixel[c]);
    }
    delete[] pixel;
  };
  const double* nearRed = scene.NearRed;
  const double* nearGreen = scene.NearGreen;
  double redOff[3], greenOff[3], redOn[3], greenOn[3];
  window->Render();
  groundColour(nearRed, redOff);
  groundColour(nearGreen, greenOff);
  pass->GetSettings()->IndirectOn();
  window->Render();
  std::printf("%s\n", pass->GetStatus().c_str());
  groundColour(nearRed, redOn);
  groundColour(nearGreen, greenOn);
  std::printf("ground by the red ball: shadows only %.3f %.3f %.3f, with the bounce %.3f %.3f "
              "%.3f\nground by the green ball: shadows only %.3f %.3f %.3f, with the bounce %.3f "
              "%.3f %.3f\n",
    redOff[0], redOff[1], redOff[2], redOn[0], redOn[1], redOn[2], greenOff[0], greenOff[1],
    greenOff[2], greenOn[0], greenOn[1], greenOn[2]);
  // The bounce (grey from the bunny and the ground, coloured from the
  // balls) adds more of the nearby ball's colour than of the other's
  // (measured: red/green gain 1.48 by the red ball, green/red 2.2 by the
  // green one).
  PGI_CHECK(redOn[0] - redOff[0] > 1.2 * (redOn[1] - redOff[1]));
  PGI_CHECK(greenOn[1] - greenOff[1] > 1.5 * (greenOn[0] - greenOff[0]));
  PGI_CHECK(redOn[0] > redOff[0] && greenOn[1] > greenOff[1]);
  // No NaN: every SH coefficient of the receiver buffer is finite, and the
  // buffer holds receivers.
  vtkNew<vtkFloatArray> visibility, mask;
  PGI_CHECK(pass->GetVisibilityBuffer(visibility, mask));
  const long nonFinite = pgitest::NonFiniteValues(visibility.Get());
  std::printf("receiver buffer: %lld samples x %d coefficients, %ld non-finite\n",
    static_cast<long long>(visibility->GetNumberOfTuples()), visibility->GetNumberOfComponents(),
    nonFinite);
  PGI_CHECK(visibility->GetNumberOfTuples() > 0 && mask->GetRange(0)[1] > 0.5);
  PGI_CHECK(nonFinite == 0);

  const int image = vtkRegressionTestImage(window);
  return (image == vtkTesting::FAILED || pgitest::Result() != EXIT_SUCCESS) ? EXIT_FAILURE
                                                                            : EXIT_SUCCESS;
}
