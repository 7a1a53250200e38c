#include "pgiSHLightTables.h"

#include "pgiSHBasis.h"
#include "pgiSHRotation.h"
#include "pgiSHTableCache.h"
#include "pgiSHZonal.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace proxygi
{
namespace sh
{

constexpr int IndirectTables::DefaultResolution;
constexpr double IndirectTables::MaxAngle;
constexpr int AnalyticLightTables::DefaultThetaResolution;
constexpr int AnalyticLightTables::DefaultPhiResolution;
constexpr double AnalyticLightTables::MaxTheta;
constexpr double AnalyticLightTables::MaxPhi;

namespace
{
void CheckOrder(int order, const char* what)
{
  if (order < 1 || order > MaxOrder)
  {
    throw std::invalid_argument(std::string(what) + ": order out of range");
  }
}

// Within this of pi/2 the sphere touches the receiver: use the limit.
constexpr double TouchEpsilon = 1e-6;

/*
 * Quadrature over the part of a sphere (centre at distance 1 from the
 * receiver, radius r = sin theta) that the receiver sees, by
 * t = cos(angle between the surface normal u and the direction centre ->
 * receiver), t in [r, 1]. The receiver-to-surface distance is
 * delta = sqrt(1 - 2 r t + r^2), and cos(gamma) = (t - r) / delta is the
 * cosine between u and the direction to the receiver. Per unit azimuth:
 *   solid angle: d omega = r^2 (t - r) / delta^3 dt,
 *   Guerrero's weight: cos(gamma) dA (unit sphere) = (t - r) / delta dt.
 * For r < 1/2 Gauss-Legendre in t; above, t in terms of x = ln(delta),
 * t = (1 + r^2 - delta^2) / (2 r), which keeps the integrand entire as the
 * receiver approaches the surface.
 */
struct SurfaceRule
{
  double R, OneMinusR; // 1 - r without cancellation (r -> 1 matters)
  std::vector<double> T, OneMinusT, Delta, Weight;
};

enum class Measure
{
  SolidAngle,
  CosineArea
};

void VisibleSurfaceRule(double theta, Measure measure, SurfaceRule& rule)
{
  // Near pi/2, r, c and 1 - r all from eps = pi/2 - theta, so they agree.
  const double eps = 0.5 * Pi - theta;
  const bool near = theta > 0.25 * Pi;
  const double r = near ? std::cos(eps) : std::sin(theta);
  const double c = near ? std::sin(eps) : std::cos(theta);
  const double oneMinusR = near ? 2.0 * std::pow(std::sin(0.5 * eps), 2) : 1.0 - r;
  std::vector<double> nodes, weights;
  if (r < 0.5)
  {
    GaussLegendre(48, r, 1.0, nodes, weights);
  }
  else
  {
    GaussLegendre(96, std::log(oneMinusR), std::log(c), nodes, weights);
  }
  const std::size_t count = nodes.size();
  rule.R = r;
  rule.OneMinusR = oneMinusR;
  rule.T.resize(count);
  rule.OneMinusT.resize(count);
  rule.Delta.resize(count);
  rule.Weight.resize(count);
  for (std::size_t q = 0; q < count; ++q)
  {
    double t, oneMinusT, delta, tMinusR, jacobian;
    if (r < 0.5)
    {
      t = nodes[q];
      oneMinusT = 1.0 - t;
      delta = std::sqrt(oneMinusR * oneMinusR + 2.0 * r * oneMinusT);
      tMinusR = t - r;
      jacobian = 1.0;
    }
    else
    {
      delta = std::exp(nodes[q]);
      oneMinusT = (delta - oneMinusR) * (delta + oneMinusR) / (2.0 * r);
      t = 1.0 - oneMinusT;
      tMinusR = (c - delta) * (c + delta) / (2.0 * r);
      jacobian = delta * delta / r; // dt = delta^2 / r dx
    }
    const double w =
      measure == Measure::SolidAngle ? r * r * tMinusR / (delta * delta * delta) : tMinusR / delta;
    rule.T[q] = t;
    rule.OneMinusT[q] = oneMinusT;
    rule.Delta[q] = delta;
    rule.Weight[q] = weights[q] * w * jacobian;
  }
}

double SinFromOneMinus(double oneMinusT, double t)
{
  return std::sqrt(std::max(0.0, oneMinusT * (1.0 + t)));
}

// Normalised average of y_l0 over the visible surface, normal axis sign
// `axis` (-1: Sloan's frame, proxy on +z; +1: axis towards the receiver).
void SurfaceAverageZonal(int order, double theta, Measure measure, double axis, double* zh)
{
  SurfaceRule rule;
  VisibleSurfaceRule(theta, measure, rule);
  double basis[MaxCoefficients];
  double total = 0.0;
  Fill(zh, order, 0.0);
  for (std::size_t q = 0; q < rule.T.size(); ++q)
  {
    EvaluateBasis(
      order, SinFromOneMinus(rule.OneMinusT[q], rule.T[q]), 0.0, axis * rule.T[q], basis);
    total += rule.Weight[q];
    for (int l = 0; l < order; ++l)
    {
      zh[l] += rule.Weight[q] * basis[Index(l, 0)];
    }
  }
  for (int l = 0; l < order; ++l)
  {
    zh[l] /= total;
  }
}

// Far-sphere limit (theta -> 0): the visible hemisphere weighted by cos(gamma) = t.
void ClampedCosineAverage(int order, double axis, double* scaledZh)
{
  ClampedCosineZonal(order, scaledZh);
  for (int l = 0; l < order; ++l)
  {
    scaledZh[l] *= ZonalScale(l) / Pi * ((l % 2 == 1 && axis < 0) ? -1.0 : 1.0);
  }
}

// Touching limit (theta -> pi/2): everything is seen at the contact normal.
void ContactAverage(int order, double axis, double* scaledZh)
{
  for (int l = 0; l < order; ++l)
  {
    // ZonalScale(l) K_l0 = 1.
    scaledZh[l] = (l % 2 == 1 && axis < 0) ? -1.0 : 1.0;
  }
}

void AverageZonal(int order, double theta, Measure measure, double axis, double* scaledZh)
{
  theta = std::min(std::max(theta, 0.0), Pi / 2);
  if (theta <= 1e-100) // also where sin^2 would underflow
  {
    ClampedCosineAverage(order, axis, scaledZh);
    return;
  }
  if (theta >= Pi / 2 - TouchEpsilon)
  {
    ContactAverage(order, axis, scaledZh);
    return;
  }
  SurfaceAverageZonal(order, theta, measure, axis, scaledZh);
  for (int l = 0; l < order; ++l)
  {
    scaledZh[l] *= ZonalScale(l);
  }
}

/*
 * Rings of the light cap about d = (sin phi, 0, cos phi): points
 * s = cos(rho) d + sin(rho) (cos(psi) e1 + sin(psi) e2), e1 = (cos phi, 0,
 * -sin phi), e2 = +y, so s_z = cos(rho) cos(phi) - sin(rho) sin(phi) cos(psi).
 * Above the horizon where cos(psi) < kappa = cos(rho) cos(phi) /
 * (sin(rho) sin(phi)): the ring is whole for rho < pi/2 - phi, empty for
 * rho < phi - pi/2, and an arc psi in (acos kappa, 2 pi - acos kappa)
 * beyond rhoBreak = |pi/2 - phi|. Mirror symmetry in y leaves only m >= 0.
 */
class RingIntegrator
{
public:
  RingIntegrator(int order, double phi)
    : Order(order)
    , CosPhi(std::cos(phi))
    , SinPhi(std::sin(phi))
    , Break(std::fabs(0.5 * Pi - phi))
    , WholeBelowBreak(phi < 0.5 * Pi)
  {
    GaussLegendre(2 * order + 10, 0.0, 1.0, this->PsiNodes, this->PsiWeights);
    GaussLegendre(12, 0.0, 1.0, this->RhoNodes, this->RhoWeights);
  }

  double GetBreak() const { return this->Break; }

  // Adds (1/pi) int_a^b sin(rho) ring(rho) drho to v; [a, b] must not straddle the break.
  void Add(double a, double b, double* v) const
  {
    if (b <= a)
    {
      return;
    }
    const bool partial = a >= this->Break;
    if (!partial && !this->WholeBelowBreak)
    {
      return; // below the horizon
    }
    // Beyond the break the ring integral goes as (rho - break)^(3/2):
    // integrate in tau = sqrt(rho - break), where it is smooth.
    const double lo = partial ? std::sqrt(a - this->Break) : a;
    const double hi = partial ? std::sqrt(b - this->Break) : b;
    for (std::size_t k = 0; k < this->RhoNodes.size(); ++k)
    {
      const double x = lo + (hi - lo) * this->RhoNodes[k];
      const double rho = partial ? this->Break + x * x : x;
      const double jacobian = (hi - lo) * this->RhoWeights[k] * (partial ? 2.0 * x : 1.0);
      this->AddRing(rho, jacobian * std::sin(rho) / Pi, v);
    }
  }

  // Adds over [a, b], split at the break and into pieces of at most `step`.
  void AddRange(double a, double b, double step, double* v) const
  {
    const double cuts[3] = { a, std::min(std::max(this->Break, a), b), b };
    for (int p = 0; p < 2; ++p)
    {
      const double pa = cuts[p], pb = cuts[p + 1];
      const int pieces = std::max(1, static_cast<int>(std::ceil((pb - pa) / step)));
      for (int i = 0; i < pieces; ++i)
      {
        this->Add(pa + (pb - pa) * i / pieces, pa + (pb - pa) * (i + 1) / pieces, v);
      }
    }
  }

private:
  void AddRing(double rho, double weight, double* v) const
  {
    const double cr = std::cos(rho), sr = std::sin(rho);
    const double num = cr * this->CosPhi, den = sr * this->SinPhi;
    double psi0;
    if (den <= 1e-300)
    {
      if (num <= 0.0)
      {
        return;
      }
      psi0 = 0.0;
    }
    else
    {
      const double kappa = num / den;
      if (kappa <= -1.0)
      {
        return;
      }
      psi0 = kappa >= 1.0 ? 0.0 : std::acos(kappa);
    }
    const double dx = this->SinPhi, dz = this->CosPhi; // d
    const double e1x = this->CosPhi, e1z = -this->SinPhi;
    double basis[MaxCoefficients];
    for (std::size_t q = 0; q < this->PsiNodes.size(); ++q)
    {
      const double psi = psi0 + (Pi - psi0) * this->PsiNodes[q];
      const double cp = std::cos(psi), sp = std::sin(psi);
      const double sx = cr * dx + sr * cp * e1x, sy = sr * sp, sz = cr * dz + sr * cp * e1z;
      const double cosine = std::max(0.0, sz);
      // Both halves of the arc: factor 2.
      const double w = 2.0 * weight * (Pi - psi0) * this->PsiWeights[q] * cosine;
      EvaluateBasis(this->Order, sx, sy, sz, basis);
      for (int l = 0; l < this->Order; ++l)
      {
        for (int m = 0; m <= l; ++m)
        {
          v[Index(l, m)] += w * basis[Index(l, m)];
        }
      }
    }
  }

  int Order;
  double CosPhi, SinPhi, Break;
  bool WholeBelowBreak;
  std::vector<double> PsiNodes, PsiWeights, RhoNodes, RhoWeights;
};

double SquaredNorm(int count, const double* v)
{
  return Dot(count, v, v);
}
} // namespace

void AveragedIndirectZonal(int order, double theta, double* scaledZh)
{
  CheckOrder(order, "AveragedIndirectZonal");
  AverageZonal(order, theta, Measure::SolidAngle, -1.0, scaledZh);
}

void SphericalLightWeightZonal(int order, double theta, double* scaledZh)
{
  CheckOrder(order, "SphericalLightWeightZonal");
  AverageZonal(order, theta, Measure::CosineArea, 1.0, scaledZh);
}

void ExactIndirectBlocks(int order, double theta, double* blocks)
{
  CheckOrder(order, "ExactIndirectBlocks");
  Fill(blocks, ExactIndirectBlockSize(order), 0.0);
  theta = std::min(std::max(theta, 0.0), Pi / 2);
  if (theta <= 1e-100)
  {
    return;
  }
  if (theta >= Pi / 2 - TouchEpsilon)
  {
    // The hemisphere above the contact point, all of it showing R(-z).
    double cap[MaxOrder];
    CapZonal(order, Pi / 2, cap);
    for (int l = 0; l < order; ++l)
    {
      for (int lp = 0; lp < order; ++lp)
      {
        blocks[l * order + lp] = cap[l] * BasisNormalization(lp, 0) * (lp % 2 == 1 ? -1.0 : 1.0);
      }
    }
    return;
  }
  // M_{(l,m),(l',m)} = A_m int y_lm(s) y_l'm(u) d omega at azimuth 0, with
  // A_0 = 2 pi and A_m = pi (int cos^2(m phi) = int sin^2(m phi)).
  SurfaceRule rule;
  VisibleSurfaceRule(theta, Measure::SolidAngle, rule);
  const double r = rule.R;
  double ys[MaxCoefficients], yu[MaxCoefficients];
  for (std::size_t q = 0; q < rule.T.size(); ++q)
  {
    const double t = rule.T[q], st = SinFromOneMinus(rule.OneMinusT[q], t);
    const double delta = rule.Delta[q];
    // Hit point q = (0, 0, 1) + r u with u = (st, 0, -t); s = q / delta.
    const double oneMinusRT = rule.OneMinusR + r * rule.OneMinusT[q];
    EvaluateBasis(order, r * st / delta, 0.0, oneMinusRT / delta, ys);
    EvaluateBasis(order, st, 0.0, -t, yu);
    for (int m = 0; m < order; ++m)
    {
      const int size = order - m;
      double* block = blocks + ExactIndirectBlockOffset(order, m);
      const double w = rule.Weight[q] * (m == 0 ? 2.0 * Pi : Pi);
      for (int l = m; l < order; ++l)
      {
        const double a = w * ys[Index(l, m)];
        for (int lp = m; lp < order; ++lp)
        {
          block[(l - m) * size + (lp - m)] += a * yu[Index(lp, m)];
        }
      }
    }
  }
}

template <typename T>
void ApplyExactIndirectBlocks(int order, const T* blocks, const T* in, T* out)
{
  Fill(out, NumCoefficients(order), T(0));
  for (int m = 0; m < order; ++m)
  {
    const int size = order - m;
    const T* block = blocks + ExactIndirectBlockOffset(order, m);
    for (int sign = (m == 0 ? 1 : -1); sign <= 1; sign += 2)
    {
      for (int l = m; l < order; ++l)
      {
        T acc = T(0);
        for (int lp = m; lp < order; ++lp)
        {
          acc += block[(l - m) * size + (lp - m)] * in[Index(lp, sign * m)];
        }
        out[Index(l, sign * m)] = acc;
      }
    }
  }
}

void AnalyticLightVector(int order, double theta, double phi, double* out)
{
  CheckOrder(order, "AnalyticLightVector");
  Fill(out, NumCoefficients(order), 0.0);
  theta = std::min(std::max(theta, 0.0), Pi / 2);
  phi = std::min(std::max(phi, 0.0), Pi);
  RingIntegrator rings(order, phi);
  rings.AddRange(0.0, theta, 0.05, out);
}

double FitZonalLobe(int order, const double* v, double fallbackAngle, ZonalLobe& lobe)
{
  CheckOrder(order, "FitZonalLobe");
  const int n2 = NumCoefficients(order);
  // Per-band optimum at a given axis; returns sum_l scaled_l^2.
  auto project = [&](double angle, double* scaled)
  {
    double basis[MaxCoefficients];
    EvaluateBasis(order, std::sin(angle), 0.0, std::cos(angle), basis);
    double total = 0.0;
    for (int l = 0; l < order; ++l)
    {
      double p = 0.0;
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        p += v[i] * basis[i];
      }
      // c_l = v_l . b_l with the unit vector b_l = ZonalScale(l) y_l(axis);
      // the fit is c_l b_l, i.e. scaled ZH c_l ZonalScale(l).
      const double c = ZonalScale(l) * p;
      scaled[l] = c * ZonalScale(l);
      total += c * c;
    }
    return total;
  };
  double scaled[MaxOrder];
  const double higher = SquaredNorm(n2 - 1, v + 1);
  double angle = fallbackAngle;
  if (order > 1 && higher > 1e-28 * std::max(1.0, v[0] * v[0]))
  {
    // The objective has period pi (axis and its opposite fit alike) and at
    // most order - 1 maxima per period: a grid of 16 order samples brackets
    // the best, golden section refines it.
    const int samples = 16 * order;
    const double h = Pi / samples;
    double best = -1.0;
    for (int k = 0; k < samples; ++k)
    {
      const double f = project(k * h, scaled);
      if (f > best)
      {
        best = f;
        angle = k * h;
      }
    }
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = angle - h, b = angle + h;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = project(x1, scaled), f2 = project(x2, scaled);
    for (int it = 0; it < 80 && b - a > 1e-14; ++it)
    {
      if (f1 > f2)
      {
        b = x2;
        x2 = x1;
        f2 = f1;
        x1 = b - g * (b - a);
        f1 = project(x1, scaled);
      }
      else
      {
        a = x1;
        x1 = x2;
        f1 = f2;
        x2 = a + g * (b - a);
        f2 = project(x2, scaled);
      }
    }
    angle = 0.5 * (a + b);
    project(angle, scaled);
    if (scaled[1] < 0.0)
    {
      angle += Pi;
    }
  }
  angle = std::remainder(angle, 2.0 * Pi); // (-pi, pi]
  project(angle, scaled);
  lobe.Angle = angle;
  Fill(lobe.ScaledZh, MaxOrder, 0.0);
  std::copy(scaled, scaled + order, lobe.ScaledZh);
  double fit[MaxCoefficients];
  EvaluateZonalLobe(order, angle, scaled, fit);
  double residual = 0.0;
  for (int i = 0; i < n2; ++i)
  {
    residual += (v[i] - fit[i]) * (v[i] - fit[i]);
  }
  return residual;
}

template <typename T>
void EvaluateZonalLobe(int order, T angle, const T* scaledZh, T* out)
{
  RotateScaledZonal(order, scaledZh, std::sin(angle), T(0), std::cos(angle), out);
}

// ---------------------------------------------------------------------------
IndirectTables::IndirectTables(int order, int resolution, int fitDegree)
  : Order(order)
  , Resolution(resolution)
  , FitDegree(fitDegree)
{
  CheckOrder(order, "IndirectTables");
  if (resolution < 2)
  {
    throw std::invalid_argument("IndirectTables: resolution must be at least 2");
  }
  if (fitDegree < 0 || fitDegree > 12)
  {
    throw std::invalid_argument("IndirectTables: fit degree must lie in 0..12");
  }
  this->ThetaScale = (resolution - 1) / MaxAngle;
  ClampedCosineZonal(order, this->DiffuseScaled);
  for (int l = 0; l < order; ++l)
  {
    this->DiffuseScaled[l] *= ZonalScale(l) / Pi; // as DiffuseTransfer
  }
  const int mSize = ExactIndirectBlockSize(order);
  this->D.resize(resolution * order);
  this->W.resize(resolution * order);
  this->M.resize(resolution * mSize);
  // Each angle's integrals (the tables' cost), a sample each: the tables'
  // angles (D, W, M), then the fit's grid of alpha = sin theta (D alone).
  // Read from the disk cache where it holds them, else computed (in
  // parallel: a process's first update waits on these tables) and written.
  const int samples = 1024, terms = fitDegree + 1, width = 2 * order + mSize;
  std::vector<double> integrals(static_cast<std::size_t>(resolution + samples) * width, 0.0);
  const auto integrate = [&](int s, double* out)
  {
    if (s < resolution)
    {
      const double theta = MaxAngle * s / (resolution - 1);
      AveragedIndirectZonal(order, theta, out);
      SphericalLightWeightZonal(order, theta, out + order);
      ExactIndirectBlocks(order, theta, out + 2 * order);
    }
    else
    {
      const double alpha = static_cast<double>(s - resolution) / (samples - 1);
      AveragedIndirectZonal(order, std::asin(alpha), out);
      std::fill(out + order, out + width, 0.0);
    }
  };
  char name[120];
  std::snprintf(
    name, sizeof(name), "indirect-order%d-resolution%d-samples%d.bin", order, resolution, samples);
  CachedSamples(name, width, integrals, integrate);
  for (int i = 0; i < resolution; ++i)
  {
    const double* at = &integrals[static_cast<std::size_t>(i) * width];
    std::copy_n(at, order, &this->D[i * order]);
    std::copy_n(at + order, order, &this->W[i * order]);
    std::copy_n(at + 2 * order, mSize, &this->M[i * mSize]);
  }
  this->DF.assign(this->D.begin(), this->D.end());
  this->WF.assign(this->W.begin(), this->W.end());
  this->MF.assign(this->M.begin(), this->M.end());

  // Least-squares polynomial in alpha = sin theta, per band, on a fine
  // uniform alpha grid (Sloan's Figure 4 fits against sin theta).
  Eigen::MatrixXd vandermonde(samples, terms);
  Eigen::MatrixXd values(samples, order);
  for (int k = 0; k < samples; ++k)
  {
    const double alpha = static_cast<double>(k) / (samples - 1);
    double power = 1.0;
    for (int p = 0; p < terms; ++p, power *= alpha)
    {
      vandermonde(k, p) = power;
    }
    for (int l = 0; l < order; ++l)
    {
      values(k, l) = integrals[static_cast<std::size_t>(resolution + k) * width + l];
    }
  }
  const Eigen::MatrixXd coefficients = vandermonde.colPivHouseholderQr().solve(values);
  const Eigen::MatrixXd fitted = vandermonde * coefficients;
  this->Fit.resize(order * terms);
  this->FitError.resize(order);
  for (int l = 0; l < order; ++l)
  {
    for (int p = 0; p < terms; ++p)
    {
      this->Fit[l * terms + p] = coefficients(p, l);
    }
    const double norm = values.col(l).squaredNorm();
    this->FitError[l] = norm > 0.0 ? (fitted.col(l) - values.col(l)).squaredNorm() / norm : 0.0;
  }
}

const IndirectTables& IndirectTables::Get(int order)
{
  CheckOrder(order, "IndirectTables::Get");
  static std::array<std::unique_ptr<IndirectTables>, MaxOrder + 1> cache;
  static std::array<std::once_flag, MaxOrder + 1> once;
  std::call_once(once[order], [order]() { cache[order].reset(new IndirectTables(order)); });
  return *cache[order];
}

template <typename T>
T IndirectTables::AveragedRadiance(T theta, const T d[3], const T* radiance) const
{
  T kappa;
  this->AveragedRadiances(theta, d, 1, &radiance, &kappa);
  return kappa;
}

template <typename T>
void IndirectTables::AveragedRadiances(
  T theta, const T d[3], int count, const T* const* radiances, T* kappas) const
{
  T basis[MaxCoefficients];
  EvaluateBasis(this->Order, d[0], d[1], d[2], basis);
  this->AveragedRadiancesFromBasis(theta, basis, count, radiances, kappas);
}

template <typename T>
void IndirectTables::AveragedRadiancesFromBasis(
  T theta, const T* basis, int count, const T* const* radiances, T* kappas) const
{
  T zh[MaxOrder];
  this->AveragedIndirect(theta, zh);
  for (int c = 0; c < count; ++c)
  {
    const T* radiance = radiances[c];
    T kappa = T(0);
    for (int l = 0; l < this->Order; ++l)
    {
      T band = T(0);
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        band += basis[i] * radiance[i];
      }
      kappa += zh[l] * band;
    }
    kappas[c] = kappa;
  }
}

