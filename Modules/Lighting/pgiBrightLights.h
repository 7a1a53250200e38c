/**
 * @file pgiBrightLights.h
 * @brief The few brightest compact regions of an environment map (a sun, a
 * lamp) taken out as distant lights, leaving a residual map that low-order
 * SH carries well.
 *
 * Peak finding: the brightest texel left seeds a region that grows through
 * its brightest neighbours (8-connected, wrapping in phi) while they stay
 * above PeakRatio x the map's mean luminance and the region's solid angle
 * stays under a cone of MaxHalfAngle. The region's texels are lowered to the
 * mean of the texels around it (never raised); what was removed is the
 * light: its direction the removed power's centroid, its half-angle from the
 * power's second angular moment (a uniform disk of half-angle a has
 * <theta^2> = a^2 / 2), its radiance the removed power over that cone's solid
 * angle. A region holding less than MinFraction of the map's power ends the
 * search. The removed power plus the residual's is the map's, per channel.
 */
#ifndef pgiBrightLights_h
#define pgiBrightLights_h

#include "ProxyGILightingModule.h"

#include "pgiEnvironmentMap.h"

#include <vector>

namespace proxygi
{

/// A light at infinity: a uniform disk of directions.
struct PROXYGILIGHTING_EXPORT DistantLight
{
  double Direction[3] = { 0, 0, 1 }; // world space, unit, towards the light
  double HalfAngle = 0.0;            // radians
  double Radiance[3] = { 0, 0, 0 };
  /// 2 pi (1 - cos HalfAngle).
  double SolidAngle() const;
  /// Its share of the map's power (luminance-weighted).
  double Fraction = 0.0;
};

struct PROXYGILIGHTING_EXPORT BrightLightOptions
{
  int MaxLights = 4;
  /// A peak holding less of the map's power ends the search.
  double MinFraction = 0.05;
  /// A region's texels stay above this many times the mean luminance.
  double PeakRatio = 20.0;
  /// A region's solid angle stays under this cone (radians).
  double MaxHalfAngle = 0.1;
};

struct PROXYGILIGHTING_EXPORT BrightLightResult
{
  std::vector<DistantLight> Lights;
  EnvironmentMap Residual;
  /// The share of the map's power in the brightest compact peak found, taken
  /// out or not (the plan's reason), and the shares taken out in all.
  double BrightestFraction = 0.0, ExtractedFraction = 0.0;
};

/// Extracts the bright lights of `map` (rotation included). Allocates the
/// residual even when nothing is taken out (then it equals the map).
PROXYGILIGHTING_EXPORT void ExtractBrightLights(
  const EnvironmentMap& map, const BrightLightOptions& options, BrightLightResult& result);

/// A right-handed unit frame (x, y, z) about the unit vector z.
PROXYGILIGHTING_EXPORT void FrameAbout(const double z[3], double x[3], double y[3]);

/**
 * `count` directions over the light's disk (stratified: a spherical
 * Fibonacci spiral of equal areas, turned by `turn` radians), 3 floats each,
 * for shadow rays and the cosine's integral.
 */
PROXYGILIGHTING_EXPORT void DistantLightDirections(
  const DistantLight& light, int count, double turn, float* directions);

} // namespace proxygi

#endif
