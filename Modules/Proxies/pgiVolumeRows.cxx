#include "pgiVolumeRows.h"

#include "pgiMeshQueries.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace proxygi
{

void VolumeRows::Build(
  const MeshQueries& queries, const double region[6], const double meshBounds[6], double h)
{
  this->H = h;
  const double ey = region[3] - region[2], ez = region[5] - region[4];
  this->NY = std::max(1, static_cast<int>(std::ceil(ey / h)));
  this->NZ = std::max(1, static_cast<int>(std::ceil(ez / h)));
  this->Y0 = 0.5 * (region[2] + region[3]) - 0.5 * this->NY * h;
  this->Z0 = 0.5 * (region[4] + region[5]) - 0.5 * this->NZ * h;
  const int rows = this->NY * this->NZ;
  std::vector<std::vector<double>> intervals(rows);
  std::vector<char> odd(rows, 0), traced(rows, 0);
  for (int j = 0; j < this->NY; ++j)
  {
    for (int k = 0; k < this->NZ; ++k)
    {
      const double y = this->RowY(j), z = this->RowZ(k);
      traced[j * this->NZ + k] =
        y >= meshBounds[2] && y <= meshBounds[3] && z >= meshBounds[4] && z <= meshBounds[5];
    }
  }
  const double size = std::max({ meshBounds[1] - meshBounds[0], meshBounds[3] - meshBounds[2],
    meshBounds[5] - meshBounds[4], h });
  const double x0 = meshBounds[0] - 0.01 * size - h;
  vtkSMPTools::For(0, rows,
    [&](int begin, int end)
    {
      std::vector<double> t;
      for (int r = begin; r < end; ++r)
      {
        if (!traced[r])
        {
          continue;
        }
        const double origin[3] = { x0, this->RowY(r / this->NZ), this->RowZ(r % this->NZ) };
        const double direction[3] = { 1.0, 0.0, 0.0 };
        queries.Crossings(origin, direction, t);
        if (t.size() % 2)
        {
          odd[r] = 1;
          continue;
        }
        for (double v : t)
        {
          intervals[r].push_back(x0 + v);
        }
      }
    });
  this->Traced = 0;
  this->Resolved = 0;
  for (int r = 0; r < rows; ++r)
  {
    this->Traced += traced[r];
    this->Resolved += odd[r];
  }
  this->IsSolid = this->Resolved <= this->Traced / 4;
  if (!this->IsSolid)
  {
    for (auto& v : intervals)
    {
      v.clear();
    }
  }
  else if (this->Resolved > 0)
  {
    // Point by point along the row, half a row spacing apart.
    const double step = 0.5 * h;
    const int samples =
      std::max(1, static_cast<int>(std::ceil((meshBounds[1] - meshBounds[0]) / step)));
    vtkSMPTools::For(0, rows,
      [&](int begin, int end)
      {
        for (int r = begin; r < end; ++r)
        {
          if (!odd[r])
          {
            continue;
          }
          bool inside = false;
          for (int i = 0; i < samples; ++i)
          {
            const double p[3] = { meshBounds[0] + (i + 0.5) * step, this->RowY(r / this->NZ),
              this->RowZ(r % this->NZ) };
            const bool now = queries.IsInside(p);
            if (now != inside)
            {
              intervals[r].push_back(meshBounds[0] + i * step);
              inside = now;
            }
          }
          if (inside)
          {
            intervals[r].push_back(meshBounds[1]);
          }
        }
      });
  }
  this->Start.assign(rows + 1, 0);
  this->Ends.clear();
  for (int r = 0; r < rows; ++r)
  {
    this->Start[r] = static_cast<int>(this->Ends.size() / 2);
    this->Ends.insert(this->Ends.end(), intervals[r].begin(), intervals[r].end());
  }
  this->Start[rows] = static_cast<int>(this->Ends.size() / 2);
}

int VolumeRows::IndexY(double y) const
{
  return static_cast<int>(std::floor((y - this->Y0) / this->H - JitterY));
}

int VolumeRows::IndexZ(double z) const
{
  return static_cast<int>(std::floor((z - this->Z0) / this->H - JitterZ));
}

bool VolumeRows::Inside(int j, int k, double x) const
{
  int n;
  const double* e = this->Intervals(j, k, n);
  for (int i = 0; i < n; ++i)
  {
    if (x >= e[2 * i] && x <= e[2 * i + 1])
    {
      return true;
    }
  }
  return false;
}

double VolumeRows::Volume() const
{
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < this->Ends.size(); i += 2)
  {
    length += this->Ends[i + 1] - this->Ends[i];
  }
  return length * this->H * this->H;
}

