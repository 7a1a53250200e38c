#include "pgiProxyMesh.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataSetAttributes.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>

namespace proxygi
{

double ProxyMesh::Diagonal() const
{
  const double dx = this->Bounds[1] - this->Bounds[0], dy = this->Bounds[3] - this->Bounds[2],
               dz = this->Bounds[5] - this->Bounds[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

void ProxyMesh::Analyse()
{
  const int np = this->NumberOfPoints(), nt = this->NumberOfTriangles();
  for (int k = 0; k < 3; ++k)
  {
    this->Bounds[2 * k] = np ? this->Points[k] : 0.0;
    this->Bounds[2 * k + 1] = np ? this->Points[k] : 0.0;
  }
  for (int i = 1; i < np; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      this->Bounds[2 * k] = std::min(this->Bounds[2 * k], this->Points[3 * i + k]);
      this->Bounds[2 * k + 1] = std::max(this->Bounds[2 * k + 1], this->Points[3 * i + k]);
    }
  }
  // Edges as sorted vertex pairs; runs of equal pairs count the triangles.
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * static_cast<std::size_t>(nt));
  const double diagonal = this->Diagonal();
  this->ZeroAreaTriangles = 0;
  for (int t = 0; t < nt; ++t)
  {
    const int* v = this->Triangles.data() + 3 * t;
    for (int e = 0; e < 3; ++e)
    {
      const std::uint64_t a = static_cast<std::uint32_t>(std::min(v[e], v[(e + 1) % 3]));
      const std::uint64_t b = static_cast<std::uint32_t>(std::max(v[e], v[(e + 1) % 3]));
      if (a != b)
      {
        edges.push_back((a << 32) | b);
      }
    }
    const double *p = this->Point(v[0]), *q = this->Point(v[1]), *r = this->Point(v[2]);
    const double u[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
    const double w[3] = { r[0] - p[0], r[1] - p[1], r[2] - p[2] };
    const double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
      u[0] * w[1] - u[1] * w[0] };
    const double area2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(area2 > 1e-14 * diagonal * diagonal))
    {
      ++this->ZeroAreaTriangles;
    }
  }
  std::sort(edges.begin(), edges.end());
  this->BoundaryEdges = this->NonManifoldEdges = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
    {
      ++j;
    }
    if (j - i == 1)
    {
      ++this->BoundaryEdges;
    }
    else if (j - i > 2)
    {
      ++this->NonManifoldEdges;
    }
    i = j;
  }
}

double ProxyMesh::SignedVolume() const
{
  double volume = 0.0;
  for (int t = 0; t < this->NumberOfTriangles(); ++t)
  {
    const double* a = this->Point(this->Triangles[3 * t]);
    const double* b = this->Point(this->Triangles[3 * t + 1]);
    const double* c = this->Point(this->Triangles[3 * t + 2]);
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) /
      6.0;
  }
  return volume;
}

