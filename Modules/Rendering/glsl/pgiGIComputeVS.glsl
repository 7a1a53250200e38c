//VTK::System::Dec

// Per-vertex GI, one GL point per mesh point: vtkPGIGIPolyDataMapper draws
// the points with rasterisation off and captures pgiRadiance (and, when
// asked, the visibility vector) by transform feedback, once per change of
// the scene; the surface pass then reads the captured buffer as a vertex
// attribute.

//PGI::Defines

//PGI::Library

//PGI::ISLibrary

#if PGI_SPHERICAL_LIGHTS
//PGI::SLLibrary
#endif

in vec3 pgiPositionMC;
in vec3 pgiNormalMC;
in vec3 pgiAlbedoMC;

// Model to world (the actor's matrix) for points and normals.
uniform mat4 pgiModelToWorld;
uniform mat3 pgiNormalToWorld;
// 0 when the actor's matrix is the identity: points and normals (unit,
// normalised in double on upload as the CPU filter does) are used as they are.
uniform int pgiMoved;
uniform int pgiShadows;
// 1: blocker planes carried by the light (PLANES_IN_LIGHT) for receivers
// above every plane: light 1 (L times the planes' steps) and no planes in
// log space; the others keep L and the planes in log space.
uniform int pgiPlanesInLight;
// The planes' visibility (LightAbovePlanes; its dot product with a
// visibility gives the combined coverage, for xi).
uniform float pgiPlaneVisibility[PGI_SH_N2];
// One-bounce unshadowed indirect light from the proxies (albedo texture, the
// proxy texture's layout) and the planes (pgiPlaneAlbedo, pgiResponse).
uniform int pgiIndirect;
// 1: the shadowed model (proxies as spherical lights, pgiShadowedIndirect);
// the proxy terms then only count for xi and the planes still reflect.
uniform int pgiIndirectShadowed;
uniform sampler2D pgiProxyAlbedo;
// 1: planes reflect less where the proxies shadow them (PlaneBounceShadows).
uniform int pgiPlaneBounceShadows;
// The planes' light maps (PlaneLightMap, pgiPlaneLightMap.cxx, built on the
// CPU by BuildPlaneLightMaps): pgiPlaneMapDirections look-ups per receiver
// (0: one plane point, pgiPlaneShadowScale). pgiPlaneMapGrid holds s (rgb)
// of plane k in its rows from pgiPlaneMapSize[k].z; pgiPlaneMapTable, per
// plane two rows of one texel per direction: (w, step u), (0, step v).
// pgiPlaneMapSky: PlaneLightMap::SetSky's table, plane k's bin b in row
// k pgiPlaneSkyBins + b, height j's axis a (U, V, m) in column 3 j + a (rgb).
uniform int pgiPlaneMapDirections;
uniform sampler2D pgiPlaneMapGrid;
uniform sampler2D pgiPlaneMapTable;
uniform sampler2D pgiPlaneMapSky;
uniform int pgiPlaneSkyBins;
uniform int pgiPlaneSkyHeights;
uniform int pgiPlaneSkyRows;
uniform vec3 pgiPlaneMapU[PGI_MAX_PLANES];
uniform vec3 pgiPlaneMapV[PGI_MAX_PLANES];
uniform vec4 pgiPlaneMapFrame[PGI_MAX_PLANES]; // U0, V0, cell, bounded (1)
uniform vec4 pgiPlaneMapSize[PGI_MAX_PLANES];  // columns, rows, first row
uniform vec4 pgiPlaneMapDual[PGI_MAX_PLANES];  // the extent's dual vectors in (U, V)
// rgb: exit radiance (albedo included; direct + indirect + local lights,
// the filter's Radiance); a: blockers accumulated.
out vec4 pgiRadiance;

//PGI::Capture::Dec

