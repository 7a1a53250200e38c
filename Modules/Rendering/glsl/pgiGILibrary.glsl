// ProxyGI per-vertex GI on the GPU: the GLSL twins of the CPU kernels of the
// SphericalHarmonics and Shading modules. Each function names its C++ twin;
// TestRenderingGLSLTwins compares every pair. Formulas live in C++: the
// tables (cap log, optimal linear, product matrix of the light, diffuse
// transfer) are the arrays the C++ code built, read here from textures and
// uniforms; the SH square is generated from the triple-product tensor.
//
// Needs PGI_SH_ORDER, PGI_SH_N2 (= order^2), PGI_MAX_PLANES defined and
// pgiSHBasis (pgiSHBasis.glsl) before it.

const float pgiSqrtFourPi = 3.5449077018110320546;
const float pgiPi = 3.14159265358979323846;

// CapTables (pgiSHTables.h): Resolution rows of order scaled ZH values.
uniform sampler2D pgiCapLogTable; // R: texel (l, row)
uniform int pgiCapResolution;
uniform float pgiCapThetaScale;   // (Resolution - 1) / MaxAngle
uniform sampler2D pgiCapVisTable; // R: texel (l, row), cap visibility
// IndirectTables (pgiSHLightTables.h): D(theta), Resolution rows of order values.
uniform sampler2D pgiDTable;      // R: texel (l, row)
uniform int pgiDResolution;
uniform float pgiDThetaScale;
uniform sampler2D pgiOLTable;     // RG: (a, b) at texel (row, 0)
uniform int pgiOLResolution;
uniform float pgiOLScale;         // (Resolution - 1) / OLMaxNorm
// HYB threshold and the range guard's tolerance (< 0: guard off).
uniform float pgiHybridMaxNorm;
uniform float pgiRangeTolerance;

// Blockers: spheres (x, y, z, r) in a texture, infinite planes.
uniform sampler2D pgiProxyTexture;
uniform int pgiProxyTextureWidth;
uniform int pgiNumProxies;
uniform int pgiNumPlanes;
uniform vec3 pgiPlaneOrigin[PGI_MAX_PLANES];
uniform vec3 pgiPlaneNormal[PGI_MAX_PLANES];
uniform float pgiSinMinAngle;
// Receivers at most this high above a blocker plane count as on it (0, the
// default, for exact positions; image-space GI sets it to cover the rounding
// of positions rebuilt from view coordinates).
uniform float pgiPlaneTolerance;
uniform int pgiSelfShadowRules;

// Height of p above blocker plane k, written out in the C++ twin's order.
float pgiPlaneHeight(int k, vec3 p)
{
  vec3 o = pgiPlaneOrigin[k];
  vec3 pn = pgiPlaneNormal[k];
  return (p.x - o.x) * pn.x + (p.y - o.y) * pn.y + (p.z - o.z) * pn.z;
}

// Environment light: L (per channel), its product matrix M_L and the scaled
// ZH of the diffuse transfer H (pgiEnvironmentShading.h).
// Two lights share the matrix texture: light 0 is the environment L (rows
// 0..n2-1), light 1 the light above the blocker planes, L times the planes'
// steps (LightAbovePlanes, built on the CPU; rows n2..2 n2-1; L itself when
// no planes are carried by the light).
uniform vec3 pgiLight[PGI_SH_N2];
uniform vec3 pgiLightAbove[PGI_SH_N2];
uniform sampler2D pgiLightMatrix; // RGB: texel (j, light n2 + i) = (M_R, M_G, M_B)_ij
uniform float pgiTransferZH[PGI_SH_ORDER];

// std::asin to float precision. The drivers' built-in asin is an
// approximation (llvmpipe's is off by up to 3e-4 rad), and its error would
// pass through the cap table to every visibility vector. Cephes' asinf:
// polynomial on [0, 0.5], asin(x) = pi/2 - 2 asin(sqrt((1 - x)/2)) above.
float pgiAsin(float x)
{
  float a = abs(x);
  bool high = a > 0.5;
  float z = high ? 0.5 * (1.0 - a) : a * a;
  float w = high ? sqrt(z) : a;
  float p = ((((4.2163199048e-2 * z + 2.4181311049e-2) * z + 4.5470025998e-2) * z +
               7.4953002686e-2) * z + 1.6666752422e-1) * z * w + w;
  float y = high ? 0.5 * pgiPi - 2.0 * p : p;
  return x < 0.0 ? -y : y;
}

