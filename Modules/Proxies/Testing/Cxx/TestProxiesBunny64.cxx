// The paper's comparison: 64 spheres on the bunny. The SHEXP paper reports
// E = 0.35 for the variational method (octree 4.1 with 575 spheres, medial
// axis 0.52 with 64); ours must do better, in the union sense (the issue's
// E) and in the paper's sum over spheres. Then the hierarchy above them:
// every parent bounds its subtree, before and after the leaves move.
#include "pgiProxyMetrics.h"
#include "pgiSphereTree.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGISphereHierarchy.h"
#include "vtkPGISphereSetApproximation.h"

#include "pgiTesting.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

int TestProxiesBunny64(int, char*[])
{
  vtkSMPTools::SetBackend("STDThread");
  vtkNew<vtkPGIOFFReader> reader;
  const std::string path = std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
  reader->SetFileName(path.c_str());
  vtkNew<vtkPGISphereSetApproximation> approx;
  approx->SetInputConnection(reader->GetOutputPort());
  approx->SetNumberOfSpheres(64);
  approx->Update();
  vtkPolyData* leaves = approx->GetOutput();
  const double e = approx->GetOutsideVolumeRatio(0), sum = approx->GetOutsideVolumeRatioSum(0);
  std::printf("bunny, 64 variational spheres: E %.4f, paper's sum %.4f, %.1f s\n", e, sum,
    approx->GetBuildTime(0));
  PGI_CHECK(leaves->GetNumberOfPoints() == 64);
  PGI_BELOW(e, 0.35);
  PGI_BELOW(sum, 0.35);
  vtkDataArray* fieldE = leaves->GetFieldData()->GetArray("OutsideVolumeRatio");
  PGI_CHECK(fieldE && fieldE->GetNumberOfTuples() == 1 && fieldE->GetTuple1(0) == e);
  std::string error;
  proxygi::CoverageMeasure surface;
  PGI_CHECK(proxygi::MeasureSurfaceCoverage(reader->GetOutput(), leaves, 2, surface, error));
  PGI_CHECK(surface.Outside == 0);

  // Hierarchy: branching about 4 (2 to 8 per parent) gives three levels.
  vtkNew<vtkPGISphereHierarchy> hierarchy;
  hierarchy->SetInputConnection(approx->GetOutputPort());
  hierarchy->Update();
  vtkPolyData* tree = hierarchy->GetOutput();
  std::vector<proxygi::Sphere> nodes;
  std::vector<int> level;
  std::vector<long long> parent;
  PGI_CHECK(proxygi::GetSphereTree(tree, nodes, level, parent, error));
  proxygi::SphereTreeStats stats = proxygi::AnalyseSphereTree(nodes, level, parent);
  std::printf("hierarchy: %d leaves, %d parents, depth %d, branching mean %.2f (min %d, max %d), "
              "largest violation %.3g\n",
    stats.Leaves, stats.Parents, stats.Depth, stats.MeanBranching, stats.MinBranching,
    stats.MaxBranching, stats.MaximumViolation);
  PGI_CHECK(stats.Leaves == 64 && stats.Roots == 1);
  PGI_CHECK(stats.Depth == 3);
  PGI_CHECK(stats.MeanBranching >= 3.0 && stats.MeanBranching <= 5.0);
  PGI_CHECK(stats.MinBranching >= 2 && stats.MaxBranching <= 8);
  PGI_BELOW(stats.MaximumViolation, 1e-12);
  PGI_BELOW(vtkPGISphereHierarchy::GetMaximumBoundingViolation(tree), 1e-12);
  PGI_CHECK(tree->GetFieldData()->GetArray("HierarchyDepth") != nullptr);
  // Leaves keep their ids and values.
  for (vtkIdType i = 0; i < 64; ++i)
  {
    double a[3], b[3];
    leaves->GetPoint(i, a);
    tree->GetPoint(i, b);
    if (!PGI_CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && level[i] == 0))
    {
      break;
    }
  }
  // E only counts the leaves.
  proxygi::OutsideVolumeMeasure m;
  PGI_CHECK(proxygi::MeasureOutsideVolume(reader->GetOutput(), tree, 256, m, error));
  PGI_NEAR(m.Ratio, e, 1e-12);

  // Leaves move (random jitter of a tenth of their radius); refit restores
  // bounding.
  vtkNew<vtkPolyData> moved;
  moved->DeepCopy(tree);
  std::mt19937 rng(3);
  vtkDataArray* radius = moved->GetPointData()->GetArray("Radius");
  for (vtkIdType i = 0; i < 64; ++i)
  {
    double c[3];
    moved->GetPoint(i, c);
    for (double& v : c)
    {
      v += 0.3 * radius->GetTuple1(i) * ((rng() + 0.5) / 4294967296.0 - 0.5);
    }
    moved->GetPoints()->SetPoint(i, c);
  }
  const double before = vtkPGISphereHierarchy::GetMaximumBoundingViolation(moved);
  PGI_CHECK(vtkPGISphereHierarchy::Refit(moved));
  const double after = vtkPGISphereHierarchy::GetMaximumBoundingViolation(moved);
  std::printf("leaves jittered: violation %.3g before refit, %.3g after\n", before, after);
  PGI_CHECK(before > 0.0);
  PGI_BELOW(after, 1e-12);
  return pgitest::Result();
}
