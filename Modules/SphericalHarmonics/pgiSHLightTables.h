/**
 * @file pgiSHLightTables.h
 * @brief Tables for light from spheres: indirect light from proxies (Sloan
 * et al. 2007), average radiance of spherical lights (Guerrero et al. 2008)
 * and analytic spherical lights (SHEXP, Ren et al. 2006, section 7).
 *
 * Geometry: a sphere of angular radius theta in [0, pi/2] seen from a
 * receiver p (centre at distance 1, radius sin theta). Its "radiance SH"
 * R is a function of the sphere's outward surface normal: the radiance the
 * sphere's surface leaves with, in radiance units (for a diffuse proxy
 * under distant light L: R_lm = albedo ZonalScale(l) g_l / pi L_lm with g
 * the ClampedCosineZonal, i.e. albedo / pi times the irradiance SH). A
 * uniform R = 1 gives 1 everywhere.
 *
 * 1-D tables (IndirectTables, 256 uniform samples of theta in [0, pi/2]):
 * - D(theta), Sloan 2007 eq. 14, the averaged operator: the solid-angle
 *   average over the visible disk of R at the surface point hit,
 *   D_l = (1/omega) int_cap y_l0(n(s)) ds. Stored as scaled ZH about +z =
 *   direction receiver -> proxy centre (its lobe points back at -z);
 *   kappa = sum_lm D_l y_lm(d) R_lm is that average for a proxy in
 *   direction d, and kappa * cap(theta, d) (CapZonal rotated) is the
 *   proxy's incident radiance SH at p.
 * - w_theta, Guerrero 2008 eqs. 16-18: R averaged over the visible part of
 *   the sphere with weight max(0, cos gamma) dA (no 1/distance^2, as in the
 *   paper; D is the exact solid-angle average). Scaled ZH about +z =
 *   direction centre -> receiver.
 * - M(theta), Sloan 2007 eq. 16, the exact operator in the canonical frame
 *   (proxy centre on +z): I_j = sum_k M_jk R_k is the projection of the
 *   incident radiance v(s) R(n(s)). It commutes with rotations about z, so
 *   it is stored as blocks m = 0..n-1 of size (n-m)^2 (row l, column l',
 *   l, l' >= m) applied alike to the +m and -m coefficients.
 * - a polynomial fit of D_l in alpha = sin theta (Sloan's Figure 4).
 *
 * 2-D table (AnalyticLightTables, 64 x 64 uniform samples of theta in
 * [0, pi/2] and phi in [0, pi]): L_H(theta, phi), SHEXP section 7, the SH
 * projection of (1/pi) max(s.z, 0) * cap(theta, d(phi))(s) with
 * d(phi) = (sin phi, 0, cos phi): the light of radiance 1 times H(N) for
 * N = +z. L_H . g is the exit radiance of a white receiver with visibility
 * g (the same units as DiffuseTransfer); L_H . (sqrt(4 pi), 0, ..) =
 * sin^2 theta cos phi when the light is above the horizon. Stored as the
 * fitted single lobe: angle beta of the lobe axis (sin beta, 0, cos beta)
 * and n scaled ZH values.
 *
 * "Scaled ZH" means z_l * sqrt(4 pi / (2l + 1)) (as in CapTables): the SH
 * vector of the ZH turned to the unit axis a is scaled_l * y_lm(a)
 * (RotateScaledZonal).
 */
#ifndef pgiSHLightTables_h
#define pgiSHLightTables_h

#include "pgiSH.h"

#include <vector>

