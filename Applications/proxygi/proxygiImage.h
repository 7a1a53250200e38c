// Writing what proxygi renders: tone-mapped PNGs of radiance images.
#ifndef proxygiImage_h
#define proxygiImage_h

#include "pgiSRGB.h" // ToSRGB8, FromSRGB8, Luminance

#include <string>
#include <vector>

class vtkImageData;
class vtkPolyData;

namespace proxygi
{
namespace cli
{
/// The one automatic exposure rule of the pictures proxygi writes: the 95th
/// percentile of the luminance to 0.8 (1 when that is not positive).
/// `luminance` is reordered.
double AutoExposure(std::vector<double>& luminance);
/// The same for a float RGB radiance image (point scalars).
double AutoExposure(vtkImageData* radiance);

/// Writes `image` (bytes) as a PNG, under a temporary name then renamed;
/// false (and no file) on failure.
bool WritePNG(vtkImageData* image, const std::string& path);
/// Writes `data` as a .vtp (appended binary) the same way.
bool WritePolyData(vtkPolyData* data, const std::string& path);

/// Writes a float RGB radiance image (point scalars) as an sRGB PNG.
bool WriteTonemappedPNG(vtkImageData* radiance, double exposure, const std::string& path);
} // namespace cli
} // namespace proxygi

#endif
