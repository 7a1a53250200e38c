#include "pgiPlaneLightMap.h"

#include "pgiBrightLightShadows.h"
#include "pgiEnvironmentShading.h"
#include "pgiIndirectLight.h"
#include "pgiSHBasis.h"
#include "pgiSHBatch.h"
#include "pgiSoftShadowsBatch.h"
#include "vtkPGIGIBake.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxygi
{

namespace
{
float Dot(const float a[3], const float b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Directions per block of the products below.
constexpr int DotLanes = sh::BatchWidth;

int PaddedDirections(int count)
{
  return (count + DotLanes - 1) / DotLanes * DotLanes;
}

// A direction's basis, stored coefficient-major.
void StoreBasis(int order, const float w[3], float* basis, int stride, int k)
{
  float y[sh::MaxCoefficients];
  sh::EvaluateBasis(order, w[0], w[1], w[2], y);
  for (int i = 0; i < order * order; ++i)
  {
    basis[static_cast<std::size_t>(i) * stride + k] = y[i];
  }
}
}

void PlaneLightMap::Layout(const Blockers& blockers, int plane,
  const std::vector<DistantLight>& lights, int resolution, int directions, int order)
{
  std::copy_n(&blockers.PlaneOrigin[3 * plane], 3, this->Origin);
  std::copy_n(&blockers.PlaneNormal[3 * plane], 3, this->Normal);
  const double m[3] = { this->Normal[0], this->Normal[1], this->Normal[2] };
  double u[3], v[3];
  FrameAbout(m, u, v);
  for (int c = 0; c < 3; ++c)
  {
    this->U[c] = static_cast<float>(u[c]);
    this->V[c] = static_cast<float>(v[c]);
  }

  // The look-up directions: uniform in solid angle over the half-space below
  // the plane (a spherical Fibonacci spiral), fixed in the plane's frame.
  const int count = std::max(0, std::min(MaxDirections, directions));
  this->Directions.resize(3 * static_cast<std::size_t>(count));
  this->Coefficients = order * order;
  this->DirectionStride = PaddedDirections(count);
  // Zeros past the last direction: the batched terms read whole blocks.
  this->StepU.assign(this->DirectionStride, 0.0f);
  this->StepV.assign(this->DirectionStride, 0.0f);
  this->Basis.assign(static_cast<std::size_t>(this->Coefficients) * this->DirectionStride, 0.0f);
  const double golden = (1.0 + std::sqrt(5.0)) / 2.0, pi = 3.14159265358979323846;
  for (int k = 0; k < count; ++k)
  {
    const double down = (k + 0.5) / count, side = std::sqrt(std::max(0.0, 1.0 - down * down));
    const double phi = 2.0 * pi * k / golden;
    const double a = side * std::cos(phi), b = side * std::sin(phi);
    for (int c = 0; c < 3; ++c)
    {
      this->Directions[3 * k + c] = static_cast<float>(a * u[c] + b * v[c] - down * m[c]);
    }
    this->StepU[k] = static_cast<float>(a / down);
    this->StepV[k] = static_cast<float>(b / down);
    if (order > 0)
    {
      StoreBasis(order, &this->Directions[3 * k], this->Basis.data(), this->DirectionStride, k);
    }
  }

  // The extent: extent coordinates (a, b) of plane coordinates (x, y) are
  // (x, y) . Dual1 and . Dual2, the inverse of [e1 e2] in (U, V).
  const float* e = &blockers.PlaneExtent[6 * plane];
  const double e1[2] = { e[0] * u[0] + e[1] * u[1] + e[2] * u[2],
    e[0] * v[0] + e[1] * v[1] + e[2] * v[2] };
  const double e2[2] = { e[3] * u[0] + e[4] * u[1] + e[5] * u[2],
    e[3] * v[0] + e[4] * v[1] + e[5] * v[2] };
  const double det = e1[0] * e2[1] - e1[1] * e2[0];
  const double size = std::max(std::hypot(e1[0], e1[1]), std::hypot(e2[0], e2[1]));
  this->Bounded = std::isfinite(det) && std::abs(det) > 1e-12 * size * size && size > 0.0;
  if (this->Bounded)
  {
    this->Dual1[0] = static_cast<float>(e2[1] / det);
    this->Dual1[1] = static_cast<float>(-e2[0] / det);
    this->Dual2[0] = static_cast<float>(-e1[1] / det);
    this->Dual2[1] = static_cast<float>(e1[0] / det);
  }

  // The region the spheres can darken, in plane coordinates.
  double lo[2] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max() };
  double hi[2] = { -lo[0], -lo[1] };
  const auto include = [&](double cu, double cv, double reach)
  {
    lo[0] = std::min(lo[0], cu - reach);
    lo[1] = std::min(lo[1], cv - reach);
    hi[0] = std::max(hi[0], cu + reach);
    hi[1] = std::max(hi[1], cv + reach);
  };
  for (std::size_t i = 0; i < blockers.Spheres(); ++i)
  {
    const double d[3] = { blockers.X[i] - this->Origin[0], blockers.Y[i] - this->Origin[1],
      blockers.Z[i] - this->Origin[2] };
    const double h = d[0] * m[0] + d[1] * m[1] + d[2] * m[2], r = blockers.R[i];
    const double top = h + r;
    if (!(top > 0.0) || !std::isfinite(top))
    {
      continue;
    }
    const double cu = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    const double cv = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
    include(cu, cv, r + 2.5 * top);
    for (const DistantLight& light : lights)
    {
      const double* w = light.Direction;
      const double rise = w[0] * m[0] + w[1] * m[1] + w[2] * m[2];
      if (!(rise > 0.0))
      {
        continue; // below the horizon: it lights nothing on the plane
      }
      // The sphere's shadow: its centre moved away from the light by h / rise
      // along the light's tangential part, stretched by 1 / rise (at most 20).
      const double stretch = std::min(1.0 / rise, 20.0);
      const double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
      const double wv = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
      const double along = std::max(0.0, h) * stretch;
      include(cu - along * wu, cv - along * wv, r * stretch + r);
    }
  }
  if (this->Bounded)
  {
    // No light is reflected off the extent: the grid need not reach past it.
    const double reach[2] = { std::abs(e1[0]) + std::abs(e2[0]),
      std::abs(e1[1]) + std::abs(e2[1]) };
    for (int c = 0; c < 2; ++c)
    {
      lo[c] = std::max(lo[c], -reach[c]);
      hi[c] = std::min(hi[c], reach[c]);
    }
  }
  if (!(hi[0] > lo[0]) || !(hi[1] > lo[1]))
  {
    this->Columns = this->Rows = 0;
    this->S.clear();
    return;
  }
  const int cells = std::max(1, resolution);
  this->Cell = static_cast<float>(std::max(hi[0] - lo[0], hi[1] - lo[1]) / cells);
  this->U0 = static_cast<float>(lo[0]);
  this->V0 = static_cast<float>(lo[1]);
  this->Columns = 2 + static_cast<int>((hi[0] - lo[0]) / this->Cell);
  this->Rows = 2 + static_cast<int>((hi[1] - lo[1]) / this->Cell);
  this->S.assign(3 * static_cast<std::size_t>(this->Columns) * this->Rows, 1.0f);
}

void PlaneLightMap::Point(int i, float q[3]) const
{
  const int column = i % this->Columns, row = i / this->Columns;
  const float a = this->U0 + this->Cell * static_cast<float>(column);
  const float b = this->V0 + this->Cell * static_cast<float>(row);
  for (int c = 0; c < 3; ++c)
  {
    q[c] = this->Origin[c] + a * this->U[c] + b * this->V[c];
  }
}

namespace
{
// Bilinear s at grid coordinates (fu, fv); 1 outside.
inline void Bilinear(const float* grid, int columns, int rows, float fu, float fv, float s[3])
{
  if (!(fu >= 0.0f) || !(fv >= 0.0f) || !(fu < static_cast<float>(columns - 1)) ||
    !(fv < static_cast<float>(rows - 1)))
  {
    s[0] = s[1] = s[2] = 1.0f;
    return;
  }
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const float a = fu - static_cast<float>(i), b = fv - static_cast<float>(j);
  const float* p00 = &grid[3 * (static_cast<std::size_t>(j) * columns + i)];
  const float* p10 = p00 + 3;
  const float* p01 = p00 + 3 * static_cast<std::size_t>(columns);
  const float* p11 = p01 + 3;
  for (int c = 0; c < 3; ++c)
  {
    const float bottom = p00[c] + a * (p10[c] - p00[c]);
    const float top = p01[c] + a * (p11[c] - p01[c]);
    s[c] = bottom + b * (top - bottom);
  }
}
}

bool PlaneLightMap::SkyKey::operator==(const SkyKey& o) const
{
  return this->Texels == o.Texels && this->Checksum == o.Checksum && this->Rotation == o.Rotation &&
    this->Width == o.Width && this->Height == o.Height && this->Coefficients == o.Coefficients &&
    std::equal(this->Frame, this->Frame + 9, o.Frame);
}

void PlaneLightMap::SetSky(const EnvironmentMap& map)
{
  const double pi = 3.14159265358979323846, binWidth = 2.0 * pi / SkyBins;
  // The bins' axes follow the extent, which the table's key leaves out.
  this->SkyAxes.resize(4 * SkyBins);
  for (int b = 0; b < SkyBins; ++b)
  {
    const float phi = static_cast<float>(binWidth * (b + 0.5));
    const float c = std::cos(phi), sn = std::sin(phi);
    const float axes[4] = { c, sn, c * this->Dual1[0] + sn * this->Dual1[1],
      c * this->Dual2[0] + sn * this->Dual2[1] };
    for (int k = 0; k < 4; ++k)
    {
      this->SkyAxes[k * SkyBins + b] = axes[k];
    }
  }
  SkyKey key;
  key.Texels = map.GetRGB().data();
  key.Rotation = map.GetRotation();
  key.Width = map.GetWidth();
  key.Height = map.GetHeight();
  key.Coefficients = this->Coefficients;
  // A map set anew in the same buffer: a sparse checksum of its texels.
  const std::vector<float>& texels = map.GetRGB();
  const std::size_t stride = std::max<std::size_t>(1, texels.size() / 4096);
  for (std::size_t i = 0; i < texels.size(); i += stride)
  {
    key.Checksum += static_cast<double>(texels[i]) * static_cast<double>(i % 7919 + 1);
  }
  std::copy_n(this->U, 3, key.Frame);
  std::copy_n(this->V, 3, key.Frame + 3);
  std::copy_n(this->Normal, 3, key.Frame + 6);
  if (!this->SkyTable.empty() && key == this->SkyBuiltFor)
  {
    return;
  }
  constexpr int Heights = SkyHeights + 1, AlongPhi = 8, AlongS = 4;
  const double step = 1.0 / SkyHeights;
  const double cell = (binWidth / AlongPhi) * (step / AlongS);
  this->SkyTable.assign(9 * static_cast<std::size_t>(SkyBins) * Heights, 0.0f);
  const auto world = [this](double c, double sn, double s, double w[3])
  {
    const double side = std::sqrt(std::max(0.0, 1.0 - s * s));
    for (int k = 0; k < 3; ++k)
    {
      w[k] = side * (c * this->U[k] + sn * this->V[k]) - s * this->Normal[k];
    }
  };
  vtkSMPTools::For(0, SkyBins,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType b = first; b < last; ++b)
      {
        double sum[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
        float* cumulative = &this->SkyTable[9 * static_cast<std::size_t>(b) * Heights];
        for (int j = 0; j < SkyHeights; ++j)
        {
          for (int q = 0; q < AlongPhi * AlongS; ++q)
          {
            const int inPhi = q % AlongPhi, inS = q / AlongPhi;
            const double phi = binWidth * (static_cast<double>(b) + (inPhi + 0.5) / AlongPhi);
            const double s = step * (j + (inS + 0.5) / AlongS);
            const double c = std::cos(phi), sn = std::sin(phi), side = std::sqrt(1.0 - s * s);
            double w[3];
            world(c, sn, s, w);
            float rgb[3];
            map.Lookup(w, rgb);
            const double local[3] = { side * c, side * sn, -s };
            for (int a = 0; a < 3; ++a)
            {
              for (int ch = 0; ch < 3; ++ch)
              {
                sum[3 * a + ch] += cell * local[a] * rgb[ch];
              }
            }
          }
          for (int k = 0; k < 9; ++k)
          {
            cumulative[9 * (j + 1) + k] = static_cast<float>(sum[k]);
          }
        }
      }
    });
  this->SkyBasis.assign(static_cast<std::size_t>(this->Coefficients) * SkyBins * SkyRows, 0.0f);
  const int order = static_cast<int>(std::lround(std::sqrt(this->Coefficients)));
  for (int b = 0; b < SkyBins && order > 0; ++b)
  {
    const double phi = binWidth * (b + 0.5);
    for (int r = 0; r < SkyRows; ++r)
    {
      double w[3];
      world(std::cos(phi), std::sin(phi), (r + 0.5) / SkyRows, w);
      const float wf[3] = { static_cast<float>(w[0]), static_cast<float>(w[1]),
        static_cast<float>(w[2]) };
      StoreBasis(order, wf, this->SkyBasis.data(), SkyBins * SkyRows, b * SkyRows + r);
    }
  }
  this->SkyBuiltFor = key;
}