bool ExtractProxyMesh(vtkPolyData* input, ProxyMesh& mesh, ProxyMeshReport& report,
  std::string& error, std::vector<vtkIdType>* inputIds)
{
  if (inputIds)
  {
    inputIds->clear();
  }
  mesh = ProxyMesh();
  report = ProxyMeshReport();
  if (!input || input->GetNumberOfPoints() == 0)
  {
    error = "the mesh has no points";
    return false;
  }
  vtkSmartPointer<vtkPolyData> owned;
  if (vtkUnsignedCharArray* ghosts = input->GetCellGhostArray())
  {
    for (vtkIdType c = 0; c < ghosts->GetNumberOfValues(); ++c)
    {
      report.GhostCells += (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL) ? 1 : 0;
    }
    if (report.GhostCells > 0)
    {
      owned = vtkSmartPointer<vtkPolyData>::New();
      owned->DeepCopy(input);
      owned->RemoveGhostCells();
      input = owned;
    }
  }
  vtkPoints* points = input->GetPoints();
  const vtkIdType np = input->GetNumberOfPoints();
  for (vtkIdType i = 0; i < np; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      ++report.NonFinitePoints;
    }
  }
  if (report.NonFinitePoints > 0)
  {
    error = std::to_string(report.NonFinitePoints) + " of " + std::to_string(np) +
      " points have NaN or Inf coordinates";
    return false;
  }
  report.IgnoredCells = input->GetNumberOfVerts() + input->GetNumberOfLines();

  // Only polygons and strips enclose anything; triangulate them when needed.
  vtkCellArray* polys = input->GetPolys();
  bool needsTriangulation = input->GetNumberOfStrips() > 0;
  if (polys)
  {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      if (n != 3)
      {
        needsTriangulation = true;
        ++report.PolygonsSplit;
      }
    }
  }
  report.PolygonsSplit += input->GetNumberOfStrips();
  vtkSmartPointer<vtkPolyData> surface = input;
  if (needsTriangulation)
  {
    vtkNew<vtkPolyData> only;
    only->SetPoints(points);
    only->SetPolys(input->GetPolys());
    only->SetStrips(input->GetStrips());
    vtkNew<vtkTriangleFilter> triangulate;
    triangulate->SetInputData(only);
    triangulate->PassVertsOff();
    triangulate->PassLinesOff();
    triangulate->Update();
    surface = triangulate->GetOutput();
  }
  // Indices are int, and 3 x index must stay in range.
  constexpr vtkIdType MaxElements = std::numeric_limits<int>::max() / 3;
  if (np > MaxElements || surface->GetNumberOfPolys() > MaxElements)
  {
    error = "the mesh has " + std::to_string(np) + " points and " +
      std::to_string(surface->GetNumberOfPolys()) + " triangles; at most " +
      std::to_string(MaxElements) + " of each";
    return false;
  }
  std::vector<int> index(static_cast<std::size_t>(np), -1);
  auto addCorner = [&](vtkIdType id)
  {
    int& slot = index[id];
    if (slot < 0)
    {
      slot = mesh.NumberOfPoints();
      double p[3];
      points->GetPoint(id, p);
      mesh.Points.insert(mesh.Points.end(), p, p + 3);
      if (inputIds)
      {
        inputIds->push_back(id); // vtkTriangleFilter keeps point ids
      }
    }
    mesh.Triangles.push_back(slot);
  };
  vtkCellArray* triangles = surface->GetPolys();
  if (triangles)
  {
    auto it = vtk::TakeSmartPointer(triangles->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      if (n != 3)
      {
        continue; // vtkTriangleFilter drops what it cannot split
      }
      for (int k = 0; k < 3; ++k)
      {
        addCorner(ids[k]);
      }
    }
  }
  if (needsTriangulation)
  {
    // vtkTriangleFilter drops the corners of some degenerate polygons (a
    // repeated point, collinear runs); found by fuzzing. Such a polygon is
    // fanned instead, so that every corner of every polygon is bounded.
    for (vtkCellArray* cells : { input->GetPolys(), input->GetStrips() })
    {
      if (!cells)
      {
        continue;
      }
      const bool strip = cells == input->GetStrips();
      auto it = vtk::TakeSmartPointer(cells->NewIterator());
      for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
      {
        vtkIdType n;
        const vtkIdType* ids;
        it->GetCurrentCell(n, ids);
        bool dropped = false;
        for (vtkIdType k = 0; k < n && n >= 3 && !dropped; ++k)
        {
          dropped = index[ids[k]] < 0;
        }
        for (vtkIdType k = 1; dropped && k + 1 < n; ++k)
        {
          addCorner(ids[strip ? k - 1 : 0]);
          addCorner(ids[k]);
          addCorner(ids[k + 1]);
          ++report.PolygonsFanned;
        }
      }
    }
  }
  if (mesh.Triangles.empty())
  {
    error = "the mesh has no polygons (only " + std::to_string(report.IgnoredCells) +
      " vertex or line cells): nothing encloses a volume";
    return false;
  }
  report.UnusedPoints = np - mesh.NumberOfPoints();
  mesh.Analyse();
  return true;
}