template <typename T>
T IndirectTables::SphericalLightRadiance(T theta, const T d[3], const T* radiance) const
{
  T basis[MaxCoefficients];
  EvaluateBasis(this->Order, d[0], d[1], d[2], basis);
  return this->SphericalLightRadianceFromBasis(theta, basis, radiance);
}

template <typename T>
T IndirectTables::SphericalLightRadianceFromBasis(T theta, const T* basis, const T* radiance) const
{
  // w's axis is -d: y_lm(-d) = (-1)^l y_lm(d).
  T zh[MaxOrder];
  this->SphericalLightWeight(theta, zh);
  T value = T(0);
  for (int l = 0; l < this->Order; ++l)
  {
    T band = T(0);
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      band += basis[i] * radiance[i];
    }
    value += (l % 2 == 1 ? -zh[l] : zh[l]) * band;
  }
  return value;
}

namespace
{
// Rotation taking +z to d (F) and its transpose.
template <typename T>
void ProxyFrame(const T d[3], double frame[9], double frameT[9])
{
  FrameFromAxis(d[0], d[1], d[2], frame);
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      frameT[i * 3 + j] = frame[j * 3 + i];
    }
  }
}
} // namespace

template <typename T>
void IndirectTables::ExactIndirectRadiance(
  T theta, const T d[3], const T* radiance, T* incident) const
{
  double frame[9], frameT[9];
  ProxyFrame(d, frame, frameT);
  T blocks[ExactIndirectBlockSize(MaxOrder)], canonical[MaxCoefficients], result[MaxCoefficients];
  this->ExactIndirect(theta, blocks);
  // Canonical radiance R_c(s) = R(F s); result back by I(s) = I_c(F^T s).
  RotateSH(this->Order, frameT, radiance, canonical);
  ApplyExactIndirectBlocks(this->Order, blocks, canonical, result);
  RotateSH(this->Order, frame, result, incident);
}

