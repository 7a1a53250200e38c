/**
 * @file pgiLightCloudGlossy.h
 * @brief Glossy receivers in the light cloud: the exit radiance of a
 * receiver as a function of the view direction, projected on SH by least
 * squares over the hemisphere above it (Sloan et al. 2003, as Kristensen
 * et al. 2005 do), and its evaluation toward a viewer.
 *
 * The BRDF is Lambert plus normalised Phong: f = kd/pi + ks (e+2)/(2 pi)
 * max(0, r . wi)^e with r the view direction mirrored about the normal.
 * Per receiver the exit radiance is projected in its own frame (normal on
 * +z, FrameFromAxis) with one fixed matrix, then turned to the world frame
 * (RotateSH), so relighting adds world-frame coefficients and a viewer
 * evaluates them at its world direction.
 */
#ifndef pgiLightCloudGlossy_h
#define pgiLightCloudGlossy_h

#include "ProxyGILightCloudModule.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace proxygi
{
/// The normalised Phong lobe (e+2)/(2 pi) max(0, r . wi)^e, r = 2 (n.wo) n - wo.
PROXYGILIGHTCLOUD_EXPORT double PhongLobe(
  const double n[3], const double wi[3], const double wo[3], double exponent);

class PROXYGILIGHTCLOUD_EXPORT GlossyProjection
{
public:
  /// SH of `order` (order^2 coefficients) for a lobe of `exponent`.
  GlossyProjection(int order, double exponent);

  int GetOrder() const { return this->Order; }
  int GetCoefficients() const { return this->Order * this->Order; }
  int GetDirections() const { return static_cast<int>(this->Directions.size() / 3); }

  /// The receiver's frame (row-major, maps +z to n) and the C x C matrix
  /// turning its local coefficients to world ones (row-major).
  void Frame(const double n[3], double R[9], std::vector<double>& toWorld) const;
  /// The hemisphere's view directions the projection samples (local).
  const double* GetDirection(int m) const
  {
    return &this->Directions[3 * static_cast<std::size_t>(m)];
  }
  /// Least-squares coefficients (C values, set) of a function given by its
  /// values at the GetDirections() directions.
  void Project(const double* values, double* out) const;

  /// Local direction of world direction w (R^T w).
  static void ToLocal(const double R[9], const double w[3], double local[3]);

  /**
   * Local coefficients of the Phong lobe for unit irradiance from the local
   * direction wi: added, times `scale`, to out[c] (C values).
   */
  void AddLobe(const double wiLocal[3], double scale, double* out) const;
  /**
   * The lobes of `count` local incident directions at once: transfer is
   * C x count, row-major (coefficient c of direction s at c * count + s).
   */
  void Lobes(const double* wiLocal, int count, std::vector<double>& transfer) const;

  /// sum_c coefficients[c * stride] y_c(wo), world frame, wo unit.
  static double Evaluate(int order, const float* coefficients, int stride, const double wo[3]);
  /// The coefficient 0 of the constant function 1 (sqrt(4 pi)).
  static double ConstantCoefficient();

private:
  int Order;
  double Exponent;
  std::vector<double> Directions; // the hemisphere's view directions, local
  std::vector<double> Projection; // C x directions, least squares
};

/**
 * The receivers' unit point normals as the light cloud uses them: the
 * input's, or computed without splitting (so points stay 1:1); +z where a
 * normal is zero or not finite. False (with `error`) when none can be had.
 */
PROXYGILIGHTCLOUD_EXPORT bool ReceiverNormals(
  vtkPolyData* receivers, std::vector<double>& normals, std::string& error);
} // namespace proxygi

#endif
