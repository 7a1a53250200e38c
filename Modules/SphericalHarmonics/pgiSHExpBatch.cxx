// The batched exp (HYB): compiled once per instruction set by Highway's
// foreach_target.h, and built with -ffp-contract=off, so that every Mul and
// Add rounds as the scalar exp's: the squarings double any relative
// difference per step, so the lanes are held to the scalar code bit for bit
// (fused multiply-adds only where the file says so).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pgiSHExpBatch.cxx"
#include "hwy/foreach_target.h" // IWYU pragma: keep

#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"

#include "pgiSHBatch.h"
#include "pgiSHExp.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#ifndef PGI_SH_EXP_BATCH_ONCE
#define PGI_SH_EXP_BATCH_ONCE
namespace proxygi
{
namespace sh
{
namespace batch
{
// Square's terms grouped by output coefficient, each with its factor
// (2 Gamma for j < k), in TripleProduct's order: out[i] = sum over
// [Start[i], Start[i+1]) of (C f_J) f_K.
struct SquareProgram
{
  std::vector<std::uint32_t> Start;
  std::vector<std::uint16_t> J, K;
  std::vector<float> C;
  explicit SquareProgram(int order)
  {
    const TripleProduct& tp = TripleProduct::Get(order);
    const int n2 = NumCoefficients(order);
    this->Start.assign(n2 + 1, 0);
    for (const TripleProduct::Term& t : tp.Terms()) // sorted by I
    {
      this->J.push_back(t.J);
      this->K.push_back(t.K);
      this->C.push_back(t.J == t.K ? t.ValueF : 2.0f * t.ValueF);
      ++this->Start[t.I + 1];
    }
    for (int i = 0; i < n2; ++i)
    {
      this->Start[i + 1] += this->Start[i];
    }
  }
  static const SquareProgram& Get(int order)
  {
    static std::array<std::unique_ptr<SquareProgram>, MaxOrder + 1> cache;
    static std::array<std::once_flag, MaxOrder + 1> once;
    std::call_once(once[order], [order]() { cache[order].reset(new SquareProgram(order)); });
    return *cache[order];
  }
};
} // namespace batch
} // namespace sh
} // namespace proxygi
#endif

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

// out = f * f over BatchWidth lanes: TripleProduct::Square's terms in its
// order, ((C f_J) f_K) added to the sum.
void SquareLanes(const batch::SquareProgram& program, int n2, const float* f, float* out)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  for (int k = 0; k < W; k += lanes)
  {
    for (int i = 0; i < n2; ++i)
    {
      V acc = hn::Zero(d);
      for (std::uint32_t t = program.Start[i]; t < program.Start[i + 1]; ++t)
      {
        const V fj = hn::Load(d, f + program.J[t] * W + k);
        const V fk = hn::Load(d, f + program.K[t] * W + k);
        acc = hn::Add(acc, hn::Mul(hn::Mul(hn::Set(d, program.C[t]), fj), fk));
      }
      hn::Store(acc, d, out + i * W + k);
    }
  }
}

void BatchSquareImpl(int order, const float* f, float* out)
{
  SquareLanes(batch::SquareProgram::Get(order), NumCoefficients(order), f, out);
}

// g = a g + b h in the lanes where b > 0 (HybridExp's blend).
void BlendImpl(int n2, const float* a, const float* b, const float* h, float* g)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  for (int k = 0; k < W; k += lanes)
  {
    const V bk = hn::Load(d, b + k), ak = hn::Load(d, a + k);
    const auto take = hn::Gt(bk, hn::Zero(d));
    for (int i = 0; i < n2; ++i)
    {
      const V gi = hn::Load(d, g + i * W + k);
      const V mixed = hn::Add(hn::Mul(ak, gi), hn::Mul(bk, hn::Load(d, h + i * W + k)));
      hn::Store(hn::IfThenElse(take, mixed, gi), d, g + i * W + k);
    }
  }
}

