#include "pgiSHLog.h"

#include "pgiSHBasis.h"
#include "pgiSHTripleProduct.h"

#include <Eigen/Dense>

#include <algorithm>

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
} // namespace

Status Log(int order, const double* g, double* f, const LogOptions& options)
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
  if (!(options.RelativeClip >= 0.0) || !(options.AbsoluteFloor > 0.0))
  {
    return Status::InvalidArgument;
  }
  Eigen::MatrixXd m(n2, n2);
  TripleProduct::Get(order).ProductMatrix(g, m.data()); // symmetric: layout is moot
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m);
  if (eig.info() != Eigen::Success)
  {
    return Status::NonFiniteResult;
  }
  const Eigen::VectorXd& d = eig.eigenvalues();
  const double floor = std::max(options.RelativeClip * d.maxCoeff(), options.AbsoluteFloor);
  Eigen::VectorXd q(n2);
  for (int i = 0; i < n2; ++i)
  {
    q[i] = LogRatio(std::max(d[i], floor));
  }
  Eigen::VectorXd gm1 = Eigen::Map<const Eigen::VectorXd>(g, n2);
  gm1[0] -= SqrtFourPi;
  const Eigen::MatrixXd& r = eig.eigenvectors();
  const Eigen::VectorXd result = r * q.asDiagonal() * (r.transpose() * gm1);
  if (!result.allFinite())
  {
    return Status::NonFiniteResult;
  }
  Eigen::Map<Eigen::VectorXd>(f, n2) = result;
  return Status::Ok;
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
