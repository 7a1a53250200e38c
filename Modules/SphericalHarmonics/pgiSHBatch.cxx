// Compiled once per instruction set by Highway's foreach_target.h; the code
// between HWY_BEFORE_NAMESPACE and HWY_AFTER_NAMESPACE is the per-target part.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pgiSHBatch.cxx"
#include "hwy/foreach_target.h" // IWYU pragma: keep

#include "hwy/highway.h"

#include "pgiSHBatch.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <vector>

#ifndef PGI_SH_BATCH_ONCE
#define PGI_SH_BATCH_ONCE
namespace proxygi
{
namespace sh
{
namespace batch
{
// Square's terms grouped by output coefficient, each with its factor
// (2 Gamma for j < k): out[i] = sum over [Start[i], Start[i+1]) of C f_J f_K.
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

  // out = f * f over BatchWidth lanes.
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
        acc = hn::MulAdd(hn::Mul(hn::Set(d, program.C[t]), fj), fk, acc);
      }
      hn::Store(acc, d, out + i * W + k);
    }
  }
}

void BatchSquareImpl(int order, const float* f, float* out)
{
  SquareLanes(batch::SquareProgram::Get(order), NumCoefficients(order), f, out);
}

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
      const auto base = hn::Mul(row, hn::Set(di, tableOrder));
      Lane zh[order];
      for (int l = 0; l < order; ++l)
      {
        const auto at = hn::Add(base, hn::Set(di, l));
        const V r0 = hn::GatherIndex(d, table, at);
        const V r1 = hn::GatherIndex(d, table, hn::Add(at, hn::Set(di, tableOrder)));
        V z = hn::MulAdd(hn::Sub(r1, r0), t, r0);
        if (ratios)
        {
          z = hn::Mul(z, hn::Set(d, ratios[b * order + l]));
        }
        zh[l] = Lane(hn::IfThenElseZero(keep, z));
      }
      // Skipped lanes may hold any direction: zero it, so y stays finite.
      Lane y[order * order];
      BasisLanes(order, Lane(hn::IfThenElseZero(keep, hn::Load(d, dirX + b * W + k))),
        Lane(hn::IfThenElseZero(keep, hn::Load(d, dirY + b * W + k))),
        Lane(hn::IfThenElseZero(keep, hn::Load(d, dirZ + b * W + k))), y);
      for (int l = 0; l < order; ++l)
      {
        for (int i = l * l; i < (l + 1) * (l + 1); ++i)
        {
          acc[i] = hn::MulAdd(y[i].v, zh[l].v, acc[i]);
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

// The guard's sampled extremes of the reconstruction, per lane.
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
    for (int s = 0; s < count; ++s)
    {
      const float* y = basis + s * n2;
      V v = hn::Mul(c[0], hn::Set(d, y[0]));
      for (int i = 1; i < n2; ++i)
      {
        v = hn::MulAdd(c[i], hn::Set(d, y[i]), v);
      }
      lo = hn::Min(lo, v);
      hi = hn::Max(hi, v);
    }
    hn::Store(lo, d, vmin + k);
    hn::Store(hi, d, vmax + k);
  }
}

// g = a g + b h in the lanes where b > 0.
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
      const V mixed = hn::MulAdd(bk, hn::Load(d, h + i * W + k), hn::Mul(ak, gi));
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
HWY_EXPORT(BatchAddCapsImpl);
HWY_EXPORT(GuardExtremesImpl);
HWY_EXPORT(BlendImpl);
HWY_EXPORT(RepeatedSquareImpl);

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

void BatchSquare(int order, const float* f, float* out)
{
  HWY_DYNAMIC_DISPATCH(BatchSquareImpl)(order, f, out);
}

void BatchAddCaps(const CapTables& tables, int order, int count, const float* theta,
  const float* dirX, const float* dirY, const float* dirZ, const float* ratios, float* f)
{
  HWY_DYNAMIC_DISPATCH(BatchAddCapsImpl)
  (tables, order, count, theta, dirX, dirY, dirZ, ratios, f);
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
  // OL base at 2^-s and 2^-(s+1). Only the products are vectorised.
  const CapTables& tables = CapTables::Get(order);
  alignas(64) float finer[MaxCoefficients * W], squared[MaxCoefficients * W], keepWeight[W],
    squaredWeight[W];
  alignas(64) std::int32_t steps[W];
  bool blend = false;
  for (int k = 0; k < W; ++k)
  {
    bool finite = true;
    float norm2 = 0.0f;
    for (int i = 0; i < n2; ++i)
    {
      finite = finite && std::isfinite(f[i * W + k]);
      norm2 += i > 0 ? f[i * W + k] * f[i * W + k] : 0.0f;
    }
    status[k] = finite ? Status::Ok : Status::NonFiniteInput;
    const double norm = finite ? std::sqrt(norm2) : 0.0;
    const double dcExponent = finite ? static_cast<double>(f[k]) / SqrtFourPi : 0.0;
    int s = 0;
    double wk = 0.0;
    HybridSchedule(order, norm, options, s, wk);
    steps[k] = s;
    keepWeight[k] = static_cast<float>(1.0 - wk);
    squaredWeight[k] = static_cast<float>(wk);
    blend = blend || wk > 0.0;
    for (int level = 0; level < 2; ++level)
    {
      float* out = level == 0 ? g : finer;
      const float scale = static_cast<float>(std::ldexp(1.0, -(s + level)));
      float a, b;
      tables.OptimalLinear(static_cast<float>(norm) * scale, a, b);
      const float e = static_cast<float>(std::exp(std::ldexp(dcExponent, -(s + level))));
      for (int i = 1; i < n2; ++i)
      {
        out[i * W + k] = finite ? (f[i * W + k] * scale * b) * e : 0.0f;
      }
      out[k] = finite ? a * static_cast<float>(SqrtFourPi) * e : 0.0f;
    }
  }
  if (blend)
  {
    HWY_DYNAMIC_DISPATCH(BatchSquareImpl)(order, finer, squared);
    HWY_DYNAMIC_DISPATCH(BlendImpl)(n2, keepWeight, squaredWeight, squared, g);
  }
  HWY_DYNAMIC_DISPATCH(RepeatedSquareImpl)(order, steps, g);
  bool guard = false, check[W] = {};
  for (int k = 0; k < W; ++k)
  {
    bool finite = true;
    for (int i = 0; i < n2; ++i)
    {
      finite = finite && std::isfinite(g[i * W + k]);
    }
    if (!finite || status[k] != Status::Ok)
    {
      for (int i = 0; i < n2; ++i)
      {
        g[i * W + k] = 0.0f;
      }
      status[k] = status[k] != Status::Ok ? status[k] : Status::NonFiniteResult;
    }
    else if (options.RangeGuard)
    {
      float gl[MaxCoefficients];
      for (int i = 0; i < n2; ++i)
      {
        gl[i] = g[i * W + k];
      }
      check[k] = !GuardInBounds(order, gl, options.RangeTolerance);
      guard = guard || check[k];
    }
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