// The tables' lookup (CapTables and IndirectTables, float path): theta
// clamped to [0, (resolution - 1) / thetaScale], linear interpolation
// between the rows of `table` (texel (l, row): band l's scaled ZH value).
void pgiTableRows(sampler2D table, int resolution, float thetaScale, float theta,
  out float zh[PGI_SH_ORDER])
{
  int last = resolution - 1;
  float u = theta * thetaScale;
  u = u > 0.0 ? (u < float(last) ? u : float(last)) : 0.0;
  int i = int(u);
  i = i < last ? i : last - 1;
  float t = u - float(i);
  for (int l = 0; l < PGI_SH_ORDER; ++l)
  {
    float r0 = texelFetch(table, ivec2(l, i), 0).r;
    float r1 = texelFetch(table, ivec2(l, i + 1), 0).r;
    zh[l] = r0 + (r1 - r0) * t;
  }
}

// CapTables::CapLog (float path).
void pgiCapLog(float theta, out float zh[PGI_SH_ORDER])
{
  pgiTableRows(pgiCapLogTable, pgiCapResolution, pgiCapThetaScale, theta, zh);
}

// CapTables::CapVisibility (float path).
void pgiCapVisibility(float theta, out float zh[PGI_SH_ORDER])
{
  pgiTableRows(pgiCapVisTable, pgiCapResolution, pgiCapThetaScale, theta, zh);
}

// IndirectTables::AveragedIndirect (float path): D(theta) as scaled ZH.
void pgiAveragedIndirect(float theta, out float zh[PGI_SH_ORDER])
{
  pgiTableRows(pgiDTable, pgiDResolution, pgiDThetaScale, theta, zh);
}

// sh::RotateScaledZonal: out_lm = zh_l y_lm(d).
void pgiRotateScaledZonal(float zh[PGI_SH_ORDER], vec3 d, out float v[PGI_SH_N2])
{
  pgiSHBasis(d, v);
  for (int l = 0; l < PGI_SH_ORDER; ++l)
  {
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      v[i] *= zh[l];
    }
  }
}

// CapTables::OptimalLinear: a(x), b(x); beyond the table the last values.
void pgiOptimalLinear(float x, out float a, out float b)
{
  float u = x * pgiOLScale;
  int last = pgiOLResolution - 1;
  if (!(u < float(last)))
  {
    vec2 e = texelFetch(pgiOLTable, ivec2(last, 0), 0).rg;
    a = e.x;
    b = e.y;
    return;
  }
  int i = u > 0.0 ? int(u) : 0;
  float t = u - float(i);
  vec2 e0 = texelFetch(pgiOLTable, ivec2(i, 0), 0).rg;
  vec2 e1 = texelFetch(pgiOLTable, ivec2(i + 1, 0), 0).rg;
  a = e0.x + (e1.x - e0.x) * t;
  b = e0.y + (e1.y - e0.y) * t;
}

// TripleProduct::Square, the terms of the tensor written out by C++.
void pgiSHSquare(float f[PGI_SH_N2], out float o[PGI_SH_N2])
{
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    o[i] = 0.0;
  }
  //PGI::Square::Impl
}

// HYB's base: OL of f^/2^s, times exp(f0/sqrt(4 pi))^(2^-s) (pgiSHExp.cxx).
void pgiScaledBase(float fHat[PGI_SH_N2], float norm, float dcExponent, int s,
  out float g[PGI_SH_N2])
{
  float k = exp2(-float(s));
  float a, b;
  pgiOptimalLinear(norm * k, a, b);
  float dc = exp(dcExponent * k);
  g[0] = a * pgiSqrtFourPi * dc;
  for (int i = 1; i < PGI_SH_N2; ++i)
  {
    g[i] = b * (fHat[i] * k) * dc;
  }
}

