/**
 * @file pgiBrightLightShadows.h
 * @brief The bright lights taken out of an environment map
 * (pgiBrightLights.h), shaded at a receiver with their own sharp shadows.
 *
 * A light is a uniform disk of directions (half-angle a, radiance L). At a
 * white receiver (p, n) its exit radiance is
 *   (1/pi) int_disk L max(n.w, 0) V(w) dw
 *   ~ L Omega / (pi K) sum_k max(n.w_k, 0) V(w_k)
 * over K equal-area directions w_k of the disk (DistantLightDirections), so
 * the terminator is smooth and the penumbra follows the light's size. V comes
 * from one of two routes:
 *  - rays: the real meshes, through a vtkPGIOccluder (one ray per w_k);
 *  - proxies: the cone against each sphere after the self-shadow rules,
 *    analytically: the disk's fraction covered by the sphere's cap (the area
 *    of two caps' intersection), blockers combined as a product of their
 *    visible fractions, the way the SH route adds their logs.
 * Planes block the half-space beneath them for receivers above them, in both.
 *
 * The ground's bounce (BrightLightsOnPlane): a plane lit by a sun is dark only
 * in the shadows, so the part of it a receiver sees is sampled: the visibility
 * of each light where cosine-weighted directions from the receiver meet the
 * plane, the mean weighted by each light's irradiance of the plane.
 */
#ifndef pgiBrightLightShadows_h
#define pgiBrightLightShadows_h

#include "ProxyGIShadingModule.h"

#include "pgiBrightLights.h"
#include "pgiSoftShadows.h"

#include <vector>

class vtkPGIOccluder;

namespace proxygi
{

/// The area where two caps of angular radii a and b, centres g apart, overlap.
PROXYGISHADING_EXPORT double CapOverlapArea(double a, double b, double g);

/// The lights a filter shades with and their directions (built once per light).
struct PROXYGISHADING_EXPORT BrightLightSet
{
  std::vector<DistantLight> Lights;
  int Rays = 16;
  std::vector<float> Directions; // Lights x Rays x 3
  /// L Omega / (pi K) per light, RGB.
  std::vector<float> Scale;
  void Set(const std::vector<DistantLight>& lights, int rays);
  bool Empty() const { return this->Lights.empty(); }
};

/// Per-thread buffers for the rays route (no allocation per receiver).
struct BrightLightScratch
{
  std::vector<float> Origins, Directions, Weights, Points;
  std::vector<int> Light, Point;
  std::vector<unsigned char> Blocked;
};

/**
 * The visible fraction of light `l`'s disk at q (normal n) past the spheres
 * (after the self-shadow rules) and planes of `blockers`, as a product of
 * each blocker's uncovered fraction.
 */
PROXYGISHADING_EXPORT double ConeVisibility(const BrightLightSet& lights, std::size_t l,
  const Blockers& blockers, const float q[3], const float n[3], float minAngle);

/**
 * Adds the lights' exit radiance at (p, n) to rgb, shadowed by the proxies
 * and planes of `blockers` (analytic route; `shadows` false: unshadowed).
 */
PROXYGISHADING_EXPORT void BrightLightsFromProxies(const BrightLightSet& lights,
  const Blockers& blockers, const float p[3], const float n[3], float minAngle, bool shadows,
  float rgb[3]);

/**
 * Adds the lights' exit radiance at (p, n) to rgb, shadowed by the
 * occluder's meshes (rays from p + offset n, starting at `offset`) and the
 * planes of `blockers`.
 */
PROXYGISHADING_EXPORT void BrightLightsFromRays(const BrightLightSet& lights,
  const Blockers& blockers, const vtkPGIOccluder& occluder, const float p[3], const float n[3],
  float offset, BrightLightScratch& scratch, float rgb[3]);

/// The same at `points` points at once (p, n and rgb: 3 floats each), their
/// rays traced together.
PROXYGISHADING_EXPORT void BrightLightsFromRays(const BrightLightSet& lights,
  const Blockers& blockers, const vtkPGIOccluder& occluder, int points, const float* p,
  const float* n, float offset, BrightLightScratch& scratch, float* rgb);

/// `count` cosine-weighted directions about +z (stratified), 3 floats each.
PROXYGISHADING_EXPORT void CosineHemisphere(int count, float* directions);

/**
 * The bright lights' light on plane `plane` where a receiver at p (normal n)
 * sees it: over the directions of `hemisphere` (CosineHemisphere, turned to
 * n) that meet the plane, each light's visibility at the meeting point (one
 * ray per point through `occluder`, or the proxies' cones when it is null),
 * averaged; `shadowed` receives the sum over lights of that mean times the
 * light's unshadowed exit radiance off the plane (white; `open` gets that
 * unshadowed sum). False when no direction meets the plane.
 */
PROXYGISHADING_EXPORT bool BrightLightsOnPlane(const BrightLightSet& lights,
  const Blockers& blockers, int plane, const vtkPGIOccluder* occluder, float offset, float minAngle,
  const float p[3], const float n[3], const std::vector<float>& hemisphere,
  BrightLightScratch& scratch, float shadowed[3], float open[3]);

} // namespace proxygi

#endif