void PlaneLightMap::SkyPastEdges(
  float x, float y, float h, const float n[3], const float* g, float gap[3]) const
{
  gap[0] = gap[1] = gap[2] = 0.0f;
  if (!this->Bounded || this->SkyTable.empty() || !(h > 0.0f))
  {
    return;
  }
  constexpr int Heights = SkyHeights + 1;
  const float pi = 3.14159265358979323846f;
  const float nl[3] = { Dot(n, this->U), Dot(n, this->V), Dot(n, this->Normal) };
  const float a1 = x * this->Dual1[0] + y * this->Dual1[1];
  const float a2 = x * this->Dual2[0] + y * this->Dual2[1];
  const float big = std::numeric_limits<float>::max();
  // The table at s in [0, 1], linear between heights: 9 floats.
  const auto at = [](const float* row, float s, float out[9])
  {
    const float f = std::min(1.0f, std::max(0.0f, s)) * SkyHeights;
    const int j = std::min(SkyHeights - 1, static_cast<int>(f));
    const float t = f - static_cast<float>(j);
    const float* lo = &row[9 * j];
    for (int k = 0; k < 9; ++k)
    {
      out[k] = lo[k] + t * (lo[9 + k] - lo[k]);
    }
  };
  // The bins' stretches of heights that miss the extent and face n, in the
  // order they are summed; then V at the rows they read, the blocks of
  // DotLanes rows they need together; then the sum.
  static_assert(SkyBins * SkyRows % DotLanes == 0, "the sky's rows fill the products' blocks");
  constexpr int SkyStride = SkyBins * SkyRows;
  int stretchBin[2 * SkyBins];
  float stretchFrom[2 * SkyBins], stretchTo[2 * SkyBins];
  int stretches = 0;
  const bool batched = sh::BatchKernelsEnabled();
  if (batched)
  {
    static_assert(SkyBins % sh::BatchWidth == 0, "the bins fill the batches");
    float from[2 * SkyBins], to[2 * SkyBins];
    detail::SkyStretches(this->SkyAxes.data(), SkyBins, nl, a1, a2, h, from, to);
    for (int b = 0; b < SkyBins; ++b)
    {
      for (int r = 0; r < 2; ++r)
      {
        if (to[r * SkyBins + b] > from[r * SkyBins + b])
        {
          stretchBin[stretches] = b;
          stretchFrom[stretches] = from[r * SkyBins + b];
          stretchTo[stretches] = to[r * SkyBins + b];
          ++stretches;
        }
      }
    }
  }
  for (int b = 0; !batched && b < SkyBins; ++b)
  {
    const float c = this->SkyAxes[b], sn = this->SkyAxes[SkyBins + b];
    // Where n.w > 0 along the bin's centre: n.w = A cos e - m sin e changes
    // sign at most once over the quarter turn from the horizon down.
    const float along = nl[0] * c + nl[1] * sn, m = nl[2];
    const bool atHorizon = along > 0.0f, atNadir = m < 0.0f;
    if (!atHorizon && !atNadir)
    {
      continue;
    }
    float lo = 0.0f, hi = 1.0f;
    if (atHorizon != atNadir)
    {
      (atHorizon ? hi : lo) = std::abs(along) / std::sqrt(along * along + m * m);
    }
    // The rays' feet x + t (c, sn), t >= 0, inside the extent: [in, out].
    float in = 0.0f, out = big;
    for (int q = 0; q < 2; ++q)
    {
      const float a = q == 0 ? a1 : a2, da = this->SkyAxes[(2 + q) * SkyBins + b];
      if (da == 0.0f)
      {
        if (std::abs(a) > 1.0f)
        {
          in = big;
        }
        continue;
      }
      const float t1 = (-1.0f - a) / da, t2 = (1.0f - a) / da;
      in = std::max(in, std::min(t1, t2));
      out = std::min(out, std::max(t1, t2));
    }
    // s = h / sqrt(h^2 + t^2): from the horizon (t endless) down to the foot.
    float ranges[4];
    int count = 0;
    if (!(in <= out))
    {
      ranges[0] = 0.0f;
      ranges[1] = 1.0f;
      count = 1;
    }
    else
    {
      ranges[0] = 0.0f;
      ranges[1] = out < big ? h / std::sqrt(h * h + out * out) : 0.0f;
      count = 1;
      if (in > 0.0f)
      {
        ranges[2] = h / std::sqrt(h * h + in * in);
        ranges[3] = 1.0f;
        count = 2;
      }
    }
    for (int r = 0; r < count; ++r)
    {
      const float s0 = std::max(lo, ranges[2 * r]), s1 = std::min(hi, ranges[2 * r + 1]);
      if (!(s1 > s0))
      {
        continue;
      }
      stretchBin[stretches] = b;
      stretchFrom[stretches] = s0;
      stretchTo[stretches] = s1;
      ++stretches;
    }
  }
  // V at the middle of a stretch's heights, linear between the two rows
  // around it (the nearest row alone jumps as the receiver moves).
  const auto rowsAround = [](int b, float s0, float s1, int& first, float& t)
  {
    const float middle =
      std::min(static_cast<float>(SkyRows - 1), std::max(0.0f, 0.5f * (s0 + s1) * SkyRows - 0.5f));
    const int k = std::min(SkyRows - 2, static_cast<int>(middle));
    t = middle - static_cast<float>(k);
    first = b * SkyRows + k;
  };
  float skyV[SkyStride];
  if (g)
  {
    bool needed[SkyStride / DotLanes] = {};
    for (int e = 0; e < stretches; ++e)
    {
      int first = 0;
      float t = 0.0f;
      rowsAround(stretchBin[e], stretchFrom[e], stretchTo[e], first, t);
      needed[first / DotLanes] = needed[(first + 1) / DotLanes] = true;
    }
    int blocks[SkyStride / DotLanes], count = 0;
    for (int block = 0; block < SkyStride / DotLanes; ++block)
    {
      if (needed[block])
      {
        blocks[count++] = block;
      }
    }
    detail::DotBlocks(this->Coefficients, g, this->SkyBasis.data(), SkyStride, blocks, count, skyV);
  }
  float sum[3] = { 0, 0, 0 };
  for (int e = 0; e < stretches; ++e)
  {
    const float* row = &this->SkyTable[9 * static_cast<std::size_t>(stretchBin[e]) * Heights];
    const float s0 = stretchFrom[e], s1 = stretchTo[e];
    float t0[9], t1[9];
    at(row, s0, t0);
    at(row, s1, t1);
    float v = 1.0f;
    if (g)
    {
      int first = 0;
      float t = 0.0f;
      rowsAround(stretchBin[e], s0, s1, first, t);
      const float rows[2] = { std::min(1.0f, std::max(0.0f, skyV[first])),
        std::min(1.0f, std::max(0.0f, skyV[first + 1])) };
      v = rows[0] + t * (rows[1] - rows[0]);
    }
    for (int ch = 0; ch < 3; ++ch)
    {
      const float e3 = nl[0] * (t1[ch] - t0[ch]) + nl[1] * (t1[3 + ch] - t0[3 + ch]) +
        nl[2] * (t1[6 + ch] - t0[6 + ch]);
      sum[ch] += v * std::max(0.0f, e3);
    }
  }
  for (int ch = 0; ch < 3; ++ch)
  {
    gap[ch] = sum[ch] / pi;
  }
}

