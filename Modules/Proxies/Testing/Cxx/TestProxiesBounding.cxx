// Bounding on the five CGAL meshes, for the three methods: every vertex,
// every triangle (samples on it), every interior sample the filter clusters
// lies in a sphere; independent random interior points are counted too.
// E is finite and ranks the methods: variational < k-means < octree.
#include "pgiProxyMetrics.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGISphereSetApproximation.h"

#include "pgiTesting.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdio>
#include <string>

int TestProxiesBounding(int, char*[])
{
  vtkSMPTools::SetBackend("STDThread");
  const char* meshes[] = { "bunny00", "armadillo", "ChineseDragon-10kv", "cow", "dino" };
  const int count = 32;
  for (const char* name : meshes)
  {
    vtkNew<vtkPGIOFFReader> reader;
    const std::string path = std::string(PROXYGI_DATA_DIR) + "/meshes/" + name + ".off";
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkPolyData* mesh = reader->GetOutput();
    if (!PGI_CHECK(mesh->GetNumberOfPoints() > 0))
    {
      continue;
    }
    double e[3] = { 0, 0, 0 };
    for (int method = 0; method < 3; ++method)
    {
      // The dragon has a small hole: a warning, caught here.
      vtkNew<vtkTest::ErrorObserver> observer;
      vtkNew<vtkPGISphereSetApproximation> approx;
      approx->AddObserver(vtkCommand::WarningEvent, observer);
      approx->AddObserver(vtkCommand::ErrorEvent, observer);
      approx->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
      approx->SetInputData(mesh);
      approx->SetMethod(method);
      approx->SetNumberOfSpheres(count);
      approx->SetMaximumIterations(30); // the full search is in the slow sweep
      approx->Update();
      vtkPolyData* proxies = approx->GetOutput();
      PGI_CHECK(!observer->GetError());
      PGI_CHECK(proxies->GetNumberOfPoints() > 0 && proxies->GetNumberOfPoints() <= count);
      PGI_CHECK(proxies->GetPointData()->GetArray("Radius") != nullptr);
      PGI_CHECK(proxies->GetPointData()->GetArray("ObjectId") != nullptr);
      PGI_CHECK(proxies->GetPointData()->GetArray("Level") != nullptr);
      PGI_CHECK(proxies->GetPointData()->GetArray("Parent") != nullptr);
      std::string error;
      proxygi::CoverageMeasure surface, grid, random;
      PGI_CHECK(proxygi::MeasureSurfaceCoverage(mesh, proxies, 3, surface, error));
      PGI_CHECK(proxygi::MeasureInteriorCoverage(mesh, proxies, approx->GetVolumeResolution(),
        approx->GetInteriorResolution(), 50000, 11, grid, random, error));
      e[method] = approx->GetOutsideVolumeRatio(0);
      std::printf("%-20s %-11s %2lld spheres  E %.3f (sum %.3f)  %.2f s  surface %lld/%lld out, "
                  "interior grid %lld/%lld out, random interior %lld/%lld out (max gap %.2g)\n",
        name, vtkPGISphereSetApproximation::GetMethodName(method),
        static_cast<long long>(proxies->GetNumberOfPoints()), e[method],
        approx->GetOutsideVolumeRatioSum(0), approx->GetBuildTime(0), surface.Outside,
        surface.Samples, grid.Outside, grid.Samples, random.Outside, random.Samples,
        random.MaximumGap);
      // Vertices and triangle samples: all inside (radii carry 1e-9 slack).
      PGI_CHECK(surface.Samples > mesh->GetNumberOfPoints());
      PGI_CHECK(surface.Outside == 0);
      PGI_CHECK(grid.Samples > 100 && grid.Outside == 0);
      // Random interior points can fall between the samples; the
      // variational spheres leave (almost) none out.
      PGI_CHECK(random.Samples > 1000);
      PGI_BELOW(static_cast<double>(random.Outside) / random.Samples, method == 0 ? 1e-3 : 1e-2);
      PGI_CHECK(std::isfinite(e[method]) && e[method] > 0.0);
      PGI_CHECK(approx->GetOutsideVolumeRatioSum(0) >= e[method]);
    }
    PGI_CHECK(e[0] < e[2] && e[2] < e[1]);
  }
  return pgitest::Result();
}
