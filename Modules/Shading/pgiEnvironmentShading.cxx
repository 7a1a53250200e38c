#include "pgiEnvironmentShading.h"

#include "pgiEnvironmentMap.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace proxygi
{
namespace
{
// a . b in four partial sums (SIMD lanes at any width; an n that is not a
// multiple of 4 adds its tail to the first), then the two pairs.
inline float FourWayDot(int n, const float* a, const float* b)
{
  float part[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  int q = 0;
  for (; q + 4 <= n; q += 4)
  {
    for (int j = 0; j < 4; ++j)
    {
      part[j] += a[q + j] * b[q + j];
    }
  }
  for (; q < n; ++q)
  {
    part[0] += a[q] * b[q];
  }
  return (part[0] + part[1]) + (part[2] + part[3]);
}
} // namespace

EnvironmentShading::EnvironmentShading(
  int order, const double* red, const double* green, const double* blue, Path path, int tableHeight)
  : Order(order)
  , Width(2 * tableHeight)
  , Height(tableHeight)
  , ShadingPath(path)
{
  const int n2 = sh::NumCoefficients(order);
  const double* channels[3] = { red, green, blue };
  this->Light.resize(3 * n2);
  for (int c = 0; c < 3; ++c)
  {
    std::copy(channels[c], channels[c] + n2, this->Light.begin() + c * n2);
  }
  // M_L per channel (M_L g = L * g): the ProductMatrix path keeps it; the
  // table path takes L * H(N) = M_L H(N) per node, a dense matrix-vector
  // product (a sparse triple product per node took 3.5x as long at order 4
  // and 9x at order 6: ShadingTable benchmark).
  const sh::TripleProduct& tp = sh::TripleProduct::Get(order);
  std::vector<double> light(3 * static_cast<std::size_t>(n2) * n2);
  for (int c = 0; c < 3; ++c)
  {
    tp.ProductMatrix(channels[c], &light[static_cast<std::size_t>(c) * n2 * n2]);
  }
  if (path == Path::ProductMatrix)
  {
    this->Matrix.assign(light.begin(), light.end());
    return;
  }
  // Grid nodes at the cell corners, poles included, so interpolation reaches them.
  this->LHTable.resize(static_cast<std::size_t>(this->Height + 1) * (this->Width + 1) * 3 * n2);
  // (M_L H)_k = sum_l M_kl H_l, summed over l in order as columns of M_L
  // scaled by H_l: the n2 sums run side by side (vectorised) instead of
  // one dependent chain each, with the same additions in the same order.
  this->Columns.resize(light.size());
  for (int c = 0; c < 3; ++c)
  {
    const double* m = &light[static_cast<std::size_t>(c) * n2 * n2];
    double* t = &this->Columns[static_cast<std::size_t>(c) * n2 * n2];
    for (int k = 0; k < n2; ++k)
    {
      for (int l = 0; l < n2; ++l)
      {
        t[l * n2 + k] = m[k * n2 + l];
      }
    }
  }
  // Rows are filled when first read: a ground's receivers read one row, a
  // plane map reads this table at the plane's normal only.
  this->RowsBuilt.reset(new std::once_flag[this->Height + 1]);
}

void EnvironmentShading::BuildRow(int j) const
{
  const int n2 = sh::NumCoefficients(this->Order);
  double h[sh::MaxCoefficients], sum[sh::MaxCoefficients];
  const double theta = sh::Pi * j / this->Height;
  for (int i = 0; i <= this->Width; ++i)
  {
    const double phi = 2 * sh::Pi * i / this->Width;
    sh::DiffuseTransfer(this->Order, std::sin(theta) * std::cos(phi),
      std::sin(theta) * std::sin(phi), std::cos(theta), h);
    for (int c = 0; c < 3; ++c)
    {
      const double* t = &this->Columns[static_cast<std::size_t>(c) * n2 * n2];
      std::fill_n(sum, n2, 0.0);
      for (int l = 0; l < n2; ++l)
      {
        const double hl = h[l];
        const double* column = t + static_cast<std::size_t>(l) * n2;
        for (int k = 0; k < n2; ++k)
        {
          sum[k] += column[k] * hl;
        }
      }
      std::copy_n(sum, n2,
        this->LHTable.begin() +
          ((static_cast<std::size_t>(j) * (this->Width + 1) + i) * 3 + c) * n2);
    }
  }
}

void EnvironmentShading::EnsureRow(int j) const
{
  std::call_once(this->RowsBuilt[j], [this, j]() { this->BuildRow(j); });
}

void EnvironmentShading::BuildTable() const
{
  if (this->ShadingPath != Path::Table)
  {
    return;
  }
  vtkSMPTools::For(0, this->Height + 1,
    [this](int first, int last)
    {
      for (int j = first; j < last; ++j)
      {
        this->EnsureRow(j);
      }
    });
}

void EnvironmentShading::Shade(const float n[3], const float* g, float rgb[3]) const
{
  const int n2 = sh::NumCoefficients(this->Order);
  if (this->ShadingPath == Path::ProductMatrix)
  {
    float h[sh::MaxCoefficients];
    sh::DiffuseTransfer(this->Order, n[0], n[1], n[2], h);
    for (int c = 0; c < 3; ++c)
    {
      const float* m = &this->Matrix[static_cast<std::size_t>(c) * n2 * n2];
      float sum = 0.0f;
      for (int i = 0; i < n2; ++i)
      {
        float row = 0.0f;
        for (int j = 0; j < n2; ++j)
        {
          row += m[i * n2 + j] * g[j];
        }
        sum += row * h[i];
      }
      rgb[c] = std::max(0.0f, sum);
    }
    return;
  }
  const float z = std::max(-1.0f, std::min(1.0f, n[2]));
  float phi = std::atan2(n[1], n[0]);
  if (phi < 0.0f)
  {
    phi += 2.0f * static_cast<float>(sh::Pi);
  }
  const float u = phi / (2.0f * static_cast<float>(sh::Pi)) * this->Width;
  const float v = std::acos(z) / static_cast<float>(sh::Pi) * this->Height;
  const int i = std::min(this->Width - 1, std::max(0, static_cast<int>(u)));
  const int j = std::min(this->Height - 1, std::max(0, static_cast<int>(v)));
  const float fu = std::min(1.0f, std::max(0.0f, u - i)),
              fv = std::min(1.0f, std::max(0.0f, v - j));
  const float w[4] = { (1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv };
  this->EnsureRow(j);
  this->EnsureRow(j + 1);
  const std::size_t stride = static_cast<std::size_t>(this->Width) + 1;
  const std::size_t corners[4] = { j * stride + i, j * stride + i + 1, (j + 1) * stride + i,
    (j + 1) * stride + i + 1 };
  for (int c = 0; c < 3; ++c)
  {
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k)
    {
      // A normal on a grid line (a ground's +z) needs fewer corners.
      if (w[k] != 0.0f)
      {
        sum += w[k] * FourWayDot(n2, &this->LHTable[(corners[k] * 3 + c) * n2], g);
      }
    }
    rgb[c] = std::max(0.0f, sum);
  }
}

void EnvironmentShading::ShadeUnshadowed(const float n[3], float rgb[3]) const
{
  const int n2 = sh::NumCoefficients(this->Order);
  float h[sh::MaxCoefficients];
  sh::DiffuseTransfer(this->Order, n[0], n[1], n[2], h);
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = sh::Dot(n2, h, &this->Light[c * n2]);
  }
}

int LightAbovePlanesOrder(int order)
{
  return std::max(order, std::min(8, sh::MaxOrder));
}

void LightAbovePlanes(const EnvironmentMap& environment, int order, const float* planeNormals,
  int planes, double* red, double* green, double* blue, double* planeVisibility)
{
  const int h2 = sh::NumCoefficients(LightAbovePlanesOrder(order));
  std::vector<double> light(3 * h2);
  environment.ProjectSH(LightAbovePlanesOrder(order), &light[0], &light[h2], &light[2 * h2]);
  LightAbovePlanes(light, order, planeNormals, planes, red, green, blue, planeVisibility);
}

void LightAbovePlanes(const std::vector<double>& light, int order, const float* planeNormals,
  int planes, double* red, double* green, double* blue, double* planeVisibility)
{
  const int high = LightAbovePlanesOrder(order);
  const int n2 = sh::NumCoefficients(order), h2 = sh::NumCoefficients(high);
  if (light.size() != 3 * static_cast<std::size_t>(h2))
  {
    for (double* out : { red, green, blue, planeVisibility })
    {
      if (out)
      {
        std::fill(out, out + n2, 0.0);
      }
    }
    return; // not the projection this needs
  }
  std::vector<double> v(h2, 0.0), step(h2), product(h2), zh(high);
  // V = product of the steps (1 above each plane), at the high order.
  v[0] = std::sqrt(4.0 * sh::Pi);
  const sh::TripleProduct& tp = sh::TripleProduct::Get(high);
  sh::CapVisibilityZonal(high, 0.5 * sh::Pi, zh.data());
  for (int k = 0; k < planes; ++k)
  {
    const float* m = planeNormals + 3 * k;
    sh::RotateZonal(high, zh.data(), -double(m[0]), -double(m[1]), -double(m[2]), step.data());
    tp.Product(v.data(), step.data(), product.data());
    v = product;
  }
  double* out[3] = { red, green, blue };
  for (int c = 0; c < 3; ++c)
  {
    tp.Product(&light[c * h2], v.data(), product.data());
    std::copy(product.begin(), product.begin() + n2, out[c]);
  }
  if (planeVisibility)
  {
    std::copy(v.begin(), v.begin() + n2, planeVisibility);
  }
}

} // namespace proxygi
