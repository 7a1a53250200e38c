#include "pgiSHLog.h"

#include "pgiSHBasis.h"
#include "pgiSHTripleProduct.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxygi
{
namespace sh
{

namespace
{
// log(x) / (x - 1), continuous at x = 1.
double LogRatio(double x)
{
  const double d = x - 1.0;
  if (std::fabs(d) < 1e-6)
  {
    return 1.0 - 0.5 * d + d * d / 3.0;
  }
  return std::log(x) / d;
}

// Log's and LogZonal's input checks; out (count values) zeroed first.
Status CheckInput(int order, const double* in, int count, const LogOptions& options, double* out)
{
  if (order < 1 || order > MaxOrder)
  {
    return Status::InvalidOrder;
  }
  Fill(out, count, 0.0);
  if (!AllFinite(in, count))
  {
    return Status::NonFiniteInput;
  }
  if (!(options.RelativeClip >= 0.0) || !(options.AbsoluteFloor > 0.0))
  {
    return Status::InvalidArgument;
  }
  return Status::Ok;
}

// log(g) = R q'(max(D, floor)) R^T (g - 1) from M_g's eigensystem; g's first
// coefficient is its DC (the constant 1 is sqrt(4 pi) there).
Status ClippedLog(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eig, double floor,
  const double* g, double* f)
{
  const Eigen::VectorXd& d = eig.eigenvalues();
  const Eigen::Index n = d.size();
  Eigen::VectorXd q(n);
  for (Eigen::Index i = 0; i < n; ++i)
  {
    q[i] = LogRatio(std::max(d[i], floor));
  }
  Eigen::VectorXd gm1 = Eigen::Map<const Eigen::VectorXd>(g, n);
  gm1[0] -= SqrtFourPi;
  const Eigen::MatrixXd& r = eig.eigenvectors();
  const Eigen::VectorXd result = r * q.asDiagonal() * (r.transpose() * gm1);
  if (!result.allFinite())
  {
    return Status::NonFiniteResult;
  }
  Eigen::Map<Eigen::VectorXd>(f, n) = result;
  return Status::Ok;
}
} // namespace

Status Log(int order, const double* g, double* f, const LogOptions& options)
{
  const int n2 = NumCoefficients(order);
  const Status input = CheckInput(order, g, n2, options, f);
  if (input != Status::Ok)
  {
    return input;
  }
  Eigen::MatrixXd m(n2, n2);
  TripleProduct::Get(order).ProductMatrix(g, m.data()); // symmetric: layout is moot
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m);
  if (eig.info() != Eigen::Success)
  {
    return Status::NonFiniteResult;
  }
  const double floor =
    std::max(options.RelativeClip * eig.eigenvalues().maxCoeff(), options.AbsoluteFloor);
  return ClippedLog(eig, floor, g, f);
}

Status LogZonal(int order, const double* zh, double* logZh, const LogOptions& options)
{
  const Status input = CheckInput(order, zh, order, options, logZh);
  if (input != Status::Ok)
  {
    return input;
  }
  const int n2 = NumCoefficients(order);
  double g[MaxCoefficients];
  Fill(g, n2, 0.0);
  for (int l = 0; l < order; ++l)
  {
    g[Index(l, 0)] = zh[l];
  }
  Eigen::MatrixXd m(n2, n2);
  TripleProduct::Get(order).ProductMatrix(g, m.data());
  // Block m couples the bands l >= |m| of that m only.
  double largest = -std::numeric_limits<double>::infinity();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> zonal;
  for (int k = -(order - 1); k < order; ++k)
  {
    const int low = std::abs(k), size = order - low;
    Eigen::MatrixXd block(size, size);
    for (int a = 0; a < size; ++a)
    {
      for (int b = 0; b < size; ++b)
      {
        block(a, b) = m(Index(low + a, k), Index(low + b, k));
      }
    }
    if (k == 0)
    {
      zonal.compute(block);
      if (zonal.info() != Eigen::Success)
      {
        return Status::NonFiniteResult;
      }
      largest = std::max(largest, zonal.eigenvalues().maxCoeff());
    }
    else
    {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> values(block, Eigen::EigenvaluesOnly);
      if (values.info() != Eigen::Success)
      {
        return Status::NonFiniteResult;
      }
      largest = std::max(largest, values.eigenvalues().maxCoeff());
    }
  }
  return ClippedLog(
    zonal, std::max(options.RelativeClip * largest, options.AbsoluteFloor), zh, logZh);
}

Status LogByProjection(int order, const double* g, double* f, double epsilon)
{
  if (order < 1 || order > MaxOrder)
  {
    return Status::InvalidOrder;
  }
  const int n2 = NumCoefficients(order);
  Fill(f, n2, 0.0);
  if (!AllFinite(g, n2))
  {
    return Status::NonFiniteInput;
  }
  if (!(epsilon > 0.0))
  {
    return Status::InvalidArgument;
  }
  const SphereQuadrature rule(4 * order + 8);
  Project(
    order,
    [&](double x, double y, double z)
    { return std::log(std::max(Reconstruct(order, g, x, y, z), epsilon)); },
    rule, f);
  return Status::Ok;
}

} // namespace sh
} // namespace proxygi