float pgiDot3(vec3 a, vec3 b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Bilinear s of plane k at grid coordinates (fu, fv); 1 outside (Bilinear).
vec3 pgiPlaneMapBilinear(int k, float fu, float fv)
{
  int columns = int(pgiPlaneMapSize[k].x), rows = int(pgiPlaneMapSize[k].y);
  int first = int(pgiPlaneMapSize[k].z);
  if (!(fu >= 0.0) || !(fv >= 0.0) || !(fu < float(columns - 1)) || !(fv < float(rows - 1)))
  {
    return vec3(1.0);
  }
  int i = int(fu), j = int(fv);
  float a = fu - float(i), b = fv - float(j);
  vec3 p00 = texelFetch(pgiPlaneMapGrid, ivec2(i, first + j), 0).rgb;
  vec3 p10 = texelFetch(pgiPlaneMapGrid, ivec2(i + 1, first + j), 0).rgb;
  vec3 p01 = texelFetch(pgiPlaneMapGrid, ivec2(i, first + j + 1), 0).rgb;
  vec3 p11 = texelFetch(pgiPlaneMapGrid, ivec2(i + 1, first + j + 1), 0).rgb;
  vec3 bottom = p00 + a * (p10 - p00);
  vec3 top = p01 + a * (p11 - p01);
  return bottom + b * (top - bottom);
}

// Plane k's sky table of bin b, axis a, at s (linear between heights).
vec3 pgiPlaneSkyAt(int k, int b, int a, float s)
{
  float f = clamp(s, 0.0, 1.0) * float(pgiPlaneSkyHeights);
  int j = min(pgiPlaneSkyHeights - 1, int(f));
  float t = f - float(j);
  int row = k * pgiPlaneSkyBins + b;
  vec3 lo = texelFetch(pgiPlaneMapSky, ivec2(3 * j + a, row), 0).rgb;
  vec3 hi = texelFetch(pgiPlaneMapSky, ivec2(3 * (j + 1) + a, row), 0).rgb;
  return lo + t * (hi - lo);
}

// PlaneLightMap::SkyPastEdges: the sky's exit radiance past bounded plane
// k's edges at a receiver whose foot is (x, y), at height h, normal n.
vec3 pgiPlaneSkyPastEdges(
  int k, float x, float y, float h, vec3 n, bool weighted, float g[PGI_SH_N2])
{
  vec3 pu = pgiPlaneMapU[k], pv = pgiPlaneMapV[k], pm = pgiPlaneNormal[k];
  vec3 nl = vec3(pgiDot3(n, pu), pgiDot3(n, pv), pgiDot3(n, pm));
  vec4 dual = pgiPlaneMapDual[k];
  float a1 = x * dual.x + y * dual.y, a2 = x * dual.z + y * dual.w;
  float big = 3.402823e38;
  float binWidth = 2.0 * pgiPi / float(pgiPlaneSkyBins);
  vec3 sum = vec3(0.0);
  for (int b = 0; b < pgiPlaneSkyBins; ++b)
  {
    float phi = binWidth * (float(b) + 0.5);
    float c = cos(phi), sn = sin(phi);
    float along = nl.x * c + nl.y * sn, m = nl.z;
    bool atHorizon = along > 0.0, atNadir = m < 0.0;
    if (!atHorizon && !atNadir)
    {
      continue;
    }
    float lo = 0.0, hi = 1.0;
    if (atHorizon != atNadir)
    {
      float cross = abs(along) / sqrt(along * along + m * m);
      if (atHorizon)
      {
        hi = cross;
      }
      else
      {
        lo = cross;
      }
    }
    float tin = 0.0, tout = big;
    for (int q = 0; q < 2; ++q)
    {
      float a = q == 0 ? a1 : a2;
      float da = q == 0 ? c * dual.x + sn * dual.y : c * dual.z + sn * dual.w;
      if (da == 0.0)
      {
        if (abs(a) > 1.0)
        {
          tin = big;
        }
        continue;
      }
      float t1 = (-1.0 - a) / da, t2 = (1.0 - a) / da;
      tin = max(tin, min(t1, t2));
      tout = min(tout, max(t1, t2));
    }
    vec4 ranges = vec4(0.0, 1.0, 0.0, 0.0);
    int count = 1;
    if (tin <= tout)
    {
      ranges.y = tout < big ? h / sqrt(h * h + tout * tout) : 0.0;
      if (tin > 0.0)
      {
        ranges.zw = vec2(h / sqrt(h * h + tin * tin), 1.0);
        count = 2;
      }
    }
    for (int r = 0; r < count; ++r)
    {
      float s0 = max(lo, r == 0 ? ranges.x : ranges.z);
      float s1 = min(hi, r == 0 ? ranges.y : ranges.w);
      if (!(s1 > s0))
      {
        continue;
      }
      vec3 e = nl.x * (pgiPlaneSkyAt(k, b, 0, s1) - pgiPlaneSkyAt(k, b, 0, s0)) +
        nl.y * (pgiPlaneSkyAt(k, b, 1, s1) - pgiPlaneSkyAt(k, b, 1, s0)) +
        nl.z * (pgiPlaneSkyAt(k, b, 2, s1) - pgiPlaneSkyAt(k, b, 2, s0));
      float v = 1.0;
      if (weighted)
      {
        float at = min(float(pgiPlaneSkyRows - 1),
          max(0.0, 0.5 * (s0 + s1) * float(pgiPlaneSkyRows) - 0.5));
        int k0 = min(pgiPlaneSkyRows - 2, int(at));
        float t = at - float(k0);
        float rows[2];
        for (int q = 0; q < 2; ++q)
        {
          float s = (float(k0 + q) + 0.5) / float(pgiPlaneSkyRows);
          vec3 w = sqrt(max(0.0, 1.0 - s * s)) * (c * pu + sn * pv) - s * pm;
          float yq[PGI_SH_N2];
          pgiSHBasis(w, yq);
          float dot = 0.0;
          for (int i = 0; i < PGI_SH_N2; ++i)
          {
            dot += g[i] * yq[i];
          }
          rows[q] = min(1.0, max(0.0, dot));
        }
        v = rows[0] + t * (rows[1] - rows[0]);
      }
      sum += v * max(e, vec3(0.0));
    }
  }
  return sum / pgiPi;
}

// PlaneLightMap::Scale: the scale of plane k's light a receiver at p
// (normal n) sees, each direction weighted by the visibility g when
// `weighted`, and (wantGap) the sky past a bounded plane's edges (gap).
// False (scale 1, gap 0) when the receiver is not above the plane or sees
// none of it.
bool pgiPlaneLightScale(vec3 p, vec3 n, int k, bool weighted, float g[PGI_SH_N2], bool wantGap,
  out vec3 scale, out vec3 gap)
{
  scale = vec3(1.0);
  gap = vec3(0.0);
  vec3 d = p - pgiPlaneOrigin[k];
  float h = pgiDot3(d, pgiPlaneNormal[k]);
  if (!(h > 0.0))
  {
    return false;
  }
  float x = pgiDot3(d, pgiPlaneMapU[k]), y = pgiDot3(d, pgiPlaneMapV[k]);
  vec4 frame = pgiPlaneMapFrame[k];
  vec4 dual = pgiPlaneMapDual[k];
  float inv = 1.0 / frame.z;
  float fu = (x - frame.x) * inv, fv = (y - frame.y) * inv, hu = h * inv;
  bool empty = pgiPlaneMapSize[k].x < 1.0;
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int q = 0; q < pgiPlaneMapDirections; ++q)
  {
    vec4 wu = texelFetch(pgiPlaneMapTable, ivec2(q, 2 * k), 0);
    vec4 sv = texelFetch(pgiPlaneMapTable, ivec2(q, 2 * k + 1), 0);
    float c = pgiDot3(n, wu.xyz);
    if (!(c > 0.0))
    {
      continue;
    }
    weights += c;
    float seen = c;
    if (weighted)
    {
      float yq[PGI_SH_N2];
      pgiSHBasis(wu.xyz, yq);
      float v = 0.0;
      for (int i = 0; i < PGI_SH_N2; ++i)
      {
        v += g[i] * yq[i];
      }
      seen *= min(1.0, max(0.0, v));
    }
    if (frame.w > 0.5)
    {
      float ex = x + h * wu.w, ey = y + h * sv.w;
      float a = ex * dual.x + ey * dual.y, b = ex * dual.z + ey * dual.w;
      if (!(abs(a) <= 1.0 && abs(b) <= 1.0))
      {
        continue;
      }
    }
    vec3 s = empty ? vec3(1.0) : pgiPlaneMapBilinear(k, fu + hu * wu.w, fv + hu * sv.w);
    sum += seen * s;
  }
  if (!(weights > 0.0))
  {
    return false;
  }
  scale = clamp(sum / weights, 0.0, 1.0);
  if (wantGap && frame.w > 0.5)
  {
    gap = pgiPlaneSkyPastEdges(k, x, y, h, n, weighted, g);
  }
  return true;
}

