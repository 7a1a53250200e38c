// The reference renderer against closed forms: irradiance on a plane under
// a sphere in uniform unit light, E = pi (1 - (r/d)^2 cos(beta)), swept over
// receivers; the error falls as 1/sqrt(samples); the reported standard
// error is honest (the error stays within a few of them).
#include "pgiEnvironmentMap.h"
#include "pgiReferenceTracer.h"
#include "pgiTesting.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace proxygi;

namespace
{
const double Pi = 3.14159265358979323846;

struct Fixture
{
  EnvironmentMap Sky = EnvironmentMap::Uniform(1.0f, 1.0f, 1.0f);
  ReferenceTracer Tracer;
  double Center[3] = { 0.0, 0.0, 1.5 }, Radius = 1.0;
  Fixture()
  {
    // Exact sphere (Embree's sphere primitive) over a large plane.
    std::string error;
    const float albedo[3] = { 0.8f, 0.8f, 0.8f };
    Tracer.AddSphere(Center, Radius, albedo, error);
    const std::vector<float> plane = { -100, -100, 0, 100, -100, 0, 100, 100, 0, -100, 100, 0 };
    Tracer.AddMesh(plane, { 0, 1, 2, 0, 2, 3 }, nullptr, albedo, error);
    Tracer.SetEnvironment(&Sky);
    Tracer.Commit(error);
  }
  double Exact(const double x[3]) const
  {
    const double d[3] = { Center[0] - x[0], Center[1] - x[1], Center[2] - x[2] };
    const double dist2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double cosBeta = d[2] / std::sqrt(dist2);
    return Pi * (1.0 - Radius * Radius / dist2 * cosBeta);
  }
};
} // namespace