template <typename T>
T IndirectTables::ExactIndirectExitRadiance(
  T theta, const T d[3], const T normal[3], const T* radiance) const
{
  double frame[9], frameT[9];
  ProxyFrame(d, frame, frameT);
  T blocks[ExactIndirectBlockSize(MaxOrder)], canonical[MaxCoefficients], result[MaxCoefficients],
    h[MaxCoefficients], hZh[MaxOrder];
  this->ExactIndirect(theta, blocks);
  RotateSH(this->Order, frameT, radiance, canonical);
  ApplyExactIndirectBlocks(this->Order, blocks, canonical, result);
  // The dot product is rotation invariant: turn N into the canonical frame.
  T n[3];
  for (int i = 0; i < 3; ++i)
  {
    n[i] = static_cast<T>(
      frameT[3 * i] * normal[0] + frameT[3 * i + 1] * normal[1] + frameT[3 * i + 2] * normal[2]);
  }
  for (int l = 0; l < this->Order; ++l)
  {
    hZh[l] = static_cast<T>(this->DiffuseScaled[l]);
  }
  RotateScaledZonal(this->Order, hZh, n[0], n[1], n[2], h);
  return Dot(NumCoefficients(this->Order), h, result);
}

template <typename T>
void IndirectTables::AveragedIndirectFit(T alpha, T* scaledZh) const
{
  alpha = alpha > T(0) ? (alpha < T(1) ? alpha : T(1)) : T(0);
  const int terms = this->FitDegree + 1;
  for (int l = 0; l < this->Order; ++l)
  {
    const double* c = &this->Fit[l * terms];
    T value = static_cast<T>(c[terms - 1]);
    for (int p = terms - 2; p >= 0; --p)
    {
      value = value * alpha + static_cast<T>(c[p]);
    }
    scaledZh[l] = value;
  }
}

