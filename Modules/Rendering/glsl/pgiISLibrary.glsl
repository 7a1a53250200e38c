// ProxyGI image-space GI: what its passes share, after pgiGILibrary.glsl.
// The indirect functions are the GLSL twins of IndirectExitRadiance
// (pgiIndirectLight.cxx, averaged operator) split into the per-proxy term,
// splatted, and the per-receiver resolve (planes, overlap normalisation xi).

// SecondaryLights::Response: a white secondary light's radiance SH per
// channel (with the planes' visibility when there are planes).
uniform vec3 pgiResponse[PGI_SH_N2];
uniform vec3 pgiPlaneAlbedo[PGI_MAX_PLANES];

// Smooth clamp of a proxy's contribution: 0 at the boundary of its sphere
// of influence (sin theta = 1 / expansion), 1 four cap-table rows further
// in (Sloan et al. 2007, 4.1: the table entries around 1/eta weighted
// smoothly to 0, smaller ones forced to 0).
float pgiInfluenceWeight(float sinTheta, float expansion)
{
  float theta0 = pgiAsin(min(1.0, 1.0 / expansion));
  float t = (pgiAsin(min(1.0, sinTheta)) - theta0) * pgiCapThetaScale * 0.25;
  return smoothstep(0.0, 1.0, t);
}

// H(N) . (the cap of half-angle theta about d): the cap's irradiance weight.
float pgiCapWeight(float theta, vec3 d, float h[PGI_SH_N2])
{
  float zh[PGI_SH_ORDER];
  pgiCapVisibility(theta, zh);
  zh[0] = 4.0 * pgiPi - zh[0]; // visibility -> cap (scaled ZH)
  for (int l = 1; l < PGI_SH_ORDER; ++l)
  {
    zh[l] = -zh[l];
  }
  float cap[PGI_SH_N2];
  pgiRotateScaledZonal(zh, d, cap);
  float w = 0.0;
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    w += h[i] * cap[i];
  }
  return w;
}

// One proxy's one-bounce light at receiver (p, n), white receiver: rgb =
// kappa (H(N) . cap) with the averaged operator, a = its solid angle (the
// terms IndirectExitRadiance sums over the blockers SoftShadows::Visibility
// saw; zero for the blockers it skips). h: H(N) (pgiDiffuseTransfer of n),
// computed once per receiver by the caller.
vec4 pgiProxyIndirectTermH(vec3 p, vec3 n, float h[PGI_SH_N2], vec4 sphere, vec3 albedo)
{
  vec3 c = sphere.xyz;
  float r = sphere.w;
  if (!(r > 0.0))
  {
    return vec4(0.0);
  }
  if (pgiSelfShadowRules != 0 && !pgiReplaceBlocker(p, n, c, r))
  {
    return vec4(0.0);
  }
  vec3 dir = c - p;
  float len = sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
  if (!(len > 0.0) || r < pgiSinMinAngle * len)
  {
    return vec4(0.0);
  }
  float theta = pgiAsin(min(1.0, r / len));
  vec3 d = dir / len;
  float s = sin(0.5 * theta);
  float omega = 4.0 * pgiPi * s * s;
  vec3 rgb = vec3(0.0);
  if (albedo.r > 0.0 || albedo.g > 0.0 || albedo.b > 0.0)
  {
    rgb = albedo * pgiAveragedRadiance(theta, d, pgiResponse) * pgiCapWeight(theta, d, h);
  }
  return vec4(rgb, omega);
}

vec4 pgiProxyIndirectTerm(vec3 p, vec3 n, vec4 sphere, vec3 albedo)
{
  float h[PGI_SH_N2];
  pgiDiffuseTransfer(n, h);
  return pgiProxyIndirectTermH(p, n, h, sphere, albedo);
}

