#include "pgiSHTables.h"

#include "pgiSHTableCache.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace proxygi
{
namespace sh
{

constexpr int CapTables::DefaultResolution;
constexpr double CapTables::MaxAngle;
constexpr int CapTables::BandPadding;

namespace
{
// Cap log as a ZH (unscaled): the eigen-inversion log of the zonal vector.
void CapLogZonal(int order, double theta, const LogOptions& options, double* zh)
{
  double zv[MaxOrder];
  CapVisibilityZonal(order, theta, zv);
  LogZonal(order, zv, zh, options);
}
} // namespace

CapTables::CapTables(int order, int resolution, const LogOptions& log)
  : Order(order)
  , Resolution(resolution)
{
  if (order < 1 || order > MaxOrder)
  {
    throw std::invalid_argument("CapTables: order out of range");
  }
  if (resolution < 2)
  {
    throw std::invalid_argument("CapTables: resolution must be at least 2");
  }
  this->ThetaScale = (resolution - 1) / MaxAngle;
  this->Visibility.resize(resolution * order);
  this->LogD.resize(resolution * order);
  // The cap logs, an eigen-inversion each (the tables' cost): at the
  // table's angles, then at the fit's, finer (sample 0 unused). Read from
  // the disk cache where it holds them, else computed (in parallel: a
  // process's first update waits on these tables) and written there.
  const int fitSamples = 4 * resolution;
  const auto angle = [&](int s)
  {
    return s < resolution ? MaxAngle * s / (resolution - 1)
                          : MaxAngle * (s - resolution) / (fitSamples - 1);
  };
  std::vector<double> logs(static_cast<std::size_t>(resolution + fitSamples) * order, 0.0);
  const auto capLog = [&](int s, double* zf)
  {
    if (s != resolution)
    {
      CapLogZonal(order, angle(s), log, zf);
    }
  };
  char name[160];
  std::snprintf(name, sizeof(name), "cap-logs-order%d-resolution%d-clip%a-floor%a.bin", order,
    resolution, log.RelativeClip, log.AbsoluteFloor);
  TripleProduct::Get(order);
  CachedSamples(name, order, logs, capLog);
  for (int i = 0; i < resolution; ++i)
  {
    double zv[MaxOrder];
    CapVisibilityZonal(order, angle(i), zv);
    for (int l = 0; l < order; ++l)
    {
      this->Visibility[i * order + l] = zv[l] * ZonalScale(l);
      this->LogD[i * order + l] = logs[i * order + l] * ZonalScale(l);
    }
  }
  this->VisibilityF.assign(this->Visibility.begin(), this->Visibility.end());
  this->LogF.assign(this->LogD.begin(), this->LogD.end());
  const int stride = this->GetLogBandStride();
  this->LogBands.resize(static_cast<std::size_t>(order) * stride);
  for (int l = 0; l < order; ++l)
  {
    for (int i = 0; i < stride; ++i)
    {
      this->LogBands[l * stride + i] = this->LogF[std::min(i, resolution - 1) * order + l];
    }
  }

  // Optimal linear fit (eq. 24) on caps sampled finer than the output grid.
  std::vector<double> xs(1, 0.0), as(1, 1.0), bs(1, 1.0);
  for (int i = 1; i < fitSamples; ++i)
  {
    double zv[MaxOrder];
    CapVisibilityZonal(order, angle(resolution + i), zv);
    const double* zf = &logs[static_cast<std::size_t>(resolution + i) * order];
    // ZH vectors: the dot products over m reduce to l sums.
    const double dc = std::exp(-zf[0] / SqrtFourPi);
    double fHatSq = 0.0, gDotF = 0.0;
    for (int l = 1; l < order; ++l)
    {
      fHatSq += zf[l] * zf[l];
      gDotF += dc * zv[l] * zf[l];
    }
    const double x = std::sqrt(fHatSq);
    if (!(x > xs.back()))
    {
      break; // keep the monotone part only
    }
    xs.push_back(x);
    as.push_back(dc * zv[0] / SqrtFourPi);
    bs.push_back(fHatSq > 0.0 ? gDotF / fHatSq : 1.0);
  }
  this->OLMaxNorm = xs.back();
  this->OLA.resize(resolution);
  this->OLB.resize(resolution);
  if (xs.size() < 2)
  {
    // Order 1: a cap's log has no non-constant part, so the fit is its
    // value at |f^| = 0 (the loop below would read past the one sample).
    this->OLScale = 0.0;
    std::fill(this->OLA.begin(), this->OLA.end(), as[0]);
    std::fill(this->OLB.begin(), this->OLB.end(), bs[0]);
    return;
  }
  this->OLScale = (resolution - 1) / this->OLMaxNorm;
  std::size_t j = 0;
  for (int i = 0; i < resolution; ++i)
  {
    const double x = this->OLMaxNorm * i / (resolution - 1);
    while (j + 2 < xs.size() && xs[j + 1] < x)
    {
      ++j;
    }
    const double t = std::min(1.0, std::max(0.0, (x - xs[j]) / (xs[j + 1] - xs[j])));
    this->OLA[i] = as[j] + (as[j + 1] - as[j]) * t;
    this->OLB[i] = bs[j] + (bs[j + 1] - bs[j]) * t;
  }
}

const CapTables& CapTables::Get(int order)
{
  if (order < 1 || order > MaxOrder)
  {
    throw std::invalid_argument("CapTables::Get: order out of range");
  }
  static std::array<std::unique_ptr<CapTables>, MaxOrder + 1> cache;
  static std::array<std::once_flag, MaxOrder + 1> once;
  std::call_once(once[order], [order]() { cache[order].reset(new CapTables(order)); });
  return *cache[order];
}

} // namespace sh
} // namespace proxygi