namespace
{
inline bool InExtent(const float dual1[2], const float dual2[2], float x, float y)
{
  const float a = x * dual1[0] + y * dual1[1], b = x * dual2[0] + y * dual2[1];
  return std::abs(a) <= 1.0f && std::abs(b) <= 1.0f;
}
}

bool PlaneLightMap::Inside(const float x[3]) const
{
  const float d[3] = { x[0] - this->Origin[0], x[1] - this->Origin[1], x[2] - this->Origin[2] };
  return !this->Bounded || InExtent(this->Dual1, this->Dual2, Dot(d, this->U), Dot(d, this->V));
}

void PlaneLightMap::Lookup(const float x[3], float s[3]) const
{
  const float d[3] = { x[0] - this->Origin[0], x[1] - this->Origin[1], x[2] - this->Origin[2] };
  if (this->S.empty())
  {
    s[0] = s[1] = s[2] = 1.0f;
    return;
  }
  Bilinear(this->S.data(), this->Columns, this->Rows, (Dot(d, this->U) - this->U0) / this->Cell,
    (Dot(d, this->V) - this->V0) / this->Cell, s);
}

bool PlaneLightMap::Scale(
  const float p[3], const float n[3], float scale[3], const float* g, float gap[3]) const
{
  scale[0] = scale[1] = scale[2] = 1.0f;
  if (gap)
  {
    gap[0] = gap[1] = gap[2] = 0.0f;
  }
  const float d[3] = { p[0] - this->Origin[0], p[1] - this->Origin[1], p[2] - this->Origin[2] };
  const float h = Dot(d, this->Normal);
  if (!(h > 0.0f))
  {
    return false;
  }
  // The receiver's foot in plane coordinates, and in grid cells.
  const float x = Dot(d, this->U), y = Dot(d, this->V);
  const float inv = 1.0f / this->Cell;
  const float fu = (x - this->U0) * inv, fv = (y - this->V0) * inv, hu = h * inv;
  const bool empty = this->S.empty();
  float sum[3] = { 0, 0, 0 }, weights = 0.0f;
  const int count = this->GetNumberOfDirections();
  // V at the directions the receiver faces (Layout allows at most
  // MaxDirections), a block of DotLanes directions at a time.
  float cosines[MaxDirections], v[MaxDirections];
  for (int k = 0; k < count; ++k)
  {
    cosines[k] = Dot(n, &this->Directions[3 * k]);
  }
  std::fill(cosines + count, cosines + this->DirectionStride, 0.0f);
  int blocks[MaxDirections / DotLanes], facing = 0;
  for (int k0 = 0; k0 < count; k0 += DotLanes)
  {
    if (std::any_of(cosines + k0, cosines + k0 + DotLanes, [](float c) { return c > 0.0f; }))
    {
      blocks[facing++] = k0 / DotLanes;
    }
  }
  if (g && facing > 0)
  {
    detail::DotBlocks(this->Coefficients, g, this->Basis.data(),
      static_cast<std::size_t>(this->DirectionStride), blocks, facing, v);
  }
  const bool batched = sh::BatchKernelsEnabled();
  if (batched)
  {
    // The terms side by side, then summed in the scalar loop's order (the
    // directions it skips add zeros).
    detail::PlaneLookUps in;
    in.Cosines = cosines;
    in.V = g ? v : nullptr;
    in.StepU = this->StepU.data();
    in.StepV = this->StepV.data();
    in.X = x;
    in.Y = y;
    in.H = h;
    in.FU = fu;
    in.FV = fv;
    in.HU = hu;
    in.Bounded = this->Bounded;
    std::copy_n(this->Dual1, 2, in.Dual1);
    std::copy_n(this->Dual2, 2, in.Dual2);
    // A grid of one row or column has no cell: s is 1 everywhere.
    in.Grid = empty || this->Columns < 2 || this->Rows < 2 ? nullptr : this->S.data();
    in.Columns = this->Columns;
    in.Rows = this->Rows;
    float w[MaxDirections], terms[3 * MaxDirections];
    detail::PlaneTerms(in, blocks, facing, w, terms, MaxDirections);
    for (int b = 0; b < facing; ++b)
    {
      for (int k = blocks[b] * DotLanes; k < (blocks[b] + 1) * DotLanes; ++k)
      {
        weights += w[k];
        for (int ch = 0; ch < 3; ++ch)
        {
          sum[ch] += terms[ch * MaxDirections + k];
        }
      }
    }
  }
  for (int k = 0; !batched && k < count; ++k)
  {
    const float c = cosines[k];
    if (!(c > 0.0f))
    {
      continue;
    }
    weights += c;
    float seen = c;
    if (g)
    {
      seen *= std::min(1.0f, std::max(0.0f, v[k]));
    }
    const float su = this->StepU[k], sv = this->StepV[k];
    if (this->Bounded && !InExtent(this->Dual1, this->Dual2, x + h * su, y + h * sv))
    {
      continue;
    }
    float s[3] = { 1.0f, 1.0f, 1.0f };
    if (!empty)
    {
      Bilinear(this->S.data(), this->Columns, this->Rows, fu + hu * su, fv + hu * sv, s);
    }
    for (int ch = 0; ch < 3; ++ch)
    {
      sum[ch] += seen * s[ch];
    }
  }
  if (!(weights > 0.0f))
  {
    return false;
  }
  for (int ch = 0; ch < 3; ++ch)
  {
    scale[ch] = std::min(1.0f, std::max(0.0f, sum[ch] / weights));
  }
  if (gap)
  {
    this->SkyPastEdges(x, y, h, n, g, gap);
  }
  return true;
}

