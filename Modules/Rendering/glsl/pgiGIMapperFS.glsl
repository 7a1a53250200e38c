//VTK::Light::Dec
// ProxyGI: per-vertex GI radiance, interpolated.
in vec3 pgiRadianceVSOutput;
uniform float pgiExposure;
uniform int pgiCombineWithVTKLighting;
uniform int pgiSRGBOutput;
vec3 pgiEncodeSRGB(vec3 c)
{
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
