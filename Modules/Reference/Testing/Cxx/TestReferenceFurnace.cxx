// White furnace and local lights: a closed diffuse scene with albedo 1 in
// uniform light must come out at radiance 1 (convex: direct only; concave:
// all bounces); point and spherical lights against their closed forms.
#include "vtkPGIReferenceIllumination.h"

#include "pgiEnvironmentMap.h"
#include "pgiReferenceTracer.h"
#include "pgiTesting.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPGILighting.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <string>

using namespace proxygi;

namespace
{
// Worst |radiance - 1| in standard errors, and the mean radiance.
void Compare(vtkPolyData* out, double& mean, double& worstSigmas)
{
  vtkDataArray* r = out->GetPointData()->GetArray("Radiance");
  vtkDataArray* e = out->GetPointData()->GetArray("RadianceStdErr");
  mean = 0.0;
  worstSigmas = 0.0;
  for (vtkIdType i = 0; i < r->GetNumberOfTuples(); ++i)
  {
    mean += r->GetComponent(i, 0) / r->GetNumberOfTuples();
    const double sig =
      std::fabs(r->GetComponent(i, 0) - 1.0) / std::max(e->GetComponent(i, 0), 1e-4);
    worstSigmas = std::max(worstSigmas, sig);
  }
}
} // namespace

int TestReferenceFurnace(int, char*[])
{
  vtkNew<vtkPGILighting> sky; // uniform radiance 1
  // Convex: a sphere sees only the sky; direct = 1, indirect = 0.
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(48);
    sphere->SetPhiResolution(24);
    vtkNew<vtkPGIReferenceIllumination> reference;
    reference->SetInputConnection(sphere->GetOutputPort());
    reference->SetLighting(sky);
    reference->SetDefaultAlbedo(1, 1, 1);
    reference->SetSamples(64);
    reference->Update();
    double mean, sigmas;
    Compare(reference->GetOutput(), mean, sigmas);
    vtkDataArray* ind = reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
    std::printf("convex furnace: mean radiance %.5f, worst %.2f sigma, indirect max %.2g\n", mean,
      sigmas, ind->GetRange(0)[1]);
    PGI_NEAR(mean, 1.0, 2e-3);
    PGI_BELOW(sigmas, 5.0);
    PGI_NEAR(ind->GetRange(0)[1], 0.0, 0.0);
  }
  // Concave: two spheres close above a ground plane (crevices, mutual
  // light), all bounces (64), albedo 1: radiance 1 everywhere.
  {
    vtkNew<vtkSphereSource> a, b;
    for (vtkSphereSource* s : { a.Get(), b.Get() })
    {
      s->SetThetaResolution(40);
      s->SetPhiResolution(20);
    }
    a->SetCenter(0, 0, 1.05);
    b->SetCenter(1.2, 0.3, 1.2); // 0.15 apart from a
    b->SetRadius(0.6);
    vtkNew<vtkPlaneSource> ground;
    ground->SetOrigin(-20, -20, 0);
    ground->SetPoint1(20, -20, 0);
    ground->SetPoint2(-20, 20, 0);
    vtkNew<vtkPGIReferenceIllumination> reference;
    reference->SetInputConnection(a->GetOutputPort());
    reference->AddSceneObjectConnection(b->GetOutputPort());
    reference->AddSceneObjectConnection(ground->GetOutputPort());
    reference->SetLighting(sky);
    reference->SetDefaultAlbedo(1, 1, 1);
    reference->SetMaxBounces(64);
    reference->SetSamples(128);
    reference->Update();
    double mean, sigmas;
    Compare(reference->GetOutput(), mean, sigmas);
    vtkDataArray* ind = reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
    std::printf("concave furnace (two spheres over a plane, 64 bounces): mean %.5f, worst %.2f "
                "sigma, indirect up to %.3f\n",
      mean, sigmas, ind->GetRange(0)[1]);
    PGI_NEAR(mean, 1.0, 5e-3);
    PGI_BELOW(sigmas, 5.0);
    PGI_CHECK(ind->GetRange(0)[1] > 0.2); // interreflection really happened
  }

  // Point light: E = I cos / d^2, exact (no sampling involved).
  {
    ReferenceTracer tracer;
    std::string error;
    const float albedo[3] = { 0.5f, 0.5f, 0.5f }, intensity[3] = { 10, 5, 2 };
    tracer.AddMesh({ -10, -10, 0, 10, -10, 0, 10, 10, 0, -10, 10, 0 }, { 0, 1, 2, 0, 2, 3 },
      nullptr, albedo, error);
    const double p[3] = { 1, 2, 3 };
    tracer.AddPointLight(p, intensity);
    PGI_CHECK(tracer.Commit(error));
    ReferenceTracer::Settings s;
    s.Samples = 4;
    const double x[3] = { -1, 0.5, 0 }, n[3] = { 0, 0, 1 };
    ReferenceTracer::Estimate e;
    tracer.EstimateIrradiance(x, n, 0, s, e);
    const double d2 = 4 + 2.25 + 9, cosT = 3 / std::sqrt(d2);
    PGI_NEAR(e.Direct[0], 10 * cosT / d2, 1e-9);
    PGI_NEAR(e.Direct[2], 2 * cosT / d2, 1e-9);
    PGI_NEAR(e.Indirect[0], 0.0, 0.0); // nothing above the plane to bounce from
  }
  // Spherical light of radiance L fully above the horizon: E = pi L sin^2(a) cos(b).
  {
    ReferenceTracer tracer;
    std::string error;
    const float albedo[3] = { 0.5f, 0.5f, 0.5f }, radiance[3] = { 3, 3, 3 };
    tracer.AddMesh({ -10, -10, 0, 10, -10, 0, 10, 10, 0, -10, 10, 0 }, { 0, 1, 2, 0, 2, 3 },
      nullptr, albedo, error);
    const double c[3] = { 0.5, -0.3, 2.0 };
    tracer.AddSphereLight(c, 0.6, radiance);
    PGI_CHECK(tracer.Commit(error));
    ReferenceTracer::Settings s;
    s.Samples = 20000;
    s.MaxBounces = 0;
    const double x[3] = { -0.4, 0.2, 0 }, n[3] = { 0, 0, 1 };
    ReferenceTracer::Estimate e;
    tracer.EstimateIrradiance(x, n, 0, s, e);
    const double d2 = 0.81 + 0.25 + 4.0, cosB = 2.0 / std::sqrt(d2);
    const double exact = 3.14159265358979323846 * 3 * (0.36 / d2) * cosB;
    std::printf("sphere light: %.5f +- %.5f, exact %.5f\n", e.Direct[0], e.DirectStdErr[0], exact);
    PGI_NEAR(e.Direct[0], exact, 4 * e.DirectStdErr[0] + 1e-9);
    PGI_BELOW(e.DirectStdErr[0], 0.01 * exact);
  }
  return pgitest::Result();
}
