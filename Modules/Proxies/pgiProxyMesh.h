/**
 * @file pgiProxyMesh.h
 * @brief The triangle soup the proxy builders work on: one object's
 * triangles (polygons and strips triangulated), the vertices they use, and
 * what is wrong with it (open or non-manifold edges, zero-area triangles).
 * Private to the Proxies module.
 */
#ifndef pgiProxyMesh_h
#define pgiProxyMesh_h

#include "vtkType.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace proxygi
{
struct ProxyMesh
{
  std::vector<double> Points; // xyz of the vertices the triangles use
  std::vector<int> Triangles; // three vertex indices each
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  long long BoundaryEdges = 0;    // edges with one triangle: the mesh is open
  long long NonManifoldEdges = 0; // edges with more than two triangles
  long long ZeroAreaTriangles = 0;

  int NumberOfPoints() const { return static_cast<int>(this->Points.size() / 3); }
  int NumberOfTriangles() const { return static_cast<int>(this->Triangles.size() / 3); }
  const double* Point(int i) const { return this->Points.data() + 3 * i; }
  bool Closed() const { return this->BoundaryEdges == 0 && this->NonManifoldEdges == 0; }
  double Diagonal() const;
  /// Bounds and the edge/area diagnostics, after Points/Triangles change.
  void Analyse();
  /// Signed volume by the divergence theorem (meaningful for closed meshes).
  double SignedVolume() const;
};

struct ProxyMeshReport
{
  long long NonFinitePoints = 0;
  long long IgnoredCells = 0;   // vertices and lines: nothing to bound
  long long PolygonsSplit = 0;  // polygons with more than 3 points, and strips
  long long PolygonsFanned = 0; // triangles fanned where vtkTriangleFilter dropped corners
  long long UnusedPoints = 0;   // points no triangle uses (not bounded)
  long long GhostCells = 0;     // duplicated cells of a distributed piece: left out
};

/**
 * Triangles of a vtkPolyData (polygons and triangle strips; polygons with
 * more than three points are triangulated with vtkTriangleFilter). Fails,
 * with a message, on NaN/Inf coordinates or when nothing is left to bound.
 * Cells marked as ghosts (vtkGhostType DUPLICATECELL: another rank owns
 * them) are left out, so that a distributed mesh bounds each cell once.
 * `inputIds` (optional) receives the input point id of each mesh vertex.
 */
bool ExtractProxyMesh(vtkPolyData* input, ProxyMesh& mesh, ProxyMeshReport& report,
  std::string& error, std::vector<vtkIdType>* inputIds = nullptr);

/// Connected components (triangles sharing a vertex), largest first.
void SplitComponents(const ProxyMesh& mesh, std::vector<ProxyMesh>& parts);

/// Appends the triangles of `from` to `to` (then call Analyse()).
void AppendMesh(ProxyMesh& to, const ProxyMesh& from);

/**
 * Closes the holes of an open mesh: each loop of boundary edges gets a fan
 * of triangles to a new vertex at the loop's centroid, oriented like the
 * triangles around it. A distributed piece of a closed object is open along
 * its cut; capped, it encloses its share of the volume again, so its inside
 * (interior samples, outside volume) is defined. Boundary chains that do not
 * close are left open. Returns the loops capped (then Analyse() has run).
 */
int CapBoundaryLoops(ProxyMesh& mesh);
} // namespace proxygi

#endif
