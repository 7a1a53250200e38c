// The default scene's bunny on a ground plane under the forest map, per-vertex
// GI on the GPU: the bunny shadowed by its 32 sphere proxies (self-shadowing
// through the replacement rules) and the ground, the ground by the proxies.
// The proxies were built once by vtkPGISphereSetApproximation (variational,
// 32 spheres, E = 0.36) on the bunny as placed here and are committed
// (Testing/Data/bunny-proxies-32.vtp), so the image does not follow changes
// of that algorithm. Checks GPU against CPU on the bunny, then the image.
// Needs the data set-up fetches (skipped without it).
#include "pgiBunnyScene.h"
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"
#include "vtkPGIEXRReader.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTesting.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

int TestRenderingBunny(int argc, char* argv[])
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

  // The bunny as the default scene places it: z up, feet on z = 0.
  vtkSmartPointer<vtkPolyData> bunny = pgitest::PlacedBunny();

  vtkNew<vtkPlaneSource> ground;
  ground->SetOrigin(-3, -3, 0);
  ground->SetPoint1(3, -3, 0);
  ground->SetPoint2(-3, 3, 0);
  ground->SetResolution(96, 96);

  vtkSmartPointer<vtkPolyData> proxies = pgitest::BunnyProxies();
  PGI_CHECK(proxies->GetNumberOfPoints() == 32);

  vtkSmartPointer<vtkPGILighting> lighting = pgitest::ForestLighting();

  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
  vtkNew<vtkPGIGIPolyDataMapper> bunnyMapper, groundMapper;
  bunnyMapper->GetSettings()->IndirectOff();  // the GPU default before the shared settings
  groundMapper->GetSettings()->IndirectOff(); // the GPU default before the shared settings
  bunnyMapper->SetInputData(bunny);
  bunnyMapper->AddBlockerPlane(origin, up);
  groundMapper->SetInputConnection(ground->GetOutputPort());
  groundMapper->GetSettings()->SetDefaultAlbedo(0.5, 0.5, 0.5);
  for (vtkPGIGIPolyDataMapper* m : { bunnyMapper.Get(), groundMapper.Get() })
  {
    m->SetProxies(proxies);
    m->SetLighting(lighting);
    m->GetSettings()->SetOrder(4);
    m->SetExposure(0.6);
  }
  vtkNew<vtkActor> bunnyActor, groundActor;
  bunnyActor->SetMapper(bunnyMapper);
  groundActor->SetMapper(groundMapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(bunnyActor);
  renderer->AddActor(groundActor);
  renderer->SetBackground(0.1, 0.1, 0.12);
  window->AddRenderer(renderer);
  window->SetSize(300, 300);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.6, -2.6, 1.5);
  camera->SetFocalPoint(0, 0, 0.35);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  renderer->ResetCameraClippingRange();
  window->Render();
  std::printf("bunny: %s\nground: %s\n", bunnyMapper->GetGIStatus().c_str(),
    groundMapper->GetGIStatus().c_str());

  // GPU against the CPU filter on the bunny (product-matrix path).
  vtkNew<vtkFloatArray> radiance;
  PGI_CHECK(bunnyMapper->GetPerVertexResults(radiance));
  vtkNew<vtkPGIGlobalIllumination> cpu;
  cpu->SetInputData(bunny);
  cpu->SetProxiesData(proxies);
  cpu->SetLighting(lighting);
  cpu->GetSettings()->SetOrder(4);
  cpu->GetSettings()->IndirectOff();
  cpu->GetSettings()->LocalLightsOff();
  cpu->GetSettings()->BrightLightsOff(); // the GPU backends keep the whole map in the SH
  cpu->GetSettings()->SetShadingPath(vtkPGIGISettings::SHADING_PRODUCT_MATRIX);
  cpu->AddBlockerPlane(origin, up);
  cpu->Update();
  vtkDataArray* reference = cpu->GetOutput()->GetPointData()->GetArray("DirectShadowed");
  double worst = 0.0, peak = 0.0;
  pgitest::ErrorSum errors;
  // One finite RGB per vertex read back (a failed read-back has none).
  PGI_CHECK(radiance->GetNumberOfTuples() == bunny->GetNumberOfPoints());
  PGI_CHECK(pgitest::NonFiniteValues(radiance.Get()) == 0);
  for (vtkIdType i = 0; i < std::min(radiance->GetNumberOfTuples(), bunny->GetNumberOfPoints());
       ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double a = radiance->GetComponent(i, k), b = reference->GetComponent(i, k);
      worst = std::max(worst, std::fabs(a - b));
      peak = std::max(peak, std::fabs(b));
      errors.Add(a, b);
    }
  }
  std::printf("bunny, %lld vertices, 32 proxies: GPU vs CPU max %.2e (relative %.2e), relative "
              "RMS %.2e\n",
    static_cast<long long>(bunny->GetNumberOfPoints()), worst, worst / peak, errors.RelativeRMSE());
  PGI_BELOW(worst / peak, 1e-4);
  PGI_BELOW(errors.RelativeRMSE(), 1e-4); // false for NaN

  const int image = vtkRegressionTestImage(window);
  return (image == vtkTesting::FAILED || pgitest::Result() != EXIT_SUCCESS) ? EXIT_FAILURE
                                                                            : EXIT_SUCCESS;
}