namespace proxygi
{
namespace sh
{

/// Solid angle 2 pi (1 - cos theta) of a sphere of angular radius theta.
template <typename T>
inline T CapSolidAngle(T theta)
{
  // 1 - cos = 2 sin^2(theta / 2) without cancellation.
  const T s = std::sin(T(0.5) * theta);
  return T(4.0 * Pi) * s * s;
}

/**
 * Overlap normalisation xi of Sloan 2007 eq. 12: the solid angle all proxies
 * cover together over the sum of their solid angles,
 *   xi = (1 - O)_0 / (omega_sum / sqrt(4 pi)) = (4 pi - sqrt(4 pi) O_0) / omega_sum,
 * O_0 the DC coefficient of the total visibility (exp of the summed logs),
 * omega_sum = sum_i CapSolidAngle(theta_i) (or, with re-weighted tables,
 * sum_i sqrt(4 pi) (V_i)_0). Multiplies the summed indirect radiance.
 * Clamped to [0, 1] (SH approximations can leave the exact range); 1 when
 * no proxy covers anything.
 */
template <typename T>
inline T OverlapNormalization(T visibilityDC, T summedSolidAngle)
{
  if (!(summedSolidAngle > T(0)))
  {
    return T(1);
  }
  const T covered = static_cast<T>(4.0 * Pi) - static_cast<T>(SqrtFourPi) * visibilityDC;
  const T xi = covered / summedSolidAngle;
  return xi > T(1) ? T(1) : (xi > T(0) ? xi : T(0));
}

/// D(theta) as scaled ZH (order values), computed directly (double).
PROXYGISPHERICALHARMONICS_EXPORT void AveragedIndirectZonal(
  int order, double theta, double* scaledZh);

/// Guerrero's w_theta as scaled ZH (order values), computed directly.
PROXYGISPHERICALHARMONICS_EXPORT void SphericalLightWeightZonal(
  int order, double theta, double* scaledZh);

/// Number of values of the M(theta) blocks: n (n + 1) (2n + 1) / 6.
constexpr int ExactIndirectBlockSize(int order)
{
  return order * (order + 1) * (2 * order + 1) / 6;
}

/// Offset of block m in the M(theta) blocks: sum_{k<m} (n - k)^2.
constexpr int ExactIndirectBlockOffset(int order, int m)
{
  return m == 0 ? 0 : ExactIndirectBlockOffset(order, m - 1) + (order - m + 1) * (order - m + 1);
}

/// M(theta) blocks computed directly.
PROXYGISPHERICALHARMONICS_EXPORT void ExactIndirectBlocks(int order, double theta, double* blocks);

/// out = M in in the canonical frame (in and out must not alias).
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void ApplyExactIndirectBlocks(
  int order, const T* blocks, const T* in, T* out);

/// L_H(theta, phi) in the canonical frame, order^2 values, computed directly.
PROXYGISPHERICALHARMONICS_EXPORT void AnalyticLightVector(
  int order, double theta, double phi, double* out);

/// A single ZH lobe about (sin Angle, 0, cos Angle) (Sloan et al. 2005).
struct ZonalLobe
{
  double Angle = 0.0;
  double ScaledZh[MaxOrder] = {};
};

/**
 * Least-squares single-lobe fit of an order^2 vector whose lobe axis lies
 * in the xz plane: maximises sum_l c_l^2 over the angle, with
 * c_l = sqrt(4 pi/(2l+1)) sum_m v_lm y_lm(axis) the per-band optimum
 * (scaled ZH c_l sqrt(4 pi/(2l+1))).
 * The axis is taken on the side where c_1 >= 0. `fallbackAngle` is
 * used when the vector has no band-1 or higher content. Returns the
 * squared residual |v - fit|^2.
 */
PROXYGISPHERICALHARMONICS_EXPORT double FitZonalLobe(
  int order, const double* v, double fallbackAngle, ZonalLobe& lobe);

/// The SH vector of a lobe: scaledZh_l y_lm((sin angle, 0, cos angle)).
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void EvaluateZonalLobe(
  int order, T angle, const T* scaledZh, T* out);

/**
 * D(theta), w_theta and M(theta) tabulated over theta in [0, pi/2], and the
 * polynomial fit of D. Lookups clamp theta and interpolate linearly; the
 * float overloads read float copies of the same double tables.
 */
class PROXYGISPHERICALHARMONICS_EXPORT IndirectTables
{
public:
  static constexpr int DefaultResolution = 256;
  static constexpr double MaxAngle = Pi / 2;

  /// Cached tables of one order (1..MaxOrder) at the default resolution; thread-safe.
  static const IndirectTables& Get(int order);

  /// fitDegree: highest power of sin theta in the D fit (bands 1..n-1).
  IndirectTables(int order, int resolution = DefaultResolution, int fitDegree = 3);

