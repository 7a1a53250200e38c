// The outside-volume metric E against closed forms on a cube, the union
// against the sum for overlapping spheres, and its convergence with the row
// resolution on the bunny (the error stated in Documentation/Proxies.md).
#include "pgiProxyMetrics.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGISphereSetApproximation.h"

#include "pgiTesting.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
// Divergence-theorem volume of a closed triangle mesh.
double MeshVolume(vtkPolyData* mesh)
{
  double volume = 0.0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    double a[3], b[3], d[3];
    mesh->GetPoint(ids->GetId(0), a);
    for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
    {
      mesh->GetPoint(ids->GetId(k), b);
      mesh->GetPoint(ids->GetId(k + 1), d);
      volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                  a[2] * (b[0] * d[1] - b[1] * d[0])) /
        6.0;
    }
  }
  return volume;
}
} // namespace

int TestProxiesOutsideVolume(int, char*[])
{
  using namespace proxygi;
  vtkSMPTools::SetBackend("STDThread");
  // A closed cube [-1, 1]^3 (quads, merged corners: triangulated inside).
  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->SetXLength(2.0);
  cubeSource->SetYLength(2.0);
  cubeSource->SetZLength(2.0);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(cubeSource->GetOutputPort());
  clean->Update();
  vtkPolyData* cube = clean->GetOutput();
  std::string error;
  OutsideVolumeMeasure m;

  // Circumscribed sphere: E = (4/3 pi 3^1.5 - 8) / 8.
  const double r3 = std::sqrt(3.0);
  PGI_CHECK(MeasureOutsideVolume(cube, std::vector<Sphere>{ { { 0, 0, 0 }, r3 } }, 256, m, error));
  const double exact = (SphereVolume(r3) - 8.0) / 8.0;
  std::printf("cube, circumsphere: E %.6f (exact %.6f), sum %.6f, mesh volume %.6f\n", m.Ratio,
    exact, m.SumRatio, m.MeshVolume);
  PGI_NEAR(m.MeshVolume, 8.0, 1e-9);
  PGI_NEAR(m.Ratio, exact, 1e-3 * exact);
  PGI_NEAR(m.SumRatio, exact, 1e-3 * exact);
  PGI_NEAR(m.UncoveredVolume, 0.0, 1e-9);

  // Inscribed sphere: nothing outside; the rest of the cube is uncovered.
  PGI_CHECK(MeasureOutsideVolume(cube, std::vector<Sphere>{ { { 0, 0, 0 }, 1.0 } }, 256, m, error));
  PGI_NEAR(m.Ratio, 0.0, 1e-12);
  PGI_NEAR(m.UncoveredVolume, 8.0 - SphereVolume(1.0), 2e-3);

  // Half a sphere out of a face.
  PGI_CHECK(
    MeasureOutsideVolume(cube, std::vector<Sphere>{ { { 1, 0.2, -0.1 }, 0.5 } }, 256, m, error));
  std::printf("half out of a face: E %.6f (exact %.6f)\n", m.Ratio, 0.5 * SphereVolume(0.5) / 8.0);
  PGI_NEAR(m.Ratio, 0.5 * SphereVolume(0.5) / 8.0, 2e-3 * 0.5 * SphereVolume(0.5) / 8.0);

  // Two overlapping spheres outside: the union counts the lens once, the
  // paper's sum twice.
  {
    const std::vector<Sphere> two = { { { 2.0, 0, 0 }, 0.5 }, { { 2.5, 0, 0 }, 0.5 } };
    PGI_CHECK(MeasureOutsideVolume(cube, two, 256, m, error));
    const double lens = LensVolume(two[0], two[1]);
    const double v = SphereVolume(0.5);
    std::printf("two overlapping spheres: E %.6f (exact %.6f), sum %.6f (exact %.6f)\n", m.Ratio,
      (2 * v - lens) / 8, m.SumRatio, 2 * v / 8);
    PGI_NEAR(m.Ratio, (2 * v - lens) / 8, 2e-3 * (2 * v - lens) / 8);
    PGI_NEAR(m.SumRatio, 2 * v / 8, 2e-3 * 2 * v / 8);
    PGI_NEAR(m.SphereOutside[0], v, 2e-3 * v);
  }

  // The bunny: the rows' volume against the divergence theorem, and E of a
  // k-means sphere set at three resolutions.
  vtkNew<vtkPGIOFFReader> reader;
  const std::string bunny = std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
  reader->SetFileName(bunny.c_str());
  reader->Update();
  vtkNew<vtkPGISphereSetApproximation> approx;
  approx->SetInputConnection(reader->GetOutputPort());
  approx->SetMethodToKMeans();
  approx->SetNumberOfSpheres(32);
  approx->Update();
  const int resolutions[3] = { 128, 256, 512 };
  double e[3], sum[3], volume[3];
  for (int i = 0; i < 3; ++i)
  {
    PGI_CHECK(
      MeasureOutsideVolume(reader->GetOutput(), approx->GetOutput(), resolutions[i], m, error));
    e[i] = m.Ratio;
    sum[i] = m.SumRatio;
    volume[i] = m.MeshVolume;
    std::printf("bunny, 32 k-means spheres, resolution %d: E %.5f, sum %.5f, volume %.6f, "
                "uncovered %.2e, odd rows %d\n",
      resolutions[i], e[i], sum[i], volume[i], m.UncoveredVolume / m.MeshVolume, m.ResolvedRows);
  }
  const double divergence = MeshVolume(reader->GetOutput());
  std::printf("bunny volume by the divergence theorem %.6f\n", divergence);
  PGI_NEAR(volume[2], divergence, 1e-3 * divergence);
  PGI_NEAR(volume[1], divergence, 2e-3 * divergence);
  // Resolution 256 (the default) within 0.5% of 512, 128 within 2%.
  PGI_NEAR(e[1], e[2], 5e-3 * e[2]);
  PGI_NEAR(e[0], e[2], 2e-2 * e[2]);
  PGI_NEAR(sum[1], sum[2], 5e-3 * sum[2]);
  // The filter reports the same E as the metric at its resolution.
  PGI_NEAR(approx->GetOutsideVolumeRatio(0), e[1], 1e-9);
  return pgitest::Result();
}