// sh::GuardRange: remaps g affinely into [-tol, 1 + tol] on the guard's
// Fibonacci directions when the per-band bound says it may leave it.
void pgiGuardRange(inout float g[PGI_SH_N2], float tolerance)
{
  float mean = g[0] / pgiSqrtFourPi;
  float bound = 0.0;
  for (int l = 1; l < PGI_SH_ORDER; ++l)
  {
    float band = 0.0;
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      band += g[i] * g[i];
    }
    bound += sqrt(band * float(2 * l + 1) / (4.0 * pgiPi));
  }
  float lo = -tolerance, hi = 1.0 + tolerance;
  if (mean - bound >= lo && mean + bound <= hi)
  {
    return;
  }
  int count = max(128, 8 * PGI_SH_N2);
  float vmin = 3.0e38, vmax = -3.0e38;
  for (int s = 0; s < count; ++s)
  {
    float z = 1.0 - (2.0 * float(s) + 1.0) / float(count);
    float r = sqrt(max(0.0, 1.0 - z * z));
    // golden * s reduced mod 2 pi as a fraction of a turn: float keeps its
    // digits that way (the C++ twin computes phi in double).
    float phi = 2.0 * pgiPi * fract(float(s) * 0.38196601125010515);
    float y[PGI_SH_N2];
    pgiSHBasis(vec3(r * cos(phi), r * sin(phi), z), y);
    float v = 0.0;
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      v += g[i] * y[i];
    }
    vmin = min(vmin, v);
    vmax = max(vmax, v);
  }
  if (vmin >= lo && vmax <= hi)
  {
    return;
  }
  float newMin = min(max(vmin, lo), hi);
  float newMax = max(min(vmax, hi), lo);
  float range = vmax - vmin;
  float scale = range > 0.0 ? (newMax - newMin) / range : 0.0;
  float offset = newMin - vmin * scale;
  for (int i = 1; i < PGI_SH_N2; ++i)
  {
    g[i] *= scale;
  }
  g[0] = range > 0.0 ? g[0] * scale + offset * pgiSqrtFourPi : newMin * pgiSqrtFourPi;
}

// sh::Exp with ExpMethod::Hybrid: DC isolation, OL after scaling |f^| below
// the threshold, a continuous blend between s and s + 1 squarings, s
// squarings, then the range guard. Returns false on non-finite results
// (g is then 0, as the C++ twin leaves it).
bool pgiExpHybrid(float f[PGI_SH_N2], out float g[PGI_SH_N2])
{
  float fHat[PGI_SH_N2] = f;
  fHat[0] = 0.0;
  float dcExponent = f[0] / pgiSqrtFourPi;
  float norm2 = 0.0;
  for (int i = 1; i < PGI_SH_N2; ++i)
  {
    norm2 += fHat[i] * fHat[i];
  }
  float norm = sqrt(norm2);
  int steps = 0;
  float w = 0.0;
  if (norm > 0.0)
  {
    float u = log2(norm / pgiHybridMaxNorm);
    if (u > -1.0)
    {
      steps = max(0, int(ceil(u)));
      w = min(1.0, u - float(steps - 1));
    }
  }
  pgiScaledBase(fHat, norm, dcExponent, steps, g);
  if (w > 0.0)
  {
    float finer[PGI_SH_N2], squared[PGI_SH_N2];
    pgiScaledBase(fHat, norm, dcExponent, steps + 1, finer);
    pgiSHSquare(finer, squared);
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      g[i] = (1.0 - w) * g[i] + w * squared[i];
    }
  }
  for (int k = 0; k < steps; ++k)
  {
    float squared[PGI_SH_N2];
    pgiSHSquare(g, squared);
    g = squared;
  }
  bool finite = true;
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    finite = finite && !isnan(g[i]) && !isinf(g[i]);
  }
  if (!finite)
  {
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      g[i] = 0.0;
    }
    return false;
  }
  if (pgiRangeTolerance >= 0.0)
  {
    pgiGuardRange(g, pgiRangeTolerance);
  }
  return true;
}