  int GetOrder() const { return this->Order; }
  int GetResolution() const { return this->Resolution; }
  /// theta's scale to table rows, and the float D table AveragedIndirect
  /// reads (Resolution rows of Order values; the batched kernels gather it).
  double GetThetaScale() const { return this->ThetaScale; }
  const std::vector<float>& GetAveragedTableFloat() const { return this->DF; }

  /// D(theta): scaled ZH, lobe axis +z = receiver -> proxy centre.
  template <typename T>
  void AveragedIndirect(T theta, T* scaledZh) const
  {
    this->Lookup(this->DF, this->D, this->Order, theta, scaledZh);
  }
  /// w_theta: scaled ZH, lobe axis +z = light centre -> receiver.
  template <typename T>
  void SphericalLightWeight(T theta, T* scaledZh) const
  {
    this->Lookup(this->WF, this->W, this->Order, theta, scaledZh);
  }
  /// M(theta): ExactIndirectBlockSize(order) values.
  template <typename T>
  void ExactIndirect(T theta, T* blocks) const
  {
    this->Lookup(this->MF, this->M, ExactIndirectBlockSize(this->Order), theta, blocks);
  }

  /**
   * kappa = rot(D(theta), d) . R: the average radiance of a proxy of
   * angular radius theta in unit direction d (receiver -> centre) whose
   * surface radiance SH is R. Its incident radiance SH at the receiver is
   * kappa times the cap of half-angle theta about d.
   */
  template <typename T>
  T AveragedRadiance(T theta, const T d[3], const T* radiance) const;

  /// AveragedRadiance for several radiance SH about one proxy (the colour
  /// channels), sharing the table look-up and the basis: the same values.
  template <typename T>
  void AveragedRadiances(
    T theta, const T d[3], int count, const T* const* radiances, T* kappas) const;

  /// The same with the basis at d already evaluated (EvaluateBasis), for
  /// callers that need it for the cap too.
  template <typename T>
  void AveragedRadiancesFromBasis(
    T theta, const T* basis, int count, const T* const* radiances, T* kappas) const;

  /// Guerrero's average radiance w_theta . R for a light in direction d (receiver -> centre).
  template <typename T>
  T SphericalLightRadiance(T theta, const T d[3], const T* radiance) const;

  /// The same with the basis at d already evaluated (EvaluateBasis).
  template <typename T>
  T SphericalLightRadianceFromBasis(T theta, const T* basis, const T* radiance) const;

  /**
   * Exact incident radiance SH at the receiver, R^-1 M(theta) R applied to
   * the proxy radiance (Sloan eq. 17): order^2 values in the world frame.
   */
  template <typename T>
  void ExactIndirectRadiance(T theta, const T d[3], const T* radiance, T* incident) const;

  /**
   * H(N) . (R^-1 M R radiance): the exit radiance of a white receiver with
   * unit normal N lit by the proxy (unshadowed), with one SH rotation
   * instead of two.
   */
  template <typename T>
  T ExactIndirectExitRadiance(T theta, const T d[3], const T normal[3], const T* radiance) const;

  /// Polynomial fit of D: scaled ZH at alpha = sin theta in [0, 1].
  template <typename T>
  void AveragedIndirectFit(T alpha, T* scaledZh) const;
  /// Coefficients, band-major, power-minor: Order rows of FitDegree + 1 values.
  const std::vector<double>& GetFitCoefficients() const { return this->Fit; }
  int GetFitDegree() const { return this->FitDegree; }
  /// Relative squared error of the fit of band l, sum (fit - D)^2 / sum D^2 over alpha.
  double GetFitRelativeSquaredError(int l) const { return this->FitError[l]; }

  /// Raw tables for upload: Resolution rows of Order (D, W) or
  /// ExactIndirectBlockSize(Order) (M) values; row i is theta = i * pi/2 / (Resolution - 1).
  const std::vector<double>& GetAveragedIndirectTable() const { return this->D; }
  const std::vector<double>& GetSphericalLightWeightTable() const { return this->W; }
  const std::vector<double>& GetExactIndirectTable() const { return this->M; }

private:
  template <typename T>
  void Lookup(const std::vector<float>& tf, const std::vector<double>& td, int rowSize, T theta,
    T* out) const;

