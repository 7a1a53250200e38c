// SoftShadowOfSphere: how the SphericalHarmonics module shades one receiver
// under one spherical blocker and an environment light.
//
// 1. The blocker's log-visibility: a table lookup by its angular radius,
//    rotated to its direction (ZH rotation rule). With many blockers these
//    vectors are simply summed.
// 2. exp turns the summed log back into a visibility vector g (HYB method).
// 3. Shading: exit radiance = albedo * H(N) . (L * g), with L the lighting's
//    SH vector and H(N) the diffuse transfer of the normal N.
//
// Here L is a uniform white sky, so L * g = g and the exact answer is
// albedo * (1 - (r/d)^2 cos(beta)); the program prints both.
#include "pgiSHExp.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include <cmath>
#include <cstdio>

int main()
{
  using namespace proxygi::sh;
  const int order = 4;
  const double receiver[3] = { 0.8, 0.0, 0.0 }, normal[3] = { 0.0, 0.0, 1.0 };
  const double center[3] = { 0.0, 0.0, 1.5 }, radius = 1.0, albedo = 0.8;

  // 1. Log-visibility of the blocker as seen from the receiver.
  double dir[3], d = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    dir[k] = center[k] - receiver[k];
    d += dir[k] * dir[k];
  }
  d = std::sqrt(d);
  for (double& c : dir)
  {
    c /= d;
  }
  const CapTables& tables = CapTables::Get(order);
  double zh[MaxOrder], logVisibility[MaxCoefficients];
  tables.CapLog(std::asin(radius / d), zh);
  RotateScaledZonal(order, zh, dir[0], dir[1], dir[2], logVisibility);

  // 2. Back to visibility.
  double visibility[MaxCoefficients];
  const Status status = Exp(order, logVisibility, visibility);
  if (status != Status::Ok)
  {
    std::fprintf(stderr, "exp failed: %s\n", StatusString(status));
    return 1;
  }

  // 3. Shade: a uniform sky of radiance 1 (any L works through the product).
  double light[MaxCoefficients], shadowedLight[MaxCoefficients], transfer[MaxCoefficients];
  SetConstant(order, 1.0, light);
  TripleProduct::Get(order).Product(light, visibility, shadowedLight);
  DiffuseTransfer(order, normal[0], normal[1], normal[2], transfer);
  const double radiance = albedo * Dot(NumCoefficients(order), transfer, shadowedLight);

  const double cosBeta = dir[0] * normal[0] + dir[1] * normal[1] + dir[2] * normal[2];
  const double exact = albedo * (1.0 - (radius / d) * (radius / d) * cosBeta);
  std::printf("SH soft shadow (order %d, HYB): %.5f   closed form: %.5f   error %.2f%%\n", order,
    radiance, exact, 100.0 * std::fabs(radiance - exact) / exact);
  return std::fabs(radiance - exact) < 0.01 * exact ? 0 : 1;
}
