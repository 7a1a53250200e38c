//VTK::Light::Dec
// ProxyGI: per-vertex GI radiance, interpolated.
in vec3 pgiRadianceVSOutput;
uniform float pgiExposure;
uniform int pgiCombineWithVTKLighting;
uniform int pgiSRGBOutput;
// Radiance a subclass adds to the GI before exposure and sRGB (the light
// cloud mapper's; none by default).
#ifndef PGI_EXTRA_RADIANCE
#define PGI_EXTRA_RADIANCE vec3(0.0)
#endif
//PGI::SRGB
