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
// kappa (H(N) . cap) with the averaged operator, a = its solid angle; both
// times the smooth clamp of the sphere of influence.
vec4 pgiProxyIndirect(vec3 p, vec3 n, vec4 sphere, vec3 albedo, float expansion)
{
  vec3 c = sphere.xyz;
  float r = sphere.w;
  if (!(r > 0.0))
  {
    return vec4(0.0);
  }
  vec3 v = c - p;
  float dist = sqrt(dot(v, v));
  float weight = dist > 0.0 ? pgiInfluenceWeight(r / dist, expansion) : 1.0;
  if (!(weight > 0.0))
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
    float h[PGI_SH_N2];
    pgiDiffuseTransfer(n, h);
    rgb = albedo * pgiAveragedRadiance(theta, d, pgiResponse) * pgiCapWeight(theta, d, h);
  }
  return weight * vec4(rgb, omega);
}

// The receiver's one-bounce light from the summed proxy terms `sum`
// (pgiProxyIndirect), the blocker planes as uniform secondary lights, and
// xi from the visibility's DC coefficient (OverlapNormalization).
vec3 pgiResolveIndirect(vec3 p, vec3 n, vec4 sum, float visibilityDC)
{
  vec3 rgb = sum.rgb;
  float omega = sum.a;
  float h[PGI_SH_N2];
  pgiDiffuseTransfer(n, h);
  for (int k = 0; k < pgiNumPlanes; ++k)
  {
    vec3 o = pgiPlaneOrigin[k];
    vec3 pn = pgiPlaneNormal[k];
    float height = (p.x - o.x) * pn.x + (p.y - o.y) * pn.y + (p.z - o.z) * pn.z;
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
    rgb += pgiPlaneAlbedo[k] * radiance * pgiCapWeight(0.5 * pgiPi, -pn, h);
  }
  if (!(omega > 0.0))
  {
    return vec3(0.0);
  }
  float covered = 4.0 * pgiPi - pgiSqrtFourPi * visibilityDC;
  float xi = clamp(covered / omega, 0.0, 1.0);
  return max(xi * rgb, vec3(0.0));
}
