/**
 * @file pgiSRGB.h
 * @brief sRGB encoding of linear radiance (IEC 61966-2-1), for pictures and
 * for reading them back: the one place the programs and the tests take it
 * from. The GLSL pgiEncodeSRGB writes the same curve.
 */
#ifndef pgiSRGB_h
#define pgiSRGB_h

#include <cmath>
#include <cstdint>
#include <cstring>

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

/// Linear value to an 8-bit sRGB level by the curve itself.
inline unsigned char ToSRGB8ByCurve(double linear)
{
  return static_cast<unsigned char>(std::lround(255.0 * EncodeSRGB(linear)));
}

namespace detail
{
// The smallest linear value that ToSRGB8ByCurve takes to each level, found
// once by bisection over the doubles in [0, 1], so a search of them returns
// the curve's own levels without a pow per value.
struct SRGB8Levels
{
  double Lowest[256];
  // The level where each float bucket (the top 16 bits of a value in
  // [0, 1]) starts; a value's level is found from there in a step or two.
  static constexpr int Buckets = (0x3F800000 >> 16) + 1;
  unsigned char Start[Buckets];
  static int BucketOf(double x)
  {
    const float f = static_cast<float>(x);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof(bits));
    return static_cast<int>(bits >> 16);
  }
  int Search(double x) const
  {
    int level = 0;
    for (int step = 128; step > 0; step /= 2)
    {
      level += this->Lowest[level + step] <= x ? step : 0;
    }
    return level;
  }
  SRGB8Levels()
  {
    Lowest[0] = 0.0;
    for (int level = 1; level < 256; ++level)
    {
      // Positive doubles order as their bit patterns.
      std::uint64_t below = 0, at = 0;
      const double one = 1.0;
      std::memcpy(&at, &one, sizeof(at));
      while (at - below > 1)
      {
        const std::uint64_t middle = below + (at - below) / 2;
        double x;
        std::memcpy(&x, &middle, sizeof(x));
        (ToSRGB8ByCurve(x) >= level ? at : below) = middle;
      }
      std::memcpy(&Lowest[level], &at, sizeof(at));
    }
    // Every double that rounds into bucket b lies above the float just
    // below b's first float: its level is at least that one's.
    for (int b = 0; b < Buckets; ++b)
    {
      const std::uint32_t first = static_cast<std::uint32_t>(b) << 16;
      float f;
      std::memcpy(&f, &first, sizeof(f));
      const double below = b > 0 ? static_cast<double>(std::nextafter(f, 0.0f)) : 0.0;
      Start[b] = static_cast<unsigned char>(Search(below));
    }
  }
};
} // namespace detail

/// Linear value to an 8-bit sRGB level: round(255 EncodeSRGB(linear)), the
/// levels of ToSRGB8ByCurve found by search (NaN and below 0 give 0).
inline unsigned char ToSRGB8(double linear)
{
  static const detail::SRGB8Levels levels;
  if (!(linear >= levels.Lowest[1]))
  {
    return 0;
  }
  if (linear >= 1.0)
  {
    return 255;
  }
  int level = levels.Start[detail::SRGB8Levels::BucketOf(linear)];
  while (level < 255 && levels.Lowest[level + 1] <= linear)
  {
    ++level;
  }
  return static_cast<unsigned char>(level);
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
