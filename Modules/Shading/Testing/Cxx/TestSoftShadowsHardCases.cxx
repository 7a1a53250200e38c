// Hard cases of the per-vertex soft shadows: receivers inside 1-50 spheres,
// 1000 overlapping spheres, spheres grazing the tangent plane (sweeps: no
// jumps), scale 1e-4 and 1e4, zero-radius and coincident spheres, NaN input.
// No NaN or Inf may come out.
#include "pgiSHZonal.h"
#include "pgiSoftShadows.h"
#include "vtkPGIGlobalIllumination.h"

#include "pgiTesting.h"
#include "pgiTestingErrors.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace proxygi;

namespace
{
// Exit radiance (white, uniform sky of 1) of one receiver.
double Shade(const SoftShadows& shadows, const Blockers& b, const float p[3], const float n[3])
{
  float g[sh::MaxCoefficients], h[sh::MaxCoefficients];
  sh::Status status;
  shadows.Visibility(p, n, b, g, status);
  sh::DiffuseTransfer(shadows.GetOrder(), n[0], n[1], n[2], h);
  // As the shading does: radiance below 0 (ringing) is clamped.
  return std::max(0.0f, sh::Dot(shadows.GetOrder() * shadows.GetOrder(), h, g));
}

} // namespace

int TestSoftShadowsHardCases(int, char*[])
{
  SoftShadowSettings settings;
  const SoftShadows shadows(settings);
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float up[3] = { 0, 0, 1 };

  // Receivers inside 1..50 random spheres (all contain the receiver).
  double lo = 1e9, hi = -1e9;
  for (int count : { 1, 2, 5, 10, 50 })
  {
    double countLo = 1e9, countHi = -1e9;
    for (int trial = 0; trial < 20; ++trial)
    {
      Blockers b;
      for (int k = 0; k < count; ++k)
      {
        const float c[3] = { 0.5f * u(rng), 0.5f * u(rng), 0.5f * u(rng) };
        const float d = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        b.AddSphere(c[0], c[1], c[2], d + 0.1f + 0.5f * std::fabs(u(rng)));
      }
      const float p[3] = { 0, 0, 0 };
      const double v = Shade(shadows, b, p, up);
      PGI_CHECK(std::isfinite(v));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      countLo = std::min(countLo, v);
      countHi = std::max(countHi, v);
    }
    std::printf("  inside %d spheres: radiance in [%.3f, %.3f]\n", count, countLo, countHi);
    if (count == 50)
    {
      // The inside rule keeps the spheres: 50 of them leave it dark
      // (measured [0.000, 0.034] by a harness replaying this loop).
      PGI_BELOW(countHi, 0.2);
    }
  }
  std::printf("receiver inside 1-50 spheres: radiance in [%.3f, %.3f]\n", lo, hi);
  PGI_CHECK(lo >= -0.05 && hi <= 1.05);
  PGI_BELOW(lo, 0.05); // measured 0.000: some receivers are in full shadow

  // 1000 overlapping spheres above the receiver: finite, nearly black.
  {
    Blockers b;
    for (int k = 0; k < 1000; ++k)
    {
      b.AddSphere(2 * u(rng), 2 * u(rng), 2.0f + u(rng), 0.3f + 0.2f * std::fabs(u(rng)));
    }
    const float p[3] = { 0, 0, 0 };
    const double v = Shade(shadows, b, p, up);
    std::printf("under 1000 overlapping spheres: %.4f\n", v);
    PGI_CHECK(std::isfinite(v) && v >= 0.0 && v <= 1.05);
    PGI_BELOW(v, 0.05); // measured 0.0000
  }

  // Sweeps: a receiver moves through a sphere that cuts its tangent plane,
  // and past one grazing it; the largest step between neighbours must stay
  // small (a smooth function moves ~1e-3 per step here).
  // A jump stays the same size when the step shrinks; a steep but continuous
  // change shrinks with it. Sweep at two step sizes and compare.
  // The sweep must also see the shadow (a constant output has no steps):
  // least radiance range, about half the measured 0.0036, 0.0148, 0.912, 0.944.
  const float heights[4] = { -0.5f, 0.0f, 0.6f, 0.95f };
  const double minRanges[4] = { 0.002, 0.007, 0.5, 0.5 };
  for (int h = 0; h < 4; ++h)
  {
    const float height = heights[h];
    Blockers b;
    b.AddSphere(0.0f, 0.0f, height, 1.0f);
    double worst[2] = { 0.0, 0.0 };
    double vMin = 1e9, vMax = -1e9;
    const int stepCounts[2] = { 4000, 16000 };
    for (int pass = 0; pass < 2; ++pass)
    {
      double prev = 0.0;
      for (int k = 0; k <= stepCounts[pass]; ++k)
      {
        const float p[3] = { -3.0f + 6.0f * k / stepCounts[pass], 0.1f, 0.0f };
        const double v = Shade(shadows, b, p, up);
        PGI_CHECK(std::isfinite(v));
        if (k > 0)
        {
          worst[pass] = std::max(worst[pass], std::fabs(v - prev));
        }
        prev = v;
        vMin = std::min(vMin, v);
        vMax = std::max(vMax, v);
      }
    }
    std::printf("sweep through a sphere at height %.2f: largest step %.4f (4000 steps), %.4f "
                "(16000 steps), radiance in [%.4f, %.4f]\n",
      height, worst[0], worst[1], vMin, vMax);
    PGI_BELOW(worst[1], 0.35 * worst[0] + 1e-3);
    PGI_BELOW(worst[1], 0.01);
    PGI_CHECK(vMax - vMin > minRanges[h]);
  }
  // Normals turning past a sphere (tangent plane sweeping over it).
  {
    Blockers b;
    b.AddSphere(1.5f, 0.0f, 0.3f, 0.5f);
    double prev = 0.0, worst = 0.0, vMin = 1e9, vMax = -1e9;
    for (int k = 0; k <= 2000; ++k)
    {
      const float a = 3.14159265f * k / 2000;
      const float n[3] = { -std::cos(a), 0.0f, std::sin(a) };
      const float p[3] = { 0, 0, 0 };
      const double v = Shade(shadows, b, p, n);
      if (k > 0)
      {
        worst = std::max(worst, std::fabs(v - prev));
      }
      prev = v;
      vMin = std::min(vMin, v);
      vMax = std::max(vMax, v);
    }
    std::printf("normal turning past a sphere: largest step %.4f, radiance in [%.4f, %.4f]\n",
      worst, vMin, vMax);
    PGI_BELOW(worst, 0.02);
    PGI_CHECK(vMax - vMin > 0.05); // measured range 0.114 (0.886 to 1)
  }

  // Scale: the same scene at 1e-4 and 1e4 gives the same radiance.
  {
    vtkNew<vtkPlaneSource> plane;
    plane->SetResolution(20, 20);
    plane->SetOrigin(-2, -2, 0);
    plane->SetPoint1(2, -2, 0);
    plane->SetPoint2(-2, 2, 0);
    plane->Update();
    std::vector<double> reference;
    for (double scale : { 1.0, 1e-4, 1e4 })
    {
      vtkNew<vtkPolyData> scaled;
      scaled->DeepCopy(plane->GetOutput());
      for (vtkIdType i = 0; i < scaled->GetNumberOfPoints(); ++i)
      {
        double x[3];
        scaled->GetPoint(i, x);
        scaled->GetPoints()->SetPoint(i, x[0] * scale, x[1] * scale, x[2] * scale);
      }
      vtkNew<vtkPolyData> proxies;
      vtkNew<vtkPoints> centres;
      centres->InsertNextPoint(0.3 * scale, 0, 1.2 * scale);
      centres->InsertNextPoint(-0.5 * scale, 0.4 * scale, 0.6 * scale);
      proxies->SetPoints(centres);
      vtkNew<vtkDoubleArray> radius;
      radius->SetName("Radius");
      radius->InsertNextValue(0.8 * scale);
      radius->InsertNextValue(0.5 * scale);
      proxies->GetPointData()->AddArray(radius);
      vtkNew<vtkPGIGlobalIllumination> gi;
      gi->SetInputData(scaled);
      gi->SetProxiesData(proxies);
      gi->Update();
      vtkDataArray* d = gi->GetOutput()->GetPointData()->GetArray("DirectShadowed");
      double worst = 0.0;
      for (vtkIdType i = 0; i < d->GetNumberOfTuples(); ++i)
      {
        PGI_CHECK(std::isfinite(d->GetComponent(i, 0)));
        if (scale == 1.0)
        {
          reference.push_back(d->GetComponent(i, 0));
        }
        else
        {
          worst = std::max(worst, std::fabs(d->GetComponent(i, 0) - reference[i]));
        }
      }
      if (scale != 1.0)
      {
        std::printf("scale %g: largest difference to scale 1: %.2e\n", scale, worst);
        PGI_BELOW(worst, 1e-4);
      }
      else
      {
        // The reference must show the shadow, or equal outputs prove nothing
        // (uniform-sky harness: min/max about 0.31).
        const double refMin = *std::min_element(reference.begin(), reference.end());
        const double refMax = *std::max_element(reference.begin(), reference.end());
        std::printf("scale 1: DirectShadowed in [%.4f, %.4f]\n", refMin, refMax);
        PGI_CHECK(refMax > 0.0 && refMin < 0.7 * refMax);
      }
    }
  }

  // Zero-radius spheres block nothing; coincident spheres are fine.
  {
    Blockers none, zero, one, twice;
    zero.AddSphere(0, 0, 1, 0.0f);
    one.AddSphere(0.2f, 0, 1.2f, 0.5f);
    twice.AddSphere(0.2f, 0, 1.2f, 0.5f);
    twice.AddSphere(0.2f, 0, 1.2f, 0.5f);
    const float p[3] = { 0, 0, 0 };
    PGI_NEAR(Shade(shadows, zero, p, up), Shade(shadows, none, p, up), 0.0);
    const double a = Shade(shadows, one, p, up), b = Shade(shadows, twice, p, up);
    std::printf("one sphere %.4f, the same sphere twice %.4f\n", a, b);
    PGI_CHECK(std::isfinite(b) && b <= a + 1e-6 && b >= -0.05);
    // One cap of half-angle alpha, beta off the normal, blocks
    // sin^2(alpha) cos(beta) of the sky: 0.8334 (measured a 0.8249).
    const double alpha = std::asin(0.5 / std::sqrt(0.2 * 0.2 + 1.2 * 1.2));
    const double beta = std::atan2(0.2, 1.2);
    PGI_NEAR(a, 1.0 - std::sin(alpha) * std::sin(alpha) * std::cos(beta), 0.02);
    PGI_CHECK(b >= 0.6); // measured 0.7258; a second copy must not black it out
  }

  // NaN: in the receivers or in the proxies, a clear error.
  {
    vtkNew<vtkPolyData> receivers;
    vtkNew<vtkPoints> p;
    p->InsertNextPoint(0, 0, 0);
    p->InsertNextPoint(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    receivers->SetPoints(p);
    vtkNew<vtkDoubleArray> n;
    n->SetNumberOfComponents(3);
    n->InsertNextTuple3(0, 0, 1);
    n->InsertNextTuple3(0, 0, 1);
    receivers->GetPointData()->SetNormals(n);
    vtkNew<vtkPGIGlobalIllumination> gi;
    gi->SetInputData(receivers);
    PGI_CHECK(pgitest::Fails(gi));
    p->SetPoint(1, 1, 0, 0);
    p->Modified();
    vtkNew<vtkPolyData> proxies;
    vtkNew<vtkPoints> c;
    c->InsertNextPoint(0, 0, 2);
    proxies->SetPoints(c);
    vtkNew<vtkDoubleArray> r;
    r->SetName("Radius");
    r->InsertNextValue(std::numeric_limits<double>::quiet_NaN());
    proxies->GetPointData()->AddArray(r);
    gi->SetProxiesData(proxies);
    PGI_CHECK(pgitest::Fails(gi));
    r->SetValue(0, 0.5);
    r->Modified();
    PGI_CHECK(!pgitest::Fails(gi));
    vtkNew<vtkPolyData> noRadius;
    noRadius->SetPoints(c);
    gi->SetProxiesData(noRadius);
    PGI_CHECK(pgitest::Fails(gi));
  }
  return pgitest::Result();
}
