// The light cloud precompute against closed forms and its own guarantees:
//  - a plane under point lights: the direct response is a/pi cos/d^2 to
//    float precision, and its indirect light is zero (nothing to bounce);
//  - a light shut in a box lights nothing;
//  - the indirect response agrees with the Embree reference of the same
//    point light (an independent estimator), within their noise;
//  - the cache: a stopped run resumes, the resumed cloud equals an
//    uninterrupted one bit for bit, a finished cache is read, not traced;
//  - bad input: no receivers, NaN light positions, no lights, a corrupted
//    cache, each a clear error.
#include "pgiTesting.h"
#include "pgiTestingErrors.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPrecompute.h"
#include "vtkPGILighting.h"
#include "vtkPGIReferenceIllumination.h"

#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkTriangleFilter.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace
{
vtkSmartPointer<vtkPolyData> Plane(double size, int resolution, double z = 0.0)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.5 * size, -0.5 * size, z);
  plane->SetPoint1(0.5 * size, -0.5 * size, z);
  plane->SetPoint2(-0.5 * size, 0.5 * size, z);
  plane->SetResolution(resolution, resolution);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

// Stops the filter once its progress passes `At`.
class AbortAt : public vtkCommand
{
public:
  static AbortAt* New() { return new AbortAt; }
  double At = 0.5;
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    if (*static_cast<double*>(data) >= this->At)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  }
};
} // namespace

