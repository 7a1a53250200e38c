// ProxyGI shadowed one-bounce indirect light on the GPU (Guerrero, Jeschke
// and Wimmer 2008): the second pass of proxygi::ShadowedIndirect, per
// receiver, after pgiGILibrary.glsl. The first pass (each proxy's radiance
// SH Lc from its surface samples) runs on the CPU (PrepareSphericalLights);
// its results arrive as textures (GIResources::SetSphericalLights).
//
// Needs PGI_MAX_SPHERICAL_LIGHTS (>= the number of lights) defined.

#define PGI_SL_WORDS ((PGI_MAX_SPHERICAL_LIGHTS + 31) / 32)

// texel (i, 0): centre, radius of light i; (i, 1): object id, reflection
// ratio, the object's number among the lights' objects (0, 1, ...).
uniform sampler2D pgiSLGeometry;
// texel (t, i): coefficient t of light i's Lc (RGB).
uniform sampler2D pgiSLRadiance;
// Row i: the lights that belong to light i's object and overlap it; texel
// (0, i).r is their count, texels (1.., i).r their indices.
uniform sampler2D pgiSLPartners;
uniform int pgiNumSphericalLights;
// 1: per-object blocking (lights ordered by their object's nearest light).
uniform int pgiSLPerObject;
// IndirectTables' w_theta: Resolution rows of order values.
uniform sampler2D pgiWTable;
uniform int pgiWResolution;
uniform float pgiWThetaScale;

// IndirectTables::SphericalLightWeight (float path): w_theta as scaled ZH.
void pgiSphericalLightWeight(float theta, out float zh[PGI_SH_ORDER])
{
  pgiTableRows(pgiWTable, pgiWResolution, pgiWThetaScale, theta, zh);
}

// IndirectTables::SphericalLightRadiance for the three channels of light
// `light`: w_theta (axis -d) . Lc, the light's average radiance seen from a
// receiver in direction d (receiver -> centre); `basis` is y(d).
vec3 pgiSphericalLightRadianceOf(float theta, float basis[PGI_SH_N2], int light)
{
  float zh[PGI_SH_ORDER];
  pgiSphericalLightWeight(theta, zh);
  vec3 value = vec3(0.0);
  for (int l = 0; l < PGI_SH_ORDER; ++l)
  {
    vec3 band = vec3(0.0);
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      band += basis[i] * texelFetch(pgiSLRadiance, ivec2(i, light), 0).rgb;
    }
    value += (l % 2 == 1 ? -zh[l] : zh[l]) * band;
  }
  return value;
}

vec3 pgiSphericalLightRadiance(float theta, vec3 d, int light)
{
  float basis[PGI_SH_N2];
  pgiSHBasis(d, basis);
  return pgiSphericalLightRadianceOf(theta, basis, light);
}

// The scaled cap log of a light of angular radius theta, basis y(d) given.
void pgiSLLog(float theta, float basis[PGI_SH_N2], out float v[PGI_SH_N2])
{
  float zh[PGI_SH_ORDER];
  pgiCapLog(theta, zh);
  for (int l = 0; l < PGI_SH_ORDER; ++l)
  {
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      v[i] = basis[i] * zh[l];
    }
  }
}

bool pgiSameMask(uint a[PGI_SL_WORDS], uint b[PGI_SL_WORDS])
{
  bool same = true;
  for (int w = 0; w < PGI_SL_WORDS; ++w)
  {
    same = same && a[w] == b[w];
  }
  return same;
}

bool pgiEmptyMask(uint a[PGI_SL_WORDS])
{
  bool empty = true;
  for (int w = 0; w < PGI_SL_WORDS; ++w)
  {
    empty = empty && a[w] == 0u;
  }
  return empty;
}

