//VTK::Color::Dec
// ProxyGI: per-vertex GI radiance captured by the compute pass.
in vec4 pgiRadianceMC;
out vec3 pgiRadianceVSOutput;