// ---------------------------------------------------------------------------
AnalyticLightTables::AnalyticLightTables(int order, int thetaResolution, int phiResolution)
  : Order(order)
  , ThetaResolution(thetaResolution)
  , PhiResolution(phiResolution)
{
  CheckOrder(order, "AnalyticLightTables");
  if (thetaResolution < 2 || phiResolution < 2)
  {
    throw std::invalid_argument("AnalyticLightTables: resolutions must be at least 2");
  }
  this->ThetaScale = (thetaResolution - 1) / MaxTheta;
  this->PhiScale = (phiResolution - 1) / MaxPhi;
  const int n2 = NumCoefficients(order), row = order + 1;
  this->Lobes.resize(thetaResolution * phiResolution * row);
  std::vector<double> norms(thetaResolution * phiResolution), residuals(norms.size());
  double sumResidual = 0.0, sumNorm = 0.0;
  for (int j = 0; j < phiResolution; ++j)
  {
    const double phi = MaxPhi * j / (phiResolution - 1);
    RingIntegrator rings(order, phi);
    // Cumulative in theta: each entry adds the rings of one theta step.
    double v[MaxCoefficients] = {};
    for (int i = 0; i < thetaResolution; ++i)
    {
      const double theta = MaxTheta * i / (thetaResolution - 1);
      if (i > 0)
      {
        rings.AddRange(MaxTheta * (i - 1) / (thetaResolution - 1), theta, 1.0, v);
      }
      // Where nothing is lit (theta = 0, or below the horizon) the lobe
      // angle is free: take the limit direction of a small or grazing light.
      ZonalLobe lobe;
      const double residual = FitZonalLobe(order, v, std::min(phi, 0.5 * Pi), lobe);
      double* out = &this->Lobes[(i * phiResolution + j) * row];
      out[0] = lobe.Angle;
      std::copy(lobe.ScaledZh, lobe.ScaledZh + order, out + 1);
      norms[i * phiResolution + j] = std::sqrt(SquaredNorm(n2, v));
      residuals[i * phiResolution + j] = std::sqrt(residual);
      sumResidual += residual;
      sumNorm += SquaredNorm(n2, v);
    }
  }
  this->FitRms = sumNorm > 0.0 ? std::sqrt(sumResidual / sumNorm) : 0.0;
  const double largest = *std::max_element(norms.begin(), norms.end());
  for (std::size_t k = 0; k < norms.size(); ++k)
  {
    this->FitWorstAbs = std::max(this->FitWorstAbs, residuals[k]);
    if (norms[k] >= 1e-3 * largest)
    {
      this->FitWorst = std::max(this->FitWorst, residuals[k] / norms[k]);
    }
  }
  this->LobesF.assign(this->Lobes.begin(), this->Lobes.end());
}

