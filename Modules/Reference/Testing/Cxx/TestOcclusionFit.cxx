// vtkPGIOcclusionFit: a sphere too big for a round mesh shrinks to the
// mesh's radius; the bunny's bounding spheres, which block a good deal more
// than the bunny, are fitted to block about what it blocks, measured on
// sample points the fit did not see; the same radii on one thread and on
// many; bad input gives errors.
#include "vtkPGIOcclusionFit.h"

#include "pgiTesting.h"
#include "pgiTestingErrors.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGISphereSetApproximation.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace
{
double FieldValue(vtkPolyData* data, const char* name)
{
  vtkDataArray* a = data->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::numeric_limits<double>::quiet_NaN();
}

vtkSmartPointer<vtkPolyData> OneSphere(double x, double y, double z, double r)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(x, y, z);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  radius->InsertNextValue(r);
  auto proxies = vtkSmartPointer<vtkPolyData>::New();
  proxies->SetPoints(points);
  proxies->GetPointData()->AddArray(radius);
  return proxies;
}
} // namespace

int TestOcclusionFit(int, char*[])
{
  // A round mesh of radius 1 and one proxy of radius 1.5 at its centre: the
  // fit finds the mesh's radius (its flat faces lie a little inside 1).
  {
    vtkNew<vtkSphereSource> round;
    round->SetRadius(1.0);
    round->SetThetaResolution(64);
    round->SetPhiResolution(48);
    round->Update();
    vtkNew<vtkPGIOcclusionFit> fit;
    fit->SetInputData(OneSphere(0, 0, 0, 1.5));
    fit->SetMeshConnection(round->GetOutputPort());
    fit->SetSamples(128);
    fit->Update();
    vtkPolyData* out = fit->GetOutput();
    vtkDataArray* r = out->GetPointData()->GetArray("Radius");
    vtkDataArray* bounding = out->GetPointData()->GetArray("BoundingRadius");
    if (PGI_CHECK(r && bounding && r->GetNumberOfTuples() == 1))
    {
      std::printf("round mesh: radius 1.5 fitted to %.4f\n", r->GetTuple1(0));
      PGI_NEAR(r->GetTuple1(0), 0.995, 0.015);
      PGI_NEAR(bounding->GetTuple1(0), 1.5, 0.0);
    }
    std::printf("round mesh: occlusion error %.3f -> %.3f, bias %+.3f -> %+.3f\n",
      FieldValue(out, "OcclusionErrorBefore"), FieldValue(out, "OcclusionErrorAfter"),
      FieldValue(out, "OcclusionBiasBefore"), FieldValue(out, "OcclusionBiasAfter"));
    // A sphere of radius 1.5 blocks (1.5)^2-ish more than one of radius 1
    // seen from afar, and everything from the points inside it.
    PGI_CHECK(FieldValue(out, "OcclusionBiasBefore") > 0.5);
    PGI_BELOW(FieldValue(out, "OcclusionErrorAfter"), 0.03);
    PGI_BELOW(std::abs(FieldValue(out, "OcclusionBiasAfter")), 0.02);
  }

  // The bunny's 32 bounding spheres.
  vtkNew<vtkPGIOFFReader> reader;
  const std::string path = std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* bunny = reader->GetOutput();
  if (!PGI_CHECK(bunny->GetNumberOfPoints() > 0))
  {
    return pgitest::Result();
  }
  vtkNew<vtkPGISphereSetApproximation> approximation;
  approximation->SetInputData(bunny);
  approximation->SetMethod(vtkPGISphereSetApproximation::KMEANS);
  approximation->SetNumberOfSpheres(32);
  approximation->Update();
  vtkPolyData* bounding = approximation->GetOutput();

  vtkNew<vtkPGIOcclusionFit> fit;
  fit->SetInputData(bounding);
  fit->SetMeshData(bunny);
  fit->Update();
  vtkPolyData* fitted = fit->GetOutput();
  const double before = FieldValue(fitted, "OcclusionErrorBefore"),
               after = FieldValue(fitted, "OcclusionErrorAfter"),
               biasBefore = FieldValue(fitted, "OcclusionBiasBefore"),
               biasAfter = FieldValue(fitted, "OcclusionBiasAfter");
  std::printf("bunny, 32 spheres: occlusion error %.3f -> %.3f, bias %+.3f -> %+.3f, common "
              "scale %.3f\n",
    before, after, biasBefore, biasAfter, FieldValue(fitted, "CommonScale"));
  PGI_CHECK(biasBefore > 0.15);
  PGI_BELOW(after, 0.4 * before);
  PGI_BELOW(std::abs(biasAfter), 0.05);

  // The per-sphere rounds do better than one common scale.
  vtkNew<vtkPGIOcclusionFit> common;
  common->SetInputData(bounding);
  common->SetMeshData(bunny);
  common->SetIterations(0);
  common->Update();
  const double commonAfter = FieldValue(common->GetOutput(), "OcclusionErrorAfter");
  std::printf("bunny, one common scale: occlusion error %.3f\n", commonAfter);
  PGI_BELOW(after, commonAfter);

  // The same radii on one thread.
  vtkSMPTools::Initialize(1);
  vtkNew<vtkPGIOcclusionFit> serial;
  serial->SetInputData(bounding);
  serial->SetMeshData(bunny);
  serial->Update();
  vtkSMPTools::Initialize(0);
  vtkDataArray* a = fitted->GetPointData()->GetArray("Radius");
  vtkDataArray* b = serial->GetOutput()->GetPointData()->GetArray("Radius");
  double largest = 0.0;
  for (vtkIdType i = 0; a && b && i < a->GetNumberOfTuples(); ++i)
  {
    largest = std::max(largest, std::abs(a->GetTuple1(i) - b->GetTuple1(i)));
  }
  PGI_CHECK(a && b && a->GetNumberOfTuples() == bounding->GetNumberOfPoints());
  PGI_NEAR(largest, 0.0, 0.0);

  // Bad input.
  {
    vtkNew<vtkPGIOcclusionFit> bad;
    bad->SetInputData(OneSphere(0, 0, 0, 1.0));
    PGI_CHECK(pgitest::FailsSaying(bad, "No mesh"));
    vtkNew<vtkPolyData> noRadius;
    noRadius->SetPoints(OneSphere(0, 0, 0, 1.0)->GetPoints());
    bad->SetInputData(noRadius);
    bad->SetMeshData(bunny);
    PGI_CHECK(pgitest::FailsSaying(bad, "Radius"));
    bad->SetInputData(OneSphere(0, 0, 0, std::numeric_limits<double>::quiet_NaN()));
    PGI_CHECK(pgitest::FailsSaying(bad, "non-positive radius"));
    bad->SetInputData(OneSphere(0, 0, 0, -1.0));
    PGI_CHECK(pgitest::FailsSaying(bad, "non-positive radius"));
    vtkNew<vtkPolyData> pointsOnly;
    pointsOnly->SetPoints(bunny->GetPoints());
    bad->SetInputData(OneSphere(0, 0, 0, 1.0));
    bad->SetMeshData(pointsOnly);
    PGI_CHECK(pgitest::FailsSaying(bad, "no polygons"));
    vtkNew<vtkPolyData> hierarchy;
    hierarchy->DeepCopy(OneSphere(0, 0, 0, 1.0));
    vtkNew<vtkDoubleArray> level;
    level->SetName("Level");
    level->InsertNextValue(1.0);
    hierarchy->GetPointData()->AddArray(level);
    bad->SetInputData(hierarchy);
    bad->SetMeshData(bunny);
    PGI_CHECK(pgitest::FailsSaying(bad, "hierarchy"));
  }
  return pgitest::Result();
}