int TestReferenceAnalytic(int, char*[])
{
  Fixture f;
  const double n[3] = { 0, 0, 1 };
  ReferenceTracer::Settings settings;
  settings.MaxBounces = 0; // the closed form is direct light only
  settings.Samples = 16384;

  // Sweep receivers from under the sphere outwards.
  double worstSigmas = 0.0;
  pgitest::ErrorSum errors;
  const int count = 24;
  for (int i = 0; i < count; ++i)
  {
    const double x[3] = { 0.25 * i, 0.1 * i, 0.0 };
    ReferenceTracer::Estimate e;
    f.Tracer.EstimateIrradiance(x, n, i, settings, e);
    const double exact = f.Exact(x);
    const double err = e.Direct[0] - exact;
    errors.Add(e.Direct[0], exact);
    worstSigmas = std::max(worstSigmas, std::fabs(err) / std::max(e.DirectStdErr[0], 1e-12));
    PGI_NEAR(e.Direct[1], e.Direct[0], 1e-12); // grey light, grey result
  }
  const double relRmse = errors.RelativeRMSE();
  std::printf("sphere over plane, 16384 samples: relative RMSE %.4f%%, worst error %.2f sigma\n",
    100 * relRmse, worstSigmas);
  PGI_BELOW(relRmse, 5e-3);
  PGI_BELOW(worstSigmas, 4.5);

  // Convergence: error ~ 1/sqrt(samples).
  std::vector<double> spp = { 16, 64, 256, 1024 }, rmse;
  for (double s : spp)
  {
    settings.Samples = static_cast<int>(s);
    pgitest::ErrorSum sampled;
    for (int i = 0; i < 200; ++i)
    {
      const double x[3] = { 0.03 * i - 3.0, 0.5 * std::sin(0.1 * i), 0.0 };
      ReferenceTracer::Estimate e;
      f.Tracer.EstimateIrradiance(x, n, 1000 + i, settings, e);
      const double exact = f.Exact(x);
      sampled.Add(e.Direct[0], exact);
    }
    rmse.push_back(sampled.RelativeRMSE());
    std::printf("  %4d samples: relative RMSE %.5f\n", settings.Samples, rmse.back());
  }
  // Least-squares slope of log(error) against log(samples).
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < spp.size(); ++k)
  {
    mx += std::log(spp[k]) / spp.size();
    my += std::log(rmse[k]) / spp.size();
  }
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < spp.size(); ++k)
  {
    sxy += (std::log(spp[k]) - mx) * (std::log(rmse[k]) - my);
    sxx += (std::log(spp[k]) - mx) * (std::log(spp[k]) - mx);
  }
  const double slope = sxy / sxx;
  std::printf("convergence slope %.3f (1/sqrt(N) is -0.5)\n", slope);
  PGI_NEAR(slope, -0.5, 0.1);

  // Scale invariance: the same scene at 1e-4 and 1e4 gives the same numbers.
  for (double scale : { 1e-4, 1e4 })
  {
    EnvironmentMap sky = EnvironmentMap::Uniform(1, 1, 1);
    ReferenceTracer tracer;
    std::string error;
    const float albedo[3] = { 0.8f, 0.8f, 0.8f };
    const double c[3] = { 0, 0, 1.5 * scale };
    tracer.AddSphere(c, scale, albedo, error);
    const float s = static_cast<float>(100 * scale);
    tracer.AddMesh(
      { -s, -s, 0, s, -s, 0, s, s, 0, -s, s, 0 }, { 0, 1, 2, 0, 2, 3 }, nullptr, albedo, error);
    tracer.SetEnvironment(&sky);
    PGI_CHECK(tracer.Commit(error));
    settings.Samples = 256;
    ReferenceTracer::Estimate a, b;
    const double xs[3] = { 0.7 * scale, 0.2 * scale, 0.0 }, x1[3] = { 0.7, 0.2, 0.0 };
    tracer.EstimateIrradiance(xs, n, 5, settings, a);
    f.Tracer.EstimateIrradiance(x1, n, 5, settings, b);
    std::printf("scale %g: E = %.6f vs %.6f at scale 1\n", scale, a.Direct[0], b.Direct[0]);
    PGI_NEAR(a.Direct[0], b.Direct[0], 1e-3 * b.Direct[0]);
  }

  // OccludedRays (packets of 16, the last one partly idle) against the
  // closed form: 37 rays from random points above the plane, outside the
  // sphere, in random directions, unbounded and then with lengths; rays
  // within 1e-3 of grazing the sphere or ending within 1e-3 of a surface
  // are left out of the comparison.
  const int rays = 37;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<float> origins, directions, lengths;
  while (static_cast<int>(origins.size()) < 3 * rays)
  {
    const double o[3] = { 3 * unit(random), 3 * unit(random), 1.5 + 1.4 * unit(random) };
    double d[3] = { unit(random), unit(random), unit(random) };
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double oc[3] = { o[0] - f.Center[0], o[1] - f.Center[1], o[2] - f.Center[2] };
    if (!(len > 0.1) || oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] < 1.1)
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      origins.push_back(static_cast<float>(o[c]));
      directions.push_back(static_cast<float>(d[c] / len));
    }
    lengths.push_back(static_cast<float>(2.5 * (unit(random) + 1.0)));
  }
  int compared = 0, agree = 0, blocked = 0;
  for (bool bounded : { false, true })
  {
    std::vector<unsigned char> hit(rays, 2);
    f.Tracer.OccludedRays(rays, origins.data(), directions.data(), 0.0f,
      bounded ? lengths.data() : nullptr, hit.data());
    for (int i = 0; i < rays; ++i)
    {
      const float* o = &origins[3 * i];
      const float* d = &directions[3 * i];
      const double limit = bounded ? lengths[i] : 1e30;
      // The first surface: the sphere (|o + t d - c| = r) or the plane z = 0.
      const double oc[3] = { o[0] - f.Center[0], o[1] - f.Center[1], o[2] - f.Center[2] };
      const double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
      const double disc = b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 1.0);
      double first = d[2] < 0.0 ? -o[2] / d[2] : 1e30;
      if (disc > 0.0 && -b - std::sqrt(disc) > 0.0)
      {
        first = std::min(first, -b - std::sqrt(disc));
      }
      if (std::fabs(disc) < 1e-3 || (bounded && std::fabs(first - limit) < 1e-3))
      {
        continue;
      }
      const unsigned char expected = first < limit ? 1 : 0;
      ++compared;
      agree += hit[i] == expected ? 1 : 0;
      blocked += expected;
    }
  }
  std::printf(
    "OccludedRays: %d of %d rays as the closed form (%d blocked)\n", agree, compared, blocked);
  PGI_CHECK(compared > 60);
  PGI_CHECK(blocked > 10 && blocked < compared - 10);
  PGI_CHECK(agree == compared);
  return pgitest::Result();
}
