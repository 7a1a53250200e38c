// Two modules, one light: the tracer's importance-sampled irradiance from the
// forest map (unoccluded) against the SH irradiance the Lighting module
// projects from the same map, with the map rotated.
#include "pgiEnvironmentMap.h"
#include "pgiReferenceTracer.h"
#include "vtkPGIEXRReader.h"

#include "pgiSHBasis.h"
#include "pgiTesting.h"
#include "vtkImageData.h"
#include "vtkNew.h"

#include <cmath>
#include <string>
#include <vector>

using namespace proxygi;

int TestReferenceEnvironment(int, char*[])
{
  vtkNew<vtkPGIEXRReader> reader;
  reader->SetFileName((std::string(PROXYGI_DATA_DIR) + "/environments/forest.exr").c_str());
  reader->Update();
  EnvironmentMap forest;
  std::string error;
  PGI_CHECK(EnvironmentMap::FromImage(reader->GetOutput(), forest, error));
  forest.SetRotation(0.5);
  // Order 16: the clamped cosine's bands beyond 8 still carry about 1% for
  // a map with a sun (measured: order 8 is 1-2% high everywhere).
  const int order = 16, n2 = order * order;
  std::vector<double> r(n2), g(n2), b(n2), y(n2);
  forest.ProjectIrradianceSH(order, r.data(), g.data(), b.data());

  ReferenceTracer tracer;
  const float albedo[3] = { 0.5f, 0.5f, 0.5f };
  // A speck far away: the scene must hold geometry, the light must be open.
  tracer.AddMesh({ 1e3f, 1e3f, -1e3f, 1e3f + 1e-3f, 1e3f, -1e3f, 1e3f, 1e3f + 1e-3f, -1e3f },
    { 0, 1, 2 }, nullptr, albedo, error);
  tracer.SetEnvironment(&forest);
  PGI_CHECK(tracer.Commit(error));
  ReferenceTracer::Settings settings;
  settings.MaxBounces = 0;
  settings.Samples = 40000;
  double worst = 0.0;
  for (int k = 0; k < 8; ++k)
  {
    const double t = 0.4 + 0.3 * k, p = 2.1 * k;
    const double n[3] = { std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t) };
    const double x[3] = { 0, 0, 0 };
    ReferenceTracer::Estimate e;
    tracer.EstimateIrradiance(x, n, k, settings, e);
    sh::EvaluateBasis(order, n[0], n[1], n[2], y.data());
    const double shE = sh::Dot(n2, g.data(), y.data());
    const double diff = std::fabs(e.Direct[1] - shE);
    std::printf("normal %d: traced E %.4f +- %.4f, SH order 16 E %.4f\n", k, e.Direct[1],
      e.DirectStdErr[1], shE);
    worst = std::max(worst, diff / shE);
    PGI_BELOW(diff, 4 * e.DirectStdErr[1] + 0.005 * shE);
  }
  std::printf("largest relative difference %.3f%%\n", 100 * worst);
  return pgitest::Result();
}
