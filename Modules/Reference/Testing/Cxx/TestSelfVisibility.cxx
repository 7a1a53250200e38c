// vtkPGISelfVisibility against closed forms: a convex mesh shadows nothing
// of itself; the floor of a round well sees the sky through a cone, so its
// log-visibility is the log of a known zonal function and its bounce
// weights sum to cos^2 of the cone's angle. Bad input gives errors.
#include "vtkPGISelfVisibility.h"

#include "pgiSHBasis.h"
#include "pgiSHLog.h"
#include "pgiTesting.h"
#include "pgiTestingErrors.h"
#include "vtkAppendPolyData.h"
#include "vtkCylinderSource.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <limits>

namespace
{
double FieldValue(vtkPolyData* data, const char* name)
{
  vtkDataArray* a = data->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::numeric_limits<double>::quiet_NaN();
}
} // namespace

int TestSelfVisibility(int, char*[])
{
  using namespace proxygi;
  const int order = 4, n2 = order * order;

  // A convex mesh: no ray from a vertex over its tangent plane hits it.
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(16);
    vtkNew<vtkPGISelfVisibility> self;
    self->SetInputConnection(sphere->GetOutputPort());
    self->SetSamples(128);
    self->SetObjectId(7);
    self->Update();
    vtkPolyData* out = self->GetOutput();
    PGI_NEAR(FieldValue(out, "SelfVisibilityBlockedFraction"), 0.0, 0.0);
    vtkDataArray* logs = out->GetPointData()->GetArray("SelfLogVisibility");
    PGI_CHECK(logs && logs->GetNumberOfComponents() == n2);
    double largest = 0.0;
    for (vtkIdType i = 0; logs && i < logs->GetNumberOfTuples(); ++i)
    {
      for (int j = 0; j < n2; ++j)
      {
        largest = std::max(largest, std::abs(logs->GetComponent(i, j)));
      }
    }
    PGI_NEAR(largest, 0.0, 0.0);
    vtkDataArray* ids = out->GetPointData()->GetArray("ObjectId");
    PGI_CHECK(ids && ids->GetTuple1(0) == 7.0);
    vtkDataArray* targets = out->GetFieldData()->GetArray("SelfBounceTargets");
    PGI_CHECK(targets && targets->GetNumberOfTuples() == 0);
    vtkDataArray* rest = out->GetPointData()->GetArray("SelfVisibilityRest");
    PGI_CHECK(rest && rest->GetNumberOfComponents() == 3);
  }

  // A well: a floor (its centre vertex at the origin, facing +z) and an open
  // cylinder of radius R and height H standing on it. From the floor's centre
  // the sky is the cone of half-angle a = atan(R / H); the band from a to 90
  // degrees is the wall; below the tangent plane V = 1 by convention.
  const double radius = 1.0, height = 2.0, a = std::atan(radius / height);
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-1.5, -1.5, 0.0);
  floor->SetPoint1(1.5, -1.5, 0.0);
  floor->SetPoint2(-1.5, 1.5, 0.0);
  floor->SetResolution(2, 2); // a vertex at the centre
  vtkNew<vtkCylinderSource> wall;
  wall->SetRadius(radius);
  wall->SetHeight(height);
  wall->SetResolution(256);
  wall->CappingOff();
  wall->Update();
  // The source's axis is y: mirrored to z (so its winding, hence its
  // normals, face inwards, the side the floor sees), on the floor.
  vtkNew<vtkPolyData> stood;
  stood->DeepCopy(wall->GetOutput());
  for (vtkIdType i = 0; i < stood->GetNumberOfPoints(); ++i)
  {
    double p[3];
    stood->GetPoint(i, p);
    stood->GetPoints()->SetPoint(i, p[0], p[2], p[1] + 0.5 * height);
  }
  stood->GetPointData()->SetNormals(nullptr);
  vtkNew<vtkAppendPolyData> well;
  well->AddInputConnection(floor->GetOutputPort());
  well->AddInputData(stood);
  well->Update();
  // Point normals of the floor must face +z at the centre: give them.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(well->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(normals->GetOutput());
  vtkIdType centre = -1;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]) < 1e-9)
    {
      centre = i;
    }
  }
  PGI_CHECK(centre >= 0);
  const float up3[3] = { 0, 0, 1 };
  mesh->GetPointData()->GetNormals()->SetTuple(centre, up3);

  // The exact zonal visibility, projected by quadrature, and its log.
  double exact[sh::MaxCoefficients] = {}, exactLog[sh::MaxCoefficients];
  {
    const int steps = 200000;
    for (int s = 0; s < steps; ++s)
    {
      const double t = (s + 0.5) * sh::Pi / steps;
      const double v = (t > a && t < 0.5 * sh::Pi) ? 0.0 : 1.0;
      double y[sh::MaxCoefficients];
      sh::EvaluateBasis(order, std::sin(t), 0.0, std::cos(t), y);
      for (int l = 0; l < order; ++l)
      {
        const int i = sh::Index(l, 0);
        exact[i] += v * y[i] * 2.0 * sh::Pi * std::sin(t) * (sh::Pi / steps);
      }
    }
    PGI_CHECK(sh::Log(order, exact, exactLog) == sh::Status::Ok);
  }
  for (int samples : { 256, 4096 })
  {
    vtkNew<vtkPGISelfVisibility> self;
    self->SetInputData(mesh);
    self->SetSamples(samples);
    self->Update();
    vtkPolyData* out = self->GetOutput();
    vtkDataArray* logs = out->GetPointData()->GetArray("SelfLogVisibility");
    double err = 0.0, norm = 0.0;
    for (int j = 0; j < n2; ++j)
    {
      const double d = logs->GetComponent(centre, j) - exactLog[j];
      err += d * d;
      norm += exactLog[j] * exactLog[j];
    }
    std::printf(
      "well floor, %d rays: log-visibility relative error %.4f\n", samples, std::sqrt(err / norm));
    PGI_BELOW(std::sqrt(err / norm), samples >= 4096 ? 0.005 : 0.04);
    // The bounce weights: (1/pi) int over the wall of cos = cos^2(a).
    auto* offsets =
      vtkIdTypeArray::SafeDownCast(out->GetFieldData()->GetArray("SelfBounceOffsets"));
    auto* weights = vtkFloatArray::SafeDownCast(out->GetFieldData()->GetArray("SelfBounceWeights"));
    PGI_CHECK(offsets && weights && offsets->GetNumberOfTuples() == mesh->GetNumberOfPoints() + 1);
    double sum = 0.0;
    for (vtkIdType e = offsets->GetValue(centre); e < offsets->GetValue(centre + 1); ++e)
    {
      sum += weights->GetValue(e);
    }
    std::printf("well floor, %d rays: bounce weight %.5f (exact %.5f)\n", samples, sum,
      std::cos(a) * std::cos(a));
    PGI_NEAR(sum, std::cos(a) * std::cos(a), samples >= 4096 ? 2e-3 : 1e-2);
    // Where the hits lie: on the wall (a 256-gon of radius R, 0 <= z <= H),
    // in a triangle of their target corner (its quads span the height).
    auto* hits = vtkFloatArray::SafeDownCast(out->GetFieldData()->GetArray("SelfBounceHitPoints"));
    auto* targets =
      vtkIdTypeArray::SafeDownCast(out->GetFieldData()->GetArray("SelfBounceTargets"));
    PGI_CHECK(hits && targets && hits->GetNumberOfComponents() == 3 &&
      hits->GetNumberOfTuples() == weights->GetNumberOfTuples());
    if (hits && targets)
    {
      const double inner = radius * std::cos(sh::Pi / 256), reach = std::hypot(height, 0.025);
      double worstRadius = 0.0, worstHeight = 0.0, farthest = 0.0;
      vtkIdType inside = 0; // between the rims, not at a corner (grazing rays hit low)
      const vtkIdType entries = offsets->GetValue(centre + 1) - offsets->GetValue(centre);
      for (vtkIdType e = offsets->GetValue(centre); e < offsets->GetValue(centre + 1); ++e)
      {
        double h[3], corner[3];
        hits->GetTuple(e, h);
        mesh->GetPoint(targets->GetValue(e), corner);
        const double r = std::hypot(h[0], h[1]);
        worstRadius = std::max(worstRadius, std::max(inner - r, r - radius));
        worstHeight = std::max(worstHeight, std::max(-h[2], h[2] - height));
        farthest = std::max(farthest, std::sqrt(vtkMath::Distance2BetweenPoints(h, corner)));
        inside += h[2] > 1e-3 && h[2] < height - 1e-3 ? 1 : 0;
      }
      std::printf("well floor, %d rays: hit points off the wall by %.2g (radius), %.2g (height); "
                  "%.4f from their corner (a quad's diagonal %.4f)\n",
        samples, worstRadius, worstHeight, farthest, reach);
      PGI_BELOW(worstRadius, 1e-5);
      PGI_BELOW(worstHeight, 1e-5);
      PGI_BELOW(farthest, reach);
      PGI_CHECK(entries > 0 && inside >= 0.9 * entries);
    }
    PGI_CHECK(FieldValue(out, "SelfVisibilityBlockedFraction") > 0.0);
  }

  // Same seed, same result; another seed, another turn of the directions.
  {
    vtkNew<vtkPGISelfVisibility> one, two, other;
    for (vtkPGISelfVisibility* f : { one.Get(), two.Get(), other.Get() })
    {
      f->SetInputData(mesh);
      f->SetSamples(64);
    }
    other->SetSeed(2);
    for (vtkPGISelfVisibility* f : { one.Get(), two.Get(), other.Get() })
    {
      f->Update();
    }
    vtkDataArray* l1 = one->GetOutput()->GetPointData()->GetArray("SelfLogVisibility");
    vtkDataArray* l2 = two->GetOutput()->GetPointData()->GetArray("SelfLogVisibility");
    vtkDataArray* l3 = other->GetOutput()->GetPointData()->GetArray("SelfLogVisibility");
    double same = 0.0, differ = 0.0;
    for (vtkIdType i = 0; i < l1->GetNumberOfTuples(); ++i)
    {
      for (int j = 0; j < n2; ++j)
      {
        same = std::max(same, std::abs(l1->GetComponent(i, j) - l2->GetComponent(i, j)));
        differ = std::max(differ, std::abs(l1->GetComponent(i, j) - l3->GetComponent(i, j)));
      }
    }
    PGI_NEAR(same, 0.0, 0.0);
    PGI_CHECK(differ > 0.0);
  }

  // Bad input: no points, no polygons, a NaN point.
  {
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkPGISelfVisibility> self;
    self->SetInputData(empty);
    PGI_CHECK(pgitest::Fails(self));
    vtkNew<vtkPolyData> cloud;
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    cloud->SetPoints(points);
    self->SetInputData(cloud);
    PGI_CHECK(pgitest::Fails(self));
    vtkNew<vtkPolyData> bad;
    bad->DeepCopy(mesh);
    bad->GetPoints()->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
    self->SetInputData(bad);
    PGI_CHECK(pgitest::Fails(self));
  }
  return pgitest::Result();
}
