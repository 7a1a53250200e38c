#include "pgiSHTripleProduct.h"

#include "pgiSHBasis.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace proxygi
{
namespace sh
{

namespace
{
constexpr int MaxTensorOrder = 2 * MaxOrder;
constexpr double KeepThreshold = 1e-12;

void LM(int i, int& l, int& m)
{
  l = BandOf(i);
  m = i - l * l - l;
}
} // namespace

bool TripleProduct::Allowed(int i, int j, int k)
{
  int l1, m1, l2, m2, l3, m3;
  LM(i, l1, m1);
  LM(j, l2, m2);
  LM(k, l3, m3);
  if ((l1 + l2 + l3) % 2 != 0)
  {
    return false;
  }
  if (l3 < std::abs(l1 - l2) || l3 > l1 + l2)
  {
    return false;
  }
  // sin(m phi) factors (m < 0) must come in pairs for the phi integral to live.
  const int negatives = (m1 < 0) + (m2 < 0) + (m3 < 0);
  if (negatives % 2 != 0)
  {
    return false;
  }
  const int a = std::abs(m1), b = std::abs(m2), c = std::abs(m3);
  return c == a + b || c == std::abs(a - b);
}

std::size_t TripleProduct::CountAllowed(int order)
{
  const int n2 = NumCoefficients(order);
  std::size_t count = 0;
  for (int i = 0; i < n2; ++i)
  {
    for (int j = 0; j < n2; ++j)
    {
      for (int k = 0; k < n2; ++k)
      {
        count += Allowed(i, j, k) ? 1 : 0;
      }
    }
  }
  return count;
}

TripleProduct::TripleProduct(int order)
  : Order(order)
{
  if (order < 1 || order > MaxTensorOrder)
  {
    throw std::invalid_argument("TripleProduct: order out of range");
  }
  const int n2 = NumCoefficients(order);
  const SphereQuadrature rule = SphereQuadrature::ForDegree(3 * (order - 1));
  const std::size_t nq = rule.Size();
  std::vector<double> basis(nq * n2);
  for (std::size_t q = 0; q < nq; ++q)
  {
    EvaluateBasis(order, rule.X[q], rule.Y[q], rule.Z[q], &basis[q * n2]);
  }

  // Unique sorted triples a <= b <= c.
  std::map<std::tuple<int, int, int>, double> unique;
  for (int a = 0; a < n2; ++a)
  {
    for (int b = a; b < n2; ++b)
    {
      for (int c = b; c < n2; ++c)
      {
        if (!Allowed(a, b, c))
        {
          continue;
        }
        double v = 0.0;
        for (std::size_t q = 0; q < nq; ++q)
        {
          const double* y = &basis[q * n2];
          v += rule.W[q] * y[a] * y[b] * y[c];
        }
        if (std::fabs(v) > KeepThreshold)
        {
          unique[std::make_tuple(a, b, c)] = v;
          this->NonzeroOrdered += (a == b && b == c) ? 1 : ((a == b || b == c) ? 3 : 6);
        }
      }
    }
  }

  for (int i = 0; i < n2; ++i)
  {
    for (int j = 0; j < n2; ++j)
    {
      for (int k = j; k < n2; ++k)
      {
        std::array<int, 3> s = { i, j, k };
        std::sort(s.begin(), s.end());
        const auto it = unique.find(std::make_tuple(s[0], s[1], s[2]));
        if (it == unique.end())
        {
          continue;
        }
        Term t;
        t.I = static_cast<std::uint16_t>(i);
        t.J = static_cast<std::uint16_t>(j);
        t.K = static_cast<std::uint16_t>(k);
        t.Value = it->second;
        t.ValueF = static_cast<float>(it->second);
        this->Entries.push_back(t);
      }
    }
  }
}

const TripleProduct& TripleProduct::Get(int order)
{
  if (order < 1 || order > MaxTensorOrder)
  {
    throw std::invalid_argument("TripleProduct::Get: order out of range");
  }
  static std::array<std::unique_ptr<TripleProduct>, MaxTensorOrder + 1> cache;
  static std::array<std::once_flag, MaxTensorOrder + 1> once;
  std::call_once(once[order], [order]() { cache[order].reset(new TripleProduct(order)); });
  return *cache[order];
}

double TripleProduct::Value(int i, int j, int k) const
{
  if (j > k)
  {
    std::swap(j, k);
  }
  for (const Term& t : this->Entries)
  {
    if (t.I == i && t.J == j && t.K == k)
    {
      return t.Value;
    }
  }
  return 0.0;
}

namespace
{
template <typename T>
inline T TermValue(const TripleProduct::Term& t);
template <>
inline double TermValue<double>(const TripleProduct::Term& t)
{
  return t.Value;
}
template <>
inline float TermValue<float>(const TripleProduct::Term& t)
{
  return t.ValueF;
}
} // namespace

template <typename T>
void TripleProduct::Product(const T* f, const T* g, T* out) const
{
  Fill(out, NumCoefficients(this->Order), T(0));
  for (const Term& t : this->Entries)
  {
    const T v = TermValue<T>(t);
    if (t.J == t.K)
    {
      out[t.I] += v * f[t.J] * g[t.J];
    }
    else
    {
      out[t.I] += v * (f[t.J] * g[t.K] + f[t.K] * g[t.J]);
    }
  }
}

template <typename T>
void TripleProduct::Square(const T* f, T* out) const
{
  Fill(out, NumCoefficients(this->Order), T(0));
  for (const Term& t : this->Entries)
  {
    const T v = TermValue<T>(t);
    out[t.I] += (t.J == t.K ? v : T(2) * v) * f[t.J] * f[t.K];
  }
}

template <typename T>
void TripleProduct::ProductMatrix(const T* f, T* matrix) const
{
  const int n2 = NumCoefficients(this->Order);
  Fill(matrix, n2 * n2, T(0));
  for (const Term& t : this->Entries)
  {
    const T v = TermValue<T>(t);
    matrix[t.I * n2 + t.J] += v * f[t.K];
    if (t.J != t.K)
    {
      matrix[t.I * n2 + t.K] += v * f[t.J];
    }
  }
}

// T is a type here: it cannot take the parentheses the check asks for.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PGI_INSTANTIATE(T)                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void TripleProduct::Product<T>(const T*, const T*, T*) \
    const;                                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void TripleProduct::Square<T>(const T*, T*) const;     \
  template PROXYGISPHERICALHARMONICS_EXPORT void TripleProduct::ProductMatrix<T>(const T*, T*)     \
    const;
PGI_INSTANTIATE(float)
PGI_INSTANTIATE(double)
#undef PGI_INSTANTIATE
// NOLINTEND(bugprone-macro-parentheses)

} // namespace sh
} // namespace proxygi
