#include "pgiIndirectLight.h"

#include "pgiEnvironmentShading.h"

#include "pgiSHBasis.h"
#include "pgiSHBatch.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include <algorithm>
#include <cmath>

namespace proxygi
{

const char* IndirectOperatorName(IndirectOperator op)
{
  switch (op)
  {
    case IndirectOperator::PointSampled:
      return "point-sampled";
    case IndirectOperator::Averaged:
      return "averaged D(theta)";
    case IndirectOperator::Exact:
      return "exact M(theta)";
  }
  return "?";
}

SecondaryLights::SecondaryLights(
  int order, const double* red, const double* green, const double* blue, const Blockers* planes)
  : Order(order)
{
  const int n2 = sh::NumCoefficients(order);
  const double* light[3] = { red, green, blue };
  std::vector<double> shadowed;
  if (planes && planes->Planes() > 0)
  {
    // V = exp(sum of the planes' 90-degree cap logs); L' = L * V.
    const sh::CapTables& caps = sh::CapTables::Get(order);
    double zh[sh::MaxOrder], f[sh::MaxCoefficients] = {}, v[sh::MaxCoefficients],
                             rotated[sh::MaxCoefficients];
    caps.CapLog(sh::CapTables::MaxAngle, zh);
    for (std::size_t k = 0; k < planes->Planes(); ++k)
    {
      const float* pn = &planes->PlaneNormal[3 * k];
      sh::RotateScaledZonal(order, zh, -double(pn[0]), -double(pn[1]), -double(pn[2]), rotated);
      for (int i = 0; i < n2; ++i)
      {
        f[i] += rotated[i];
      }
    }
    if (sh::Exp(order, f, v) == sh::Status::Ok)
    {
      shadowed.resize(3 * n2);
      for (int c = 0; c < 3; ++c)
      {
        sh::TripleProduct::Get(order).Product(light[c], v, &shadowed[c * n2]);
        light[c] = &shadowed[c * n2];
      }
    }
  }
  this->Response.resize(3 * n2);
  double kernel[sh::MaxBasisOrder];
  sh::ClampedCosineZonal(order, kernel);
  for (int c = 0; c < 3; ++c)
  {
    for (int l = 0; l < order; ++l)
    {
      const double s = sh::ZonalScale(l) * kernel[l] / sh::Pi;
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        this->Response[c * n2 + i] = static_cast<float>(s * light[c][i]);
      }
    }
  }
}

