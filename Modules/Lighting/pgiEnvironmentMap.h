/**
 * @file pgiEnvironmentMap.h
 * @brief A distant environment light stored as a lat-long RGB radiance map.
 *
 * Convention (one for the whole project): row 0 is the top (+z); the texel
 * (i, j) of a W x H map covers phi in 2 pi [i, i+1)/W and theta in
 * pi [j, j+1)/H, with direction (sin t cos p, sin t sin p, cos t) in map
 * space. A rotation about +z (radians) turns map space into world space.
 * Radiance is piecewise constant per texel; the SH projection integrates
 * each texel's exact solid angle, and the importance sampler draws from the
 * same piecewise-constant density, so the reference renderer and the SH
 * shading see one and the same light.
 */
#ifndef pgiEnvironmentMap_h
#define pgiEnvironmentMap_h

#include "ProxyGILightingModule.h"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

class vtkImageData;

namespace proxygi
{

class PROXYGILIGHTING_EXPORT EnvironmentMap
{
public:
  EnvironmentMap() = default;
  /// A uniform environment of the given radiance (a 2 x 1 map).
  static EnvironmentMap Uniform(float r, float g, float b);

  /// From a vtkImageData with a 3- or 4-component float point array (VTK rows
  /// run bottom-up). Fails with a message for non-2:1 or non-finite data.
  static bool FromImage(vtkImageData* image, EnvironmentMap& map, std::string& error);
  /// To a vtkImageData with a 3-component float "Radiance" array.
  void ToImage(vtkImageData* image) const;

  /// Builds the map from top-down RGB rows; width must be 2 x height.
  bool Set(int width, int height, const float* rgb, std::string& error);
  /// The same, taking the rows without a copy.
  bool Set(int width, int height, std::vector<float>&& rgb, std::string& error);
  /// Fills with a function of the map-space direction.
  void SetFromFunction(int width, int height,
    void (*radiance)(const double dir[3], float rgb[3], void* data), void* data);

  int GetWidth() const { return this->Width; }
  int GetHeight() const { return this->Height; }
  const std::vector<float>& GetRGB() const { return this->RGB; }

  void SetRotation(double radiansAboutZ);
  double GetRotation() const { return this->Rotation; }

  /// Radiance arriving from the world-space direction d (unit).
  void Lookup(const double d[3], float rgb[3]) const;

  /// Draws a world-space direction with density proportional to luminance
  /// (x sin theta); returns its solid-angle pdf. u1, u2 in [0, 1).
  double Sample(double u1, double u2, double d[3], float rgb[3]) const;
  /// The solid-angle pdf Sample() has for direction d.
  double Pdf(const double d[3]) const;

  /// SH projection of each channel (order n: 3 rows of n^2), in world space.
  void ProjectSH(int order, double* red, double* green, double* blue) const;

  /// Irradiance E(n) = int L max(n.w, 0) dw as SH (the projection convolved
  /// with the clamped cosine); E(n) = sum_i e_i y_i(n).
  void ProjectIrradianceSH(int order, double* red, double* green, double* blue) const;

  /// Mean radiance over the sphere (solid-angle weighted).
  void Mean(double rgb[3]) const;

  /// World space to map space and back (the rotation about +z).
  void ToMap(const double world[3], double map[3]) const;
  void ToWorld(const double map[3], double world[3]) const;

private:
  // Sampler: conditional CDFs per row over columns, marginal CDF over rows.
  // Built on the first Sample or Pdf (the SH route never samples a map, and
  // for a 2k map the tables are 32 MB); copies of the map share them.
  struct SamplerTables
  {
    std::once_flag Built;
    std::vector<double> RowCdf, ColumnCdf, TexelWeight;
    double TotalWeight = 0.0;
  };
  const SamplerTables& Sampler() const;
  void BuildSampler(SamplerTables& tables) const;

  int Width = 0, Height = 0;
  double Rotation = 0.0, CosR = 1.0, SinR = 0.0;
  std::vector<float> RGB;
  std::shared_ptr<SamplerTables> Sampling = std::make_shared<SamplerTables>();
};

} // namespace proxygi

#endif
