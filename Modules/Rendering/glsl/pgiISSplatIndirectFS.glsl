//VTK::System::Dec
//PGI::Library
//VTK::Output::Dec

// ProxyGI image-space GI, indirect splat: the proxy's one-bounce light at
// the receiver of this pixel (pgiProxyIndirect: averaged operator, white
// receiver) and its solid angle, both smoothly clamped to 0 at the boundary
// of its sphere of influence, added (blending ONE, ONE) into one target.

flat in vec4 pgiSphere;
flat in vec3 pgiAlbedo;
uniform sampler2D pgiReceiverPosition; // world xyz, eye depth
uniform sampler2D pgiReceiverNormal;   // world normal, w = 1 on receivers
uniform float pgiExpansion;

void main()
{
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 rn = texelFetch(pgiReceiverNormal, px, 0);
  if (!(rn.w > 0.5))
  {
    discard;
  }
  vec3 p = texelFetch(pgiReceiverPosition, px, 0).xyz;
  vec4 c = pgiProxyIndirect(p, rn.xyz, pgiSphere, pgiAlbedo, pgiExpansion);
  if (c == vec4(0.0))
  {
    discard;
  }
  gl_FragData[0] = c;
}