// s squarings per lane: g = g^(2^steps[lane]).
void RepeatedSquareImpl(int order, const std::int32_t* steps, float* g)
{
  const D d;
  const hn::RebindToSigned<D> di;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const int n2 = NumCoefficients(order);
  const batch::SquareProgram& program = batch::SquareProgram::Get(order);
  int most = 0;
  for (int k = 0; k < W; ++k)
  {
    most = std::max(most, static_cast<int>(steps[k]));
  }
  alignas(64) float squared[MaxCoefficients * W];
  for (int step = 0; step < most; ++step)
  {
    SquareLanes(program, n2, g, squared);
    for (int k = 0; k < W; k += lanes)
    {
      const auto take = hn::RebindMask(d, hn::Gt(hn::Load(di, steps + k), hn::Set(di, step)));
      for (int i = 0; i < n2; ++i)
      {
        const V old = hn::Load(d, g + i * W + k);
        hn::Store(hn::IfThenElse(take, hn::Load(d, squared + i * W + k), old), d, g + i * W + k);
      }
    }
  }
}

// The guard's sampled extremes of the reconstruction, per lane; each sample's
// sum as the scalar Dot rounds it.
void GuardExtremesImpl(int order, const float* g, float* vmin, float* vmax)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const int n2 = NumCoefficients(order);
  int count = 0;
  const float* basis = GuardBasis(order, count);
  for (int k = 0; k < W; k += lanes)
  {
    V c[MaxCoefficients];
    for (int i = 0; i < n2; ++i)
    {
      c[i] = hn::Load(d, g + i * W + k);
    }
    V lo = hn::Set(d, HUGE_VALF), hi = hn::Set(d, -HUGE_VALF);
    // Four samples at a time: four independent chains of sums
    // (each sample's sum keeps its order).
    constexpr int group = 4;
    int s = 0;
    for (; s + group <= count; s += group)
    {
      const float* y = basis + s * n2;
      V v[group];
      for (int q = 0; q < group; ++q)
      {
        v[q] = hn::Mul(c[0], hn::Set(d, y[q * n2]));
      }
      for (int i = 1; i < n2; ++i)
      {
        for (int q = 0; q < group; ++q)
        {
          v[q] = hn::Add(v[q], hn::Mul(c[i], hn::Set(d, y[q * n2 + i])));
        }
      }
      for (int q = 0; q < group; ++q)
      {
        lo = hn::Min(lo, v[q]);
        hi = hn::Max(hi, v[q]);
      }
    }
    for (; s < count; ++s)
    {
      const float* y = basis + s * n2;
      V v = hn::Mul(c[0], hn::Set(d, y[0]));
      for (int i = 1; i < n2; ++i)
      {
        v = hn::Add(v, hn::Mul(c[i], hn::Set(d, y[i])));
      }
      lo = hn::Min(lo, v);
      hi = hn::Max(hi, v);
    }
    hn::Store(lo, d, vmin + k);
    hn::Store(hi, d, vmax + k);
  }
}

// Per lane: 1 where every coefficient is finite (else 0), and the sum of
// squares of rows 1..n2-1 added in row order (the scalar sum's order).
void LaneNormsImpl(int n2, const float* f, float* norm2, float* finite)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  for (int k = 0; k < W; k += lanes)
  {
    const V first = hn::Load(d, f + k);
    auto ok = hn::IsFinite(first);
    V sum = hn::Zero(d);
    for (int i = 1; i < n2; ++i)
    {
      const V v = hn::Load(d, f + i * W + k);
      ok = hn::And(ok, hn::IsFinite(v));
      sum = hn::Add(sum, hn::Mul(v, v));
    }
    hn::Store(sum, d, norm2 + k);
    hn::Store(hn::IfThenElseZero(ok, hn::Set(d, 1.0f)), d, finite + k);
  }
}

