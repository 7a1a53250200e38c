#include "pgiEnvironmentMap.h"

#include "pgiEnvironmentMapBatch.h"
#include "pgiSHBasis.h"
#include "pgiSHBatch.h"
#include "pgiSHZonal.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace proxygi
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

double Luminance(const float* rgb)
{
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}
} // namespace

EnvironmentMap EnvironmentMap::Uniform(float r, float g, float b)
{
  EnvironmentMap map;
  const float rgb[6] = { r, g, b, r, g, b };
  std::string error;
  map.Set(2, 1, rgb, error);
  return map;
}

bool EnvironmentMap::Set(int width, int height, const float* rgb, std::string& error)
{
  if (width < 2 || height < 1 || width != 2 * height)
  {
    return this->Set(width, height, std::vector<float>(), error);
  }
  return this->Set(width, height,
    std::vector<float>(rgb, rgb + static_cast<std::size_t>(width) * height * 3), error);
}

bool EnvironmentMap::Set(int width, int height, std::vector<float>&& rgb, std::string& error)
{
  if (width < 2 || height < 1 || width != 2 * height)
  {
    error = "a lat-long environment map must be twice as wide as high (got " +
      std::to_string(width) + " x " + std::to_string(height) + ")";
    return false;
  }
  const std::size_t count = static_cast<std::size_t>(width) * height * 3;
  if (rgb.size() != count)
  {
    error = "environment map rows hold " + std::to_string(rgb.size()) + " values, not " +
      std::to_string(count);
    return false;
  }
  for (std::size_t k = 0; k < count; ++k)
  {
    if (!std::isfinite(rgb[k]) || rgb[k] < 0.0f)
    {
      error = "environment map holds NaN, Inf or negative radiance";
      return false;
    }
  }
  this->Width = width;
  this->Height = height;
  this->RGB = std::move(rgb);
  this->Sampling = std::make_shared<SamplerTables>();
  return true;
}

void EnvironmentMap::SetFromFunction(
  int width, int height, void (*radiance)(const double[3], float[3], void*), void* data)
{
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int j = 0; j < height; ++j)
  {
    const double theta = Pi * (j + 0.5) / height;
    for (int i = 0; i < width; ++i)
    {
      const double phi = 2 * Pi * (i + 0.5) / width;
      const double d[3] = { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
        std::cos(theta) };
      radiance(d, &rgb[3 * (static_cast<std::size_t>(j) * width + i)], data);
    }
  }
  std::string error;
  this->Set(width, height, std::move(rgb), error);
}

