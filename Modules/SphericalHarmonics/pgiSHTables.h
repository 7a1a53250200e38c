/**
 * @file pgiSHTables.h
 * @brief The 1-D tables the shading reads, built once per SH order in
 * double precision (CPU kernels read them; the GPU path uploads the same
 * arrays as textures):
 *
 * - cap visibility and cap log-visibility as ZH vectors, for a blocker of
 *   angular radius theta in [0, pi/2] (a sphere seen from outside), with the
 *   rotation factor sqrt(4 pi/(2l+1)) already folded in: the SH vector of a
 *   blocker in direction d is table_l(theta) * y_lm(d);
 * - the optimal-linear exponential curves a(x), b(x), x = |f^| (SHEXP
 *   eq. 24), fitted on the cap logs of the same angular range.
 *
 * Lookups interpolate linearly between the `Resolution` uniform samples.
 */
#ifndef pgiSHTables_h
#define pgiSHTables_h

#include "pgiSH.h"
#include "pgiSHLog.h"

#include <vector>

namespace proxygi
{
namespace sh
{

class PROXYGISPHERICALHARMONICS_EXPORT CapTables
{
public:
  static constexpr int DefaultResolution = 256;

  /// Cached tables of one order at the default resolution; thread-safe.
  static const CapTables& Get(int order);

  CapTables(int order, int resolution = DefaultResolution, const LogOptions& log = LogOptions());

  int GetOrder() const { return this->Order; }
  int GetResolution() const { return this->Resolution; }
  /// Largest tabulated angular radius (pi/2).
  static constexpr double MaxAngle = Pi / 2;

  /// Scaled ZH of the cap visibility at angular radius theta (clamped to range).
  template <typename T>
  void CapVisibility(T theta, T* scaledZh) const
  {
    this->Lookup(this->VisibilityF, this->Visibility, theta, scaledZh);
  }
  /// Scaled ZH of the cap log-visibility.
  template <typename T>
  void CapLog(T theta, T* scaledZh) const
  {
    this->Lookup(this->LogF, this->LogD, theta, scaledZh);
  }

  /// Optimal-linear coefficients at x = |f^|; beyond the table the last values.
  template <typename T>
  void OptimalLinear(T x, T& a, T& b) const
  {
    const T u = x * static_cast<T>(this->OLScale);
    const int last = this->Resolution - 1;
    if (!(u < static_cast<T>(last)))
    {
      a = static_cast<T>(this->OLA[last]);
      b = static_cast<T>(this->OLB[last]);
      return;
    }
    const int i = u > T(0) ? static_cast<int>(u) : 0;
    const T t = u - static_cast<T>(i);
    a = static_cast<T>(this->OLA[i] + (this->OLA[i + 1] - this->OLA[i]) * t);
    b = static_cast<T>(this->OLB[i] + (this->OLB[i + 1] - this->OLB[i]) * t);
  }
  /// Largest x the OL curves were fitted on (x of a cap of radius pi/2).
  double GetOptimalLinearMaxNorm() const { return this->OLMaxNorm; }
  /// x's scale to the OL tables' rows.
  double GetOptimalLinearScale() const { return this->OLScale; }

  /// Raw tables for upload: Resolution rows of Order scaled ZH values.
  const std::vector<double>& GetVisibilityTable() const { return this->Visibility; }
  const std::vector<double>& GetLogTable() const { return this->LogD; }
  const std::vector<double>& GetOptimalLinearA() const { return this->OLA; }
  const std::vector<double>& GetOptimalLinearB() const { return this->OLB; }
  /// The float log table the lookups read, and theta's scale to its rows
  /// (the batched kernels gather from it).
  const std::vector<float>& GetLogTableFloat() const { return this->LogF; }
  /// The float visibility table CapVisibility reads.
  const std::vector<float>& GetVisibilityTableFloat() const { return this->VisibilityF; }
  /// The same floats band by band: band l's rows start at l * BandStride and
  /// run on past the last row (repeated) far enough for a vector load from
  /// any row, so lanes whose rows lie close take theirs by permutation.
  const std::vector<float>& GetLogBandTable() const { return this->LogBands; }
  int GetLogBandStride() const { return this->Resolution + BandPadding; }
  static constexpr int BandPadding = 64;
  double GetThetaScale() const { return this->ThetaScale; }

private:
  template <typename T, typename Table>
  void Lookup(const std::vector<float>& tf, const Table& td, T theta, T* out) const;

  int Order;
  int Resolution;
  double ThetaScale; // (Resolution - 1) / MaxAngle
  double OLScale;    // (Resolution - 1) / OLMaxNorm
  double OLMaxNorm;
  std::vector<double> Visibility, LogD, OLA, OLB;
  std::vector<float> VisibilityF, LogF, LogBands;
};

template <typename T, typename Table>
inline void CapTables::Lookup(const std::vector<float>& tf, const Table& td, T theta, T* out) const
{
  T u = theta * static_cast<T>(this->ThetaScale);
  const int last = this->Resolution - 1;
  u = u > T(0) ? (u < static_cast<T>(last) ? u : static_cast<T>(last)) : T(0);
  int i = static_cast<int>(u);
  i = i < last ? i : last - 1;
  const T t = u - static_cast<T>(i);
  const int n = this->Order;
  if (sizeof(T) == sizeof(float))
  {
    const float* r0 = &tf[i * n];
    const float* r1 = r0 + n;
    for (int l = 0; l < n; ++l)
    {
      out[l] = static_cast<T>(r0[l] + (r1[l] - r0[l]) * t);
    }
  }
  else
  {
    const double* r0 = &td[i * n];
    const double* r1 = r0 + n;
    for (int l = 0; l < n; ++l)
    {
      out[l] = static_cast<T>(r0[l] + (r1[l] - r0[l]) * t);
    }
  }
}

} // namespace sh
} // namespace proxygi

#endif