// ReplaceBlocker (pgiSoftShadows.cxx): the continuous self-shadow rules.
// Receivers on a proxy's surface near the point where their tangent plane
// touches it (h -> -r, d -> r) make rho - delta a difference of two tiny
// square roots: PGI_PRECISE keeps the compiler from fusing the products
// into FMAs there, so the rounding is the C++ twin's.
bool pgiReplaceBlocker(vec3 p, vec3 n, inout vec3 c, inout float r)
{
  PGI_PRECISE vec3 v = c - p;
  PGI_PRECISE float h = v.x * n.x + v.y * n.y + v.z * n.z;
  if (h <= -r)
  {
    return false;
  }
  if (h >= r)
  {
    return true;
  }
  PGI_PRECISE float d2 = v.x * v.x + v.y * v.y + v.z * v.z;
  PGI_PRECISE float hh = h * h;
  PGI_PRECISE float rr = r * r;
  PGI_PRECISE float rho = sqrt(max(0.0, d2 - hh));
  PGI_PRECISE float delta = sqrt(max(0.0, rr - hh));
  vec3 foot = c - h * n;
  if (d2 < rr)
  {
    if (h <= 0.0)
    {
      return false;
    }
    float ramp = delta > 0.0 ? min(1.0, 2.0 * (delta - rho) / delta) : 0.0;
    r = h * max(0.0, ramp);
    return r > 0.0;
  }
  float ramp = delta > 0.0 ? min(1.0, (rho - delta) / delta) : 1.0;
  float halfHeight = 0.5 * (h + r);
  c = foot + halfHeight * n;
  r = halfHeight * max(0.0, ramp);
  return r > 0.0;
}

void pgiSetConstantOne(out float g[PGI_SH_N2])
{
  for (int i = 1; i < PGI_SH_N2; ++i)
  {
    g[i] = 0.0;
  }
  g[0] = pgiSqrtFourPi;
}

// Adds the scaled cap log of a blocker of angular radius theta seen in
// direction d to f.
void pgiAccumulateCap(float theta, vec3 d, inout float f[PGI_SH_N2])
{
  float zh[PGI_SH_ORDER];
  pgiCapLog(theta, zh);
  float v[PGI_SH_N2];
  pgiRotateScaledZonal(zh, d, v);
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    f[i] += v[i];
  }
}

// SoftShadows::Visibility: blockers' log-visibility summed, then HYB exp.
// Returns the number of blockers accumulated (0: g = 1, no exp run; -1: the
// exp overflowed and g = 1, as the CPU filter leaves such receivers).
// planesInLogSpace: SoftShadowSettings::PlanesInLogSpace (false: the planes
// are carried by the light and left out here).
int pgiVisibilityOf(vec3 p, vec3 n, bool planesInLogSpace, out float g[PGI_SH_N2])
{
  float f[PGI_SH_N2];
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    f[i] = 0.0;
  }
  int used = 0;
  for (int s = 0; s < pgiNumProxies; ++s)
  {
    vec4 sphere =
      texelFetch(pgiProxyTexture, ivec2(s % pgiProxyTextureWidth, s / pgiProxyTextureWidth), 0);
    vec3 c = sphere.xyz;
    float r = sphere.w;
    if (!(r > 0.0))
    {
      continue;
    }
    if (pgiSelfShadowRules != 0 && !pgiReplaceBlocker(p, n, c, r))
    {
      continue;
    }
    vec3 d = c - p;
    float len = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (!(len > 0.0) || r < pgiSinMinAngle * len)
    {
      continue;
    }
    pgiAccumulateCap(pgiAsin(min(1.0, r / len)), d / len, f);
    ++used;
  }
  for (int k = 0; planesInLogSpace && k < pgiNumPlanes; ++k)
  {
    vec3 pn = pgiPlaneNormal[k];
    float height = pgiPlaneHeight(k, p);
    if (!(height > pgiPlaneTolerance))
    {
      continue;
    }
    pgiAccumulateCap(0.5 * pgiPi, -pn, f);
    ++used;
  }
  if (used == 0)
  {
    pgiSetConstantOne(g);
    return 0;
  }
  if (!pgiExpHybrid(f, g))
  {
    pgiSetConstantOne(g);
    return -1;
  }
  return used;
}

// The planes accumulated in log space (SoftShadows' default settings).
int pgiVisibility(vec3 p, vec3 n, out float g[PGI_SH_N2])
{
  return pgiVisibilityOf(p, n, true, g);
}

// Whether p is strictly above every blocker plane (the receivers whose light
// carries the planes; vtkPGIGlobalIllumination's aboveEveryPlane).
bool pgiAboveEveryPlane(vec3 p)
{
  for (int k = 0; k < pgiNumPlanes; ++k)
  {
    if (!(pgiPlaneHeight(k, p) > 0.0))
    {
      return false;
    }
  }
  return true;
}

// sh::DiffuseTransfer: H(N), the clamped cosine over pi rotated to N.
void pgiDiffuseTransfer(vec3 n, out float h[PGI_SH_N2])
{
  pgiSHBasis(n, h);
  for (int l = 0; l < PGI_SH_ORDER; ++l)
  {
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      h[i] *= pgiTransferZH[l];
    }
  }
}