const AnalyticLightTables& AnalyticLightTables::Get(int order)
{
  CheckOrder(order, "AnalyticLightTables::Get");
  static std::array<std::unique_ptr<AnalyticLightTables>, MaxOrder + 1> cache;
  static std::array<std::once_flag, MaxOrder + 1> once;
  std::call_once(once[order], [order]() { cache[order].reset(new AnalyticLightTables(order)); });
  return *cache[order];
}

template <typename T>
void AnalyticLightTables::Lookup(T theta, T phi, T& angle, T* scaledZh) const
{
  const int lastT = this->ThetaResolution - 1, lastP = this->PhiResolution - 1;
  T u = theta * static_cast<T>(this->ThetaScale);
  T w = phi * static_cast<T>(this->PhiScale);
  u = u > T(0) ? (u < static_cast<T>(lastT) ? u : static_cast<T>(lastT)) : T(0);
  w = w > T(0) ? (w < static_cast<T>(lastP) ? w : static_cast<T>(lastP)) : T(0);
  const int i = std::min(static_cast<int>(u), lastT - 1);
  const int j = std::min(static_cast<int>(w), lastP - 1);
  const T tu = u - static_cast<T>(i), tw = w - static_cast<T>(j);
  const int row = this->Order + 1;
  const std::size_t r00 = (i * this->PhiResolution + j) * row;
  const std::size_t r01 = r00 + row, r10 = r00 + this->PhiResolution * row, r11 = r10 + row;
  auto blend = [&](const auto& table, int k)
  {
    const T a = static_cast<T>(table[r00 + k] + (table[r01 + k] - table[r00 + k]) * tw);
    const T b = static_cast<T>(table[r10 + k] + (table[r11 + k] - table[r10 + k]) * tw);
    return a + (b - a) * tu;
  };
  for (int k = 0; k < row; ++k)
  {
    const T value = sizeof(T) == sizeof(float) ? blend(this->LobesF, k) : blend(this->Lobes, k);
    if (k == 0)
    {
      angle = value;
    }
    else
    {
      scaledZh[k - 1] = value;
    }
  }
}

