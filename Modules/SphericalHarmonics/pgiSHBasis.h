/**
 * @file pgiSHBasis.h
 * @brief Real SH basis evaluation, sphere quadrature, projection and
 * reconstruction (conventions in pgiSH.h).
 */
#ifndef pgiSHBasis_h
#define pgiSHBasis_h

#include "pgiSH.h"

#include <functional>
#include <vector>

namespace proxygi
{
namespace sh
{

/**
 * Evaluates all order^2 basis functions at the unit direction (x, y, z).
 * Uses the closed-form polynomials for order <= 6 and the recurrence above.
 * order must lie in 1..MaxBasisOrder; the direction is not normalised here.
 */
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void EvaluateBasis(int order, T x, T y, T z, T* out);

/// Closed-form polynomials (generated), order 1..6.
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void EvaluateBasisPolynomial(int order, T x, T y, T z, T* out);

/// Associated-Legendre recurrence, order 1..MaxBasisOrder.
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void EvaluateBasisRecurrence(int order, T x, T y, T z, T* out);

/// Reconstructs sum_i coeffs[i] y_i(x, y, z).
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT T Reconstruct(int order, const T* coeffs, T x, T y, T z);

/**
 * Product quadrature on the sphere: Gauss-Legendre in z = cos(theta) times
 * uniform in phi. With n z-nodes and 2n phi-nodes it integrates every
 * spherical polynomial of degree <= 2n - 1 exactly.
 */
class PROXYGISPHERICALHARMONICS_EXPORT SphereQuadrature
{
public:
  explicit SphereQuadrature(int zNodes);

  /// Smallest rule exact for polynomials of the given total degree.
  static SphereQuadrature ForDegree(int degree);

  std::size_t Size() const { return this->W.size(); }
  int ZNodes() const { return this->NumZ; }

  std::vector<double> X, Y, Z, W;

private:
  int NumZ;
};

/// Gauss-Legendre nodes and weights on [a, b].
PROXYGISPHERICALHARMONICS_EXPORT void GaussLegendre(
  int count, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

using SphericalFunction = std::function<double(double x, double y, double z)>;

/**
 * Projects f onto the order-n basis with the given quadrature. Exact for
 * polynomial f of degree <= (2 * zNodes - 1) - (order - 1); discontinuous f
 * converges as the rule grows.
 */
PROXYGISPHERICALHARMONICS_EXPORT void Project(
  int order, const SphericalFunction& f, const SphereQuadrature& rule, double* out);

/// Normalisation K_lm (times sqrt(2) for m != 0), double precision.
PROXYGISPHERICALHARMONICS_EXPORT double BasisNormalization(int l, int m);

} // namespace sh
} // namespace proxygi

#endif