// IndirectTables::AveragedRadiance for three channels: rot(D(theta), d) . R.
vec3 pgiAveragedRadiance(float theta, vec3 d, vec3 radiance[PGI_SH_N2])
{
  float zh[PGI_SH_ORDER];
  pgiAveragedIndirect(theta, zh);
  float basis[PGI_SH_N2];
  pgiSHBasis(d, basis);
  vec3 kappa = vec3(0.0);
  for (int l = 0; l < PGI_SH_ORDER; ++l)
  {
    vec3 band = vec3(0.0);
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      band += basis[i] * radiance[i];
    }
    kappa += zh[l] * band;
  }
  return kappa;
}

// Rows [0, rows) of M_L g for light 0 (L) or 1 (the light above the
// planes): the SH of the shadowed incident radiance.
void pgiShadowedLightOf(int light, float g[PGI_SH_N2], int rows, out vec3 lg[PGI_SH_N2])
{
  int first = light * PGI_SH_N2;
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    vec3 row = vec3(0.0);
    if (i < rows)
    {
      for (int j = 0; j < PGI_SH_N2; ++j)
      {
        row += texelFetch(pgiLightMatrix, ivec2(j, first + i), 0).rgb * g[j];
      }
    }
    lg[i] = row;
  }
}

void pgiShadowedLight(float g[PGI_SH_N2], int rows, out vec3 lg[PGI_SH_N2])
{
  pgiShadowedLightOf(0, g, rows, lg);
}

// max(0, lg . H(N)) over the first `rows` coefficients.
vec3 pgiShadeShadowedLight(vec3 n, vec3 lg[PGI_SH_N2], int rows)
{
  float h[PGI_SH_N2];
  pgiDiffuseTransfer(n, h);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < rows; ++i)
  {
    sum += lg[i] * h[i];
  }
  return max(sum, vec3(0.0));
}

// EnvironmentShading::Shade, product-matrix path: max(0, (M_L g) . H(N)),
// for light 0 (L) or 1 (the light above the planes).
vec3 pgiShadeOf(int light, vec3 n, float g[PGI_SH_N2])
{
  vec3 lg[PGI_SH_N2];
  pgiShadowedLightOf(light, g, PGI_SH_N2, lg);
  return pgiShadeShadowedLight(n, lg, PGI_SH_N2);
}

vec3 pgiShade(vec3 n, float g[PGI_SH_N2])
{
  return pgiShadeOf(0, n, g);
}

// EnvironmentShading::ShadeUnshadowed: H(N) . L, exact, not clamped.
vec3 pgiShadeUnshadowedOf(int light, vec3 n)
{
  float h[PGI_SH_N2];
  pgiDiffuseTransfer(n, h);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < PGI_SH_N2; ++i)
  {
    sum += (light == 0 ? pgiLight[i] : pgiLightAbove[i]) * h[i];
  }
  return sum;
}

vec3 pgiShadeUnshadowed(vec3 n)
{
  return pgiShadeUnshadowedOf(0, n);
}

// Local lights (spherical and point lights of vtkPGILighting) with the
// analytic L_H table: AnalyticLightTables (pgiSHLightTables.h), its raw lobe
// table uploaded as a texture: row (i * phiResolution + j) holds the lobe
// angle, then order scaled ZH values (texel (k, row)).
uniform sampler2D pgiLobeTable;
uniform int pgiLobeThetaResolution;
uniform int pgiLobePhiResolution;
uniform float pgiLobeThetaScale; // (thetaResolution - 1) / MaxTheta
uniform float pgiLobePhiScale;   // (phiResolution - 1) / MaxPhi

// std::acos to float precision, through pgiAsin.
float pgiAcos(float x)
{
  return 0.5 * pgiPi - pgiAsin(x);
}

