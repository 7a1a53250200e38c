//VTK::System::Dec
//PGI::Library
//VTK::Output::Dec

// ProxyGI image-space GI, per receiver of the buffer: the shadowed incident
// radiance M_L g (pgiShadowedLight, the first half of pgiShade), rows
// [0, PGI_SHADE_ROWS) only: H(N) of the clamped cosine has nothing in band
// 3, so shading needs bands 0..2. Linear in g, so interpolating it is
// interpolating g; the full-resolution pass then only evaluates H(N).
// With indirect light, also the receiver's resolved one-bounce light
// (pgiResolveIndirect: planes, xi from g's DC coefficient), three more
// floats, interpolated as a shaded result.

in vec2 texCoord;
uniform sampler2D pgiReceiverPosition;
uniform sampler2D pgiReceiverNormal;
uniform sampler2D pgiIndirectSum;
uniform int pgiIndirect;
//PGI::Input::Dec

void main()
{
  ivec2 px = ivec2(texCoord * vec2(textureSize(pgiReceiverNormal, 0)));
  float g[PGI_SH_N2];
  //PGI::Input::Impl
  vec3 lg[PGI_SH_N2];
  pgiShadowedLight(g, PGI_SHADE_ROWS, lg);
  float c[3 * PGI_SHADE_ROWS + 3];
  for (int i = 0; i < PGI_SHADE_ROWS; ++i)
  {
    c[3 * i] = lg[i].r;
    c[3 * i + 1] = lg[i].g;
    c[3 * i + 2] = lg[i].b;
  }
  vec3 indirect = vec3(0.0);
  vec4 rn = texelFetch(pgiReceiverNormal, px, 0);
  if (pgiIndirect != 0 && rn.w > 0.5)
  {
    vec3 p = texelFetch(pgiReceiverPosition, px, 0).xyz;
    indirect = pgiResolveIndirect(p, rn.xyz, texelFetch(pgiIndirectSum, px, 0), g[0]);
  }
  c[3 * PGI_SHADE_ROWS] = indirect.r;
  c[3 * PGI_SHADE_ROWS + 1] = indirect.g;
  c[3 * PGI_SHADE_ROWS + 2] = indirect.b;
  //PGI::Output::Impl
}