double VolumeRows::InsideVolume(const double c[3], double radius) const
{
  const int j0 = std::max(0, this->IndexY(c[1] - radius)),
            j1 = std::min(this->NY - 1, this->IndexY(c[1] + radius) + 1);
  const int k0 = std::max(0, this->IndexZ(c[2] - radius)),
            k1 = std::min(this->NZ - 1, this->IndexZ(c[2] + radius) + 1);
  const double r2 = radius * radius;
  double length = 0.0;
  for (int j = j0; j <= j1; ++j)
  {
    const double dy = this->RowY(j) - c[1];
    for (int k = k0; k <= k1; ++k)
    {
      const double dz = this->RowZ(k) - c[2];
      const double w2 = r2 - dy * dy - dz * dz;
      if (w2 > 0.0)
      {
        const double w = std::sqrt(w2);
        length += this->InsideLength(j, k, c[0] - w, c[0] + w);
      }
    }
  }
  return length * this->H * this->H;
}

int VolumeRows::StrideFor(double radius, double rows) const
{
  return std::max(1, static_cast<int>(radius / (rows * this->H)));
}

namespace
{
// First index >= i that is a multiple of s.
int Aligned(int i, int s)
{
  const int m = ((i % s) + s) % s;
  return m == 0 ? i : i + s - m;
}
} // namespace

double VolumeRows::OutsideVolume(const double c[3], double radius, int stride) const
{
  const int s = std::max(1, stride);
  const int j0 = Aligned(this->IndexY(c[1] - radius), s), j1 = this->IndexY(c[1] + radius) + 1;
  const int k0 = Aligned(this->IndexZ(c[2] - radius), s), k1 = this->IndexZ(c[2] + radius) + 1;
  const double r2 = radius * radius;
  double length = 0.0;
  // Rows beyond the region count too (all outside): the quadrature must be
  // the same for every sphere, wherever it lies.
  for (int j = j0; j <= j1; j += s)
  {
    const double dy = this->RowY(j) - c[1];
    for (int k = k0; k <= k1; k += s)
    {
      const double dz = this->RowZ(k) - c[2];
      const double w2 = r2 - dy * dy - dz * dz;
      if (w2 > 0.0)
      {
        const double w = std::sqrt(w2);
        length += 2.0 * w - this->InsideLength(j, k, c[0] - w, c[0] + w);
      }
    }
  }
  return length * this->H * this->H * s * s;
}

void VolumeRows::OutsideProfile(
  const double c[3], double step, int bins, std::vector<double>& table, int stride) const
{
  table.assign(bins + 1, 0.0);
  const int s = std::max(1, stride);
  const double rmax = bins * step;
  const int j0 = Aligned(this->IndexY(c[1] - rmax), s), j1 = this->IndexY(c[1] + rmax) + 1;
  const int k0 = Aligned(this->IndexZ(c[2] - rmax), s), k1 = this->IndexZ(c[2] + rmax) + 1;
  const double area = this->H * this->H * s * s;
  for (int j = j0; j <= j1; j += s)
  {
    const double dy = this->RowY(j) - c[1];
    for (int k = k0; k <= k1; k += s)
    {
      const double dz = this->RowZ(k) - c[2];
      const double rho2 = dy * dy + dz * dz;
      const double rho = std::sqrt(rho2);
      if (rho >= rmax)
      {
        continue;
      }
      int n;
      const double* e = this->Intervals(j, k, n);
      for (int b = std::max(1, static_cast<int>(std::ceil(rho / step))); b <= bins; ++b)
      {
        const double u = std::sqrt(std::max(0.0, (b * step) * (b * step) - rho2));
        double inside = 0.0;
        for (int i = 0; i < n; ++i)
        {
          const double lo = std::max(c[0] - u, e[2 * i]), hi = std::min(c[0] + u, e[2 * i + 1]);
          if (hi > lo)
          {
            inside += hi - lo;
          }
        }
        table[b] += area * (2.0 * u - inside);
      }
    }
  }
}
} // namespace proxygi
