#include "pgiProxyMetrics.h"

#include "pgiMeshQueries.h"
#include "pgiProxyMesh.h"
#include "pgiSphereSetBuilder.h"
#include "pgiVolumeRows.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace proxygi
{

bool GetLeafSpheres(vtkPolyData* proxies, std::vector<Sphere>& spheres, std::string& error,
  std::vector<int>* objectIds, std::vector<long long>* ids)
{
  spheres.clear();
  if (objectIds)
  {
    objectIds->clear();
  }
  if (ids)
  {
    ids->clear();
  }
  if (!proxies)
  {
    error = "no proxies";
    return false;
  }
  vtkDataArray* radius = proxies->GetPointData()->GetArray("Radius");
  if (!radius && proxies->GetNumberOfPoints() > 0)
  {
    error = "proxies need a \"Radius\" point array";
    return false;
  }
  vtkDataArray* level = proxies->GetPointData()->GetArray("Level");
  vtkDataArray* object = proxies->GetPointData()->GetArray("ObjectId");
  for (vtkIdType i = 0; i < proxies->GetNumberOfPoints(); ++i)
  {
    if (level && level->GetTuple1(i) != 0.0)
    {
      continue;
    }
    Sphere s;
    proxies->GetPoint(i, s.Center);
    s.Radius = radius->GetTuple1(i);
    spheres.push_back(s);
    if (objectIds)
    {
      objectIds->push_back(object ? static_cast<int>(object->GetTuple1(i)) : 0);
    }
    if (ids)
    {
      ids->push_back(i);
    }
  }
  return true;
}

namespace
{
// E of spheres against an extracted mesh (shared with the filter).
void Measure(const ProxyMesh& mesh, const MeshQueries& queries, const std::vector<Sphere>& spheres,
  int resolution, OutsideVolumeMeasure& m)
{
  m = OutsideVolumeMeasure();
  const double h = RowSpacing(mesh.Bounds, resolution);
  double region[6];
  std::copy(mesh.Bounds, mesh.Bounds + 6, region);
  for (const Sphere& s : spheres)
  {
    for (int q = 0; q < 3; ++q)
    {
      region[2 * q] = std::min(region[2 * q], s.Center[q] - s.Radius);
      region[2 * q + 1] = std::max(region[2 * q + 1], s.Center[q] + s.Radius);
    }
  }
  VolumeRows rows;
  rows.Build(queries, region, mesh.Bounds, h);
  m.RowSpacing = h;
  m.ResolvedRows = rows.ResolvedRows();
  m.Solid = rows.Solid();
  m.MeshVolume = rows.Volume();
  const int ny = rows.RowsY(), nz = rows.RowsZ();
  // Each row's sphere intervals, then their union against the inside.
  std::vector<std::vector<double>> spans(static_cast<std::size_t>(ny) * nz);
  for (const Sphere& s : spheres)
  {
    const double r2 = s.Radius * s.Radius;
    const int j0 = std::max(0, rows.IndexY(s.Center[1] - s.Radius));
    const int j1 = std::min(ny - 1, rows.IndexY(s.Center[1] + s.Radius) + 1);
    const int k0 = std::max(0, rows.IndexZ(s.Center[2] - s.Radius));
    const int k1 = std::min(nz - 1, rows.IndexZ(s.Center[2] + s.Radius) + 1);
    for (int j = j0; j <= j1; ++j)
    {
      const double dy = rows.RowY(j) - s.Center[1];
      for (int k = k0; k <= k1; ++k)
      {
        const double dz = rows.RowZ(k) - s.Center[2];
        const double w2 = r2 - dy * dy - dz * dz;
        if (w2 > 0.0)
        {
          const double w = std::sqrt(w2);
          auto& v = spans[static_cast<std::size_t>(j) * nz + k];
          v.push_back(s.Center[0] - w);
          v.push_back(s.Center[0] + w);
        }
      }
    }
  }
  std::vector<double> outside(spans.size(), 0.0), uncovered(spans.size(), 0.0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(spans.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<std::pair<double, double>> u;
      for (vtkIdType r = begin; r < end; ++r)
      {
        const int j = static_cast<int>(r / nz), k = static_cast<int>(r % nz);
        int n;
        const double* in = rows.Intervals(j, k, n);
        double insideLength = 0.0;
        for (int i = 0; i < n; ++i)
        {
          insideLength += in[2 * i + 1] - in[2 * i];
        }
        u.clear();
        const auto& v = spans[r];
        for (std::size_t i = 0; i < v.size(); i += 2)
        {
          u.emplace_back(v[i], v[i + 1]);
        }
        std::sort(u.begin(), u.end());
        double unionLength = 0.0, covered = 0.0;
        for (std::size_t i = 0; i < u.size();)
        {
          double a = u[i].first, b = u[i].second;
          std::size_t next = i + 1;
          while (next < u.size() && u[next].first <= b)
          {
            b = std::max(b, u[next].second);
            ++next;
          }
          unionLength += b - a;
          for (int q = 0; q < n; ++q)
          {
            const double lo = std::max(a, in[2 * q]), hi = std::min(b, in[2 * q + 1]);
            if (hi > lo)
            {
              covered += hi - lo;
            }
          }
          i = next;
        }
        outside[r] = unionLength - covered;
        uncovered[r] = insideLength - covered;
      }
    });
  const double area = h * h;
  for (std::size_t r = 0; r < spans.size(); ++r)
  {
    m.OutsideVolume += area * outside[r];
    m.UncoveredVolume += area * std::max(0.0, uncovered[r]);
  }
  double sum = 0.0;
  m.SphereOutside.resize(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    m.SphereOutside[i] = rows.OutsideVolume(spheres[i].Center, spheres[i].Radius);
    sum += m.SphereOutside[i];
  }
  if (m.Solid && m.MeshVolume > 0.0)
  {
    m.Ratio = m.OutsideVolume / m.MeshVolume;
    m.SumRatio = sum / m.MeshVolume;
  }
}

bool Prepare(vtkPolyData* input, ProxyMesh& mesh, std::string& error)
{
  ProxyMeshReport report;
  if (!ExtractProxyMesh(input, mesh, report, error))
  {
    error = "mesh: " + error;
    return false;
  }
  return true;
}
} // namespace

bool MeasureOutsideVolume(vtkPolyData* meshData, const std::vector<Sphere>& spheres, int resolution,
  OutsideVolumeMeasure& measure, std::string& error)
{
  ProxyMesh mesh;
  if (!Prepare(meshData, mesh, error))
  {
    return false;
  }
  MeshQueries queries(mesh);
  if (!queries.Ok())
  {
    error = queries.Error();
    return false;
  }
  Measure(mesh, queries, spheres, std::max(4, resolution), measure);
  return true;
}

bool MeasureOutsideVolume(vtkPolyData* mesh, vtkPolyData* proxies, int resolution,
  OutsideVolumeMeasure& measure, std::string& error)
{
  std::vector<Sphere> spheres;
  if (!GetLeafSpheres(proxies, spheres, error))
  {
    return false;
  }
  return MeasureOutsideVolume(mesh, spheres, resolution, measure, error);
}

CoverageMeasure MeasureCoverage(const std::vector<double>& xyz, const std::vector<Sphere>& spheres)
{
  CoverageMeasure m;
  const vtkIdType n = static_cast<vtkIdType>(xyz.size() / 3);
  m.Samples = n;
  std::vector<double> gap(n, 0.0);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double* p = xyz.data() + 3 * i;
        double best = std::numeric_limits<double>::max();
        for (const Sphere& s : spheres)
        {
          const double dx = p[0] - s.Center[0], dy = p[1] - s.Center[1], dz = p[2] - s.Center[2];
          const double d = std::sqrt(dx * dx + dy * dy + dz * dz) - s.Radius;
          if (d < best)
          {
            best = d;
            if (best <= 0.0)
            {
              break;
            }
          }
        }
        gap[i] = std::max(0.0, best);
      }
    });
  double sum = 0.0;
  for (double g : gap)
  {
    m.Outside += g > 0.0;
    m.MaximumGap = std::max(m.MaximumGap, g);
    sum += g;
  }
  m.MeanGap = n > 0 ? sum / n : 0.0;
  return m;
}

