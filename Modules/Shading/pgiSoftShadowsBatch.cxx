// Compiled once per instruction set by Highway's foreach_target.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pgiSoftShadowsBatch.cxx"
#include "hwy/foreach_target.h" // IWYU pragma: keep

#include "hwy/highway.h"

#include "pgiSHBatch.h"
#include "pgiSoftShadowsBatch.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

HWY_BEFORE_NAMESPACE();
namespace proxygi
{
namespace detail
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<float>;
using V = hn::Vec<D>;
constexpr int W = sh::BatchWidth;

// asin(x) for 0 <= x <= 1 (NaN stays NaN): Highway's float asin (its
// coefficients and its two branches, |x| < 0.5 and the square root past it),
// with a multiplication and an addition per step instead of its fused
// multiply-adds, so that every target, and the scalar path, round alike.
// belowHalf: every lane is below 0.5 (no square root).
template <class DF>
HWY_INLINE hn::Vec<DF> AsinLanes(DF d, hn::Vec<DF> x, bool belowHalf)
{
  using VF = hn::Vec<DF>;
  const VF half = hn::Set(d, 0.5f);
  const auto small = hn::Lt(x, half);
  // Past 0.5: asin(x) = pi/2 - 2 asin(sqrt((1 - x) / 2)).
  const VF yy = belowHalf ? hn::Mul(x, x)
                          : hn::IfThenElse(small, hn::Mul(x, x), hn::Sub(half, hn::Mul(x, half)));
  const VF y = belowHalf ? x : hn::IfThenElse(small, x, hn::Sqrt(yy));
  VF p = hn::Set(d, 0.04197454825f);
  p = hn::Add(hn::Mul(p, yy), hn::Set(d, 0.02424046025f));
  p = hn::Add(hn::Mul(p, yy), hn::Set(d, 0.04547423869f));
  p = hn::Add(hn::Mul(p, yy), hn::Set(d, 0.07495029271f));
  p = hn::Add(hn::Mul(p, yy), hn::Set(d, 0.1666677296f));
  const VF z0 = hn::Add(hn::Mul(p, hn::Mul(yy, y)), y);
  if (belowHalf)
  {
    return z0;
  }
  const VF z1 = hn::Sub(hn::Set(d, 1.57079632679489661923f), hn::Mul(z0, hn::Set(d, 2.0f)));
  return hn::IfThenElse(small, z0, z1);
}

// The blockers' angular radius for the scalar path: AsinLanes on one lane.
float BlockerAsinImpl(float x)
{
  const hn::CappedTag<float, 1> d1;
  return hn::GetLane(AsinLanes(d1, hn::Set(d1, x), false));
}

// ReplaceBlocker and the MinAngle cut of VisitBlockers, lane by lane: every
// branch is computed and the lane's case selected. No fused multiply-adds
// (and -ffp-contract=off for this file): a receiver on its own proxy where
// the tangent plane touches it (h -> -r) keeps or drops a blocker on the
// last bit of h, so the rounding must be the scalar code's, bit for bit.
void BlockerLanesImpl(const float* lanes, const float* X, const float* Y, const float* Z,
  const float* R, int rows, float sinMin, bool rules, float* theta, float* dx, float* dy, float* dz)
{
  const D d;
  const int count = static_cast<int>(hn::Lanes(d));
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f),
          two = hn::Set(d, 2.0f), skip = hn::Set(d, -1.0f), sinCut = hn::Set(d, sinMin);
  for (int k = 0; k < W; k += count)
  {
    const V px = hn::Load(d, lanes + k), py = hn::Load(d, lanes + W + k),
            pz = hn::Load(d, lanes + 2 * W + k), nx = hn::Load(d, lanes + 3 * W + k),
            ny = hn::Load(d, lanes + 4 * W + k), nz = hn::Load(d, lanes + 5 * W + k);
    for (int s = 0; s < rows; ++s)
    {
      float* out = theta + s * W + k;
      if (!(R[s] > 0.0f))
      {
        hn::Store(skip, d, out); // zero-radius (or NaN) spheres block nothing
        continue;
      }
      const V cx = hn::Set(d, X[s]), cy = hn::Set(d, Y[s]), cz = hn::Set(d, Z[s]);
      V r = hn::Set(d, R[s]);
      V qx = cx, qy = cy, qz = cz;
      auto keep = hn::Eq(zero, zero);
      if (rules)
      {
        const V vx = hn::Sub(cx, px), vy = hn::Sub(cy, py), vz = hn::Sub(cz, pz);
        const V h = hn::Add(hn::Add(hn::Mul(vx, nx), hn::Mul(vy, ny)), hn::Mul(vz, nz));
        const auto behind = hn::Le(h, hn::Neg(r));
        const auto front = hn::Ge(h, r);
        keep = hn::Not(behind);
        // Only spheres the tangent plane cuts change (most lanes: none).
        if (!hn::AllTrue(d, hn::Or(front, behind)))
        {
          const V d2 = hn::Add(hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy)), hn::Mul(vz, vz));
          const V r2 = hn::Mul(r, r), h2 = hn::Mul(h, h);
          const V rho = hn::Sqrt(hn::Max(zero, hn::Sub(d2, h2)));
          const V delta = hn::Sqrt(hn::Max(zero, hn::Sub(r2, h2)));
          const auto cut = hn::Gt(delta, zero);
          const auto inside = hn::Lt(d2, r2);
          // Inside: shrunk to the sphere tangent to T_p, ramped.
          const V rampIn = hn::IfThenElse(
            cut, hn::Min(one, hn::Div(hn::Mul(two, hn::Sub(delta, rho)), delta)), zero);
          const V rIn = hn::Mul(h, hn::Max(zero, rampIn));
          // Outside and cut: the sphere from the highest point down to T_p.
          const V rampOut = hn::IfThenElse(
            cut, hn::Min(one, hn::Div(hn::Div(hn::Sub(d2, r2), hn::Add(rho, delta)), delta)), one);
          const V halfH = hn::Mul(half, hn::Add(h, r));
          const V rOut = hn::Mul(halfH, hn::Max(zero, rampOut));
          const V ox = hn::Add(hn::Sub(cx, hn::Mul(h, nx)), hn::Mul(halfH, nx));
          const V oy = hn::Add(hn::Sub(cy, hn::Mul(h, ny)), hn::Mul(halfH, ny));
          const V oz = hn::Add(hn::Sub(cz, hn::Mul(h, nz)), hn::Mul(halfH, nz));
          const V rCut = hn::IfThenElse(inside, rIn, rOut);
          const auto keepCut =
            hn::And(hn::Gt(rCut, zero), hn::Or(hn::Not(inside), hn::Gt(h, zero)));
          r = hn::IfThenElse(front, r, rCut);
          qx = hn::IfThenElse(hn::Or(front, inside), cx, ox);
          qy = hn::IfThenElse(hn::Or(front, inside), cy, oy);
          qz = hn::IfThenElse(hn::Or(front, inside), cz, oz);
          keep = hn::AndNot(behind, hn::Or(front, keepCut));
        }
      }
      const V ex = hn::Sub(qx, px), ey = hn::Sub(qy, py), ez = hn::Sub(qz, pz);
      const V dist = hn::Sqrt(hn::Add(hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey)), hn::Mul(ez, ez)));
      keep = hn::And(keep, hn::And(hn::Gt(dist, zero), hn::Ge(r, hn::Mul(sinCut, dist))));
      // One division (the scalar path's too).
      const V inverse = hn::Div(one, dist);
      const V sine = hn::Min(one, hn::Mul(r, inverse));
      // Most blockers subtend less than 30 degrees: then no square root.
      const V angle = AsinLanes(d, sine, hn::AllTrue(d, hn::Lt(sine, half)));
      hn::Store(hn::IfThenElse(keep, angle, skip), d, out);
      hn::Store(hn::Mul(ex, inverse), d, dx + s * W + k);
      hn::Store(hn::Mul(ey, inverse), d, dy + s * W + k);
      hn::Store(hn::Mul(ez, inverse), d, dz + s * W + k);
    }
  }
}

