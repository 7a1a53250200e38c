/**
 * @file pgiMeshQueries.h
 * @brief Embree queries on one object's triangles: every crossing of a ray
 * with the surface, inside/outside by ray parity (majority of three rays, so
 * one ray through a small hole or along an edge does not decide), and the
 * closest surface point. Thread-safe after construction. Private to the
 * Proxies module.
 */
#ifndef pgiMeshQueries_h
#define pgiMeshQueries_h

#include <memory>
#include <string>
#include <vector>

namespace proxygi
{
struct ProxyMesh;

class MeshQueries
{
public:
  explicit MeshQueries(const ProxyMesh& mesh);
  ~MeshQueries();
  MeshQueries(const MeshQueries&) = delete;
  MeshQueries& operator=(const MeshQueries&) = delete;

  /// False when Embree failed; Error() says why.
  bool Ok() const;
  const std::string& Error() const;

  /**
   * Distances t > 0 along origin + t * direction (unit) where the ray
   * crosses the surface, ascending. Hits of neighbouring triangles at one
   * point (the ray through an edge or a vertex) count once when the surface
   * is crossed there and not at all when it is only touched.
   */
  void Crossings(const double origin[3], const double direction[3], std::vector<double>& t) const;

  /// Parity inside test, majority of three fixed oblique directions.
  bool IsInside(const double p[3]) const;

  /// Closest surface point q to p; returns the distance, sets the triangle.
  double ClosestPoint(const double p[3], double q[3], int& triangle) const;

private:
  struct Internal;
  std::unique_ptr<Internal> Impl;
};
} // namespace proxygi

#endif