bool MeasureSurfaceCoverage(vtkPolyData* meshData, vtkPolyData* proxies, int subdivisions,
  CoverageMeasure& measure, std::string& error)
{
  ProxyMesh mesh;
  std::vector<Sphere> spheres;
  if (!Prepare(meshData, mesh, error) || !GetLeafSpheres(proxies, spheres, error))
  {
    return false;
  }
  std::vector<double> xyz(mesh.Points);
  const int s = std::max(1, subdivisions);
  for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const double* a = mesh.Point(mesh.Triangles[3 * t]);
    const double* b = mesh.Point(mesh.Triangles[3 * t + 1]);
    const double* c = mesh.Point(mesh.Triangles[3 * t + 2]);
    for (int i = 0; i <= s; ++i)
    {
      for (int j = 0; i + j <= s; ++j)
      {
        if ((i == 0 && j == 0) || i == s || j == s)
        {
          continue; // the corners are the vertices
        }
        const double u = static_cast<double>(i) / s, v = static_cast<double>(j) / s;
        for (int q = 0; q < 3; ++q)
        {
          xyz.push_back(a[q] + u * (b[q] - a[q]) + v * (c[q] - a[q]));
        }
      }
    }
  }
  measure = MeasureCoverage(xyz, spheres);
  return true;
}