// exp(f) for the blocker set `mask` (bits: sorted light entries): exactly 1
// for the empty set without planes, a cached result when the set was met
// before (the previous light's F + G is often this light's F), else HYB.
bool pgiSLExp(float f[PGI_SH_N2], uint mask[PGI_SL_WORDS], bool planeLogs,
  inout uint cacheMask[2 * PGI_SL_WORDS], inout float cacheExp[2 * PGI_SH_N2],
  inout int cacheValid[2], inout int cacheNext, out float g[PGI_SH_N2])
{
  if (!planeLogs && pgiEmptyMask(mask))
  {
    pgiSetConstantOne(g);
    return true;
  }
  for (int c = 0; c < 2; ++c)
  {
    bool same = cacheValid[c] != 0;
    for (int w = 0; w < PGI_SL_WORDS; ++w)
    {
      same = same && cacheMask[c * PGI_SL_WORDS + w] == mask[w];
    }
    if (same)
    {
      for (int i = 0; i < PGI_SH_N2; ++i)
      {
        g[i] = cacheExp[c * PGI_SH_N2 + i];
      }
      return true;
    }
  }
  if (!pgiExpHybrid(f, g))
  {
    return false;
  }
  int c = cacheNext;
  cacheNext = 1 - cacheNext;
  cacheValid[c] = 1;
  for (int w = 0; w < PGI_SL_WORDS; ++w)
  {
    cacheMask[c * PGI_SL_WORDS + w] = mask[w];
  }
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    cacheExp[c * PGI_SH_N2 + i] = g[i];
  }
  return true;
}

