#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pgiBenchPeak.cxx"
#include "hwy/foreach_target.h" // IWYU pragma: keep

#include "hwy/highway.h"

#include "pgiBenchPeak.h"

HWY_BEFORE_NAMESPACE();
namespace proxygi
{
namespace bench
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

double FmaPeakImpl(long iterations, float* sink)
{
  const hn::ScalableTag<float> d;
  // Twelve chains: enough to cover the FMA latency (4 cycles) on two ports.
  auto a0 = hn::Set(d, 1.0f), a1 = hn::Set(d, 1.1f), a2 = hn::Set(d, 1.2f), a3 = hn::Set(d, 1.3f);
  auto a4 = hn::Set(d, 1.4f), a5 = hn::Set(d, 1.5f), a6 = hn::Set(d, 1.6f), a7 = hn::Set(d, 1.7f);
  auto a8 = hn::Set(d, 1.8f), a9 = hn::Set(d, 1.9f), a10 = hn::Set(d, 2.0f), a11 = hn::Set(d, 2.1f);
  const auto b = hn::Set(d, 0.999999f), c = hn::Set(d, 1e-7f);
  for (long i = 0; i < iterations; ++i)
  {
    a0 = hn::MulAdd(a0, b, c);
    a1 = hn::MulAdd(a1, b, c);
    a2 = hn::MulAdd(a2, b, c);
    a3 = hn::MulAdd(a3, b, c);
    a4 = hn::MulAdd(a4, b, c);
    a5 = hn::MulAdd(a5, b, c);
    a6 = hn::MulAdd(a6, b, c);
    a7 = hn::MulAdd(a7, b, c);
    a8 = hn::MulAdd(a8, b, c);
    a9 = hn::MulAdd(a9, b, c);
    a10 = hn::MulAdd(a10, b, c);
    a11 = hn::MulAdd(a11, b, c);
  }
  const auto sum = hn::Add(
    hn::Add(hn::Add(hn::Add(a0, a1), hn::Add(a2, a3)), hn::Add(hn::Add(a4, a5), hn::Add(a6, a7))),
    hn::Add(hn::Add(a8, a9), hn::Add(a10, a11)));
  *sink = hn::GetLane(hn::SumOfLanes(d, sum));
  return 2.0 * 12.0 * static_cast<double>(hn::Lanes(d)) * static_cast<double>(iterations);
}

int FmaPeakLanesImpl()
{
  return static_cast<int>(hn::Lanes(hn::ScalableTag<float>()));
}
} // namespace HWY_NAMESPACE
} // namespace bench
} // namespace proxygi
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace proxygi
{
namespace bench
{
HWY_EXPORT(FmaPeakImpl);
HWY_EXPORT(FmaPeakLanesImpl);

double FmaPeak(long iterations, float* sink)
{
  return HWY_DYNAMIC_DISPATCH(FmaPeakImpl)(iterations, sink);
}

int FmaPeakLanes()
{
  return HWY_DYNAMIC_DISPATCH(FmaPeakLanesImpl)();
}
} // namespace bench
} // namespace proxygi
#endif
