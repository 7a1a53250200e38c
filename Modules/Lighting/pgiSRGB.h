/**
 * @file pgiSRGB.h
 * @brief sRGB encoding of linear radiance (IEC 61966-2-1), for pictures and
 * for reading them back: the one place the programs and the tests take it
 * from. The GLSL pgiEncodeSRGB writes the same curve.
 */
#ifndef pgiSRGB_h
#define pgiSRGB_h

#include <cmath>

namespace proxygi
{
/// Linear value in [0, 1] to its sRGB value in [0, 1] (clamped first).
inline double EncodeSRGB(double linear)
{
  const double v = linear < 0.0 ? 0.0 : (linear > 1.0 ? 1.0 : linear);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

/// sRGB value in [0, 1] to linear.
inline double DecodeSRGB(double encoded)
{
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

/// Linear value to an 8-bit sRGB level.
inline unsigned char ToSRGB8(double linear)
{
  return static_cast<unsigned char>(std::lround(255.0 * EncodeSRGB(linear)));
}

/// An 8-bit sRGB level to linear.
inline double FromSRGB8(unsigned char level)
{
  return DecodeSRGB(level / 255.0);
}

/// Rec. 709 luminance of linear RGB.
inline double Luminance(double r, double g, double b)
{
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}
} // namespace proxygi

#endif