// ShadowedIndirect::ExitRadiance (emitting lights, no local emitters, the
// blocker planes): the exit radiance of a white receiver at p (normal n)
// from the spherical lights, each light k contributing
//   Lbar_k max(0, H(n) . (exp(F_k) - exp(F_k + G_k))),
// F_k the planes' (planesInLogSpace) and the nearer lights' log-visibility
// without the lights of k's object that intersect it.
vec3 pgiShadowedIndirect(vec3 p, vec3 n, bool planesInLogSpace)
{
  int index[PGI_MAX_SPHERICAL_LIGHTS];
  float key[PGI_MAX_SPHERICAL_LIGHTS], objectKey[PGI_MAX_SPHERICAL_LIGHTS];
  float theta[PGI_MAX_SPHERICAL_LIGHTS], object[PGI_MAX_SPHERICAL_LIGHTS];
  vec3 dir[PGI_MAX_SPHERICAL_LIGHTS];
  int count = 0;
  for (int i = 0; i < pgiNumSphericalLights; ++i)
  {
    vec4 s = texelFetch(pgiSLGeometry, ivec2(i, 0), 0);
    vec3 c = s.xyz;
    float r = s.w;
    if (!(r > 0.0) || (pgiSelfShadowRules != 0 && !pgiReplaceBlocker(p, n, c, r)))
    {
      continue;
    }
    vec3 d = c - p;
    float dist = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (!(dist > r) || r < pgiSinMinAngle * dist)
    {
      continue; // inside (rules off) or too small to resolve
    }
    index[count] = i;
    key[count] = dist;
    theta[count] = pgiAsin(r / dist);
    dir[count] = d / dist;
    object[count] = texelFetch(pgiSLGeometry, ivec2(i, 1), 0).b;
    ++count;
  }
  if (count == 0)
  {
    return vec3(0.0);
  }
  // Sort keys: distance, or (per object) the object's nearest light first
  // (objects are numbered 0.. in pgiSLGeometry's row 1, b).
  float nearest[PGI_MAX_SPHERICAL_LIGHTS];
  for (int a = 0; a < count; ++a)
  {
    nearest[int(object[a])] = 3.0e38;
  }
  for (int a = 0; a < count; ++a)
  {
    nearest[int(object[a])] = min(nearest[int(object[a])], key[a]);
  }
  for (int a = 0; a < count; ++a)
  {
    objectKey[a] = pgiSLPerObject != 0 ? nearest[int(object[a])] : key[a];
  }
  int rank[PGI_MAX_SPHERICAL_LIGHTS], position[PGI_MAX_SPHERICAL_LIGHTS];
  for (int i = 0; i < pgiNumSphericalLights; ++i)
  {
    position[i] = -1; // sorted position of light i, -1: not seen
  }
  for (int a = 0; a < count; ++a)
  {
    int e = a;
    int b = a - 1;
    for (; b >= 0; --b)
    {
      int q = rank[b];
      bool before = objectKey[e] != objectKey[q] ? objectKey[e] < objectKey[q]
        : key[e] != key[q]                       ? key[e] < key[q]
                                                 : index[e] < index[q];
      if (!before)
      {
        break;
      }
      rank[b + 1] = q;
    }
    rank[b + 1] = e;
  }
  for (int k = 0; k < count; ++k)
  {
    position[index[rank[k]]] = k;
  }

  // Planes block every light as 90-degree caps when they are in log space.
  float running[PGI_SH_N2];
  for (int t = 0; t < PGI_SH_N2; ++t)
  {
    running[t] = 0.0;
  }
  for (int k = 0; planesInLogSpace && k < pgiNumPlanes; ++k)
  {
    vec3 pn = pgiPlaneNormal[k];
    float height = pgiPlaneHeight(k, p);
    if (height > 0.0)
    {
      pgiAccumulateCap(0.5 * pgiPi, -pn, running);
    }
  }
  float h[PGI_SH_N2];
  pgiDiffuseTransfer(n, h);
  uint runningMask[PGI_SL_WORDS];
  for (int w = 0; w < PGI_SL_WORDS; ++w)
  {
    runningMask[w] = 0u;
  }
  uint cacheMask[2 * PGI_SL_WORDS];
  float cacheExp[2 * PGI_SH_N2];
  int cacheValid[2];
  cacheValid[0] = 0;
  cacheValid[1] = 0;
  int cacheNext = 0;
  vec3 rgb = vec3(0.0);
  for (int k = 0; k < count; ++k)
  {
    int e = rank[k];
    int light = index[e];
    float basis[PGI_SH_N2], logK[PGI_SH_N2];
    pgiSHBasis(dir[e], basis);
    pgiSLLog(theta[e], basis, logK);
    float ratio = texelFetch(pgiSLGeometry, ivec2(light, 1), 0).g;
    vec3 lbar = ratio * pgiSphericalLightRadianceOf(theta[e], basis, light);
    if (lbar.r > 0.0 || lbar.g > 0.0 || lbar.b > 0.0)
    {
      float before[PGI_SH_N2] = running;
      uint beforeMask[PGI_SL_WORDS] = runningMask;
      // Intersecting lights of the same object do not block (their
      // occlusion is in Lc already).
      int partners = int(texelFetch(pgiSLPartners, ivec2(0, light), 0).r);
      for (int j = 1; j <= partners; ++j)
      {
        int q = position[int(texelFetch(pgiSLPartners, ivec2(j, light), 0).r)];
        if (q >= 0 && q < k)
        {
          int other = rank[q];
          float y[PGI_SH_N2], v[PGI_SH_N2];
          pgiSHBasis(dir[other], y);
          pgiSLLog(theta[other], y, v);
          for (int t = 0; t < PGI_SH_N2; ++t)
          {
            before[t] -= v[t];
          }
          beforeMask[q / 32] &= ~(1u << uint(q % 32));
        }
      }
      float after[PGI_SH_N2];
      for (int t = 0; t < PGI_SH_N2; ++t)
      {
        after[t] = before[t] + logK[t];
      }
      uint afterMask[PGI_SL_WORDS] = beforeMask;
      afterMask[k / 32] |= 1u << uint(k % 32);
      float expBefore[PGI_SH_N2], expAfter[PGI_SH_N2];
      bool planeLogs = planesInLogSpace;
      if (pgiSLExp(before, beforeMask, planeLogs, cacheMask, cacheExp, cacheValid, cacheNext,
            expBefore) &&
        pgiSLExp(after, afterMask, planeLogs, cacheMask, cacheExp, cacheValid, cacheNext, expAfter))
      {
        float vbar = 0.0;
        for (int t = 0; t < PGI_SH_N2; ++t)
        {
          vbar += h[t] * (expBefore[t] - expAfter[t]);
        }
        rgb += max(lbar, vec3(0.0)) * max(0.0, vbar);
      }
    }
    runningMask[k / 32] |= 1u << uint(k % 32);
    for (int t = 0; t < PGI_SH_N2; ++t)
    {
      running[t] += logK[t];
    }
  }
  bool finite = !isnan(rgb.r) && !isnan(rgb.g) && !isnan(rgb.b) && !isinf(rgb.r) &&
    !isinf(rgb.g) && !isinf(rgb.b);
  return finite ? rgb : vec3(0.0);
}
