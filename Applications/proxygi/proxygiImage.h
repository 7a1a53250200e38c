// Writing what proxygi renders: tone-mapped PNGs of radiance images.
#ifndef proxygiImage_h
#define proxygiImage_h

#include <string>

class vtkImageData;

namespace proxygi
{
namespace cli
{
/// Linear radiance to an 8-bit sRGB value (clamped to [0, 1] first).
unsigned char ToSRGB8(double v);
/// Its inverse (linear value of an 8-bit sRGB level).
double FromSRGB8(unsigned char v);

/// Exposure that maps the 99th-percentile luminance of an RGB image to 1.
double AutoExposure(vtkImageData* radiance);

/// Writes a float RGB radiance image (point scalars) as an sRGB PNG.
bool WriteTonemappedPNG(vtkImageData* radiance, double exposure, const std::string& path);
} // namespace cli
} // namespace proxygi

#endif
