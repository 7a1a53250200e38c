// Compiled once per instruction set by Highway's foreach_target.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pgiEnvironmentMapBatch.cxx"
#include "hwy/foreach_target.h" // IWYU pragma: keep

#include "hwy/highway.h"

#include "pgiEnvironmentMapBatch.h"

HWY_BEFORE_NAMESPACE();
namespace proxygi
{
namespace detail
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

// A vector of m's at a time, six sums (three channels, cos and sin) side by
// side over the row; no fused multiply-adds (and -ffp-contract=off for
// this file), so each sum rounds as the scalar loop's.
void RowSumsImpl(const float* rgb, int width, const double* cosInt, const double* sinInt,
  int stride, double* rowCos, double* rowSin)
{
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
  for (int m = 0; m < stride; m += lanes)
  {
    V c0 = hn::Zero(d), c1 = c0, c2 = c0, s0 = c0, s1 = c0, s2 = c0;
    for (int i = 0; i < width; ++i)
    {
      const float* texel = rgb + 3 * static_cast<long long>(i);
      const V r = hn::Set(d, static_cast<double>(texel[0]));
      const V g = hn::Set(d, static_cast<double>(texel[1]));
      const V b = hn::Set(d, static_cast<double>(texel[2]));
      const V cs = hn::LoadU(d, cosInt + static_cast<long long>(i) * stride + m);
      const V sn = hn::LoadU(d, sinInt + static_cast<long long>(i) * stride + m);
      c0 = hn::Add(c0, hn::Mul(r, cs));
      c1 = hn::Add(c1, hn::Mul(g, cs));
      c2 = hn::Add(c2, hn::Mul(b, cs));
      s0 = hn::Add(s0, hn::Mul(r, sn));
      s1 = hn::Add(s1, hn::Mul(g, sn));
      s2 = hn::Add(s2, hn::Mul(b, sn));
    }
    hn::StoreU(c0, d, rowCos + m);
    hn::StoreU(c1, d, rowCos + stride + m);
    hn::StoreU(c2, d, rowCos + 2 * stride + m);
    hn::StoreU(s0, d, rowSin + m);
    hn::StoreU(s1, d, rowSin + stride + m);
    hn::StoreU(s2, d, rowSin + 2 * stride + m);
  }
}

} // namespace HWY_NAMESPACE
} // namespace detail
} // namespace proxygi
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace proxygi
{
namespace detail
{
HWY_EXPORT(RowSumsImpl);

void RowSums(const float* rgb, int width, const double* cosInt, const double* sinInt, int stride,
  double* rowCos, double* rowSin)
{
  HWY_DYNAMIC_DISPATCH(RowSumsImpl)(rgb, width, cosInt, sinInt, stride, rowCos, rowSin);
}
} // namespace detail
} // namespace proxygi
#endif
