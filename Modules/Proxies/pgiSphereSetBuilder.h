/**
 * @file pgiSphereSetBuilder.h
 * @brief Bounding sphere sets of one object: the variational method of Wang
 * et al. 2006 (as reviewed in the SHEXP paper, Section 6.2) and two
 * baselines, octree cells and k-means clusters. Private to the Proxies
 * module; vtkPGISphereSetApproximation is the user-facing filter.
 *
 * All three methods cluster the same elements: the triangles (bounded by
 * their three corners, so the spheres bound the whole surface) and interior
 * samples on a regular grid (bounded as points). Every element lies in the
 * sphere of its cluster, so every vertex, every triangle and every interior
 * sample is bounded whatever the method.
 */
#ifndef pgiSphereSetBuilder_h
#define pgiSphereSetBuilder_h

#include "pgiProxyMetrics.h"
#include "pgiSphereMath.h"
#include "pgiVolumeRows.h"

#include <functional>
#include <memory>
#include <vector>

namespace proxygi
{
struct ProxyMesh;
class MeshQueries;

enum class SphereMethod
{
  Variational = 0,
  Octree = 1,
  KMeans = 2
};

struct SphereSetOptions
{
  SphereMethod Method = SphereMethod::Variational;
  unsigned Seed = 1;
  int VolumeResolution = 128;      // rows along the longest side of the mesh box
  int InteriorResolution = 32;     // interior sample grid along the longest side
  int MaximumIterations = 100;     // clustering + update rounds, teleports included
  int MaximumTeleportFailures = 8; // rejected teleports in a row before stopping
  /// Called with the fraction done; returning false aborts.
  std::function<bool(double)> Progress;
};

struct SphereSetResult
{
  std::vector<Sphere> Spheres;
  double OutsideVolume = 0.0; // sum over spheres of V(S_i - T), row quadrature
  double MeshVolume = 0.0;    // enclosed volume, same quadrature
  int Iterations = 0;
  int Teleports = 0;
  int TeleportsAccepted = 0;
  bool Aborted = false;
};

class SphereSetBuilder
{
public:
  /// Traces the rows and places the interior samples.
  SphereSetBuilder(
    const ProxyMesh& mesh, const MeshQueries& queries, const SphereSetOptions& options);
  ~SphereSetBuilder();

  const VolumeRows& Rows() const;
  /// Interior samples, xyz triples.
  const std::vector<double>& InteriorSamples() const;
  /// Number of elements (triangles + interior samples): the most spheres.
  int NumberOfElements() const;

  /// Builds `count` spheres (fewer if there are fewer elements).
  bool Run(int count, SphereSetResult& result);

private:
  struct Internal;
  std::unique_ptr<Internal> Impl;
};

/**
 * The interior samples the builder clusters: grid points spaced (longest
 * side) / interiorResolution, on rows of `rows`, inside the object.
 */
void ComputeInteriorSamples(const VolumeRows& rows, const double meshBounds[6],
  int interiorResolution, std::vector<double>& samples);

/// Row spacing for a volume resolution over a box.
double RowSpacing(const double bounds[6], int resolution);

/// E of spheres against an extracted mesh (pgiProxyMetrics.cxx).
void MeasureOutsideVolume(const ProxyMesh& mesh, const MeshQueries& queries,
  const std::vector<Sphere>& spheres, int resolution, OutsideVolumeMeasure& measure);
} // namespace proxygi

#endif