void SplitComponents(const ProxyMesh& mesh, std::vector<ProxyMesh>& parts)
{
  parts.clear();
  const int np = mesh.NumberOfPoints(), nt = mesh.NumberOfTriangles();
  std::vector<int> root(np);
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int x)
  {
    while (root[x] != x)
    {
      root[x] = root[root[x]];
      x = root[x];
    }
    return x;
  };
  for (int t = 0; t < nt; ++t)
  {
    const int a = find(mesh.Triangles[3 * t]);
    for (int k = 1; k < 3; ++k)
    {
      const int b = find(mesh.Triangles[3 * t + k]);
      if (a != b)
      {
        root[b] = a;
      }
    }
  }
  std::vector<int> component(np, -1);
  std::vector<int> sizes;
  for (int t = 0; t < nt; ++t)
  {
    const int r = find(mesh.Triangles[3 * t]);
    if (component[r] < 0)
    {
      component[r] = static_cast<int>(sizes.size());
      sizes.push_back(0);
    }
    ++sizes[component[r]];
  }
  // Largest first, ties by first appearance: deterministic object ids.
  std::vector<int> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a] > sizes[b]; });
  std::vector<int> rank(sizes.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    rank[order[i]] = static_cast<int>(i);
  }
  parts.assign(sizes.size(), ProxyMesh());
  std::vector<int> index(np, -1);
  for (int t = 0; t < nt; ++t)
  {
    ProxyMesh& part = parts[rank[component[find(mesh.Triangles[3 * t])]]];
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.Triangles[3 * t + k];
      if (index[v] < 0)
      {
        index[v] = part.NumberOfPoints();
        part.Points.insert(part.Points.end(), mesh.Point(v), mesh.Point(v) + 3);
      }
      part.Triangles.push_back(index[v]);
    }
  }
  for (ProxyMesh& part : parts)
  {
    part.Analyse();
  }
}

int CapBoundaryLoops(ProxyMesh& mesh)
{
  // Undirected edge -> how many triangles use it, and its direction in the last one.
  std::map<std::pair<int, int>, std::pair<int, std::pair<int, int>>> edges;
  const int nt = mesh.NumberOfTriangles();
  for (int t = 0; t < nt; ++t)
  {
    const int* v = mesh.Triangles.data() + 3 * t;
    for (int e = 0; e < 3; ++e)
    {
      const int a = v[e], b = v[(e + 1) % 3];
      if (a == b)
      {
        continue;
      }
      auto& entry = edges[{ std::min(a, b), std::max(a, b) }];
      ++entry.first;
      entry.second = { a, b };
    }
  }
  // The cap runs against the boundary edges' direction: b -> a.
  std::multimap<int, int> next;
  for (const auto& e : edges)
  {
    if (e.second.first == 1)
    {
      next.emplace(e.second.second.second, e.second.second.first);
    }
  }
  int capped = 0;
  while (!next.empty())
  {
    std::vector<int> loop{ next.begin()->first };
    int at = next.begin()->second;
    next.erase(next.begin());
    bool closed = false;
    while (true)
    {
      if (at == loop.front())
      {
        closed = true;
        break;
      }
      auto it = next.find(at);
      if (it == next.end())
      {
        break;
      }
      loop.push_back(at);
      at = it->second;
      next.erase(it);
    }
    if (!closed || loop.size() < 3)
    {
      continue;
    }
    double centre[3] = { 0, 0, 0 };
    for (int v : loop)
    {
      for (int k = 0; k < 3; ++k)
      {
        centre[k] += mesh.Point(v)[k] / static_cast<double>(loop.size());
      }
    }
    const int c = mesh.NumberOfPoints();
    mesh.Points.insert(mesh.Points.end(), centre, centre + 3);
    for (std::size_t i = 0; i < loop.size(); ++i)
    {
      mesh.Triangles.push_back(loop[i]);
      mesh.Triangles.push_back(loop[(i + 1) % loop.size()]);
      mesh.Triangles.push_back(c);
    }
    ++capped;
  }
  if (capped > 0)
  {
    mesh.Analyse();
  }
  return capped;
}

void AppendMesh(ProxyMesh& to, const ProxyMesh& from)
{
  const int offset = to.NumberOfPoints();
  to.Points.insert(to.Points.end(), from.Points.begin(), from.Points.end());
  for (int v : from.Triangles)
  {
    to.Triangles.push_back(v + offset);
  }
}
} // namespace proxygi