// DotBlocks: each sum in the order of i, a multiplication and an addition
// per term (no fused multiply-adds, as the scalar loop rounds them), so the
// lanes equal the scalar sums bit for bit; four vectors' sums side by side,
// as one sum is a chain of dependent additions.
void DotBlocksImpl(int coefficients, const float* g, const float* basis, std::size_t stride,
  const int* blocks, int count, float* v)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d)), perBlock = W / lanes;
  const int total = count * perBlock;
  const auto offset = [&](int q)
  { return static_cast<std::size_t>(blocks[q / perBlock]) * W + (q % perBlock) * lanes; };
  int q = 0;
  for (; q + 4 <= total; q += 4)
  {
    const std::size_t o0 = offset(q), o1 = offset(q + 1), o2 = offset(q + 2), o3 = offset(q + 3);
    V s0 = hn::Zero(d), s1 = s0, s2 = s0, s3 = s0;
    for (int i = 0; i < coefficients; ++i)
    {
      const V gi = hn::Set(d, g[i]);
      const float* row = basis + i * stride;
      s0 = hn::Add(s0, hn::Mul(gi, hn::LoadU(d, row + o0)));
      s1 = hn::Add(s1, hn::Mul(gi, hn::LoadU(d, row + o1)));
      s2 = hn::Add(s2, hn::Mul(gi, hn::LoadU(d, row + o2)));
      s3 = hn::Add(s3, hn::Mul(gi, hn::LoadU(d, row + o3)));
    }
    hn::StoreU(s0, d, v + o0);
    hn::StoreU(s1, d, v + o1);
    hn::StoreU(s2, d, v + o2);
    hn::StoreU(s3, d, v + o3);
  }
  for (; q < total; ++q)
  {
    const std::size_t o = offset(q);
    V sum = hn::Zero(d);
    for (int i = 0; i < coefficients; ++i)
    {
      sum = hn::Add(sum, hn::Mul(hn::Set(d, g[i]), hn::LoadU(d, basis + i * stride + o)));
    }
    hn::StoreU(sum, d, v + o);
  }
}

