//VTK::Light::Dec
// ProxyGI light cloud: the reconstructed light (RGB, or RGB per SH
// coefficient for glossy receivers per fragment), interpolated.
//PGI::Cloud::Defines
in vec3 pgiCloudToViewer;
in vec3 pgiCloudRGB[PGI_CLOUD_VARYINGS];
uniform float pgiCloudExposure;
uniform int pgiCloudCombineWithVTKLighting;
uniform int pgiCloudSRGBOutput;
//PGI::SHBasis
//PGI::SRGB

// The cloud's exit radiance toward the camera, at least 0 (a compressed
// cloud's reconstruction may dip below).
vec3 pgiCloudRadiance()
{
  vec3 c = pgiCloudRGB[0];
#if PGI_CLOUD_VARYINGS > 1
  // Glossy, per fragment: the SH toward the camera.
  float pgiY[PGI_SH_N2];
  float l = length(pgiCloudToViewer);
  pgiSHBasis(l > 0.0 ? pgiCloudToViewer / l : vec3(0.0, 0.0, 1.0), pgiY);
  c = vec3(0.0);
  for (int k = 0; k < PGI_CLOUD_VARYINGS; ++k)
  {
    c += pgiY[k] * pgiCloudRGB[k];
  }
#endif
  return max(c, vec3(0.0));
}
//PGI::UnderGI