namespace
{
// Directions of a tile's union test: a tile's scale is one of many a
// receiver averages over (a lone sphere's blocked share within ~1%).
constexpr int TileDirections = 512;

// One thread's buffers for a range of grid points.
struct FillScratch
{
  std::vector<float> Points, Normals, Visibilities;
  std::vector<sh::Status> Statuses;
  std::vector<int> Used, Indices;
  Blockers Scaled;
  BrightLightScratch Bright;
};

void FillPlaneLightMap(PlaneLightMap& map, int plane, const BakedScene& b,
  const PlaneLightMapShading& how, vtkSMPThreadLocal<FillScratch>& perThread)
{
  const Blockers& blockers = b.SceneBlockers;
  const float* m = &blockers.PlaneNormal[3 * plane];
  const int n2 = b.Order * b.Order;
  float residual[3];
  b.OpenShading->ShadeUnshadowed(m, residual);
  float* scales = map.Scales();
  // Tiles of grid points: overlapping spheres near the plane (an arch's
  // tube) block far more in the SH than their union, as over a ground's
  // receivers; each tile shades with the blockers scaled at its centre to
  // block what the union blocks (ScaleCutToUnion).
  const int columns = map.GetColumns(), rows = map.GetRows();
  const int tilesU = (columns + PlaneLightMap::TileSide - 1) / PlaneLightMap::TileSide;
  const int tilesV = (rows + PlaneLightMap::TileSide - 1) / PlaneLightMap::TileSide;
  vtkSMPTools::For(0, static_cast<vtkIdType>(tilesU) * tilesV, 1,
    [&](vtkIdType firstTile, vtkIdType lastTile)
    {
      FillScratch& buffers = perThread.Local();
      for (vtkIdType tile = firstTile; tile < lastTile; ++tile)
      {
        const int u0 = static_cast<int>(tile % tilesU) * PlaneLightMap::TileSide;
        const int v0 = static_cast<int>(tile / tilesU) * PlaneLightMap::TileSide;
        const int u1 = std::min(columns, u0 + PlaneLightMap::TileSide);
        const int v1 = std::min(rows, v0 + PlaneLightMap::TileSide);
        buffers.Indices.clear();
        for (int v = v0; v < v1; ++v)
        {
          for (int u = u0; u < u1; ++u)
          {
            buffers.Indices.push_back(v * columns + u);
          }
        }
        const int count = static_cast<int>(buffers.Indices.size());
        buffers.Points.resize(3 * count);
        buffers.Normals.resize(3 * count);
        buffers.Visibilities.resize(static_cast<std::size_t>(n2) * count);
        buffers.Statuses.resize(count);
        buffers.Used.resize(count);
        for (int j = 0; j < count; ++j)
        {
          map.Point(buffers.Indices[j], &buffers.Points[3 * j]);
          std::copy_n(m, 3, &buffers.Normals[3 * j]);
        }
        float centre[3], corner[3];
        map.Point(v0 * columns + u0, centre);
        map.Point((v1 - 1) * columns + (u1 - 1), corner);
        for (int c = 0; c < 3; ++c)
        {
          centre[c] = 0.5f * (centre[c] + corner[c]);
        }
        buffers.Scaled = blockers;
        const bool scaled =
          ScaleCutToUnion(buffers.Scaled, blockers, *how.Shadows, centre, m, TileDirections) < 1.0f;
        // Every sphere is another object's: the plane's contact shadows stay dark.
        SelfVisibility plane;
        plane.OwnsNoSpheres = true;
        how.Shadows->VisibilityBatch(count, buffers.Points.data(), buffers.Normals.data(),
          scaled ? buffers.Scaled : blockers, buffers.Visibilities.data(), buffers.Statuses.data(),
          buffers.Used.data(), nullptr, plane);
        for (int j = 0; j < count; ++j)
        {
          float* scale = &scales[3 * static_cast<std::size_t>(buffers.Indices[j])];
          PlaneShadowScaleAt(*b.OpenShading, m, &buffers.Visibilities[n2 * j], buffers.Used[j],
            buffers.Statuses[j], scale);
          if (!how.Bright)
          {
            continue;
          }
          // The bright lights' share: lit over unshadowed, weighed against the
          // residual's by their light on the plane.
          const float* q = &buffers.Points[3 * j];
          float lit[3] = { 0, 0, 0 }, open[3] = { 0, 0, 0 };
          if (how.Occluder)
          {
            BrightLightsFromRays(
              *how.Bright, blockers, *how.Occluder, q, m, how.RayOffset, buffers.Bright, lit);
          }
          else
          {
            BrightLightsFromProxies(*how.Bright, blockers, q, m, how.MinAngle, how.ShadowsOn, lit);
          }
          BrightLightsFromProxies(*how.Bright, blockers, q, m, how.MinAngle, false, open);
          for (int c = 0; c < 3; ++c)
          {
            const float whole = residual[c] + open[c];
            if (whole > 0.0f)
            {
              scale[c] = std::min(1.0f, (residual[c] * scale[c] + lit[c]) / whole);
            }
          }
        }
      }
    });
}
} // namespace

int BuildPlaneLightMaps(const BakedScene& scene, const PlaneLightMapShading& how, int directions,
  std::vector<PlaneLightMap>& maps)
{
  const Blockers& blockers = scene.SceneBlockers;
  const int planes = static_cast<int>(blockers.Planes());
  const std::vector<DistantLight> none;
  vtkSMPThreadLocal<FillScratch> perThread;
  maps.resize(planes);
  int points = 0;
  for (int k = 0; k < planes; ++k)
  {
    maps[k].Layout(
      blockers, k, how.Bright ? how.Bright->Lights : none, how.Resolution, directions, scene.Order);
    if (scene.Environment)
    {
      maps[k].SetSky(*scene.Environment);
    }
    FillPlaneLightMap(maps[k], k, scene, how, perThread);
    points += maps[k].GetNumberOfPoints();
  }
  return points;
}

} // namespace proxygi
