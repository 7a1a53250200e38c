#include "pgiSHRotation.h"

#include "pgiSHBasis.h"

#include <array>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace proxygi
{
namespace sh
{

namespace
{
// Nodes and weighted basis values of a rule exact for degree 2 (order - 1).
struct RotationRule
{
  explicit RotationRule(int order)
  {
    const SphereQuadrature rule = SphereQuadrature::ForDegree(2 * (order - 1));
    const int n2 = NumCoefficients(order);
    this->X = rule.X;
    this->Y = rule.Y;
    this->Z = rule.Z;
    this->WeightedBasis.resize(rule.Size() * n2);
    for (std::size_t q = 0; q < rule.Size(); ++q)
    {
      double* row = &this->WeightedBasis[q * n2];
      EvaluateBasis(order, rule.X[q], rule.Y[q], rule.Z[q], row);
      for (int i = 0; i < n2; ++i)
      {
        row[i] *= rule.W[q];
      }
    }
  }
  std::vector<double> X, Y, Z, WeightedBasis;
};

const RotationRule& GetRule(int order)
{
  static std::array<std::unique_ptr<RotationRule>, MaxOrder + 1> cache;
  static std::array<std::once_flag, MaxOrder + 1> once;
  std::call_once(once[order], [order]() { cache[order].reset(new RotationRule(order)); });
  return *cache[order];
}
} // namespace

template <typename T>
void RotateSH(int order, const double R[9], const T* in, T* out)
{
  if (order < 1 || order > MaxOrder)
  {
    throw std::invalid_argument("RotateSH: order out of range");
  }
  const int n2 = NumCoefficients(order);
  const RotationRule& rule = GetRule(order);
  double acc[MaxCoefficients] = {};
  double basis[MaxCoefficients];
  for (std::size_t q = 0; q < rule.X.size(); ++q)
  {
    // in(R^T s_q): evaluate the input at the node turned back.
    const double x = rule.X[q], y = rule.Y[q], z = rule.Z[q];
    EvaluateBasis(order, R[0] * x + R[3] * y + R[6] * z, R[1] * x + R[4] * y + R[7] * z,
      R[2] * x + R[5] * y + R[8] * z, basis);
    double value = 0.0;
    for (int i = 0; i < n2; ++i)
    {
      value += basis[i] * in[i];
    }
    const double* wb = &rule.WeightedBasis[q * n2];
    for (int i = 0; i < n2; ++i)
    {
      acc[i] += value * wb[i];
    }
  }
  for (int i = 0; i < n2; ++i)
  {
    out[i] = static_cast<T>(acc[i]);
  }
}

void FrameFromAxis(double dx, double dy, double dz, double R[9])
{
  // Pick the helper axis least aligned with d (Frisvad-style stability).
  double ax = 0.0, ay = 0.0, az = 0.0;
  if (std::fabs(dx) <= std::fabs(dy) && std::fabs(dx) <= std::fabs(dz))
  {
    ax = 1.0;
  }
  else if (std::fabs(dy) <= std::fabs(dz))
  {
    ay = 1.0;
  }
  else
  {
    az = 1.0;
  }
  // t1 = normalize(a - (a.d) d), t2 = d x t1.
  const double ad = ax * dx + ay * dy + az * dz;
  double t1x = ax - ad * dx, t1y = ay - ad * dy, t1z = az - ad * dz;
  const double len = std::sqrt(t1x * t1x + t1y * t1y + t1z * t1z);
  t1x /= len;
  t1y /= len;
  t1z /= len;
  const double t2x = dy * t1z - dz * t1y, t2y = dz * t1x - dx * t1z, t2z = dx * t1y - dy * t1x;
  const double rows[9] = { t1x, t2x, dx, t1y, t2y, dy, t1z, t2z, dz };
  for (int i = 0; i < 9; ++i)
  {
    R[i] = rows[i];
  }
}

template PROXYGISPHERICALHARMONICS_EXPORT void RotateSH<float>(
  int, const double*, const float*, float*);
template PROXYGISPHERICALHARMONICS_EXPORT void RotateSH<double>(
  int, const double*, const double*, double*);

} // namespace sh
} // namespace proxygi
