/**
 * @file pgiProxyMetrics.h
 * @brief How good a set of sphere proxies is for its mesh: the outside-volume
 * ratio E, and how far the surface or interior leaves the spheres (after a
 * deformation, say). Also reads the leaf spheres of a proxies vtkPolyData.
 *
 * Outside volume is integrated over rows parallel to x, spaced h = (longest
 * side of the mesh box) / resolution apart in y and z; along each row the
 * union of the spheres and the inside of the mesh are exact intervals (ray
 * crossings from Embree), so the only error is the 2-D midpoint rule across
 * rows: O(h^2) for smooth boundaries. Measured on the CGAL meshes at 64
 * spheres, E at resolution 256 is within about 0.3% (relative) of E at 512;
 * see Documentation/Proxies.md.
 */
#ifndef pgiProxyMetrics_h
#define pgiProxyMetrics_h

#include "ProxyGIProxiesModule.h"
#include "pgiSphereMath.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

class vtkPolyData;

namespace proxygi
{
struct OutsideVolumeMeasure
{
  /// E = V(union of spheres - mesh) / V(mesh): what the issue and the
  /// shadows care about (overlaps outside count once). NaN without a volume.
  double Ratio = std::numeric_limits<double>::quiet_NaN();
  /// sum_i V(S_i - mesh) / V(mesh): the paper's Eq. 35 (overlaps count
  /// as often as they overlap), always >= Ratio.
  double SumRatio = std::numeric_limits<double>::quiet_NaN();
  double MeshVolume = 0.0;      // enclosed volume, same quadrature
  double OutsideVolume = 0.0;   // V(union - mesh)
  double UncoveredVolume = 0.0; // V(mesh - union): should be ~0
  double RowSpacing = 0.0;
  int ResolvedRows = 0;              // rows with odd crossings, resolved point-wise
  bool Solid = true;                 // false: the mesh does not enclose a volume
  std::vector<double> SphereOutside; // V(S_i - mesh), per sphere
};

struct CoverageMeasure
{
  long long Samples = 0;
  long long Outside = 0;   // samples in no sphere
  double MaximumGap = 0.0; // largest distance from a sample to the nearest sphere
  double MeanGap = 0.0;    // mean of that distance over all samples (0 inside)
};

/**
 * Leaf spheres of a proxies vtkPolyData: points with a "Radius" array;
 * where a "Level" array exists only level 0. `objectIds` (optional) receives
 * their "ObjectId" (0 without the array), `ids` (optional) their point ids.
 */
PROXYGIPROXIES_EXPORT bool GetLeafSpheres(vtkPolyData* proxies, std::vector<Sphere>& spheres,
  std::string& error, std::vector<int>* objectIds = nullptr, std::vector<long long>* ids = nullptr);

/// E and its parts for the leaf spheres of `proxies` against a closed mesh.
PROXYGIPROXIES_EXPORT bool MeasureOutsideVolume(vtkPolyData* mesh, vtkPolyData* proxies,
  int resolution, OutsideVolumeMeasure& measure, std::string& error);

/// Same for a sphere list.
PROXYGIPROXIES_EXPORT bool MeasureOutsideVolume(vtkPolyData* mesh,
  const std::vector<Sphere>& spheres, int resolution, OutsideVolumeMeasure& measure,
  std::string& error);

/**
 * Surface samples (every vertex, plus points on each triangle at barycentric
 * steps of 1/subdivisions) against the leaf spheres.
 */
PROXYGIPROXIES_EXPORT bool MeasureSurfaceCoverage(vtkPolyData* mesh, vtkPolyData* proxies,
  int subdivisions, CoverageMeasure& measure, std::string& error);
PROXYGIPROXIES_EXPORT CoverageMeasure MeasureCoverage(
  const std::vector<double>& xyz, const std::vector<Sphere>& spheres);

/**
 * Interior coverage: `grid` for the interior samples the approximation
 * filter bounds (same resolutions give the same samples), `random` for
 * `randomSamples` uniform points of the mesh box found inside by the
 * three-ray majority test (independent of the rows).
 */
PROXYGIPROXIES_EXPORT bool MeasureInteriorCoverage(vtkPolyData* mesh, vtkPolyData* proxies,
  int volumeResolution, int interiorResolution, int randomSamples, std::uint32_t seed,
  CoverageMeasure& grid, CoverageMeasure& random, std::string& error);
} // namespace proxygi

#endif
