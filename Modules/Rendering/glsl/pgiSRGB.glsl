// sRGB encoding of linear radiance (IEC 61966-2-1), clamped to [0, 1]
// first. C++ twin: proxygi::EncodeSRGB (pgiSRGB.h).
vec3 pgiEncodeSRGB(vec3 c)
{
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
