/**
 * @file pgiEnvironmentShading.h
 * @brief Diffuse shading of a receiver under SH environment light and SH
 * visibility: exit radiance = albedo * H(N) . (L * g) (SHEXP section 7).
 *
 * Two paths, as the paper describes:
 *  - Table (fixed lighting): the vectors LH(N) = L * H(N) tabulated once per
 *    lighting on a lat-long grid of normals (each row of the grid when a
 *    normal first needs it) and interpolated bilinearly; per receiver it
 *    costs n^2 (times 4 for the interpolation) per channel.
 *  - ProductMatrix (lighting that changes every frame): M_L once per frame,
 *    then (M_L g) . H(N) per receiver, n^4 per channel.
 * Both read the same L; a test checks they agree. Ringing in g can make the
 * product slightly negative where everything is blocked; radiance is clamped
 * at 0 (continuous, so no popping).
 */
#ifndef pgiEnvironmentShading_h
#define pgiEnvironmentShading_h

#include "ProxyGIShadingModule.h"

#include <memory>
#include <mutex>
#include <vector>

namespace proxygi
{

class PROXYGISHADING_EXPORT EnvironmentShading
{
public:
  enum class Path
  {
    Table,
    ProductMatrix
  };

  /// light: 3 rows (R, G, B) of order^2 SH radiance coefficients.
  EnvironmentShading(int order, const double* red, const double* green, const double* blue,
    Path path = Path::Table, int tableHeight = 64);

  int GetOrder() const { return this->Order; }
  Path GetPath() const { return this->ShadingPath; }

  /// Exit radiance of a white receiver (multiply by albedo) with normal n and visibility g.
  void Shade(const float n[3], const float* g, float rgb[3]) const;

  /// The same without shadows (g = 1), exact.
  void ShadeUnshadowed(const float n[3], float rgb[3]) const;
  /// The Table path fills each row of its table when Shade first reads it
  /// (thread-safe); this fills every row now, in parallel.
  void BuildTable() const;

private:
  int Order, Width, Height;
  Path ShadingPath;
  std::vector<float> Light;  // 3 x n^2
  std::vector<float> Matrix; // 3 x n^2 x n^2 (ProductMatrix path)
  // (Height + 1) x (Width + 1) x 3 x n^2 (Table path), row j filled by the
  // first EnsureRow(j) from the columns of M_L (3 x n^2 x n^2).
  mutable std::vector<float> LHTable;
  std::vector<double> Columns;
  std::unique_ptr<std::once_flag[]> RowsBuilt;
  void BuildRow(int j) const;
  void EnsureRow(int j) const;
};

class EnvironmentMap;

/**
 * Infinite blocker planes carried by the light instead of the visibility:
 * a receiver above a plane never sees below it, whatever its position, so
 * its light is L times the planes' step functions. A half-space has no
 * useful low-order log (its log is -infinity below the horizon), and SH exp
 * of a clipped 90-degree cap log darkens the open hemisphere by ~10% at
 * order 4; as part of the light the step costs nothing per receiver and is
 * exact up to the truncation of the product (taken at order >= 8).
 * planeNormals: 3 floats per plane (the side above is lit). Writes
 * order^2 coefficients per channel, and the planes' visibility itself
 * (order^2; its dot product with a visibility gives the combined coverage).
 */
PROXYGISHADING_EXPORT void LightAbovePlanes(const EnvironmentMap& environment, int order,
  const float* planeNormals, int planes, double* red, double* green, double* blue,
  double* planeVisibility = nullptr);

/// The order LightAbovePlanes projects the map at (the product's): at
/// least 8.
PROXYGISHADING_EXPORT int LightAbovePlanesOrder(int order);

/// LightAbovePlanes from the map's SH already projected at
/// LightAbovePlanesOrder(order) (3 channels one after the other): a caller
/// that needs the map's SH too projects it once (its first order^2
/// coefficients are the order-n projection's).
PROXYGISHADING_EXPORT void LightAbovePlanes(const std::vector<double>& projected, int order,
  const float* planeNormals, int planes, double* red, double* green, double* blue,
  double* planeVisibility);

} // namespace proxygi

#endif