void IndirectExitRadiance(IndirectOperator op, const SecondaryLights& lights,
  const Blockers& blockers, const std::vector<SeenBlocker>& seen, float visibilityDC,
  const float n[3], float rgb[3], const float* planeScale, bool planesOnly, int silentObject,
  bool planesSeenPast)
{
  const bool silence = silentObject >= 0 && blockers.Object.size() == blockers.Spheres();
  rgb[0] = rgb[1] = rgb[2] = 0.0f;
  if (seen.empty())
  {
    return;
  }
  const int order = lights.Order, n2 = sh::NumCoefficients(order);
  const sh::CapTables& caps = sh::CapTables::Get(order);
  const sh::IndirectTables& indirect = sh::IndirectTables::Get(order);
  float h[sh::MaxCoefficients];
  sh::DiffuseTransfer(order, n[0], n[1], n[2], h);
  float sum[3] = { 0, 0, 0 }, planeSum[3] = { 0, 0, 0 };
  float solidAngles = 0.0f;
  // Per proxy: H(N) . (cap about b.Dir), the cap's irradiance weight shared
  // by the cap-times-scalar operators, and the averaged operator's radiance
  // per channel (before the albedo: the operator is linear), for
  // sh::BatchWidth proxies at a time.
  constexpr int W = sh::BatchWidth;
  const bool averaged = op == IndirectOperator::Averaged;
  alignas(64) float theta[W], dx[W], dy[W], dz[W], weights[W], kappas[3 * W];
  const std::size_t count = seen.size();
  for (std::size_t first = 0; first < count; first += W)
  {
    const int lanes = static_cast<int>(std::min<std::size_t>(W, count - first));
    for (int q = 0; q < W; ++q)
    {
      const SeenBlocker& b = seen[first + std::min(q, lanes - 1)];
      theta[q] = q < lanes ? b.Theta : -1.0f;
      dx[q] = b.Dir[0];
      dy[q] = b.Dir[1];
      dz[q] = b.Dir[2];
    }
    sh::BatchIndirectWeights(caps, indirect, order, theta, dx, dy, dz, h, averaged ? 3 : 0,
      lights.Response.data(), weights, kappas);
    for (int q = 0; q < lanes; ++q)
    {
      const SeenBlocker& b = seen[first + q];
      const float capWeight = weights[q];
      if (b.Index >= 0 || !planesSeenPast)
      {
        solidAngles += static_cast<float>(sh::CapSolidAngle(b.Theta));
      }
      if (b.Index < 0)
      {
        // A plane: uniform radiance, its albedo times the response at its normal.
        const int k = -1 - b.Index;
        const float* pn = &blockers.PlaneNormal[3 * k];
        float* to = planesSeenPast ? planeSum : sum;
        for (int c = 0; c < 3; ++c)
        {
          const float r = blockers.PlaneAlbedo[3 * k + c] *
            (planeScale ? planeScale[3 * k + c] : 1.0f) *
            sh::Reconstruct(order, &lights.Response[c * n2], pn[0], pn[1], pn[2]);
          to[c] += r * capWeight;
        }
        continue;
      }
      const float* albedo = &blockers.Albedo[3 * static_cast<std::size_t>(b.Index)];
      if (planesOnly || (silence && blockers.Object[b.Index] == silentObject) ||
        (albedo[0] <= 0.0f && albedo[1] <= 0.0f && albedo[2] <= 0.0f))
      {
        continue;
      }
      if (averaged)
      {
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += capWeight * albedo[c] * kappas[c * W + q];
        }
        continue;
      }
      float rcs[3][sh::MaxCoefficients];
      for (int c = 0; c < 3; ++c)
      {
        for (int i = 0; i < n2; ++i)
        {
          rcs[c][i] = albedo[c] * lights.Response[c * n2 + i];
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        const float* rc = rcs[c];
        if (op == IndirectOperator::PointSampled)
        {
          // The surface point facing the receiver has outward normal -Dir.
          sum[c] += capWeight * sh::Reconstruct(order, rc, -b.Dir[0], -b.Dir[1], -b.Dir[2]);
        }
        else
        {
          sum[c] += indirect.ExactIndirectExitRadiance(b.Theta, b.Dir, n, rc);
        }
      }
    }
  }
  const float xi = sh::OverlapNormalization(visibilityDC, solidAngles);
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = std::max(0.0f, xi * sum[c] + planeSum[c]);
  }
}

bool PlaneShadowPoint(
  const Blockers& blockers, int plane, const float p[3], const float n[3], float q[3])
{
  const float* o = &blockers.PlaneOrigin[3 * plane];
  const float* m = &blockers.PlaneNormal[3 * plane];
  const float height = (p[0] - o[0]) * m[0] + (p[1] - o[1]) * m[1] + (p[2] - o[2]) * m[2];
  float d[3] = { n[0] - m[0], n[1] - m[1], n[2] - m[2] };
  const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(height > 0.0f) || !(len > 1e-3f))
  {
    return false;
  }
  const float down = -(d[0] * m[0] + d[1] * m[1] + d[2] * m[2]) / len; // cos to -m
  if (!(down > 0.0f))
  {
    return false;
  }
  // Far along a grazing direction the plane point says little: at most 4 h.
  const float t = height / std::max(down, 0.25f);
  for (int k = 0; k < 3; ++k)
  {
    q[k] = p[k] + t * d[k] / len;
  }
  return true;
}

void PlaneShadowScaleAt(const EnvironmentShading& shading, const float m[3], const float* g,
  int used, sh::Status status, float scale[3])
{
  scale[0] = scale[1] = scale[2] = 1.0f;
  if (used == 0 || status != sh::Status::Ok)
  {
    return;
  }
  float lit[3], open[3];
  shading.Shade(m, g, lit);
  shading.ShadeUnshadowed(m, open);
  for (int c = 0; c < 3; ++c)
  {
    scale[c] = open[c] > 0.0f ? std::min(1.0f, std::max(0.0f, lit[c] / open[c])) : 1.0f;
  }
}

bool PlaneShadowScale(const SoftShadows& shadows, const EnvironmentShading& shading,
  const Blockers& blockers, int plane, const float p[3], const float n[3], float scale[3])
{
  scale[0] = scale[1] = scale[2] = 1.0f;
  float q[3], g[sh::MaxCoefficients];
  if (!PlaneShadowPoint(blockers, plane, p, n, q))
  {
    return false;
  }
  sh::Status status;
  const float* m = &blockers.PlaneNormal[3 * plane];
  const int used = shadows.Visibility(q, m, blockers, g, status);
  PlaneShadowScaleAt(shading, m, g, used, status, scale);
  return true;
}

} // namespace proxygi
