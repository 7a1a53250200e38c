//VTK::Light::Dec
// ProxyGI: per-vertex GI radiance, interpolated.
in vec3 pgiRadianceVSOutput;
uniform float pgiExposure;
uniform int pgiCombineWithVTKLighting;
uniform int pgiSRGBOutput;
//PGI::SRGB
