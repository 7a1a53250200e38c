//VTK::System::Dec
//PGI::Library
//VTK::Output::Dec

// ProxyGI image-space GI, shadow splat: the proxy's log-visibility vector
// at the receiver of this pixel (self-shadow rules, cap-log table, ZH
// rotation: the per-vertex kernel's functions), smoothly clamped to 0 at the
// boundary of its sphere of influence, added (blending ONE, ONE) to the
// accumulation targets, four coefficients per target.

flat in vec4 pgiSphere;
uniform sampler2D pgiReceiverPosition; // world xyz, eye depth
uniform sampler2D pgiReceiverNormal;   // world normal, w = 1 on receivers
uniform float pgiExpansion;

void main()
{
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 rn = texelFetch(pgiReceiverNormal, px, 0);
  vec3 p = texelFetch(pgiReceiverPosition, px, 0).xyz;
  vec3 n = rn.xyz;
  vec3 c = pgiSphere.xyz;
  float r = pgiSphere.w;
  vec3 v = c - p;
  float d = sqrt(dot(v, v));
  float weight = d > 0.0 ? pgiInfluenceWeight(r / d, pgiExpansion) : 1.0;
  if (!(rn.w > 0.5) || !(weight > 0.0))
  {
    discard;
  }
  if (pgiSelfShadowRules != 0 && !pgiReplaceBlocker(p, n, c, r))
  {
    discard;
  }
  vec3 dir = c - p;
  float len = sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
  if (!(len > 0.0) || r < pgiSinMinAngle * len)
  {
    discard;
  }
  float f[PGI_SH_N2];
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    f[i] = 0.0;
  }
  pgiAccumulateCap(pgiAsin(min(1.0, r / len)), dir / len, f);
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    f[i] *= weight;
  }
  //PGI::Output::Impl
}