template <typename T>
void AnalyticLightTables::CanonicalVector(T theta, T phi, T* out) const
{
  T angle, zh[MaxOrder];
  this->Lookup(theta, phi, angle, zh);
  EvaluateZonalLobe(this->Order, angle, zh, out);
}

template <typename T>
void AnalyticLightTables::Evaluate(const T normal[3], const T d[3], T theta, T* out) const
{
  T cosPhi = normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2];
  cosPhi = cosPhi > T(-1) ? (cosPhi < T(1) ? cosPhi : T(1)) : T(-1);
  const T phi = std::acos(cosPhi);
  if (phi >= static_cast<T>(0.5 * Pi) + theta)
  {
    Fill(out, NumCoefficients(this->Order), T(0));
    return;
  }
  // Tangent towards the light; any perpendicular when the light is at the zenith.
  T t[3] = { d[0] - cosPhi * normal[0], d[1] - cosPhi * normal[1], d[2] - cosPhi * normal[2] };
  T len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  if (!(len > static_cast<T>(1e-6)))
  {
    const int k = std::fabs(normal[0]) < static_cast<T>(0.6) ? 0 : 1;
    t[0] = T(k == 0);
    t[1] = T(k == 1);
    t[2] = T(0);
    const T dot = t[0] * normal[0] + t[1] * normal[1];
    for (int c = 0; c < 3; ++c)
    {
      t[c] -= dot * normal[c];
    }
    len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  }
  T angle, zh[MaxOrder];
  this->Lookup(theta, phi, angle, zh);
  const T ca = std::cos(angle), sa = std::sin(angle) / len;
  RotateScaledZonal(this->Order, zh, ca * normal[0] + sa * t[0], ca * normal[1] + sa * t[1],
    ca * normal[2] + sa * t[2], out);
}

