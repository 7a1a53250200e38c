#include "pgiSHExp.h"

#include "pgiSHBasis.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

namespace proxygi
{
namespace sh
{

const char* ExpMethodName(ExpMethod method)
{
  switch (method)
  {
    case ExpMethod::PS:
      return "PS";
    case ExpMethod::PSStar:
      return "PS*";
    case ExpMethod::OL:
      return "OL";
    case ExpMethod::Hybrid:
      return "HYB";
  }
  return "?";
}

double DefaultHybridMaxNorm(int order)
{
  // OL is accurate for small |f^| only; orders above 4 need a smaller input
  // (sweep in Documentation/AccuracyTime.md).
  return order <= 4 ? 0.5 : 0.25;
}

int ScalingSteps(double normFHat)
{
  if (!(normFHat > 0.0))
  {
    return 0;
  }
  return std::max(0, static_cast<int>(std::floor(std::log2(normFHat) + 3.0)));
}

void HybridSchedule(int order, double norm, const ExpOptions& options, int& steps, double& w)
{
  const double limit =
    options.HybridMaxNorm > 0.0 ? options.HybridMaxNorm : DefaultHybridMaxNorm(order);
  steps = 0;
  w = 0.0;
  // log2 of at most 0.5 is at most -1: most receivers skip the log.
  if (norm > 0.0 && norm / limit > 0.5)
  {
    const double u = std::log2(norm / limit);
    if (u > -1.0)
    {
      steps = std::max(0, static_cast<int>(std::ceil(u)));
      w = std::min(1.0, u - (steps - 1));
    }
  }
}

namespace
{
// Directions the range guard samples, with their basis values per order.
struct GuardSamples
{
  int Count;
  std::vector<double> BasisD;
  std::vector<float> BasisF;
  GuardSamples(int order)
  {
    // Fibonacci sphere: near-uniform, no pole clustering.
    this->Count = std::max(128, 8 * order * order);
    const int n2 = NumCoefficients(order);
    this->BasisD.resize(static_cast<std::size_t>(this->Count) * n2);
    const double golden = Pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < this->Count; ++i)
    {
      const double z = 1.0 - (2.0 * i + 1.0) / this->Count;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = golden * i;
      EvaluateBasis(order, r * std::cos(phi), r * std::sin(phi), z, &this->BasisD[i * n2]);
    }
    this->BasisF.assign(this->BasisD.begin(), this->BasisD.end());
  }
  static const GuardSamples& Get(int order)
  {
    static std::array<std::unique_ptr<GuardSamples>, MaxOrder + 1> cache;
    static std::array<std::once_flag, MaxOrder + 1> once;
    std::call_once(once[order], [order]() { cache[order].reset(new GuardSamples(order)); });
    return *cache[order];
  }
  const double* Basis(double) const { return this->BasisD.data(); }
  const float* Basis(float) const { return this->BasisF.data(); }
};

template <typename T>
inline T NormNoDC(int n2, const T* f)
{
  T s = T(0);
  for (int i = 1; i < n2; ++i)
  {
    s += f[i] * f[i];
  }
  return std::sqrt(s);
}

template <typename T>
void Scale(int n2, T* v, T s)
{
  for (int i = 0; i < n2; ++i)
  {
    v[i] *= s;
  }
}

template <typename T>
void RepeatedSquare(const TripleProduct& tp, int n2, int steps, T* g)
{
  T tmp[MaxCoefficients];
  for (int k = 0; k < steps; ++k)
  {
    tp.Square(g, tmp);
    std::copy(tmp, tmp + n2, g);
  }
}

// PS-p: 1 + f + f^2*/2! + ... + f^p*/p!, products left to right.
template <typename T>
void ProductSeries(const TripleProduct& tp, int n2, int degree, const T* f, T* g)
{
  T term[MaxCoefficients], next[MaxCoefficients];
  Fill(g, n2, T(0));
  g[0] = static_cast<T>(SqrtFourPi);
  if (degree < 1)
  {
    return;
  }
  std::copy(f, f + n2, term);
  for (int i = 0; i < n2; ++i)
  {
    g[i] += term[i];
  }
  for (int k = 2; k <= degree; ++k)
  {
    tp.Product(term, f, next);
    const T inv = T(1) / static_cast<T>(k);
    for (int i = 0; i < n2; ++i)
    {
      term[i] = next[i] * inv;
      g[i] += term[i];
    }
  }
}

// Even/odd factored series (eq. 22) of exp, degree p, for DC-free f.
template <typename T>
void FactoredSeries(const TripleProduct& tp, int n2, int degree, const T* f, T* g)
{
  // powers[k] = f^{2k}*, built with as few products as possible.
  const int halfDegree = degree / 2;
  std::vector<std::array<T, MaxCoefficients>> powers(halfDegree + 1);
  for (int k = 1; k <= halfDegree; ++k)
  {
    if (k == 1)
    {
      tp.Square(f, powers[1].data());
    }
    else if (k % 2 == 0)
    {
      tp.Square(powers[k / 2].data(), powers[k].data());
    }
    else
    {
      tp.Product(powers[k - 1].data(), powers[1].data(), powers[k].data());
    }
  }
  // even: sum_k f^{2k}/(2k)!, odd: sum_k f^{2k}/(2k+1)!
  T even[MaxCoefficients], odd[MaxCoefficients];
  Fill(even, n2, T(0));
  Fill(odd, n2, T(0));
  even[0] = static_cast<T>(SqrtFourPi);
  odd[0] = static_cast<T>(SqrtFourPi);
  double factorial = 1.0; // (2k)!
  bool oddHasPowers = false;
  for (int k = 1; k <= halfDegree; ++k)
  {
    factorial *= (2 * k - 1) * (2 * k);
    const T ce = static_cast<T>(1.0 / factorial);
    for (int i = 0; i < n2; ++i)
    {
      even[i] += ce * powers[k][i];
    }
    if (2 * k + 1 <= degree)
    {
      const T co = static_cast<T>(1.0 / (factorial * (2 * k + 1)));
      for (int i = 0; i < n2; ++i)
      {
        odd[i] += co * powers[k][i];
      }
      oddHasPowers = true;
    }
  }
  if (degree < 1)
  {
    std::copy(even, even + n2, g);
    return;
  }
  if (oddHasPowers)
  {
    T fOdd[MaxCoefficients];
    tp.Product(f, odd, fOdd);
    for (int i = 0; i < n2; ++i)
    {
      g[i] = even[i] + fOdd[i];
    }
  }
  else
  {
    for (int i = 0; i < n2; ++i)
    {
      g[i] = even[i] + f[i];
    }
  }
}

template <typename T>
void OptimalLinear(const CapTables& tables, int n2, const T* fHat, T norm, T* g)
{
  T a, b;
  tables.OptimalLinear(norm, a, b);
  for (int i = 1; i < n2; ++i)
  {
    g[i] = b * fHat[i];
  }
  g[0] = a * static_cast<T>(SqrtFourPi);
}

// HYB: OL on f^ / 2^s, then s squarings. The number of squarings is blended
// continuously: with u = log2(|f^| / limit) in (s - 1, s], the base is
// (1 - w) OL(f/2^s) + w OL(f/2^(s+1))^2 with w = u - (s - 1), which equals
// the s + 1 result where s steps up, so g has no jumps in f.
template <typename T>
void HybridExp(int order, const TripleProduct& tp, const T* fHat, double norm, double dcExponent,
  const ExpOptions& options, T* g)
{
  const int n2 = NumCoefficients(order);
  const CapTables& tables = CapTables::Get(order);
  int steps = 0;
  double w = 0.0;
  HybridSchedule(order, norm, options, steps, w);
  T scaled[MaxCoefficients];
  auto scaledBase = [&](int s, T* out)
  {
    const T k = static_cast<T>(std::ldexp(1.0, -s));
    for (int i = 0; i < n2; ++i)
    {
      scaled[i] = fHat[i] * k;
    }
    OptimalLinear(tables, n2, scaled, static_cast<T>(norm) * k, out);
    Scale(n2, out, static_cast<T>(std::exp(std::ldexp(dcExponent, -s))));
  };
  scaledBase(steps, g);
  if (w > 0.0)
  {
    T finer[MaxCoefficients], squared[MaxCoefficients];
    scaledBase(steps + 1, finer);
    tp.Square(finer, squared);
    const T a = static_cast<T>(1.0 - w), b = static_cast<T>(w);
    for (int i = 0; i < n2; ++i)
    {
      g[i] = a * g[i] + b * squared[i];
    }
  }
  RepeatedSquare(tp, n2, steps, g);
}
} // namespace

const float* GuardBasis(int order, int& count)
{
  const GuardSamples& samples = GuardSamples::Get(order);
  count = samples.Count;
  return samples.BasisF.data();
}

template <typename T>
bool GuardInBounds(int order, const T* g, double tolerance)
{
  const double mean = g[0] / SqrtFourPi;
  // Per band, |sum_m g_lm y_lm(s)| <= |g_l| sqrt((2l+1)/(4 pi)) (Cauchy-Schwarz
  // and the addition theorem): a cheap test that rules out most results.
  double bound = 0.0;
  for (int l = 1; l < order; ++l)
  {
    double band = 0.0;
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      band += static_cast<double>(g[i]) * g[i];
    }
    bound += std::sqrt(band * (2 * l + 1) / (4.0 * Pi));
  }
  return mean - bound >= -tolerance && mean + bound <= 1.0 + tolerance;
}