int TestLightCloudPrecompute(int argc, char* argv[])
{
  const std::string dir = pgitest::TempDirectory(argc, argv);
  const double pi = vtkMath::Pi();

  // 1. Direct light on a lone plane: the closed form.
  auto plane = Plane(2.0, 8);
  vtkNew<vtkPoints> positions;
  positions->InsertNextPoint(0.1, 0.2, 1.0);
  positions->InsertNextPoint(-0.5, 0.3, 0.5);
  positions->InsertNextPoint(0.9, -0.9, 0.05);
  vtkNew<vtkPGILightCloudPrecompute> precompute;
  precompute->SetInputData(plane);
  precompute->SetLightPositions(positions);
  precompute->IncludeDirectOn();
  precompute->SetSamples(16);
  precompute->SetSurfaceMargin(0.0); // the light 0.05 over the plane stays
  precompute->Update();
  vtkPGILightCloud* cloud = precompute->GetOutput();
  PGI_CHECK(cloud->GetNumberOfLights() == 3 && cloud->GetNumberOfReceivers() == 81);
  PGI_CHECK(cloud->GetContents() == vtkPGILightCloud::DirectAndIndirect);
  double worst = 0.0;
  for (vtkIdType j = 0; j < 3; ++j)
  {
    double p[3];
    positions->GetPoint(j, p);
    for (vtkIdType i = 0; i < plane->GetNumberOfPoints(); ++i)
    {
      double x[3];
      plane->GetPoint(i, x);
      const double d2 = vtkMath::Distance2BetweenPoints(x, p);
      const double exact = 0.8 / pi * (p[2] - x[2]) / std::sqrt(d2) / d2;
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst, std::fabs(cloud->GetResponse(j)[3 * i + c] - exact) / exact);
      }
    }
  }
  std::printf("plane, direct: worst relative error %.3g\n", worst);
  PGI_BELOW(worst, 2e-5);
  precompute->IncludeDirectOff();
  precompute->Update();
  double indirect = 0.0;
  for (vtkIdType k = 0; k < 3 * 81 * 3; ++k)
  {
    indirect = std::max(indirect, static_cast<double>(std::fabs(cloud->GetResponse(0)[k])));
  }
  PGI_NEAR(indirect, 0.0, 0.0);
  PGI_CHECK(cloud->GetContents() == vtkPGILightCloud::IndirectOnly);

  // 2. A light shut in a closed box above the plane lights nothing; one
  //    outside it does (the same run).
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(0.0, 0.0, 1.0);
  cube->SetXLength(0.4);
  cube->SetYLength(0.4);
  cube->SetZLength(0.4);
  vtkNew<vtkTriangleFilter> cubeTriangles;
  cubeTriangles->SetInputConnection(cube->GetOutputPort());
  cubeTriangles->Update();
  vtkNew<vtkPoints> boxed;
  boxed->InsertNextPoint(0.0, 0.0, 1.0);
  boxed->InsertNextPoint(0.0, 0.0, 1.5);
  precompute->SetLightPositions(boxed);
  precompute->AddSceneObjectData(cubeTriangles->GetOutput());
  precompute->IncludeDirectOn();
  precompute->Update();
  PGI_CHECK(cloud->GetNumberOfLights() == 2 && precompute->GetLightsDropped() == 0);
  double shut = 0.0, open = 0.0;
  for (vtkIdType k = 0; k < 3 * 81; ++k)
  {
    shut += cloud->GetResponse(0)[k];
    open += cloud->GetResponse(1)[k];
  }
  PGI_NEAR(shut, 0.0, 0.0);
  PGI_CHECK(open > 0.1);
  // By default the shut light is left out, and one 0.05 over the plane is
  // lifted to the margin (a quarter of the lights' spacing); not below the
  // plane, which is outside the lights' bounds.
  precompute->SetSurfaceMargin(-1.0);
  boxed->InsertNextPoint(0.5, 0.5, 0.05);
  boxed->Modified();
  precompute->Update();
  PGI_CHECK(cloud->GetNumberOfLights() == 2 && precompute->GetLightsDropped() == 1 &&
    precompute->GetLightsMoved() == 1);
  double kept[3], lifted[3];
  cloud->GetLightPositions()->GetPoint(0, kept);
  PGI_NEAR(kept[2], 1.5, 0.0);
  cloud->GetLightPositions()->GetPoint(1, lifted);
  PGI_CHECK(lifted[2] > 0.05 && lifted[2] < 1.5);
  std::printf("lifted light at z = %.4f\n", lifted[2]);
  precompute->RemoveAllSceneObjects();

  // 3. Indirect light against the Embree reference: a floor and a wall, a
  //    point light between them.
  auto floor = Plane(2.0, 12);
  vtkNew<vtkPlaneSource> wallSource;
  wallSource->SetOrigin(1.0, -1.0, 0.0);
  wallSource->SetPoint1(1.0, -1.0, 2.0);
  wallSource->SetPoint2(1.0, 1.0, 0.0);
  wallSource->SetResolution(12, 12);
  vtkNew<vtkTriangleFilter> wall;
  wall->SetInputConnection(wallSource->GetOutputPort());
  wall->Update();
  vtkNew<vtkPoints> one;
  one->InsertNextPoint(0.3, 0.1, 0.6);
  vtkNew<vtkPGILightCloudPrecompute> bounce;
  bounce->SetInputData(floor);
  bounce->AddSceneObjectData(wall->GetOutput());
  bounce->SetLightPositions(one);
  bounce->SetSamples(2048);
  bounce->Update();
  vtkNew<vtkPGILighting> lighting;
  lighting->SetUniformRadiance(0.0, 0.0, 0.0);
  lighting->AddPointLight(0.3, 0.1, 0.6, 1.0, 1.0, 1.0);
  vtkNew<vtkPGIReferenceIllumination> reference;
  reference->SetInputData(floor);
  reference->AddSceneObjectData(wall->GetOutput());
  reference->SetLighting(lighting);
  reference->SetSamples(4096);
  reference->Update();
  auto* truth = vtkFloatArray::SafeDownCast(
    reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce"));
  pgitest::ErrorSum errors;
  auto* truthErr =
    vtkFloatArray::SafeDownCast(reference->GetOutput()->GetPointData()->GetArray("IndirectStdErr"));
  double sum = 0.0, sumTruth = 0.0, noise = 0.0;
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    errors.Add(bounce->GetOutput()->GetResponse(0)[3 * i], truth->GetComponent(i, 0));
    sum += bounce->GetOutput()->GetResponse(0)[3 * i];
    sumTruth += truth->GetComponent(i, 0);
    noise += truthErr->GetComponent(i, 0) * truthErr->GetComponent(i, 0);
  }
  noise = std::sqrt(noise / errors.Reference);
  std::printf("floor and wall, indirect: relative RMSE %.4f against Embree (its own noise %.4f), "
              "sums %.4f\n",
    errors.RelativeRMSE(), noise, sum / sumTruth);
  // Both are Monte Carlo: the cloud's 2048 gather rays are about as noisy
  // as the reference's 4096 samples with two rays each.
  PGI_BELOW(errors.RelativeRMSE(), 2.5 * noise);
  PGI_NEAR(sum / sumTruth, 1.0, 0.02);
  PGI_CHECK(errors.Reference > 0.0);

  // 4. The cache: stop, resume, read.
  const std::string cache = dir + "/TestLightCloudPrecompute.cloud";
  std::remove(cache.c_str());
  vtkNew<vtkPGILightCloudPrecompute> grid;
  grid->SetInputData(floor);
  grid->AddSceneObjectData(wall->GetOutput());
  grid->SetRegionOfInterest(-0.9, 0.9, -0.9, 0.9, 0.2, 1.4);
  grid->SetGridResolution(3, 3, 2);
  grid->SetSamples(16);
  grid->Update();
  vtkNew<vtkPGILightCloud> whole;
  whole->DeepCopy(grid->GetOutput());
  PGI_CHECK(whole->GetNumberOfLights() == 18 && grid->GetLightsTraced() == 18);
  grid->SetCacheFileName(cache.c_str());
  vtkNew<AbortAt> stop;
  stop->At = 0.4;
  const unsigned long tag = grid->AddObserver(vtkCommand::ProgressEvent, stop);
  PGI_CHECK(pgitest::WarnsSaying(grid, "Aborted after"));
  grid->RemoveObserver(tag);
  grid->SetAbortExecute(0);
  const vtkIdType stoppedAt = grid->GetLightsTraced();
  PGI_CHECK(stoppedAt > 0 && stoppedAt < 18);
  PGI_CHECK(grid->GetOutput()->GetNumberOfLights() == 0);
  grid->Modified();
  grid->Update();
  std::printf("cache: stopped after %lld lights, resumed with %lld from the cache, %lld traced\n",
    static_cast<long long>(stoppedAt), static_cast<long long>(grid->GetLightsFromCache()),
    static_cast<long long>(grid->GetLightsTraced()));
  PGI_CHECK(grid->GetLightsFromCache() == stoppedAt);
  PGI_CHECK(grid->GetLightsTraced() == 18 - stoppedAt);
  double diff = 0.0;
  for (vtkIdType j = 0; j < 18; ++j)
  {
    for (vtkIdType k = 0; k < 3 * floor->GetNumberOfPoints(); ++k)
    {
      diff = std::max(diff,
        static_cast<double>(
          std::fabs(grid->GetOutput()->GetResponse(j)[k] - whole->GetResponse(j)[k])));
    }
  }
  PGI_NEAR(diff, 0.0, 0.0);
  grid->Modified();
  grid->Update();
  PGI_CHECK(grid->GetLightsFromCache() == 18 && grid->GetLightsTraced() == 0);
  // Other settings: the cache is replaced, not misread.
  grid->SetSamples(8);
  PGI_CHECK(pgitest::WarnsSaying(grid, "holds another scene's or settings' cloud"));
  PGI_CHECK(grid->GetLightsTraced() == 18);
  // A corrupted cache is an error, not silently replaced.
  {
    std::fstream f(cache, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(60);
    f.put('\x7f');
  }
  PGI_CHECK(pgitest::FailsSaying(grid, "delete the file to recompute"));
  std::remove(cache.c_str());
  grid->SetCacheFileName(nullptr);

  // 5. Bad input.
  vtkNew<vtkPGILightCloudPrecompute> bad;
  bad->SetInputData(vtkNew<vtkPolyData>());
  PGI_CHECK(pgitest::FailsSaying(bad, "No receivers"));
  bad->SetInputData(floor);
  vtkNew<vtkPoints> nan;
  nan->InsertNextPoint(0.0, std::nan(""), 1.0);
  bad->SetLightPositions(nan);
  PGI_CHECK(pgitest::FailsSaying(bad, "NaN or Inf position"));
  bad->SetLightPositions(vtkNew<vtkPoints>());
  PGI_CHECK(pgitest::FailsSaying(bad, "No cloud lights"));
  bad->SetLightPositions(nullptr);
  bad->SetGridResolution(0, 3, 3);
  PGI_CHECK(pgitest::FailsSaying(bad, "GridResolution"));
  return pgitest::Result();
}
