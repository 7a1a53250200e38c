/**
 * @file pgiLightCloudCompression.h
 * @brief The light cloud's compression (Kristensen et al. 2005, sections
 * 4.1, 4.2 and 5): zones, light clustering per zone, clustered PCA per zone.
 *
 * Plain functions on arrays, used by vtkPGILightCloudPrecompute and tested
 * on their own.
 */
#ifndef pgiLightCloudCompression_h
#define pgiLightCloudCompression_h

#include "ProxyGILightCloudModule.h"

#include "vtkType.h"

#include <cstdint>
#include <vector>

namespace proxygi
{
/**
 * Top-down zoning: the box of the points is split at the middle of its
 * longest axis (at the median when the middle leaves one side empty),
 * always the zone holding most points next, while a zone holds more than
 * `zoneSize` points and there are fewer than `maximumZones`. Returns the
 * point ids of each zone.
 */
PROXYGILIGHTCLOUD_EXPORT std::vector<std::vector<vtkIdType>> SplitIntoZones(
  const std::vector<double>& points, vtkIdType zoneSize, int maximumZones);

/// Lights merged by ClusterLights: mean positions and the merged ids.
struct MergedLights
{
  std::vector<double> Positions;
  std::vector<std::vector<vtkIdType>> Members;
};

/**
 * Bottom-up clustering of `count` lights (positions xyz each) by the
 * paper's metric Delta_jk = w1 |p_j - p_k| + w2 max_c |X_j(c) - X_k(c)| +
 * V_jk, with X_j(c) light j's response at receiver c (responses[j]
 * holds `values` x receivers floats: RGB, or RGB per SH coefficient) and V_jk = 0 where visible[j *
 * count + k], else 1. Two clusters merge while every pair across them has Delta < 1 (Delta of two
 * clusters is the largest over their pairs), the closest pair first (a priority queue).
 * Deterministic.
 */
PROXYGILIGHTCLOUD_EXPORT MergedLights ClusterLights(const std::vector<const float*>& responses,
  const std::vector<double>& positions, vtkIdType receivers, double w1, double w2,
  const std::vector<char>& visible, int values = 3);

/// A clustered-PCA code of `rows` vectors of `dimension` floats.
struct ClusteredPCACode
{
  int Dimension = 0;
  std::vector<int> Cluster;     // per row
  std::vector<float> Means;     // clusters x dimension
  std::vector<int> BasisStart;  // per cluster, in vectors
  std::vector<int> BasisCount;  // per cluster
  std::vector<float> Basis;     // vectors x dimension, orthonormal per cluster
  std::vector<int> WeightStart; // per row
  std::vector<float> Weights;   // BasisCount[Cluster[row]] per row
  double SquaredError = 0.0;    // sum over rows of |x - reconstruction|^2
  double Squared = 0.0;         // sum over rows of |x|^2
  int Iterations = 0;           // reclustering passes run
};

/**
 * Clustered PCA (Sloan et al. 2003, as the paper uses it): k-means++ and
 * Lloyd start with `clusters` clusters; then, `iterations` times or until
 * no row changes cluster, a PCA per cluster, PCA vectors handed out one at
 * a time to the cluster where one more removes the most error per row (its
 * next eigenvalue over its rows) until the rows hold `vectorsPerRow`
 * weights on average, and each row moved to the cluster that reconstructs
 * it best. Deterministic for a seed.
 */
PROXYGILIGHTCLOUD_EXPORT ClusteredPCACode ClusteredPCA(const std::vector<float>& data,
  vtkIdType rows, int dimension, int clusters, double vectorsPerRow, int iterations,
  std::uint64_t seed);

/// Row `row` of the code, decoded (dimension floats).
PROXYGILIGHTCLOUD_EXPORT void DecodeRow(const ClusteredPCACode& code, vtkIdType row, float* out);
} // namespace proxygi

#endif