// The OL base per lane: out_i = ((f_i scale) b) e for i > 0, out_0 = a e
// (a holds a sqrt(4 pi)); lanes with finite 0 get zeros.
void LaneBaseImpl(int n2, const float* f, const float* scale, const float* b, const float* e,
  const float* a, const float* finite, float* out)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  for (int k = 0; k < W; k += lanes)
  {
    const auto ok = hn::Gt(hn::Load(d, finite + k), hn::Zero(d));
    const V sk = hn::Load(d, scale + k), bk = hn::Load(d, b + k), ek = hn::Load(d, e + k);
    hn::Store(hn::IfThenElseZero(ok, hn::Mul(hn::Load(d, a + k), ek)), d, out + k);
    for (int i = 1; i < n2; ++i)
    {
      const V v = hn::Mul(hn::Mul(hn::Mul(hn::Load(d, f + i * W + k), sk), bk), ek);
      hn::Store(hn::IfThenElseZero(ok, v), d, out + i * W + k);
    }
  }
}

// GuardInBounds per lane (1: the cheap bound cannot clear it), in float: a
// lane on the edge only costs the sampled check, which decides alike.
void GuardBoundsImpl(int order, const float* g, float tolerance, float* outside)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const V lo = hn::Set(d, -tolerance), hi = hn::Set(d, 1.0f + tolerance);
  for (int k = 0; k < W; k += lanes)
  {
    const V mean = hn::Mul(hn::Load(d, g + k), hn::Set(d, static_cast<float>(1.0 / SqrtFourPi)));
    V bound = hn::Zero(d);
    for (int l = 1; l < order; ++l)
    {
      V band = hn::Zero(d);
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        const V c = hn::Load(d, g + i * W + k);
        band = hn::MulAdd(c, c, band);
      }
      const float weight = static_cast<float>((2 * l + 1) / (4.0 * Pi));
      bound = hn::Add(bound, hn::Sqrt(hn::Mul(band, hn::Set(d, weight))));
    }
    const auto inside = hn::And(hn::Ge(hn::Sub(mean, bound), lo), hn::Le(hn::Add(mean, bound), hi));
    hn::Store(hn::IfThenZeroElse(inside, hn::Set(d, 1.0f)), d, outside + k);
  }
}

