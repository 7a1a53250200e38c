/**
 * @file pgiSphereTree.h
 * @brief A bounding hierarchy above a set of leaf spheres (SHEXP paper,
 * Section 6.3): levels built bottom-up by Lloyd clustering of sphere centres
 * into about n / branching clusters (then evened out: a lone member joins
 * its nearest cluster, a cluster of more than 2 * branching splits, so each
 * parent has 2 to 2 * branching children), each parent the near-minimal
 * sphere bounding its children; and the bottom-up refit by pairwise sphere
 * bounds that keeps parents bounding after the leaves move.
 *
 * Nodes are stored leaves first, then each level in turn; `level` is 0 for
 * leaves and grows towards the root; `parent` is a node index or -1.
 */
#ifndef pgiSphereTree_h
#define pgiSphereTree_h

#include "ProxyGIProxiesModule.h"
#include "pgiSphereMath.h"

#include "vtkType.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkPolyData;

namespace proxygi
{
struct SphereTreeStats
{
  int Depth = 0; // levels above the leaves
  int Leaves = 0;
  int Parents = 0;
  int Roots = 0;
  double MeanBranching = 0.0; // children per parent
  int MinBranching = 0;
  int MaxBranching = 0;
  /// Largest |c_node - c_ancestor| + r_node - r_ancestor over every node and
  /// each of its ancestors: <= 0 when every parent bounds its subtree.
  double MaximumViolation = 0.0;
};

/**
 * Appends the levels above `nodes` (all leaves on entry) to nodes, level and
 * parent, until one root. branching >= 2.
 */
PROXYGIPROXIES_EXPORT void BuildSphereTree(std::vector<Sphere>& nodes, std::vector<int>& level,
  std::vector<long long>& parent, int branching = 4, std::uint32_t seed = 1);

/**
 * Bottom-up refit: each parent becomes the running pairwise bound of its
 * children (lowest levels first). Leaves are not touched.
 */
PROXYGIPROXIES_EXPORT void RefitSphereTree(
  std::vector<Sphere>& nodes, const std::vector<int>& level, const std::vector<long long>& parent);

/**
 * All spheres of a proxies vtkPolyData (points, "Radius"; "Level" and
 * "Parent" where present, else 0 and -1).
 */
PROXYGIPROXIES_EXPORT bool GetSphereTree(vtkPolyData* proxies, std::vector<Sphere>& nodes,
  std::vector<int>& level, std::vector<long long>& parent, std::string& error);

/// Writes centres and radii back (same number of points; arrays modified).
PROXYGIPROXIES_EXPORT void SetSphereGeometry(
  vtkPolyData* proxies, const std::vector<Sphere>& nodes);

/**
 * Lloyd's algorithm on `n` points (x, y, z each) from the given initial
 * centres: assign every point to its nearest centre, move each centre to
 * its members' mean, up to `iterations` times or until nothing moves.
 * Returns each point's cluster; `centres` end as the clusters' means. The
 * sphere tree (seeded k-means++) and the GI filter's receiver clusters
 * (seeded evenly along the point order) both run it. A point's nearest
 * centre (the lowest index among equals) is searched along one axis from
 * its last one; everyCentre scans every centre instead (the reference the
 * tests hold the search to: the same clusters).
 */
PROXYGIPROXIES_EXPORT std::vector<int> LloydClusters(const double* points, vtkIdType n,
  std::vector<std::array<double, 3>>& centres, int iterations, bool everyCentre = false);

/// Depth, branching and the bounding check.
PROXYGIPROXIES_EXPORT SphereTreeStats AnalyseSphereTree(const std::vector<Sphere>& nodes,
  const std::vector<int>& level, const std::vector<long long>& parent);
} // namespace proxygi

#endif
