#include "pgiLightCloudGlossy.h"

#include "pgiSHBasis.h"
#include "pgiSHRotation.h"
#include "vtkPGIGIBake.h"

#include "vtkDataArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "vtk_eigen.h"
#include VTK_EIGEN(Dense)

#include <cmath>
#include <string>

namespace proxygi
{
double PhongLobe(const double n[3], const double wi[3], const double wo[3], double exponent)
{
  const double no = n[0] * wo[0] + n[1] * wo[1] + n[2] * wo[2];
  const double r[3] = { 2.0 * no * n[0] - wo[0], 2.0 * no * n[1] - wo[1], 2.0 * no * n[2] - wo[2] };
  const double c = r[0] * wi[0] + r[1] * wi[1] + r[2] * wi[2];
  return c > 0.0 ? (exponent + 2.0) / (2.0 * vtkMath::Pi()) * std::pow(c, exponent) : 0.0;
}

GlossyProjection::GlossyProjection(int order, double exponent)
  : Order(std::max(1, std::min(order, sh::MaxOrder)))
  , Exponent(exponent)
{
  // Equal-area spiral over the upper hemisphere: 8 directions per
  // coefficient keep the least-squares system well posed.
  const int coefficients = this->GetCoefficients();
  const int m = std::max(64, 8 * coefficients);
  this->Directions.resize(3 * static_cast<std::size_t>(m));
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  Eigen::MatrixXd basis(m, coefficients);
  std::vector<double> y(static_cast<std::size_t>(coefficients));
  for (int k = 0; k < m; ++k)
  {
    const double z = 1.0 - (k + 0.5) / m;
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    double* d = &this->Directions[3 * static_cast<std::size_t>(k)];
    d[0] = s * std::cos(golden * k);
    d[1] = s * std::sin(golden * k);
    d[2] = z;
    sh::EvaluateBasis(this->Order, d[0], d[1], d[2], y.data());
    for (int c = 0; c < coefficients; ++c)
    {
      basis(k, c) = y[c];
    }
  }
  // Least squares over the hemisphere: (B^T B)^-1 B^T.
  const Eigen::MatrixXd gram = basis.transpose() * basis;
  const Eigen::MatrixXd projection = gram.ldlt().solve(basis.transpose());
  this->Projection.resize(static_cast<std::size_t>(coefficients) * m);
  for (int c = 0; c < coefficients; ++c)
  {
    for (int k = 0; k < m; ++k)
    {
      this->Projection[static_cast<std::size_t>(c) * m + k] = projection(c, k);
    }
  }
}

void GlossyProjection::Frame(const double n[3], double R[9], std::vector<double>& toWorld) const
{
  sh::FrameFromAxis(n[0], n[1], n[2], R);
  const int coefficients = this->GetCoefficients();
  toWorld.assign(static_cast<std::size_t>(coefficients) * coefficients, 0.0);
  std::vector<double> unit(static_cast<std::size_t>(coefficients), 0.0);
  std::vector<double> column(static_cast<std::size_t>(coefficients));
  for (int c = 0; c < coefficients; ++c)
  {
    unit[c] = 1.0;
    sh::RotateSH(this->Order, R, unit.data(), column.data());
    unit[c] = 0.0;
    for (int r = 0; r < coefficients; ++r)
    {
      toWorld[static_cast<std::size_t>(r) * coefficients + c] = column[r];
    }
  }
}

void GlossyProjection::ToLocal(const double R[9], const double w[3], double local[3])
{
  for (int a = 0; a < 3; ++a)
  {
    local[a] = R[a] * w[0] + R[3 + a] * w[1] + R[6 + a] * w[2];
  }
}

void GlossyProjection::Project(const double* values, double* out) const
{
  const int m = this->GetDirections();
  const int coefficients = this->GetCoefficients();
  for (int c = 0; c < coefficients; ++c)
  {
    double sum = 0.0;
    for (int k = 0; k < m; ++k)
    {
      sum += this->Projection[static_cast<std::size_t>(c) * m + k] * values[k];
    }
    out[c] = sum;
  }
}

void GlossyProjection::AddLobe(const double wiLocal[3], double scale, double* out) const
{
  static const double up[3] = { 0.0, 0.0, 1.0 };
  const int m = this->GetDirections();
  const int coefficients = this->GetCoefficients();
  for (int k = 0; k < m; ++k)
  {
    const double f = scale *
      PhongLobe(up, wiLocal, &this->Directions[3 * static_cast<std::size_t>(k)], this->Exponent);
    if (f == 0.0)
    {
      continue;
    }
    for (int c = 0; c < coefficients; ++c)
    {
      out[c] += this->Projection[static_cast<std::size_t>(c) * m + k] * f;
    }
  }
}

void GlossyProjection::Lobes(const double* wiLocal, int count, std::vector<double>& transfer) const
{
  const int coefficients = this->GetCoefficients();
  transfer.assign(static_cast<std::size_t>(coefficients) * count, 0.0);
  std::vector<double> one(static_cast<std::size_t>(coefficients));
  for (int s = 0; s < count; ++s)
  {
    std::fill(one.begin(), one.end(), 0.0);
    this->AddLobe(wiLocal + 3 * static_cast<std::size_t>(s), 1.0, one.data());
    for (int c = 0; c < coefficients; ++c)
    {
      transfer[static_cast<std::size_t>(c) * count + s] = one[c];
    }
  }
}

double GlossyProjection::Evaluate(
  int order, const float* coefficients, int stride, const double wo[3])
{
  double y[sh::MaxCoefficients];
  sh::EvaluateBasis(order, wo[0], wo[1], wo[2], y);
  double sum = 0.0;
  for (int c = 0; c < order * order; ++c)
  {
    sum += coefficients[static_cast<std::ptrdiff_t>(c) * stride] * y[c];
  }
  return sum;
}

double GlossyProjection::ConstantCoefficient()
{
  return std::sqrt(4.0 * vtkMath::Pi());
}

bool ReceiverNormals(vtkPolyData* receivers, std::vector<double>& normals, std::string& error)
{
  // Computed as the GI filter computes them where missing.
  vtkSmartPointer<vtkDataArray> array = proxygi::ReceiverNormals(receivers);
  if (!array)
  {
    error = "could not compute receiver normals (no polygons?); give point normals";
    return false;
  }
  const vtkIdType n = receivers->GetNumberOfPoints();
  normals.resize(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double* nrm = &normals[3 * i];
    array->GetTuple(i, nrm);
    if (!(vtkMath::Normalize(nrm) > 0.0) || !std::isfinite(nrm[0]) || !std::isfinite(nrm[1]) ||
      !std::isfinite(nrm[2]))
    {
      nrm[0] = nrm[1] = 0.0;
      nrm[2] = 1.0;
    }
  }
  return true;
}
} // namespace proxygi
