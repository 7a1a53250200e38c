/**
 * @file pgiSHSphericalLight.h
 * @brief The direction set and projection table of spherical lights
 * (Guerrero et al. 2008, sections 4.2 and 5.2).
 *
 * A spherical light (SL) carries m surface samples, one per fixed direction
 * w_j from its centre (the vertices of a geodesic sphere; frequency 3 gives
 * the paper's 92). Its radiance, as a function of the direction from its
 * centre, is taken constant on the Voronoi cell of each w_j (nearest
 * neighbour), so its SH projection is sum_j L_j Y_j with the precomputed
 * basis sums Y_j = int_{cell j} y(s) ds (eq. 10). A direction without a
 * sample has L_j = 0: the SL emits nothing there.
 */
#ifndef pgiSHSphericalLight_h
#define pgiSHSphericalLight_h

#include "pgiSH.h"

#include <vector>

namespace proxygi
{
namespace sh
{

/**
 * Unit vertices of the icosahedron with every edge split into `frequency`
 * parts, projected onto the sphere: 10 f^2 + 2 directions (f = 3: 92), as
 * x, y, z triples in a fixed order.
 */
PROXYGISPHERICALHARMONICS_EXPORT std::vector<double> GeodesicDirections(int frequency);

/**
 * Voronoi basis sums: row j (order^2 values) is int over the cell of
 * directions nearer to w_j than to any other w_k of y(s) ds, integrated by
 * a Gauss product rule of `zNodes` x 2 zNodes points (the paper's jittered
 * Monte Carlo, made deterministic). The rows sum to the projection of 1.
 */
PROXYGISPHERICALHARMONICS_EXPORT std::vector<double> VoronoiBasisSums(
  int order, const std::vector<double>& directions, int zNodes = 96);

} // namespace sh
} // namespace proxygi

#endif