// pgiResolveIndirectScaled with the planes' light maps (IndirectExitRadiance
// with planesSeenPast when seenPast: the plane takes no xi and counts in
// none, visibilityDC is the spheres' alone); gap: the sky past the planes'
// edges for the direct light.
vec3 pgiResolveIndirectMapped(vec3 p, vec3 n, vec4 sum, float visibilityDC,
  bool planesInLogSpace, bool seenPast, bool weighted, float g[PGI_SH_N2], out vec3 gap)
{
  gap = vec3(0.0);
  vec3 rgb = sum.rgb, planes = vec3(0.0);
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
    float y[PGI_SH_N2];
    pgiSHBasis(pn, y);
    vec3 radiance = vec3(0.0);
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      radiance += y[i] * pgiResponse[i];
    }
    vec3 scale, skyPast;
    pgiPlaneLightScale(p, n, k, weighted, g, seenPast, scale, skyPast);
    vec3 term = pgiPlaneAlbedo[k] * scale * radiance * pgiCapWeight(0.5 * pgiPi, -pn, h);
    if (seenPast)
    {
      planes += term;
      gap += skyPast;
    }
    else
    {
      omega += 2.0 * pgiPi;
      rgb += term;
    }
  }
  float covered = 4.0 * pgiPi - pgiSqrtFourPi * visibilityDC;
  float xi = omega > 0.0 ? clamp(covered / omega, 0.0, 1.0) : 1.0;
  return max(xi * rgb + planes, vec3(0.0));
}