// PlaneTerms: Scale's per-direction terms, every lane's case computed and
// selected; the look-ups of s gathered. Each operation is the scalar
// loop's, in its order (no fused multiply-adds).
void PlaneTermsImpl(const PlaneLookUps& in, const int* blocks, int count, float* weights,
  float* terms, std::size_t stride)
{
  const D d;
  const hn::RebindToSigned<D> di;
  const int lanes = static_cast<int>(hn::Lanes(d)), perBlock = W / lanes;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V x = hn::Set(d, in.X), y = hn::Set(d, in.Y), h = hn::Set(d, in.H);
  const V fu0 = hn::Set(d, in.FU), fv0 = hn::Set(d, in.FV), hu = hn::Set(d, in.HU);
  const V d10 = hn::Set(d, in.Dual1[0]), d11 = hn::Set(d, in.Dual1[1]),
          d20 = hn::Set(d, in.Dual2[0]), d21 = hn::Set(d, in.Dual2[1]);
  const V lastColumn = hn::Set(d, static_cast<float>(in.Columns - 1)),
          lastRow = hn::Set(d, static_cast<float>(in.Rows - 1));
  const auto columns = hn::Set(di, in.Columns), three = hn::Set(di, 3);
  for (int q = 0; q < count * perBlock; ++q)
  {
    const std::size_t o =
      static_cast<std::size_t>(blocks[q / perBlock]) * W + (q % perBlock) * lanes;
    const V c = hn::LoadU(d, in.Cosines + o);
    const auto facing = hn::Gt(c, zero);
    hn::StoreU(hn::IfThenElseZero(facing, c), d, weights + o);
    V seen = c;
    if (in.V)
    {
      seen = hn::Mul(seen, hn::Min(hn::Max(hn::LoadU(d, in.V + o), zero), one));
    }
    const V su = hn::LoadU(d, in.StepU + o), sv = hn::LoadU(d, in.StepV + o);
    auto lit = facing;
    if (in.Bounded)
    {
      const V px = hn::Add(x, hn::Mul(h, su)), py = hn::Add(y, hn::Mul(h, sv));
      const V a = hn::Add(hn::Mul(px, d10), hn::Mul(py, d11));
      const V b = hn::Add(hn::Mul(px, d20), hn::Mul(py, d21));
      lit = hn::And(lit, hn::And(hn::Le(hn::Abs(a), one), hn::Le(hn::Abs(b), one)));
    }
    V s[3] = { one, one, one };
    if (in.Grid)
    {
      const V fu = hn::Add(fu0, hn::Mul(hu, su)), fv = hn::Add(fv0, hn::Mul(hu, sv));
      const auto inside = hn::And(hn::And(hn::Ge(fu, zero), hn::Ge(fv, zero)),
        hn::And(hn::Lt(fu, lastColumn), hn::Lt(fv, lastRow)));
      // Lanes off the grid read the first point (their s is 1).
      const V u = hn::IfThenElseZero(inside, fu), v = hn::IfThenElseZero(inside, fv);
      const auto i = hn::ConvertTo(di, u), j = hn::ConvertTo(di, v);
      const V a = hn::Sub(u, hn::ConvertTo(d, i)), b = hn::Sub(v, hn::ConvertTo(d, j));
      const auto base = hn::Mul(hn::Add(hn::Mul(j, columns), i), three);
      const auto above = hn::Add(base, hn::Mul(columns, three));
      for (int ch = 0; ch < 3; ++ch)
      {
        const float* grid = in.Grid + ch;
        const V p00 = hn::GatherIndex(d, grid, base), p10 = hn::GatherIndex(d, grid + 3, base);
        const V p01 = hn::GatherIndex(d, grid, above), p11 = hn::GatherIndex(d, grid + 3, above);
        const V bottom = hn::Add(p00, hn::Mul(a, hn::Sub(p10, p00)));
        const V top = hn::Add(p01, hn::Mul(a, hn::Sub(p11, p01)));
        s[ch] = hn::IfThenElse(inside, hn::Add(bottom, hn::Mul(b, hn::Sub(top, bottom))), one);
      }
    }
    for (int ch = 0; ch < 3; ++ch)
    {
      hn::StoreU(hn::IfThenElseZero(lit, hn::Mul(seen, s[ch])), d, terms + ch * stride + o);
    }
  }
}