// HybridExp's schedule per lane, in double vectors as HybridSchedule and
// CapTables::OptimalLinear compute it: the steps s and blend weight from
// |f^|, and the OL base at 2^-s and 2^-(s+1) (the finer level only where the
// lane blends; zeros elsewhere). Returns false, writing nothing useful, when
// a lane needs more than 60 steps (the caller then takes the scalar loop).
bool HybridLanesImpl(const CapTables& tables, double limit, const float* f, const float* norm2,
  const float* finite, std::int32_t* steps, float* keepWeight, float* squaredWeight, float* scale0,
  float* slope0, float* dc0, float* base0, float* scale1, float* slope1, float* dc1, float* base1,
  bool* blend)
{
  using D64 = hn::ScalableTag<double>;
  const D64 dd;
  const hn::Rebind<float, D64> df;
  const hn::Rebind<std::int32_t, D64> di;
  const hn::RebindToSigned<D64> dl;
  const int lanes = static_cast<int>(hn::Lanes(dd));
  const std::vector<double>& olA = tables.GetOptimalLinearA();
  const std::vector<double>& olB = tables.GetOptimalLinearB();
  const int last = tables.GetResolution() - 1;
  const auto olScale = hn::Set(df, static_cast<float>(tables.GetOptimalLinearScale()));
  const auto lastF = hn::Set(df, static_cast<float>(last));
  const auto zero = hn::Zero(dd);
  const auto one = hn::Set(dd, 1.0);
  bool anyBlend = false;
  for (int k = 0; k < W; k += lanes)
  {
    const auto ok = hn::Gt(hn::PromoteTo(dd, hn::LoadU(df, finite + k)), zero);
    // |f^| as the scalar exp takes it: a float square root.
    const auto norm = hn::IfThenElseZero(ok, hn::PromoteTo(dd, hn::Sqrt(hn::LoadU(df, norm2 + k))));
    const auto dcExponent = hn::IfThenElseZero(
      ok, hn::Div(hn::PromoteTo(dd, hn::LoadU(df, f + k)), hn::Set(dd, SqrtFourPi)));
    // HybridSchedule: the log only where |f^| passes half the limit.
    const auto ratio = hn::Div(norm, hn::Set(dd, limit));
    const auto need = hn::And(hn::Gt(norm, zero), hn::Gt(ratio, hn::Set(dd, 0.5)));
    const auto u = hn::Log2(dd, hn::IfThenElse(need, ratio, one));
    const auto take = hn::And(need, hn::Gt(u, hn::Set(dd, -1.0)));
    const auto s = hn::IfThenElseZero(take, hn::Max(zero, hn::Ceil(u)));
    const auto w = hn::IfThenElseZero(take, hn::Min(one, hn::Sub(u, hn::Sub(s, one))));
    if (!hn::AllTrue(dd, hn::Le(s, hn::Set(dd, 60.0))))
    {
      return false;
    }
    anyBlend = anyBlend || !hn::AllFalse(dd, hn::Gt(w, zero));
    const auto stepsL = hn::ConvertTo(dl, s);
    hn::StoreU(hn::DemoteTo(di, s), di, steps + k);
    hn::StoreU(hn::DemoteTo(df, hn::Sub(one, w)), df, keepWeight + k);
    hn::StoreU(hn::DemoteTo(df, w), df, squaredWeight + k);
    const auto normF = hn::DemoteTo(df, norm);
    for (int level = 0; level < 2; ++level)
    {
      // 2^-(s + level), exactly, from its exponent bits.
      const auto exponent = hn::Sub(hn::Set(dl, 1023 - level), stepsL);
      const auto power = hn::BitCast(dd, hn::ShiftLeft<52>(exponent));
      const auto powerF = hn::DemoteTo(df, power);
      // CapTables::OptimalLinear in float, its rows' blend in double.
      const auto x = hn::Mul(normF, powerF);
      const auto uf = hn::Mul(x, olScale);
      const auto inside = hn::Lt(uf, lastF);
      const auto inside64 = hn::Lt(hn::PromoteTo(dd, uf), hn::Set(dd, static_cast<double>(last)));
      const auto row = hn::IfThenElse(hn::RebindMask(di, inside),
        hn::ConvertTo(di, hn::Max(uf, hn::Zero(df))), hn::Set(di, last - 1));
      const auto t = hn::IfThenElse(inside, hn::Sub(uf, hn::ConvertTo(df, row)), hn::Set(df, 1.0f));
      const auto rowL = hn::PromoteTo(dl, row);
      const auto t64 = hn::PromoteTo(dd, t);
      const auto a0 = hn::GatherIndex(dd, olA.data(), rowL);
      const auto a1 = hn::GatherIndex(dd, olA.data(), hn::Add(rowL, hn::Set(dl, 1)));
      const auto b0 = hn::GatherIndex(dd, olB.data(), rowL);
      const auto b1 = hn::GatherIndex(dd, olB.data(), hn::Add(rowL, hn::Set(dl, 1)));
      // Past the table: its last values (t = 1 from row last - 1 would round).
      const auto lastA = hn::Set(dd, olA[last]), lastB = hn::Set(dd, olB[last]);
      const auto a = hn::DemoteTo(
        df, hn::IfThenElse(inside64, hn::Add(a0, hn::Mul(hn::Sub(a1, a0), t64)), lastA));
      const auto b = hn::DemoteTo(
        df, hn::IfThenElse(inside64, hn::Add(b0, hn::Mul(hn::Sub(b1, b0), t64)), lastB));
      const auto dc = hn::DemoteTo(df, hn::Exp(dd, hn::Mul(dcExponent, power)));
      const auto base = hn::Mul(a, hn::Set(df, static_cast<float>(SqrtFourPi)));
      if (level == 0)
      {
        hn::StoreU(powerF, df, scale0 + k);
        hn::StoreU(b, df, slope0 + k);
        hn::StoreU(dc, df, dc0 + k);
        hn::StoreU(base, df, base0 + k);
      }
      else
      {
        // As the blend reads it: the lane's float weight above zero.
        const auto on = hn::Gt(hn::DemoteTo(df, w), hn::Zero(df));
        hn::StoreU(hn::IfThenElseZero(on, powerF), df, scale1 + k);
        hn::StoreU(hn::IfThenElseZero(on, b), df, slope1 + k);
        hn::StoreU(hn::IfThenElseZero(on, dc), df, dc1 + k);
        hn::StoreU(hn::IfThenElseZero(on, base), df, base1 + k);
      }
    }
  }
  *blend = anyBlend;
  return true;
}