// The same times the smooth clamp of the sphere of influence (image space).
vec4 pgiProxyIndirect(vec3 p, vec3 n, vec4 sphere, vec3 albedo, float expansion)
{
  vec3 v = sphere.xyz - p;
  float dist = sqrt(dot(v, v));
  float weight = dist > 0.0 ? pgiInfluenceWeight(sphere.w / dist, expansion) : 1.0;
  if (!(sphere.w > 0.0) || !(weight > 0.0))
  {
    return vec4(0.0);
  }
  return weight * pgiProxyIndirectTerm(p, n, sphere, albedo);
}

// PlaneShadowScale (pgiIndirectLight.cxx): how much of plane k's light
// reaches the part of it a receiver at p with normal n mostly sees: the
// plane point along normalize(n - m) shaded with the proxies' visibility
// there over shaded without it (light 0, L), per channel in [0, 1]; 1 when
// the receiver does not see the plane or nothing shadows that point.
vec3 pgiPlaneShadowScale(vec3 p, vec3 n, int k, bool planesInLogSpace)
{
  vec3 m = pgiPlaneNormal[k];
  float height = pgiPlaneHeight(k, p);
  vec3 d = n - m;
  float len = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  if (!(height > 0.0) || !(len > 1e-3))
  {
    return vec3(1.0);
  }
  float down = -(d.x * m.x + d.y * m.y + d.z * m.z) / len;
  if (!(down > 0.0))
  {
    return vec3(1.0);
  }
  // Far along a grazing direction the plane point says little: at most 4 h.
  float t = height / max(down, 0.25);
  vec3 q = p + t * d / len;
  float g[PGI_SH_N2];
  if (pgiVisibilityOf(q, m, planesInLogSpace, g) <= 0)
  {
    return vec3(1.0);
  }
  vec3 lit = pgiShade(m, g);
  vec3 open = pgiShadeUnshadowed(m);
  return vec3(open.r > 0.0 ? clamp(lit.r / open.r, 0.0, 1.0) : 1.0,
    open.g > 0.0 ? clamp(lit.g / open.g, 0.0, 1.0) : 1.0,
    open.b > 0.0 ? clamp(lit.b / open.b, 0.0, 1.0) : 1.0);
}

// The receiver's one-bounce light from the summed proxy terms `sum`
// (pgiProxyIndirect), the blocker planes as uniform secondary lights
// (dimmed by pgiPlaneShadowScale when planeShadows; planesInLogSpace: the
// visibility's setting there), and xi from the visibility's DC coefficient
// (OverlapNormalization).
vec3 pgiResolveIndirectScaled(vec3 p, vec3 n, vec4 sum, float visibilityDC, bool planeShadows,
  bool planesInLogSpace)
{
  vec3 rgb = sum.rgb;
  float omega = sum.a;
  float h[PGI_SH_N2];
  pgiDiffuseTransfer(n, h);
  for (int k = 0; k < pgiNumPlanes; ++k)
  {
    vec3 pn = pgiPlaneNormal[k];
    float height = pgiPlaneHeight(k, p);
    if (!(height > pgiPlaneTolerance))
    {
      continue;
    }
    omega += 2.0 * pgiPi;
    float y[PGI_SH_N2];
    pgiSHBasis(pn, y);
    vec3 radiance = vec3(0.0);
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      radiance += y[i] * pgiResponse[i];
    }
    vec3 scale = planeShadows ? pgiPlaneShadowScale(p, n, k, planesInLogSpace) : vec3(1.0);
    rgb += pgiPlaneAlbedo[k] * scale * radiance * pgiCapWeight(0.5 * pgiPi, -pn, h);
  }
  if (!(omega > 0.0))
  {
    return vec3(0.0);
  }
  float covered = 4.0 * pgiPi - pgiSqrtFourPi * visibilityDC;
  float xi = clamp(covered / omega, 0.0, 1.0);
  return max(xi * rgb, vec3(0.0));
}

vec3 pgiResolveIndirect(vec3 p, vec3 n, vec4 sum, float visibilityDC)
{
  return pgiResolveIndirectScaled(p, n, sum, visibilityDC, false, true);
}
