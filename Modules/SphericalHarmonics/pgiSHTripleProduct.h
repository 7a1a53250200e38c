/**
 * @file pgiSHTripleProduct.h
 * @brief The SH triple-product tensor Gamma_ijk = int y_i y_j y_k, stored
 * sparse, and what it gives: the SH product f*g (truncated to order n), its
 * square, and the product matrix M_f with (M_f)_ij = sum_k Gamma_ijk f_k.
 *
 * Gamma is computed once per order by a Gauss product rule that integrates
 * the degree-3(n-1) integrands exactly, in double precision. Only entries
 * with |Gamma| > 1e-12 are kept.
 */
#ifndef pgiSHTripleProduct_h
#define pgiSHTripleProduct_h

#include "pgiSH.h"

#include <cstdint>
#include <vector>

namespace proxygi
{
namespace sh
{

class PROXYGISPHERICALHARMONICS_EXPORT TripleProduct
{
public:
  /// The cached tensor of one order (1..MaxOrder * 2); thread-safe.
  static const TripleProduct& Get(int order);

  explicit TripleProduct(int order);

  int GetOrder() const { return this->Order; }

  /// Selection rules of real SH (parity, triangle inequality, m rule).
  static bool Allowed(int i, int j, int k);
  /// Ordered triples (i, j, k) the selection rules allow.
  static std::size_t CountAllowed(int order);
  /// Ordered triples whose value is nonzero.
  std::size_t CountNonzero() const { return this->NonzeroOrdered; }
  /// Gamma_ijk (0 for entries not stored).
  double Value(int i, int j, int k) const;

  /// One stored term: out[i] += value * (f[j] g[k] + f[k] g[j]) for j < k,
  /// value * f[j] g[j] for j == k.
  struct Term
  {
    std::uint16_t I, J, K;
    double Value;
    float ValueF;
  };
  const std::vector<Term>& Terms() const { return this->Entries; }

  /// out = f * g (order n in, order n out). out may not alias f or g.
  template <typename T>
  void Product(const T* f, const T* g, T* out) const;
  /// out = f * f; cheaper than Product.
  template <typename T>
  void Square(const T* f, T* out) const;
  /// M (n^2 x n^2, row-major) with M g = f * g.
  template <typename T>
  void ProductMatrix(const T* f, T* matrix) const;

private:
  int Order;
  std::size_t NonzeroOrdered = 0;
  std::vector<Term> Entries; // sorted by I, then J <= K
};

} // namespace sh
} // namespace proxygi

#endif