// Zeros the lanes whose finite is 0.
void ZeroLanesImpl(int n2, const float* finite, float* g)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  for (int k = 0; k < W; k += lanes)
  {
    const auto ok = hn::Gt(hn::Load(d, finite + k), hn::Zero(d));
    for (int i = 0; i < n2; ++i)
    {
      hn::Store(hn::IfThenElseZero(ok, hn::Load(d, g + i * W + k)), d, g + i * W + k);
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
HWY_EXPORT(BatchSquareImpl);
HWY_EXPORT(BlendImpl);
HWY_EXPORT(RepeatedSquareImpl);
HWY_EXPORT(GuardExtremesImpl);
HWY_EXPORT(LaneNormsImpl);
HWY_EXPORT(LaneBaseImpl);
HWY_EXPORT(ZeroLanesImpl);
HWY_EXPORT(GuardBoundsImpl);
HWY_EXPORT(HybridLanesImpl);

void BatchSquare(int order, const float* f, float* out)
{
  HWY_DYNAMIC_DISPATCH(BatchSquareImpl)(order, f, out);
}

void BatchExp(int order, const float* f, float* g, const ExpOptions& options, Status* status)
{
  constexpr int W = BatchWidth;
  const int n2 = NumCoefficients(order);
  if (order < 1 || order > MaxOrder || options.Method != ExpMethod::Hybrid ||
    !BatchKernelsEnabled())
  {
    // Lane by lane through the scalar exp.
    float fl[MaxCoefficients], gl[MaxCoefficients];
    for (int k = 0; k < W; ++k)
    {
      for (int i = 0; i < n2; ++i)
      {
        fl[i] = f[i * W + k];
      }
      status[k] = Exp(order, fl, gl, options);
      for (int i = 0; i < n2; ++i)
      {
        g[i * W + k] = gl[i];
      }
    }
    return;
  }
  // Per lane, as HybridExp does: DC isolated, the schedule from |f^|, the
  // OL base at 2^-s and 2^-(s+1). The lanes' sums and products run as
  // vectors; the schedule and the OL lookups per lane.
  const CapTables& tables = CapTables::Get(order);
  alignas(64) float finer[MaxCoefficients * W], squared[MaxCoefficients * W], keepWeight[W],
    squaredWeight[W], norm2[W], finite[W], scale[2][W], slope[2][W], dcScale[2][W], base[2][W];
  alignas(64) std::int32_t steps[W];
  HWY_DYNAMIC_DISPATCH(LaneNormsImpl)(n2, f, norm2, finite);
  bool blend = false;
  const double limit =
    options.HybridMaxNorm > 0.0 ? options.HybridMaxNorm : DefaultHybridMaxNorm(order);
  const bool scheduled = HWY_DYNAMIC_DISPATCH(HybridLanesImpl)(tables, limit, f, norm2, finite,
    steps, keepWeight, squaredWeight, scale[0], slope[0], dcScale[0], base[0], scale[1], slope[1],
    dcScale[1], base[1], &blend);
  for (int k = 0; k < W; ++k)
  {
    status[k] = finite[k] > 0.0f ? Status::Ok : Status::NonFiniteInput;
  }
  for (int k = 0; !scheduled && k < W; ++k)
  {
    const bool ok = finite[k] > 0.0f;
    status[k] = ok ? Status::Ok : Status::NonFiniteInput;
    const double norm = ok ? std::sqrt(norm2[k]) : 0.0;
    const double dcExponent = ok ? static_cast<double>(f[k]) / SqrtFourPi : 0.0;
    int s = 0;
    double wk = 0.0;
    HybridSchedule(order, norm, options, s, wk);
    steps[k] = s;
    keepWeight[k] = static_cast<float>(1.0 - wk);
    squaredWeight[k] = static_cast<float>(wk);
    blend = blend || wk > 0.0;
    // The finer level only where the lane blends; elsewhere its base is zero
    // (the blend then adds 0 x 0).
    scale[1][k] = slope[1][k] = dcScale[1][k] = base[1][k] = 0.0f;
    for (int level = 0; level < (wk > 0.0 ? 2 : 1); ++level)
    {
      // Powers of two multiply exactly: the same values as ldexp, cheaper.
      const double power = s + level < 64 ? 1.0 / static_cast<double>(1ULL << (s + level))
                                          : std::ldexp(1.0, -(s + level));
      scale[level][k] = static_cast<float>(power);
      float a;
      tables.OptimalLinear(static_cast<float>(norm) * scale[level][k], a, slope[level][k]);
      dcScale[level][k] = static_cast<float>(std::exp(dcExponent * power));
      base[level][k] = a * static_cast<float>(SqrtFourPi);
    }
  }
  HWY_DYNAMIC_DISPATCH(LaneBaseImpl)(n2, f, scale[0], slope[0], dcScale[0], base[0], finite, g);
  if (blend)
  {
    HWY_DYNAMIC_DISPATCH(LaneBaseImpl)
    (n2, f, scale[1], slope[1], dcScale[1], base[1], finite, finer);
    HWY_DYNAMIC_DISPATCH(BatchSquareImpl)(order, finer, squared);
    HWY_DYNAMIC_DISPATCH(BlendImpl)(n2, keepWeight, squaredWeight, squared, g);
  }
  HWY_DYNAMIC_DISPATCH(RepeatedSquareImpl)(order, steps, g);
  // Non-finite results, and lanes that failed before, become zeros.
  HWY_DYNAMIC_DISPATCH(LaneNormsImpl)(n2, g, norm2, finite);
  alignas(64) float outside[W];
  if (options.RangeGuard)
  {
    HWY_DYNAMIC_DISPATCH(GuardBoundsImpl)
    (order, g, static_cast<float>(options.RangeTolerance), outside);
  }
  bool guard = false, check[W] = {}, zero = false;
  for (int k = 0; k < W; ++k)
  {
    if (!(finite[k] > 0.0f) || status[k] != Status::Ok)
    {
      finite[k] = 0.0f;
      zero = true;
      status[k] = status[k] != Status::Ok ? status[k] : Status::NonFiniteResult;
    }
    else if (options.RangeGuard)
    {
      check[k] = outside[k] > 0.0f;
      guard = guard || check[k];
    }
  }
  if (zero)
  {
    HWY_DYNAMIC_DISPATCH(ZeroLanesImpl)(n2, finite, g);
  }
  if (!guard)
  {
    return;
  }
  alignas(64) float vmin[W], vmax[W];
  HWY_DYNAMIC_DISPATCH(GuardExtremesImpl)(order, g, vmin, vmax);
  for (int k = 0; k < W; ++k)
  {
    if (!check[k])
    {
      continue;
    }
    float gl[MaxCoefficients];
    for (int i = 0; i < n2; ++i)
    {
      gl[i] = g[i * W + k];
    }
    if (GuardRemap(order, gl, vmin[k], vmax[k], options.RangeTolerance))
    {
      for (int i = 0; i < n2; ++i)
      {
        g[i * W + k] = gl[i];
      }
    }
  }
}

} // namespace sh
} // namespace proxygi
#endif
