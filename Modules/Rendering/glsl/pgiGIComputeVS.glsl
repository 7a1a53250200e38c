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
// rgb: exit radiance (albedo included; direct + indirect + local lights,
// the filter's Radiance); a: blockers accumulated.
out vec4 pgiRadiance;

//PGI::Capture::Dec

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
    float dc = g[0];
    if (carried)
    {
      float coverage = 0.0;
      for (int i = 0; i < PGI_SH_N2; ++i)
      {
        coverage += g[i] * pgiPlaneVisibility[i];
      }
      dc = coverage / pgiSqrtFourPi;
    }
    rgb += pgiResolveIndirectScaled(
      p, n, sum, dc, pgiPlaneBounceShadows != 0, pgiPlanesInLight == 0);
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