// AnalyticLightTables::Lookup (float path): bilinear in theta and phi.
void pgiAnalyticLightLookup(float theta, float phi, out float angle, out float zh[PGI_SH_ORDER])
{
  int lastT = pgiLobeThetaResolution - 1, lastP = pgiLobePhiResolution - 1;
  float u = theta * pgiLobeThetaScale;
  float w = phi * pgiLobePhiScale;
  u = u > 0.0 ? (u < float(lastT) ? u : float(lastT)) : 0.0;
  w = w > 0.0 ? (w < float(lastP) ? w : float(lastP)) : 0.0;
  int i = min(int(u), lastT - 1);
  int j = min(int(w), lastP - 1);
  float tu = u - float(i), tw = w - float(j);
  int r00 = i * pgiLobePhiResolution + j;
  int r10 = r00 + pgiLobePhiResolution;
  for (int k = 0; k <= PGI_SH_ORDER; ++k)
  {
    float t00 = texelFetch(pgiLobeTable, ivec2(k, r00), 0).r;
    float t01 = texelFetch(pgiLobeTable, ivec2(k, r00 + 1), 0).r;
    float t10 = texelFetch(pgiLobeTable, ivec2(k, r10), 0).r;
    float t11 = texelFetch(pgiLobeTable, ivec2(k, r10 + 1), 0).r;
    float a = t00 + (t01 - t00) * tw;
    float b = t10 + (t11 - t10) * tw;
    float value = a + (b - a) * tu;
    if (k == 0)
    {
      angle = value;
    }
    else
    {
      zh[k - 1] = value;
    }
  }
}

// AnalyticLightTables::Evaluate: L_H of a spherical light of radiance 1 and
// angular radius theta in unit direction d from a receiver with normal n.
void pgiAnalyticLight(vec3 n, vec3 d, float theta, out float lh[PGI_SH_N2])
{
  float cosPhi = n.x * d.x + n.y * d.y + n.z * d.z;
  cosPhi = cosPhi > -1.0 ? (cosPhi < 1.0 ? cosPhi : 1.0) : -1.0;
  float phi = pgiAcos(cosPhi);
  if (phi >= 0.5 * pgiPi + theta)
  {
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      lh[i] = 0.0;
    }
    return;
  }
  vec3 t = d - cosPhi * n;
  float len = sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  if (!(len > 1e-6))
  {
    t = abs(n.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    float dt = t.x * n.x + t.y * n.y;
    t -= dt * n;
    len = sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  }
  float angle;
  float zh[PGI_SH_ORDER];
  pgiAnalyticLightLookup(theta, phi, angle, zh);
  float ca = cos(angle), sa = sin(angle) / len;
  pgiRotateScaledZonal(zh, ca * n + sa * t, lh);
}

// Local lights: centre and radius (< 0: a point light), radiance (point
// lights: intensity); the lobe table's first theta node.
#define PGI_MAX_LOCAL_LIGHTS 16
uniform int pgiNumLocalLights;
uniform vec4 pgiLocalLight[PGI_MAX_LOCAL_LIGHTS];
uniform vec3 pgiLocalRadiance[PGI_MAX_LOCAL_LIGHTS];
uniform float pgiLobeMinTheta;

// The local lights' exit radiance at a white receiver, shadowed by g when
// `shadowed`: proxygi::LocalLightsRadiance's twin. Below the table's first
// node L_H grows as sin^2(theta) with a fixed shape: it is evaluated there
// and scaled (point lights: theta -> 0, radiance I / (pi d^2 sin^2 theta)).
vec3 pgiLocalLights(vec3 p, vec3 n, bool shadowed, float g[PGI_SH_N2])
{
  vec3 lit = vec3(0.0);
  for (int k = 0; k < pgiNumLocalLights; ++k)
  {
    vec4 l = pgiLocalLight[k];
    bool point = l.w < 0.0;
    float radius = point ? 0.0 : l.w;
    vec3 dir = l.xyz - p;
    float dist = sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
    if (!(dist > radius))
    {
      continue; // inside an emitter
    }
    dir /= dist;
    float sinTheta = radius / dist;
    float thetaEval = max(point ? 0.0 : pgiAsin(sinTheta), pgiLobeMinTheta);
    float s1 = sin(thetaEval);
    float scale = point ? 1.0 / (pgiPi * dist * dist * s1 * s1) : (sinTheta / s1) * (sinTheta / s1);
    float lh[PGI_SH_N2];
    pgiAnalyticLight(n, dir, thetaEval, lh);
    float weight = 0.0;
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      weight += lh[i] * (shadowed ? g[i] : (i == 0 ? pgiSqrtFourPi : 0.0));
    }
    lit += scale * pgiLocalRadiance[k] * max(0.0, weight);
  }
  return lit;
}
