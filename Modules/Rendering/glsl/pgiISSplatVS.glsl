//VTK::System::Dec
//PGI::Splat::Defines

// ProxyGI image-space GI, coverage oracle: each proxy (instance) is drawn as
// the box bounding its sphere of influence, the proxy expanded by
// pgiExpansion; the fragment shader keeps the receivers inside the sphere.
in vec3 pgiCorner; // unit cube corners, [-1, 1]^3
uniform sampler2D pgiProxyTexture;
uniform int pgiProxyTextureWidth;
uniform mat4 pgiWCDC;
uniform float pgiExpansion;
flat out vec4 pgiSphere;
#ifdef PGI_SPLAT_ALBEDO
uniform sampler2D pgiProxyAlbedo; // same layout as pgiProxyTexture
flat out vec3 pgiAlbedo;
#endif

void main()
{
  int s = gl_InstanceID;
  vec4 sphere =
    texelFetch(pgiProxyTexture, ivec2(s % pgiProxyTextureWidth, s / pgiProxyTextureWidth), 0);
  pgiSphere = sphere;
#ifdef PGI_SPLAT_ALBEDO
  pgiAlbedo =
    texelFetch(pgiProxyAlbedo, ivec2(s % pgiProxyTextureWidth, s / pgiProxyTextureWidth), 0).rgb;
#endif
  // Radius 0 (unused texels, skipped proxies): a degenerate box, no pixels.
  float r = sphere.w > 0.0 ? pgiExpansion * sphere.w : 0.0;
  gl_Position = pgiWCDC * vec4(sphere.xyz + r * pgiCorner, 1.0);
}
