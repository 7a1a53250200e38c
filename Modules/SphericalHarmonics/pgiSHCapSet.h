/**
 * @file pgiSHCapSet.h
 * @brief Visibility of a set of circular caps (what a receiver sees of a set
 * of spherical blockers), in the three ways the SHEXP paper compares:
 * log-space accumulation from the tables (what the shading kernels do),
 * product-space accumulation (Zhou et al.), and the exact visibility
 * projected by dense quadrature (the ground truth of the SH tests and
 * benchmarks). Also a seeded random cap-set generator.
 */
#ifndef pgiSHCapSet_h
#define pgiSHCapSet_h

#include "pgiSH.h"

#include <cstdint>
#include <vector>

namespace proxygi
{
namespace sh
{
class CapTables;

struct Cap
{
  double Direction[3]; // unit axis
  double HalfAngle;    // radians, [0, pi/2] for sphere blockers
};

/// Sum of the tabulated cap logs (scaled ZH rotated to each axis).
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void AccumulateLog(
  const CapTables& tables, const std::vector<Cap>& caps, T* logSum);

/// Product of the cap visibilities, left to right, by SH products.
PROXYGISPHERICALHARMONICS_EXPORT void AccumulateProduct(
  int order, const std::vector<Cap>& caps, double* visibility);

/**
 * Projection of the exact visibility prod_i (1 - cap_i(s)) with a Gauss
 * product rule of zNodes x 2 zNodes points (discontinuous integrand: the
 * error falls roughly as 1/zNodes; 256 gives about 1e-4 RMS).
 */
PROXYGISPHERICALHARMONICS_EXPORT void ProjectExactVisibility(
  int order, const std::vector<Cap>& caps, double* visibility, int zNodes = 256);

/// RMS over the sphere of the difference of two reconstructions.
PROXYGISPHERICALHARMONICS_EXPORT double RmsDifference(int order, const double* a, const double* b);

/// count caps with uniform random axes and half-angles in [minAngle, maxAngle].
PROXYGISPHERICALHARMONICS_EXPORT std::vector<Cap> RandomCaps(
  std::uint32_t seed, int count, double minAngle, double maxAngle);

} // namespace sh
} // namespace proxygi

#endif
