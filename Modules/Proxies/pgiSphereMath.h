/**
 * @file pgiSphereMath.h
 * @brief Sphere geometry the proxy code shares: volumes, lens (intersection)
 * volumes, the pairwise bound of two spheres, near-minimal bounding spheres of
 * points and of spheres, and the best-fit rigid motion of a point set.
 *
 * Every "Bound..." function returns a sphere that really contains its input
 * (the radius is the exact maximum distance from the returned centre); only
 * the minimality is approximate.
 */
#ifndef pgiSphereMath_h
#define pgiSphereMath_h

#include "ProxyGIProxiesModule.h"

#include <cstddef>
#include <vector>

namespace proxygi
{
struct Sphere
{
  double Center[3];
  double Radius;
};

/// 4/3 pi r^3.
PROXYGIPROXIES_EXPORT double SphereVolume(double radius);

/// Distance between the centres of two spheres.
PROXYGIPROXIES_EXPORT double CenterDistance(const Sphere& a, const Sphere& b);

/// True when `inner` lies in `outer` up to `tolerance` (length units).
PROXYGIPROXIES_EXPORT bool Contains(
  const Sphere& outer, const Sphere& inner, double tolerance = 0.0);

/// Volume of the intersection of two spheres (closed form).
PROXYGIPROXIES_EXPORT double LensVolume(const Sphere& a, const Sphere& b);

/// Smallest sphere containing both spheres (exact; one of them if nested).
PROXYGIPROXIES_EXPORT Sphere BoundPair(const Sphere& a, const Sphere& b);

/**
 * Near-minimal sphere containing n points (xyz triples): the centre minimises
 * the maximum distance by Nelder-Mead from the box centre; the radius is the
 * exact maximum distance from it. An empty set gives radius -1.
 */
PROXYGIPROXIES_EXPORT Sphere BoundPoints(const double* xyz, std::size_t n);

/// Same for spheres (maximum of distance plus radius).
PROXYGIPROXIES_EXPORT Sphere BoundSpheres(const std::vector<Sphere>& spheres);

/**
 * Best rigid motion (Kabsch) taking the rest points to the moved points in
 * the least-squares sense: moved ~ R (rest - restMean) + movedMean. n >= 1;
 * with fewer than 3 points or a degenerate set R is the best available
 * (identity when nothing constrains it).
 */
PROXYGIPROXIES_EXPORT void BestRigidMotion(const double* rest, const double* moved, std::size_t n,
  double rotation[3][3], double restMean[3], double movedMean[3]);

/// Largest singular value of a 3x3 matrix (how much it can stretch a length).
PROXYGIPROXIES_EXPORT double LargestStretch(const double m[3][3]);

/// Smallest singular value of a 3x3 matrix.
PROXYGIPROXIES_EXPORT double SmallestStretch(const double m[3][3]);
} // namespace proxygi

#endif
