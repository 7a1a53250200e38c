// Compiled once per instruction set by Highway's foreach_target.h; the code
// between HWY_BEFORE_NAMESPACE and HWY_AFTER_NAMESPACE is the per-target part.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pgiSHBatch.cxx"
#include "hwy/foreach_target.h" // IWYU pragma: keep

#include "hwy/highway.h"

#include "pgiSHBasis.h"
#include "pgiSHBatch.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <vector>

HWY_BEFORE_NAMESPACE();
namespace proxygi
{
namespace sh
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<float>;
using V = hn::Vec<D>;
constexpr int W = BatchWidth;

// A vector the generated basis polynomials (written for a scalar T) accept.
struct Lane
{
  V v;
  Lane() = default;
  Lane(V x)
    : v(x)
  {
  }
  Lane(double c)
    : v(hn::Set(D(), static_cast<float>(c)))
  {
  }
};
inline Lane operator+(Lane a, Lane b)
{
  return Lane(hn::Add(a.v, b.v));
}
inline Lane operator-(Lane a, Lane b)
{
  return Lane(hn::Sub(a.v, b.v));
}
inline Lane operator*(Lane a, Lane b)
{
  return Lane(hn::Mul(a.v, b.v));
}

// EvaluateBasisPolynomial for one vector of directions (orders 1..8).
template <typename T>
HWY_INLINE void BasisLanes(int order, T x, T y, T z, T* out)
#include "pgiSHBasisPolynomials.inl"

