// One-bounce light from the proxies: a sphere (albedo 0.8) over a plane in
// uniform light; the plane's indirect light from the sphere against the
// Embree reference (proxy mode, one bounce), for the three operators; and
// local lights (a spherical and a point light) against their closed forms.
#include "vtkPGIGlobalIllumination.h"

#include "pgiTesting.h"
#include "vtkAppendPolyData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPGILighting.h"
#include "vtkPGIReferenceIllumination.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>

namespace
{
// Over a's tuples (the receiver patch comes first in b).
using pgitest::RelativeRMSE;
} // namespace

int TestIndirectLight(int, char*[])
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -4, 0);
  plane->SetPoint1(4, -4, 0);
  plane->SetPoint2(-4, 4, 0);
  plane->SetResolution(32, 32);
  vtkNew<vtkPolyData> ball;
  vtkNew<vtkPoints> c;
  c->InsertNextPoint(0, 0, 1.5);
  ball->SetPoints(c);
  vtkNew<vtkDoubleArray> r;
  r->SetName("Radius");
  r->InsertNextValue(1.0);
  ball->GetPointData()->AddArray(r);

  // The reference's ground must be (nearly) infinite like the SH blocker
  // plane, or sky from below the horizon reaches the sphere's underside past
  // the plane's edge (that doubles the indirect light here): the receiver
  // patch gets a skirt out to 100, whose vertices are not compared.
  vtkNew<vtkAppendPolyData> ground;
  ground->AddInputConnection(plane->GetOutputPort());
  const double skirts[4][4] = { { -100, 100, 4, 100 }, { -100, 100, -100, -4 }, { -100, -4, -4, 4 },
    { 4, 100, -4, 4 } };
  for (const auto& k : skirts)
  {
    vtkNew<vtkPlaneSource> skirt;
    skirt->SetOrigin(k[0], k[2], 0);
    skirt->SetPoint1(k[1], k[2], 0);
    skirt->SetPoint2(k[0], k[3], 0);
    ground->AddInputConnection(skirt->GetOutputPort());
  }
  vtkNew<vtkPGIReferenceIllumination> reference;
  reference->SetInputConnection(ground->GetOutputPort());
  reference->SetProxiesData(ball);
  reference->UseProxiesOn();
  reference->SetSamples(2048);
  reference->Update();
  vtkDataArray* refIndirect = reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
  std::printf("reference indirect on the plane: up to %.4f (direct up to %.4f)\n",
    refIndirect->GetRange(0)[1],
    reference->GetOutput()->GetPointData()->GetArray("DirectShadowed")->GetRange(0)[1]);

  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, grey[3] = { 0.8, 0.8, 0.8 };
  double errors[3];
  for (int op = 0; op < 3; ++op)
  {
    vtkNew<vtkPGIGlobalIllumination> gi;
    gi->SetInputConnection(plane->GetOutputPort());
    gi->SetProxiesData(ball);
    gi->AddBlockerPlane(origin, up, grey);
    gi->GetSettings()->SetIndirectOperator(op);
    gi->Update();
    vtkDataArray* indirect = gi->GetOutput()->GetPointData()->GetArray("IndirectProxy");
    errors[op] = RelativeRMSE(indirect, refIndirect);
    std::printf("operator %d: indirect up to %.4f, relative RMSE against the reference %.1f%%\n",
      op, indirect->GetRange(0)[1], 100 * errors[op]);
    PGI_CHECK(indirect->GetRange(0)[0] >= 0.0);
  }
  // Measured 37.5%, 24.5%, 17.0%: the operators rank as the paper says. The
  // rest is the order-4 visibility of the ground seen by the sphere.
  PGI_BELOW(errors[0], 0.45);
  PGI_BELOW(errors[1], 0.30);
  PGI_BELOW(errors[2], 0.22);
  PGI_CHECK(errors[2] < errors[1] && errors[1] < errors[0]);

  // Local lights, no blockers: a spherical light (radius 0.5, radiance 4)
  // and a point light (intensity 3) over the plane: E / pi * albedo.
  {
    vtkNew<vtkPGILighting> lighting;
    lighting->SetUniformRadiance(0, 0, 0);
    const double lc[3] = { 0.5, 0, 2 }, lr[3] = { 4, 4, 4 };
    lighting->AddSphereLight(lc, 0.5, lr);
    const double pc[3] = { -1, 1, 1.5 }, pi[3] = { 3, 3, 3 };
    lighting->AddPointLight(pc, pi);
    vtkNew<vtkPGIGlobalIllumination> gi;
    gi->SetInputConnection(plane->GetOutputPort());
    gi->SetLighting(lighting);
    gi->GetSettings()->SetDefaultAlbedo(1, 1, 1);
    gi->GetSettings()->SetDefaultProxyAlbedo(1, 1, 1);
    gi->Update();
    vtkPolyData* out = gi->GetOutput();
    vtkDataArray* local = out->GetPointData()->GetArray("LocalLights");
    double sq = 0, ref = 0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      double x[3];
      out->GetPoint(i, x);
      const double d2s = std::pow(lc[0] - x[0], 2) + std::pow(lc[1] - x[1], 2) + lc[2] * lc[2];
      const double sphere = 4.0 * 0.25 / d2s * lc[2] / std::sqrt(d2s); // L sin^2 cos
      const double d2p = std::pow(pc[0] - x[0], 2) + std::pow(pc[1] - x[1], 2) + pc[2] * pc[2];
      const double point = 3.0 * pc[2] / std::sqrt(d2p) / d2p / 3.14159265358979;
      const double exact = sphere + point;
      sq += std::pow(local->GetComponent(i, 0) - exact, 2);

      ref += exact * exact;
    }
    std::printf("local lights (spherical + point), unshadowed: relative RMSE %.3f%%\n",
      100 * std::sqrt(sq / ref));
    PGI_BELOW(std::sqrt(sq / ref), 0.02);
    for (const std::string& line : gi->GetPlan())
    {
      std::printf("  plan: %s\n", line.c_str());
    }
  }
  return pgitest::Result();
}