template <typename T>
bool GuardRange(int order, T* g, double tolerance)
{
  if (GuardInBounds(order, g, tolerance))
  {
    return false;
  }
  const int n2 = NumCoefficients(order);
  const GuardSamples& samples = GuardSamples::Get(order);
  const T* basis = samples.Basis(T(0));
  double vmin = std::numeric_limits<double>::max(), vmax = -vmin;
  for (int s = 0; s < samples.Count; ++s)
  {
    const double v = Dot(n2, g, basis + s * n2);
    vmin = std::min(vmin, v);
    vmax = std::max(vmax, v);
  }
  return GuardRemap(order, g, vmin, vmax, tolerance);
}

template <typename T>
bool GuardRemap(int order, T* g, double vmin, double vmax, double tolerance)
{
  const int n2 = NumCoefficients(order);
  const double lo = -tolerance, hi = 1.0 + tolerance;
  if (vmin >= lo && vmax <= hi)
  {
    return false;
  }
  const double newMin = std::min(std::max(vmin, lo), hi);
  const double newMax = std::max(std::min(vmax, hi), lo);
  const double range = vmax - vmin;
  const double scale = range > 0.0 ? (newMax - newMin) / range : 0.0;
  // v' = newMin + (v - vmin) * scale, applied to the coefficients.
  const double offset = newMin - vmin * scale;
  for (int i = 1; i < n2; ++i)
  {
    g[i] = static_cast<T>(g[i] * scale);
  }
  g[0] = static_cast<T>(range > 0.0 ? g[0] * scale + offset * SqrtFourPi : newMin * SqrtFourPi);
  return true;
}