bool MeasureInteriorCoverage(vtkPolyData* meshData, vtkPolyData* proxies, int volumeResolution,
  int interiorResolution, int randomSamples, std::uint32_t seed, CoverageMeasure& grid,
  CoverageMeasure& random, std::string& error)
{
  ProxyMesh mesh;
  std::vector<Sphere> spheres;
  if (!Prepare(meshData, mesh, error) || !GetLeafSpheres(proxies, spheres, error))
  {
    return false;
  }
  MeshQueries queries(mesh);
  if (!queries.Ok())
  {
    error = queries.Error();
    return false;
  }
  VolumeRows rows;
  rows.Build(queries, mesh.Bounds, mesh.Bounds, RowSpacing(mesh.Bounds, volumeResolution));
  std::vector<double> samples;
  ComputeInteriorSamples(rows, mesh.Bounds, interiorResolution, samples);
  grid = MeasureCoverage(samples, spheres);
  std::mt19937 rng(seed);
  auto uniform = [&rng]() { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; };
  std::vector<double> candidates(3 * static_cast<std::size_t>(std::max(0, randomSamples)));
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    const int q = static_cast<int>(i % 3);
    candidates[i] = mesh.Bounds[2 * q] + uniform() * (mesh.Bounds[2 * q + 1] - mesh.Bounds[2 * q]);
  }
  std::vector<char> inside(candidates.size() / 3, 0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(inside.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        inside[i] = queries.IsInside(candidates.data() + 3 * i);
      }
    });
  std::vector<double> points;
  for (std::size_t i = 0; i < inside.size(); ++i)
  {
    if (inside[i])
    {
      points.insert(points.end(), candidates.begin() + 3 * i, candidates.begin() + 3 * i + 3);
    }
  }
  random = MeasureCoverage(points, spheres);
  return true;
}

// Used by vtkPGISphereSetApproximation (declared in pgiSphereSetBuilder.h).
void MeasureOutsideVolume(const ProxyMesh& mesh, const MeshQueries& queries,
  const std::vector<Sphere>& spheres, int resolution, OutsideVolumeMeasure& measure)
{
  Measure(mesh, queries, spheres, std::max(4, resolution), measure);
}
} // namespace proxygi
