/**
 * @file pgiIndirectLight.h
 * @brief One-bounce diffuse light from the proxies, unshadowed (Sloan et
 * al. 2007): every sphere a receiver sees (after the self-shadow rules) is a
 * secondary light whose surface radiance, as a function of its outward
 * normal, is the SH vector R (albedo times the diffuse response to the
 * environment). Its incident radiance at the receiver fills the cap it
 * covers, by one of three operators:
 *  - PointSampled: R at the sphere point facing the receiver, times the cap;
 *  - Averaged: the solid-angle average of R over the visible disk
 *    (D(theta), IndirectTables::AveragedRadiance), times the cap;
 *  - Exact: R^-1 M(theta) R applied to R (IndirectTables::ExactIndirectRadiance).
 * The sum is scaled by the overlap normalisation xi (covered solid angle
 * over summed solid angles), so overlapping proxies do not double-count.
 * Blocker planes count as secondary lights of uniform radiance.
 */
#ifndef pgiIndirectLight_h
#define pgiIndirectLight_h

#include "ProxyGIShadingModule.h"

#include "pgiSoftShadows.h"

#include <vector>

namespace proxygi
{

class EnvironmentShading;

enum class IndirectOperator
{
  PointSampled,
  Averaged,
  Exact
};

PROXYGISHADING_EXPORT const char* IndirectOperatorName(IndirectOperator op);

/**
 * What lights the secondary lights: the diffuse response of a white surface
 * to the environment L as a function of its normal, (1/pi) (L convolved with
 * the clamped cosine), 3 x n^2. A proxy's surface radiance is its albedo
 * times this; a plane's is its albedo times this at the plane's normal.
 */
struct PROXYGISHADING_EXPORT SecondaryLights
{
  int Order = 4;
  std::vector<float> Response; // 3 x Order^2
  /// With blocker planes, the proxies' light is first multiplied by the
  /// planes' visibility (a ground hides the sky below it from the proxies
  /// above it), so proxies' undersides are not lit by a sky they cannot see.
  SecondaryLights(int order, const double* red, const double* green, const double* blue,
    const Blockers* planes = nullptr);
};

/**
 * Exit radiance (white receiver; multiply by albedo) of the one-bounce light
 * at a receiver with normal n, from the blockers it sees (`seen`, from
 * SoftShadows::Visibility, indexing `blockers` for albedos) and its
 * visibility DC coefficient (for xi).
 */
PROXYGISHADING_EXPORT void IndirectExitRadiance(IndirectOperator op, const SecondaryLights& lights,
  const Blockers& blockers, const std::vector<SeenBlocker>& seen, float visibilityDC,
  const float n[3], float rgb[3], const float* planeScale = nullptr, bool planesOnly = false,
  int silentObject = -1, bool planesSeenPast = false);

/// (planeScale: per plane and channel, see PlaneShadowScale; planesOnly: the
/// spheres count for the overlap normalisation but emit nothing, for when
/// they are spherical lights of the shadowed model; silentObject: the same
/// for the spheres of that object, whose bounce the receiver has traced;
/// planesSeenPast: planeScale already weighs each direction to a plane by
/// the visibility of what stands in front of it (PlaneLightMap::Scale with
/// g), so the planes take no overlap normalisation and count in none, and
/// visibilityDC is that of the spheres alone.)

/**
 * How much of a plane's light reaches the part of it a receiver at p with
 * normal n mostly sees: the plane point q along normalize(n - m) (straight
 * down for a receiver facing down, 45 degrees off for one facing sideways),
 * shaded with the proxies' visibility at q over shaded without it, per
 * channel (3 floats, in [0, 1]). So a ground darkened by an object's shadow
 * reflects less onto the object's underside, at the cost of one more
 * visibility per receiver. Returns false (scale 1) when the receiver does
 * not see the plane.
 */
PROXYGISHADING_EXPORT bool PlaneShadowScale(const SoftShadows& shadows,
  const EnvironmentShading& shading, const Blockers& blockers, int plane, const float p[3],
  const float n[3], float scale[3]);

/// PlaneShadowScale in two steps, for batching the visibility at q: the
/// plane point (false: the receiver does not see the plane, scale 1), and
/// the scale from the visibility (g, used, status) at q.
PROXYGISHADING_EXPORT bool PlaneShadowPoint(
  const Blockers& blockers, int plane, const float p[3], const float n[3], float q[3]);
PROXYGISHADING_EXPORT void PlaneShadowScaleAt(const EnvironmentShading& shading, const float m[3],
  const float* g, int used, sh::Status status, float scale[3]);

} // namespace proxygi

#endif
