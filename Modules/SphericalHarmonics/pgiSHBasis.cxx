#include "pgiSHBasis.h"

#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace proxygi
{
namespace sh
{

const char* StatusString(Status status)
{
  switch (status)
  {
    case Status::Ok:
      return "ok";
    case Status::NonFiniteInput:
      return "input holds NaN or Inf";
    case Status::NonFiniteResult:
      return "result overflowed";
    case Status::InvalidOrder:
      return "SH order out of range";
    case Status::InvalidArgument:
      return "argument out of range";
  }
  return "unknown status";
}

namespace
{
// K_lm (with sqrt(2) folded in for m != 0), indexed by Index(l, m) for m >= 0.
struct NormalizationTable
{
  std::array<double, MaxBasisOrder * MaxBasisOrder> K;
  NormalizationTable()
  {
    for (int l = 0; l < MaxBasisOrder; ++l)
    {
      for (int m = 0; m <= l; ++m)
      {
        // (l-m)!/(l+m)! as a running product keeps the range safe.
        double ratio = 1.0;
        for (int k = l - m + 1; k <= l + m; ++k)
        {
          ratio /= k;
        }
        double k = std::sqrt((2 * l + 1) / (4 * Pi) * ratio);
        if (m > 0)
        {
          k *= std::sqrt(2.0);
        }
        this->K[Index(l, m)] = k;
      }
    }
  }
};

const NormalizationTable& Normalization()
{
  static const NormalizationTable table;
  return table;
}
} // namespace

double BasisNormalization(int l, int m)
{
  m = m < 0 ? -m : m;
  return Normalization().K[Index(l, m)];
}

template <typename T>
void EvaluateBasisPolynomial(int order, T x, T y, T z, T* out)
#include "pgiSHBasisPolynomials.inl"

  template <typename T>
  void EvaluateBasisRecurrence(int order, T x, T y, T z, T* out)
{
  const auto& K = Normalization().K;
  // Re/Im of (x + i y)^m: sin^m(theta) cos/sin(m phi).
  T c = T(1), s = T(0);
  // P_m^m without the sin^m factor: (2m-1)!!.
  double pmm = 1.0;
  for (int m = 0; m < order; ++m)
  {
    if (m > 0)
    {
      const T cNext = x * c - y * s;
      s = x * s + y * c;
      c = cNext;
      pmm *= (2 * m - 1);
    }
    T pPrev = static_cast<T>(pmm);
    T pCur = pPrev;
    for (int l = m; l < order; ++l)
    {
      if (l == m + 1)
      {
        pCur = z * static_cast<T>(2 * m + 1) * pPrev;
      }
      else if (l > m + 1)
      {
        const T pNext = (static_cast<T>(2 * l - 1) * z * pCur - static_cast<T>(l + m - 1) * pPrev) /
          static_cast<T>(l - m);
        pPrev = pCur;
        pCur = pNext;
      }
      const T p = static_cast<T>(K[Index(l, m)]) * pCur;
      if (m == 0)
      {
        out[Index(l, 0)] = p;
      }
      else
      {
        out[Index(l, m)] = p * c;
        out[Index(l, -m)] = p * s;
      }
    }
  }
}

template <typename T>
void EvaluateBasis(int order, T x, T y, T z, T* out)
{
  if (order <= MaxOrder)
  {
    // The batched kernels evaluate the same polynomials (pgiSHBatch.cxx).
    EvaluateBasisPolynomial(order, x, y, z, out);
  }
  else
  {
    EvaluateBasisRecurrence(order, x, y, z, out);
  }
}

template <typename T>
T Reconstruct(int order, const T* coeffs, T x, T y, T z)
{
  T basis[MaxBasisOrder * MaxBasisOrder];
  EvaluateBasis(order, x, y, z, basis);
  return Dot(NumCoefficients(order), coeffs, basis);
}

namespace
{
// The rule on [-1, 1]: nodes, and the denominators of their weights.
struct UnitGaussLegendre
{
  std::vector<double> T, Denominator;
};

UnitGaussLegendre MakeUnitGaussLegendre(int count)
{
  UnitGaussLegendre rule;
  rule.T.resize(count);
  rule.Denominator.resize(count);
  for (int i = 0; i < count; ++i)
  {
    // Newton on P_count from the Chebyshev-like first guess.
    double t = std::cos(Pi * (i + 0.75) / (count + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter)
    {
      double p0 = 1.0, p1 = t;
      for (int k = 2; k <= count; ++k)
      {
        const double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (count == 1)
      {
        p1 = t;
        p0 = 1.0;
      }
      dp = count * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::fabs(step) < 1e-16)
      {
        break;
      }
    }
    rule.T[i] = t;
    rule.Denominator[i] = (1.0 - t * t) * dp * dp;
  }
  return rule;
}
} // namespace

void GaussLegendre(
  int count, double a, double b, std::vector<double>& nodes, std::vector<double>& weights)
{
  // Newton rarely meets its 1e-16 step and runs its 100 iterations: callers
  // that ask for a rule per receiver or per light made it half a filter
  // update. Each count is solved once per process.
  static std::mutex mutex;
  static std::map<int, UnitGaussLegendre> rules;
  const UnitGaussLegendre* rule;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = rules.find(count);
    if (it == rules.end())
    {
      it = rules.emplace(count, MakeUnitGaussLegendre(count)).first;
    }
    rule = &it->second; // std::map nodes never move
  }
  nodes.resize(count);
  weights.resize(count);
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  for (int i = 0; i < count; ++i)
  {
    nodes[i] = mid + half * rule->T[i];
    weights[i] = half * 2.0 / rule->Denominator[i];
  }
}

SphereQuadrature::SphereQuadrature(int zNodes)
  : NumZ(zNodes)
{
  if (zNodes < 1)
  {
    throw std::invalid_argument("SphereQuadrature needs at least one z node");
  }
  std::vector<double> zs, ws;
  GaussLegendre(zNodes, -1.0, 1.0, zs, ws);
  const int phiNodes = 2 * zNodes;
  const double dphi = 2 * Pi / phiNodes;
  this->X.reserve(zNodes * phiNodes);
  for (int i = 0; i < zNodes; ++i)
  {
    const double st = std::sqrt(std::max(0.0, 1.0 - zs[i] * zs[i]));
    for (int j = 0; j < phiNodes; ++j)
    {
      const double phi = (j + 0.5) * dphi;
      this->X.push_back(st * std::cos(phi));
      this->Y.push_back(st * std::sin(phi));
      this->Z.push_back(zs[i]);
      this->W.push_back(ws[i] * dphi);
    }
  }
}

SphereQuadrature SphereQuadrature::ForDegree(int degree)
{
  return SphereQuadrature(std::max(1, (degree + 2) / 2));
}

void Project(int order, const SphericalFunction& f, const SphereQuadrature& rule, double* out)
{
  const int n2 = NumCoefficients(order);
  Fill(out, n2, 0.0);
  double basis[MaxBasisOrder * MaxBasisOrder];
  for (std::size_t q = 0; q < rule.Size(); ++q)
  {
    const double v = f(rule.X[q], rule.Y[q], rule.Z[q]) * rule.W[q];
    EvaluateBasis(order, rule.X[q], rule.Y[q], rule.Z[q], basis);
    for (int i = 0; i < n2; ++i)
    {
      out[i] += v * basis[i];
    }
  }
}

// T is a type here: it cannot take the parentheses the check asks for.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PGI_INSTANTIATE(T)                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void EvaluateBasis<T>(int, T, T, T, T*);               \
  template PROXYGISPHERICALHARMONICS_EXPORT void EvaluateBasisPolynomial<T>(int, T, T, T, T*);     \
  template PROXYGISPHERICALHARMONICS_EXPORT void EvaluateBasisRecurrence<T>(int, T, T, T, T*);     \
  template PROXYGISPHERICALHARMONICS_EXPORT T Reconstruct<T>(int, const T*, T, T, T);
PGI_INSTANTIATE(float)
PGI_INSTANTIATE(double)
#undef PGI_INSTANTIATE
// NOLINTEND(bugprone-macro-parentheses)

} // namespace sh
} // namespace proxygi