bool EnvironmentMap::FromImage(vtkImageData* image, EnvironmentMap& map, std::string& error)
{
  if (!image)
  {
    error = "no environment image";
    return false;
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
  {
    scalars = image->GetPointData()->GetArray("Radiance");
  }
  if (!scalars || scalars->GetNumberOfComponents() < 3)
  {
    error = "environment image needs an RGB (3- or 4-component) point array";
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  if (dims[2] != 1)
  {
    error = "environment image must be 2-D";
    return false;
  }
  std::vector<float> rgb(static_cast<std::size_t>(dims[0]) * dims[1] * 3);
  // Float texels (the EXR reader's) straight from memory; others through
  // the generic accessor.
  vtkFloatArray* floats = vtkFloatArray::FastDownCast(scalars);
  const int components = scalars->GetNumberOfComponents();
  for (int j = 0; j < dims[1]; ++j)
  {
    // VTK rows run bottom-up; the map's rows top-down.
    const int row = dims[1] - 1 - j;
    for (int i = 0; i < dims[0]; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(row) * dims[0] + i;
      float* out = &rgb[3 * (static_cast<std::size_t>(j) * dims[0] + i)];
      if (floats)
      {
        std::copy_n(floats->GetPointer(id * components), 3, out);
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        out[c] = static_cast<float>(scalars->GetComponent(id, c));
      }
    }
  }
  return map.Set(dims[0], dims[1], std::move(rgb), error);
}

void EnvironmentMap::ToImage(vtkImageData* image) const
{
  image->SetDimensions(this->Width, this->Height, 1);
  image->SetSpacing(1, 1, 1);
  image->SetOrigin(0, 0, 0);
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(static_cast<vtkIdType>(this->Width) * this->Height);
  for (int j = 0; j < this->Height; ++j)
  {
    const int row = this->Height - 1 - j;
    for (int i = 0; i < this->Width; ++i)
    {
      radiance->SetTypedTuple(static_cast<vtkIdType>(row) * this->Width + i,
        &this->RGB[3 * (static_cast<std::size_t>(j) * this->Width + i)]);
    }
  }
  image->GetPointData()->SetScalars(radiance);
}

void EnvironmentMap::SetRotation(double radians)
{
  this->Rotation = radians;
  this->CosR = std::cos(radians);
  this->SinR = std::sin(radians);
}

void EnvironmentMap::ToMap(const double w[3], double m[3]) const
{
  m[0] = this->CosR * w[0] + this->SinR * w[1];
  m[1] = -this->SinR * w[0] + this->CosR * w[1];
  m[2] = w[2];
}

void EnvironmentMap::ToWorld(const double m[3], double w[3]) const
{
  w[0] = this->CosR * m[0] - this->SinR * m[1];
  w[1] = this->SinR * m[0] + this->CosR * m[1];
  w[2] = m[2];
}

const EnvironmentMap::SamplerTables& EnvironmentMap::Sampler() const
{
  SamplerTables& tables = *this->Sampling;
  std::call_once(tables.Built, [&]() { this->BuildSampler(tables); });
  return tables;
}

void EnvironmentMap::BuildSampler(SamplerTables& tables) const
{
  const int w = this->Width, h = this->Height;
  tables.TexelWeight.assign(static_cast<std::size_t>(w) * h, 0.0);
  tables.ColumnCdf.assign(static_cast<std::size_t>(w + 1) * h, 0.0);
  tables.RowCdf.assign(h + 1, 0.0);
  double total = 0.0;
  for (int pass = 0; pass < 2 && total <= 0.0; ++pass)
  {
    // Second pass only for an all-black map: sample by solid angle.
    total = 0.0;
    for (int j = 0; j < h; ++j)
    {
      const double solid = (2 * Pi / w) * (std::cos(Pi * j / h) - std::cos(Pi * (j + 1) / h));
      double rowSum = 0.0;
      double* cdf = &tables.ColumnCdf[static_cast<std::size_t>(j) * (w + 1)];
      cdf[0] = 0.0;
      for (int i = 0; i < w; ++i)
      {
        const float* rgb = &this->RGB[3 * (static_cast<std::size_t>(j) * w + i)];
        const double weight = (pass == 0 ? Luminance(rgb) : 1.0) * solid;
        tables.TexelWeight[static_cast<std::size_t>(j) * w + i] = weight;
        rowSum += weight;
        cdf[i + 1] = rowSum;
      }
      total += rowSum;
      tables.RowCdf[j + 1] = total;
    }
  }
  tables.TotalWeight = total;
}

namespace
{
// Index k with cdf[k] <= u * cdf[n] < cdf[k + 1], skipping empty bins.
int FindBin(const double* cdf, int n, double u, double& fraction)
{
  const double target = u * cdf[n];
  int k = static_cast<int>(std::upper_bound(cdf, cdf + n + 1, target) - cdf) - 1;
  k = std::max(0, std::min(n - 1, k));
  while (k < n - 1 && cdf[k + 1] <= cdf[k])
  {
    ++k;
  }
  const double width = cdf[k + 1] - cdf[k];
  fraction = width > 0.0 ? std::min(1.0, std::max(0.0, (target - cdf[k]) / width)) : 0.5;
  return k;
}
} // namespace

double EnvironmentMap::Sample(double u1, double u2, double d[3], float rgb[3]) const
{
  const SamplerTables& tables = this->Sampler();
  const int w = this->Width, h = this->Height;
  double fj, fi;
  const int j = FindBin(tables.RowCdf.data(), h, u1, fj);
  const int i = FindBin(&tables.ColumnCdf[static_cast<std::size_t>(j) * (w + 1)], w, u2, fi);
  // Uniform in solid angle inside the texel: phi and cos(theta) uniform.
  const double z0 = std::cos(Pi * j / h), z1 = std::cos(Pi * (j + 1) / h);
  const double z = z0 + (z1 - z0) * fj;
  const double phi = 2 * Pi * (i + fi) / w;
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double m[3] = { s * std::cos(phi), s * std::sin(phi), z };
  this->ToWorld(m, d);
  const float* texel = &this->RGB[3 * (static_cast<std::size_t>(j) * w + i)];
  rgb[0] = texel[0];
  rgb[1] = texel[1];
  rgb[2] = texel[2];
  const double solid = (2 * Pi / w) * (z0 - z1);
  return tables.TexelWeight[static_cast<std::size_t>(j) * w + i] / tables.TotalWeight / solid;
}

namespace
{
void TexelOf(const double m[3], int w, int h, int& i, int& j)
{
  const double z = std::max(-1.0, std::min(1.0, m[2]));
  double phi = std::atan2(m[1], m[0]);
  if (phi < 0.0)
  {
    phi += 2 * Pi;
  }
  i = std::min(w - 1, std::max(0, static_cast<int>(phi / (2 * Pi) * w)));
  j = std::min(h - 1, std::max(0, static_cast<int>(std::acos(z) / Pi * h)));
}
} // namespace

double EnvironmentMap::Pdf(const double d[3]) const
{
  double m[3];
  this->ToMap(d, m);
  int i, j;
  TexelOf(m, this->Width, this->Height, i, j);
  const double solid = (2 * Pi / this->Width) *
    (std::cos(Pi * j / this->Height) - std::cos(Pi * (j + 1) / this->Height));
  const SamplerTables& tables = this->Sampler();
  return tables.TexelWeight[static_cast<std::size_t>(j) * this->Width + i] / tables.TotalWeight /
    solid;
}

void EnvironmentMap::Lookup(const double d[3], float rgb[3]) const
{
  double m[3];
  this->ToMap(d, m);
  int i, j;
  TexelOf(m, this->Width, this->Height, i, j);
  const float* texel = &this->RGB[3 * (static_cast<std::size_t>(j) * this->Width + i)];
  rgb[0] = texel[0];
  rgb[1] = texel[1];
  rgb[2] = texel[2];
}

void EnvironmentMap::Mean(double rgb[3]) const
{
  rgb[0] = rgb[1] = rgb[2] = 0.0;
  for (int j = 0; j < this->Height; ++j)
  {
    const double solid = (2 * Pi / this->Width) *
      (std::cos(Pi * j / this->Height) - std::cos(Pi * (j + 1) / this->Height));
    for (int i = 0; i < this->Width; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] += solid * this->RGB[3 * (static_cast<std::size_t>(j) * this->Width + i) + c];
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] /= 4 * Pi;
  }
}

void EnvironmentMap::ProjectSH(int order, double* red, double* green, double* blue) const
{
  // y_lm is separable in (z, phi): integrate each texel exactly in phi and by
  // 8-point Gauss-Legendre in z (exact for even m, ~1e-12 for odd m).
  const int w = this->Width, h = this->Height, n2 = sh::NumCoefficients(order);
  double* out[3] = { red, green, blue };
  for (double* o : out)
  {
    std::fill(o, o + n2, 0.0);
  }
  // Column integrals of cos(m phi_world) and sin(m phi_world), phi_world = phi
  // + rotation; `stride` per column (zeros past the order) for RowSums.
  const int stride = detail::RowSumsStride(order);
  std::vector<double> cosInt(static_cast<std::size_t>(w) * stride, 0.0),
    sinInt(static_cast<std::size_t>(w) * stride, 0.0);
  for (int i = 0; i < w; ++i)
  {
    const double a = 2 * Pi * i / w + this->Rotation, b = 2 * Pi * (i + 1) / w + this->Rotation;
    for (int m = 0; m < order; ++m)
    {
      if (m == 0)
      {
        cosInt[i * stride] = b - a;
        sinInt[i * stride] = 0.0;
      }
      else
      {
        cosInt[i * stride + m] = (std::sin(m * b) - std::sin(m * a)) / m;
        sinInt[i * stride + m] = (std::cos(m * a) - std::cos(m * b)) / m;
      }
    }
  }
  // Each row's z integrals and phi sums on its own (rows in parallel), then
  // the rows added in order: the same sums, in the same order, as one pass.
  std::vector<double> nodes, weights;
  // The rule on [0, 1] once, mapped onto each row's z interval.
  sh::GaussLegendre(8, 0.0, 1.0, nodes, weights);
  const std::size_t perRow = static_cast<std::size_t>(n2) + 6 * static_cast<std::size_t>(stride);
  const bool batched = sh::BatchKernelsEnabled();
  std::vector<double> rows(perRow * static_cast<std::size_t>(h), 0.0);
  vtkSMPTools::For(0, h,
    [&](vtkIdType first, vtkIdType last)
    {
      std::vector<double> basis(n2);
      for (vtkIdType j = first; j < last; ++j)
      {
        double* zInt = &rows[perRow * j];
        double* rowCos = zInt + n2;
        double* rowSin = rowCos + 3 * stride;
        // z integrals of y_l|m| at phi = 0 (carries K_lm, sqrt(2), sin^m theta).
        const double z0 = std::cos(Pi * (j + 1) / h), z1 = std::cos(Pi * j / h);
        for (std::size_t q = 0; q < nodes.size(); ++q)
        {
          const double z = z0 + (z1 - z0) * nodes[q], s = std::sqrt(std::max(0.0, 1.0 - z * z));
          sh::EvaluateBasis(order, s, 0.0, z, basis.data());
          for (int i = 0; i < n2; ++i)
          {
            zInt[i] += (z1 - z0) * weights[q] * basis[i];
          }
        }
        const float* row = &this->RGB[3 * static_cast<std::size_t>(j) * w];
        if (batched)
        {
          detail::RowSums(row, w, cosInt.data(), sinInt.data(), stride, rowCos, rowSin);
          continue;
        }
        for (int i = 0; i < w; ++i)
        {
          const float* rgb = row + 3 * static_cast<std::size_t>(i);
          for (int m = 0; m < order; ++m)
          {
            for (int c = 0; c < 3; ++c)
            {
              rowCos[c * stride + m] += rgb[c] * cosInt[i * stride + m];
              rowSin[c * stride + m] += rgb[c] * sinInt[i * stride + m];
            }
          }
        }
      }
    });
  for (int j = 0; j < h; ++j)
  {
    const double* zInt = &rows[perRow * j];
    const double* rowCos = zInt + n2;
    const double* rowSin = rowCos + 3 * stride;
    for (int l = 0; l < order; ++l)
    {
      for (int m = -l; m <= l; ++m)
      {
        const int am = m < 0 ? -m : m;
        const double zl = zInt[sh::Index(l, am)];
        for (int c = 0; c < 3; ++c)
        {
          out[c][sh::Index(l, m)] +=
            zl * (m < 0 ? rowSin[c * stride + am] : rowCos[c * stride + am]);
        }
      }
    }
  }
}

void EnvironmentMap::ProjectIrradianceSH(int order, double* red, double* green, double* blue) const
{
  this->ProjectSH(order, red, green, blue);
  double kernel[sh::MaxBasisOrder];
  sh::ClampedCosineZonal(order, kernel);
  for (double* channel : { red, green, blue })
  {
    sh::ConvolveZonal(order, kernel, channel);
  }
}

} // namespace proxygi