template <typename T>
Status Exp(int order, const T* f, T* g, const ExpOptions& options)
{
  if (order < 1 || order > MaxOrder)
  {
    return Status::InvalidOrder;
  }
  const int n2 = NumCoefficients(order);
  if (!AllFinite(f, n2))
  {
    Fill(g, n2, T(0));
    return Status::NonFiniteInput;
  }
  const TripleProduct& tp = TripleProduct::Get(order);

  if (options.Method == ExpMethod::PS)
  {
    ProductSeries(tp, n2, options.Degree, f, g);
  }
  else
  {
    // DC isolation (eq. 20): exp(f0 / sqrt(4 pi)) is applied analytically.
    // Its 2^-s-th root goes in before the s squarings, so intermediate
    // results stay in visibility range instead of overflowing.
    T fHat[MaxCoefficients];
    std::copy(f, f + n2, fHat);
    fHat[0] = T(0);
    const double dcExponent = static_cast<double>(f[0]) / SqrtFourPi;
    const double norm = NormNoDC(n2, fHat);
    if (options.Method == ExpMethod::PSStar)
    {
      const int steps = ScalingSteps(norm);
      Scale(n2, fHat, static_cast<T>(std::ldexp(1.0, -steps)));
      FactoredSeries(tp, n2, options.Degree, fHat, g);
      Scale(n2, g, static_cast<T>(std::exp(std::ldexp(dcExponent, -steps))));
      RepeatedSquare(tp, n2, steps, g);
    }
    else if (options.Method == ExpMethod::OL)
    {
      OptimalLinear(CapTables::Get(order), n2, fHat, static_cast<T>(norm), g);
      Scale(n2, g, static_cast<T>(std::exp(std::min(dcExponent, 700.0))));
    }
    else
    {
      HybridExp(order, tp, fHat, norm, dcExponent, options, g);
    }
  }
  if (!AllFinite(g, n2))
  {
    Fill(g, n2, T(0));
    return Status::NonFiniteResult;
  }
  if (options.RangeGuard)
  {
    GuardRange(order, g, options.RangeTolerance);
  }
  return Status::Ok;
}

void ExpByProjection(int order, const double* f, double* g)
{
  const SphereQuadrature rule(6 * order + 16);
  Project(
    order, [&](double x, double y, double z) { return std::exp(Reconstruct(order, f, x, y, z)); },
    rule, g);
}

// T is a type here: it cannot take the parentheses the check asks for.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PGI_INSTANTIATE(T)                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT Status Exp<T>(int, const T*, T*, const ExpOptions&);   \
  template PROXYGISPHERICALHARMONICS_EXPORT bool GuardRange<T>(int, T*, double);                   \
  template PROXYGISPHERICALHARMONICS_EXPORT bool GuardInBounds<T>(int, const T*, double);          \
  template PROXYGISPHERICALHARMONICS_EXPORT bool GuardRemap<T>(int, T*, double, double, double);
PGI_INSTANTIATE(float)
PGI_INSTANTIATE(double)
#undef PGI_INSTANTIATE
// NOLINTEND(bugprone-macro-parentheses)

} // namespace sh
} // namespace proxygi