void main()
{
  vec3 p = pgiPositionMC;
  vec3 n = pgiNormalMC;
  if (pgiMoved != 0)
  {
    p = (pgiModelToWorld * vec4(pgiPositionMC, 1.0)).xyz;
    n = pgiNormalToWorld * pgiNormalMC;
    float len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n = len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
  }
  float g[PGI_SH_N2];
  vec3 rgb;
  int used = 0;
  bool carried = pgiPlanesInLight != 0 && pgiAboveEveryPlane(p);
  int light = carried ? 1 : 0;
  if (pgiShadows != 0 || pgiIndirect != 0)
  {
    used = pgiVisibilityOf(p, n, !carried, g);
  }
  else
  {
    pgiSetConstantOne(g);
  }
  if (pgiShadows != 0)
  {
    rgb = used > 0 ? pgiShadeOf(light, n, g) : max(pgiShadeUnshadowedOf(light, n), vec3(0.0));
  }
  else
  {
    rgb = pgiShadeUnshadowed(n);
  }
  if (pgiIndirect != 0 && used >= 0)
  {
    vec4 sum = vec4(0.0);
    float h[PGI_SH_N2];
    pgiDiffuseTransfer(n, h);
    for (int s = 0; s < pgiNumProxies; ++s)
    {
      ivec2 texel = ivec2(s % pgiProxyTextureWidth, s / pgiProxyTextureWidth);
      vec3 albedo = pgiIndirectShadowed != 0 ? vec3(0.0) : texelFetch(pgiProxyAlbedo, texel, 0).rgb;
      sum += pgiProxyIndirectTermH(p, n, h, texelFetch(pgiProxyTexture, texel, 0), albedo);
    }
    // With the one plane seen past the visibility (pgiPlaneLightScale), xi
    // is the spheres' alone.
    bool seenPast = pgiPlaneMapDirections > 0 && pgiNumPlanes == 1 && carried;
    float dc = g[0];
    if (carried && !seenPast)
    {
      float coverage = 0.0;
      for (int i = 0; i < PGI_SH_N2; ++i)
      {
        coverage += g[i] * pgiPlaneVisibility[i];
      }
      dc = coverage / pgiSqrtFourPi;
    }
    if (pgiPlaneMapDirections > 0)
    {
      vec3 gap;
      rgb += pgiResolveIndirectMapped(
        p, n, sum, dc, pgiPlanesInLight == 0, seenPast, seenPast && used > 0, g, gap);
      if (pgiShadows != 0)
      {
        rgb += gap;
      }
    }
    else
    {
      rgb += pgiResolveIndirectScaled(
        p, n, sum, dc, pgiPlaneBounceShadows != 0, pgiPlanesInLight == 0);
    }
  }
#if PGI_SPHERICAL_LIGHTS
  if (pgiIndirect != 0 && pgiIndirectShadowed != 0)
  {
    rgb += pgiShadowedIndirect(p, n, pgiPlanesInLight == 0);
  }
#endif
  if (pgiNumLocalLights > 0)
  {
    rgb += pgiLocalLights(p, n, pgiShadows != 0, g);
  }
  pgiRadiance = vec4(rgb * pgiAlbedoMC, float(used));
  //PGI::Capture::Impl
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