  int Order;
  int Resolution;
  int FitDegree;
  double ThetaScale;              // (Resolution - 1) / MaxAngle
  double DiffuseScaled[MaxOrder]; // scaled ZH of H(+z)
  std::vector<double> D, W, M, Fit, FitError;
  std::vector<float> DF, WF, MF;
};

/**
 * The analytic spherical-light table L_H(theta, phi) (SHEXP section 7) as
 * fitted single lobes, with bilinear lookup, and the fit's errors.
 */
class PROXYGISPHERICALHARMONICS_EXPORT AnalyticLightTables
{
public:
  static constexpr int DefaultThetaResolution = 64;
  static constexpr int DefaultPhiResolution = 64;
  static constexpr double MaxTheta = Pi / 2;
  static constexpr double MaxPhi = Pi;

  /// Cached table of one order (1..MaxOrder) at the default resolution; thread-safe.
  static const AnalyticLightTables& Get(int order);

  AnalyticLightTables(int order, int thetaResolution = DefaultThetaResolution,
    int phiResolution = DefaultPhiResolution);

  int GetOrder() const { return this->Order; }
  int GetThetaResolution() const { return this->ThetaResolution; }
  int GetPhiResolution() const { return this->PhiResolution; }

  /// The fitted lobe at (theta, phi), bilinear in both (clamped to range).
  template <typename T>
  void Lookup(T theta, T phi, T& angle, T* scaledZh) const;

  /// L_H(theta, phi) from the fitted lobe, canonical frame (order^2 values).
  template <typename T>
  void CanonicalVector(T theta, T phi, T* out) const;

  /**
   * L_H for a receiver with unit normal N and a spherical light of radiance
   * 1 and angular radius theta in unit direction d (receiver -> light
   * centre), in the world frame: dot with a visibility vector for the exit
   * radiance of a white receiver; multiply by the light's radiance.
   * Zero when the light is wholly below the horizon.
   */
  template <typename T>
  void Evaluate(const T normal[3], const T d[3], T theta, T* out) const;

  /// Fit error over the grid: sqrt(sum |v - fit|^2 / sum |v|^2).
  double GetFitRelativeRms() const { return this->FitRms; }
  /// Largest |v - fit| / |v| over grid entries with |v| >= 1e-3 max |v|.
  double GetFitWorstRelative() const { return this->FitWorst; }
  /// Largest |v - fit| over the grid, for a light of radiance 1.
  double GetFitWorstAbsolute() const { return this->FitWorstAbs; }

  /// Raw table for upload: row (i * PhiResolution + j) for theta_i, phi_j holds
  /// Order + 1 values: the lobe angle, then Order scaled ZH values.
  const std::vector<double>& GetLobeTable() const { return this->Lobes; }

private:
  int Order;
  int ThetaResolution, PhiResolution;
  double ThetaScale, PhiScale;
  double FitRms = 0.0, FitWorst = 0.0, FitWorstAbs = 0.0;
  std::vector<double> Lobes;
  std::vector<float> LobesF;
};

template <typename T>
inline void IndirectTables::Lookup(
  const std::vector<float>& tf, const std::vector<double>& td, int rowSize, T theta, T* out) const
{
  T u = theta * static_cast<T>(this->ThetaScale);
  const int last = this->Resolution - 1;
  u = u > T(0) ? (u < static_cast<T>(last) ? u : static_cast<T>(last)) : T(0);
  int i = static_cast<int>(u);
  i = i < last ? i : last - 1;
  const T t = u - static_cast<T>(i);
  if (sizeof(T) == sizeof(float))
  {
    const float* r0 = &tf[i * rowSize];
    const float* r1 = r0 + rowSize;
    for (int k = 0; k < rowSize; ++k)
    {
      out[k] = static_cast<T>(r0[k] + (r1[k] - r0[k]) * t);
    }
  }
  else
  {
    const double* r0 = &td[i * rowSize];
    const double* r1 = r0 + rowSize;
    for (int k = 0; k < rowSize; ++k)
    {
      out[k] = static_cast<T>(r0[k] + (r1[k] - r0[k]) * t);
    }
  }
}

} // namespace sh
} // namespace proxygi

#endif