// SkyStretches: every branch of the scalar loop per lane, selected; its
// std::min and std::max as the comparisons they are, so that signed zeros
// come out as the scalar's.
void SkyStretchesImpl(const float* axes, int bins, const float normal[3], float a1, float a2,
  float h, float* from, float* to)
{
  const D d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), minusOne = hn::Set(d, -1.0f),
          big = hn::Set(d, std::numeric_limits<float>::max());
  const V n0 = hn::Set(d, normal[0]), n1 = hn::Set(d, normal[1]), m = hn::Set(d, normal[2]);
  const V hv = hn::Set(d, h), h2 = hn::Mul(hv, hv);
  const bool atNadir = normal[2] < 0.0f;
  const auto smaller = [](V a, V b)
  { return hn::IfThenElse(hn::Lt(b, a), b, a); };                                  // std::min(a, b)
  const auto larger = [](V a, V b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }; // std::max(a, b)
  for (int k = 0; k < bins; k += lanes)
  {
    const V c = hn::LoadU(d, axes + k), sn = hn::LoadU(d, axes + bins + k);
    const V along = hn::Add(hn::Mul(n0, c), hn::Mul(n1, sn));
    const auto atHorizon = hn::Gt(along, zero);
    const auto any = atNadir ? hn::Eq(zero, zero) : atHorizon;
    // Where n.w > 0 changes sign: the heights above it or below it.
    const V turn = hn::Div(hn::Abs(along), hn::Sqrt(hn::Add(hn::Mul(along, along), hn::Mul(m, m))));
    V lo = zero, hi = one;
    if (atNadir)
    {
      lo = hn::IfThenElse(atHorizon, zero, turn);
    }
    else
    {
      hi = hn::IfThenElse(atHorizon, turn, one);
    }
    V in = zero, out = big;
    for (int q = 0; q < 2; ++q)
    {
      const V a = hn::Set(d, q == 0 ? a1 : a2), da = hn::LoadU(d, axes + (2 + q) * bins + k);
      const auto flat = hn::Eq(da, zero);
      const V safe = hn::IfThenElse(flat, one, da);
      const V t1 = hn::Div(hn::Sub(minusOne, a), safe), t2 = hn::Div(hn::Sub(one, a), safe);
      const V inMoved = larger(in, smaller(t1, t2)), outMoved = smaller(out, larger(t1, t2));
      // Parallel to the edges: inside their band or never.
      const V inFlat = std::abs(q == 0 ? a1 : a2) > 1.0f ? big : in;
      in = hn::IfThenElse(flat, inFlat, inMoved);
      out = hn::IfThenElse(flat, out, outMoved);
    }
    // s = h / sqrt(h^2 + t^2) from the horizon (t endless) down to the foot.
    const auto crosses = hn::Le(in, out);
    const V outS =
      hn::IfThenElse(hn::Lt(out, big), hn::Div(hv, hn::Sqrt(hn::Add(h2, hn::Mul(out, out)))), zero);
    const V inS = hn::Div(hv, hn::Sqrt(hn::Add(h2, hn::Mul(in, in))));
    const V firstTo = hn::IfThenElse(crosses, outS, one);
    const auto second = hn::And(crosses, hn::Gt(in, zero));
    const V none = one; // from 1 to 0: no stretch
    const V s0 = larger(lo, zero), s1 = smaller(hi, firstTo);
    const V s2 = larger(lo, inS), s3 = smaller(hi, one);
    hn::StoreU(hn::IfThenElse(any, s0, none), d, from + k);
    hn::StoreU(hn::IfThenElseZero(any, s1), d, to + k);
    hn::StoreU(hn::IfThenElse(hn::And(any, second), s2, none), d, from + bins + k);
    hn::StoreU(hn::IfThenElseZero(hn::And(any, second), s3), d, to + bins + k);
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
HWY_EXPORT(BlockerLanesImpl);
HWY_EXPORT(DotBlocksImpl);
HWY_EXPORT(PlaneTermsImpl);
HWY_EXPORT(SkyStretchesImpl);

float BlockerAsin(float x)
{
  // The baseline build's target, so the scalar path is the same on every CPU.
  return HWY_STATIC_DISPATCH(BlockerAsinImpl)(x);
}

void BlockerLanes(const float* lanes, const float* X, const float* Y, const float* Z,
  const float* R, int rows, float sinMin, bool rules, float* theta, float* dx, float* dy, float* dz)
{
  HWY_DYNAMIC_DISPATCH(BlockerLanesImpl)
  (lanes, X, Y, Z, R, rows, sinMin, rules, theta, dx, dy, dz);
}

void DotBlocks(int coefficients, const float* g, const float* basis, std::size_t stride,
  const int* blocks, int count, float* v)
{
  if (sh::BatchKernelsEnabled())
  {
    HWY_DYNAMIC_DISPATCH(DotBlocksImpl)(coefficients, g, basis, stride, blocks, count, v);
    return;
  }
  for (int b = 0; b < count; ++b)
  {
    float* out = v + static_cast<std::size_t>(blocks[b]) * sh::BatchWidth;
    std::fill_n(out, sh::BatchWidth, 0.0f);
    for (int i = 0; i < coefficients; ++i)
    {
      const float gi = g[i];
      const float* row = basis + i * stride + static_cast<std::size_t>(blocks[b]) * sh::BatchWidth;
      for (int k = 0; k < sh::BatchWidth; ++k)
      {
        out[k] += gi * row[k];
      }
    }
  }
}

void PlaneTerms(const PlaneLookUps& in, const int* blocks, int count, float* weights, float* terms,
  std::size_t stride)
{
  HWY_DYNAMIC_DISPATCH(PlaneTermsImpl)(in, blocks, count, weights, terms, stride);
}

void SkyStretches(const float* axes, int bins, const float normal[3], float a1, float a2, float h,
  float* from, float* to)
{
  HWY_DYNAMIC_DISPATCH(SkyStretchesImpl)(axes, bins, normal, a1, a2, h, from, to);
}
} // namespace detail
} // namespace proxygi
#endif