  // One order at compile time: the accumulators stay in registers and the
  // basis unrolls.
  template <int Order>
  void AddCapsOfOrder(const CapTables& tables, int count, const float* theta, const float* dirX,
    const float* dirY, const float* dirZ, const float* ratios, float* f)
{
  constexpr int order = Order;
  const D d;
  const hn::RebindToSigned<D> di;
  const int lanes = static_cast<int>(hn::Lanes(d));
  constexpr int n2 = order * order;
  const int rows = tables.GetResolution(), last = rows - 1;
  const int tableOrder = tables.GetOrder();
  const float* table = tables.GetLogTableFloat().data();
#if HWY_TARGET != HWY_SCALAR
  const float* bands = tables.GetLogBandTable().data();
  const int bandStride = tables.GetLogBandStride();
#endif
  const V scale = hn::Set(d, static_cast<float>(tables.GetThetaScale()));
  const V lastRow = hn::Set(d, static_cast<float>(last));
  for (int k = 0; k < W; k += lanes)
  {
    // The lanes' accumulators stay in registers over all blockers.
    V acc[order * order];
    for (int i = 0; i < n2; ++i)
    {
      acc[i] = hn::Load(d, f + i * W + k);
    }
    for (int b = 0; b < count; ++b)
    {
      const V th = hn::Load(d, theta + b * W + k);
      const auto keep = hn::Ge(th, hn::Zero(d));
      if (hn::AllFalse(d, keep))
      {
        continue;
      }
      // CapTables::Lookup: row i and fraction t of u = theta * scale.
      const V u = hn::Min(hn::Max(hn::Mul(th, scale), hn::Zero(d)), lastRow);
      auto row = hn::ConvertTo(di, u);
      row = hn::Min(row, hn::Set(di, last - 1));
      const V t = hn::Sub(u, hn::ConvertTo(d, row));
      Lane zh[order];
      // Band l's value between the lanes' rows r0 and r1, times its ratio;
      // zero in skipped lanes.
      const auto interpolate = [&](int l, V r0, V r1)
      {
        V z = hn::Add(r0, hn::Mul(hn::Sub(r1, r0), t));
        if (ratios)
        {
          z = hn::Mul(z, hn::Set(d, ratios[b * order + l]));
        }
        return Lane(hn::IfThenElseZero(keep, z));
      };
#if HWY_TARGET != HWY_SCALAR
      // Neighbouring receivers see a blocker at nearly one angle: when the
      // lanes' rows fit in one vector from the lowest, the rows are loaded
      // and permuted into place (the same floats as the gathers).
      const auto keepRow = hn::RebindMask(di, keep);
      const int low =
        hn::GetLane(hn::MinOfLanes(di, hn::IfThenElse(keepRow, row, hn::Set(di, last))));
      const int high = hn::GetLane(hn::MaxOfLanes(di, hn::IfThenElseZero(keepRow, row)));
      if (high - low < lanes)
      {
        const auto at =
          hn::IndicesFromVec(d, hn::IfThenElseZero(keepRow, hn::Sub(row, hn::Set(di, low))));
        for (int l = 0; l < order; ++l)
        {
          const float* band = bands + l * bandStride + low;
          zh[l] = interpolate(l, hn::TableLookupLanes(hn::LoadU(d, band), at),
            hn::TableLookupLanes(hn::LoadU(d, band + 1), at));
        }
      }
      else
#endif
      {
        const auto base = hn::Mul(row, hn::Set(di, tableOrder));
        for (int l = 0; l < order; ++l)
        {
          const auto at = hn::Add(base, hn::Set(di, l));
          zh[l] = interpolate(l, hn::GatherIndex(d, table, at),
            hn::GatherIndex(d, table, hn::Add(at, hn::Set(di, tableOrder))));
        }
      }
      // Skipped lanes may hold any direction: zero it, so y stays finite.
      Lane y[order * order];
      BasisLanes(order, Lane(hn::IfThenElseZero(keep, hn::Load(d, dirX + b * W + k))),
        Lane(hn::IfThenElseZero(keep, hn::Load(d, dirY + b * W + k))),
        Lane(hn::IfThenElseZero(keep, hn::Load(d, dirZ + b * W + k))), y);
      // Unrolled, so the accumulators stay in registers.
#pragma GCC unroll 8
      for (int l = 0; l < order; ++l)
      {
#pragma GCC unroll 16
        for (int i = l * l; i < (l + 1) * (l + 1); ++i)
        {
          acc[i] = hn::Add(acc[i], hn::Mul(y[i].v, zh[l].v));
        }
      }
    }
    for (int i = 0; i < n2; ++i)
    {
      hn::Store(acc[i], d, f + i * W + k);
    }
  }
}

void BatchAddCapsImpl(const CapTables& tables, int order, int count, const float* theta,
  const float* dirX, const float* dirY, const float* dirZ, const float* ratios, float* f)
{
  switch (order)
  {
    case 1:
      return AddCapsOfOrder<1>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    case 2:
      return AddCapsOfOrder<2>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    case 3:
      return AddCapsOfOrder<3>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    case 4:
      return AddCapsOfOrder<4>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    case 5:
      return AddCapsOfOrder<5>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    case 6:
      return AddCapsOfOrder<6>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    case 7:
      return AddCapsOfOrder<7>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
    default:
      return AddCapsOfOrder<8>(tables, count, theta, dirX, dirY, dirZ, ratios, f);
  }
}

// One table look-up per band for a vector of angles: rows of `order` floats
// (CapTables and IndirectTables lay theirs out alike), linear between rows.
HWY_INLINE void TableLanes(
  const float* table, int resolution, float thetaScale, int order, V theta, Lane* out)
{
  const D d;
  const hn::RebindToSigned<D> di;
  const int last = resolution - 1;
  const V u = hn::Min(hn::Max(hn::Mul(theta, hn::Set(d, thetaScale)), hn::Zero(d)),
    hn::Set(d, static_cast<float>(last)));
  auto row = hn::Min(hn::ConvertTo(di, u), hn::Set(di, last - 1));
  const V t = hn::Sub(u, hn::ConvertTo(d, row));
  const auto base = hn::Mul(row, hn::Set(di, order));
  for (int l = 0; l < order; ++l)
  {
    const auto at = hn::Add(base, hn::Set(di, l));
    const V r0 = hn::GatherIndex(d, table, at);
    const V r1 = hn::GatherIndex(d, table, hn::Add(at, hn::Set(di, order)));
    out[l] = Lane(hn::Add(r0, hn::Mul(hn::Sub(r1, r0), t)));
  }
}

void BatchIndirectWeightsImpl(const CapTables& caps, const IndirectTables& indirect, int order,
  const float* theta, const float* dirX, const float* dirY, const float* dirZ, const float* h,
  int channels, const float* radiances, float* capWeight, float* kappa)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const float fourPi = static_cast<float>(4.0 * Pi);
  for (int k = 0; k < W; k += lanes)
  {
    const V th = hn::Load(d, theta + k);
    const auto keep = hn::Ge(th, hn::Zero(d));
    Lane zCap[MaxOrder], zAveraged[MaxOrder], y[MaxCoefficients];
    TableLanes(caps.GetVisibilityTableFloat().data(), caps.GetResolution(),
      static_cast<float>(caps.GetThetaScale()), order, th, zCap);
    // Visibility -> the cap itself: 4 pi - v_0, then -v_l.
    zCap[0] = Lane(hn::Sub(hn::Set(d, fourPi), zCap[0].v));
    for (int l = 1; l < order; ++l)
    {
      zCap[l] = Lane(hn::Neg(zCap[l].v));
    }
    // Skipped lanes may hold any direction: zero it, so y stays finite.
    BasisLanes(order, Lane(hn::IfThenElseZero(keep, hn::Load(d, dirX + k))),
      Lane(hn::IfThenElseZero(keep, hn::Load(d, dirY + k))),
      Lane(hn::IfThenElseZero(keep, hn::Load(d, dirZ + k))), y);
    // Band by band, as the scalar code sums.
    V weight = hn::Zero(d);
    for (int l = 0; l < order; ++l)
    {
      V band = hn::Zero(d);
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        band = hn::Add(band, hn::Mul(hn::Set(d, h[i]), y[i].v));
      }
      weight = hn::Add(weight, hn::Mul(zCap[l].v, band));
    }
    hn::Store(hn::IfThenElseZero(keep, weight), d, capWeight + k);
    if (channels <= 0)
    {
      continue;
    }
    TableLanes(indirect.GetAveragedTableFloat().data(), indirect.GetResolution(),
      static_cast<float>(indirect.GetThetaScale()), order, th, zAveraged);
    const int n2 = order * order;
    for (int c = 0; c < channels; ++c)
    {
      const float* r = radiances + c * n2;
      V sum = hn::Zero(d);
      for (int l = 0; l < order; ++l)
      {
        V band = hn::Zero(d);
        for (int i = l * l; i < (l + 1) * (l + 1); ++i)
        {
          band = hn::Add(band, hn::Mul(y[i].v, hn::Set(d, r[i])));
        }
        sum = hn::Add(sum, hn::Mul(zAveraged[l].v, band));
      }
      hn::Store(hn::IfThenElseZero(keep, sum), d, kappa + c * W + k);
    }
  }
}

} // namespace HWY_NAMESPACE
} // namespace sh
} // namespace proxygi
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace proxygi
{
namespace sh
{
HWY_EXPORT(BatchAddCapsImpl);
HWY_EXPORT(BatchIndirectWeightsImpl);

namespace
{
bool& EnabledFlag()
{
  static bool enabled = []()
  {
    const char* env = std::getenv("PROXYGI_SIMD");
    return !(env && env[0] == '0');
  }();
  return enabled;
}
} // namespace

bool BatchKernelsEnabled()
{
  return EnabledFlag();
}

void SetBatchKernelsEnabled(bool enabled)
{
  EnabledFlag() = enabled;
}

namespace
{
// Targets compiled in and supported, best first, read before any mock.
const std::vector<std::int64_t>& Available()
{
  static const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets;
}
std::int64_t& Forced()
{
  static std::int64_t target = 0;
  return target;
}
} // namespace

const char* BatchTargetName()
{
  if (!BatchKernelsEnabled())
  {
    return "scalar";
  }
  // HWY_DYNAMIC_DISPATCH picks the best target compiled in that the CPU runs.
  const std::int64_t chosen = Forced() ? Forced() : (Available().empty() ? 0 : Available()[0]);
  return chosen ? hwy::TargetName(chosen) : "baseline";
}

std::vector<std::string> BatchTargets()
{
  std::vector<std::string> names;
  for (std::int64_t target : Available())
  {
    names.emplace_back(hwy::TargetName(target));
  }
  return names;
}

bool SetBatchTarget(const std::string& name)
{
  static std::mutex lock;
  const std::lock_guard<std::mutex> guard(lock);
  if (name.empty())
  {
    Forced() = 0;
    hwy::SetSupportedTargetsForTest(0);
    return true;
  }
  for (std::int64_t target : Available())
  {
    if (name == hwy::TargetName(target))
    {
      Forced() = target;
      hwy::SetSupportedTargetsForTest(target);
      return true;
    }
  }
  return false;
}

void BatchAddCaps(const CapTables& tables, int order, int count, const float* theta,
  const float* dirX, const float* dirY, const float* dirZ, const float* ratios, float* f)
{
  HWY_DYNAMIC_DISPATCH(BatchAddCapsImpl)
  (tables, order, count, theta, dirX, dirY, dirZ, ratios, f);
}

void BatchIndirectWeights(const CapTables& caps, const IndirectTables& indirect, int order,
  const float* theta, const float* dirX, const float* dirY, const float* dirZ, const float* h,
  int channels, const float* radiances, float* capWeight, float* kappa)
{
  if (BatchKernelsEnabled())
  {
    HWY_DYNAMIC_DISPATCH(BatchIndirectWeightsImpl)
    (caps, indirect, order, theta, dirX, dirY, dirZ, h, channels, radiances, capWeight, kappa);
    return;
  }
  // The scalar twin, lane by lane.
  constexpr int W = BatchWidth;
  const int n2 = NumCoefficients(order);
  const float* rows[3] = { radiances, radiances + n2, radiances + 2 * n2 };
  for (int q = 0; q < W; ++q)
  {
    if (!(theta[q] >= 0.0f))
    {
      capWeight[q] = 0.0f;
      for (int c = 0; c < channels; ++c)
      {
        kappa[c * W + q] = 0.0f;
      }
      continue;
    }
    float zh[MaxOrder], basis[MaxCoefficients];
    caps.CapVisibility(theta[q], zh);
    zh[0] = static_cast<float>(4.0 * Pi) - zh[0]; // visibility -> cap (scaled ZH)
    for (int l = 1; l < order; ++l)
    {
      zh[l] = -zh[l];
    }
    // The basis serves the cap and the averaged radiance; the dot product
    // band by band (short independent sums).
    EvaluateBasis(order, dirX[q], dirY[q], dirZ[q], basis);
    float weight = 0.0f;
    for (int l = 0; l < order; ++l)
    {
      float band = 0.0f;
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        band += h[i] * basis[i];
      }
      weight += zh[l] * band;
    }
    capWeight[q] = weight;
    if (channels > 0)
    {
      float k[3];
      indirect.AveragedRadiancesFromBasis(theta[q], basis, channels, rows, k);
      for (int c = 0; c < channels; ++c)
      {
        kappa[c * W + q] = k[c];
      }
    }
  }
}

} // namespace sh
} // namespace proxygi
#endif