// T is a type here: it cannot take the parentheses the check asks for.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PGI_INSTANTIATE(T)                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void ApplyExactIndirectBlocks<T>(                      \
    int, const T*, const T*, T*);                                                                  \
  template PROXYGISPHERICALHARMONICS_EXPORT void EvaluateZonalLobe<T>(int, T, const T*, T*);       \
  template PROXYGISPHERICALHARMONICS_EXPORT T IndirectTables::AveragedRadiance<T>(                 \
    T, const T*, const T*) const;                                                                  \
  template PROXYGISPHERICALHARMONICS_EXPORT void IndirectTables::AveragedRadiances<T>(             \
    T, const T*, int, const T* const*, T*) const;                                                  \
  template PROXYGISPHERICALHARMONICS_EXPORT void IndirectTables::AveragedRadiancesFromBasis<T>(    \
    T, const T*, int, const T* const*, T*) const;                                                  \
  template PROXYGISPHERICALHARMONICS_EXPORT T IndirectTables::SphericalLightRadiance<T>(           \
    T, const T*, const T*) const;                                                                  \
  template PROXYGISPHERICALHARMONICS_EXPORT T IndirectTables::SphericalLightRadianceFromBasis<T>(  \
    T, const T*, const T*) const;                                                                  \
  template PROXYGISPHERICALHARMONICS_EXPORT void IndirectTables::AveragedIndirectFit<T>(T, T*)     \
    const;                                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void IndirectTables::ExactIndirectRadiance<T>(         \
    T, const T*, const T*, T*) const;                                                              \
  template PROXYGISPHERICALHARMONICS_EXPORT T IndirectTables::ExactIndirectExitRadiance<T>(        \
    T, const T*, const T*, const T*) const;                                                        \
  template PROXYGISPHERICALHARMONICS_EXPORT void AnalyticLightTables::Lookup<T>(T, T, T&, T*)      \
    const;                                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void AnalyticLightTables::CanonicalVector<T>(T, T, T*) \
    const;                                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void AnalyticLightTables::Evaluate<T>(                 \
    const T*, const T*, T, T*) const;
PGI_INSTANTIATE(float)
PGI_INSTANTIATE(double)
#undef PGI_INSTANTIATE
// NOLINTEND(bugprone-macro-parentheses)

} // namespace sh
} // namespace proxygi
