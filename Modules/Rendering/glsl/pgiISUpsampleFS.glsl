//VTK::System::Dec
//PGI::Library
//VTK::Output::Dec

// ProxyGI image-space GI, upsampling and shading at full resolution: the
// shadowed incident radiance M_L g (linear in the visibility vector g) of
// the 2x2 receiver-buffer samples around the pixel is interpolated with
// bilinear weights times, when pgiBilateral is set, a receiver-plane weight eps / (eps + |(p_i - p).N| / z) and a normal weight
// max(0, N.N_i)^pgiNormalPower (Sloan et al. 2007, eq. 11, with the depth
// difference measured to the pixel's tangent plane, relative to its depth,
// so slanted planes interpolate evenly). Where no sample matches (weights
// below pgiFallbackThreshold) the pixel takes the best-matching sample as
// it is, or is shaded from scratch over all proxies (the Exact fallback:
// pgiVisibility, the per-vertex kernel). Then H(N) shading with the
// pixel's own normal, plus the interpolated one-bounce light (shaded at the
// receiver-buffer samples), times albedo, exposure, sRGB; pixels without a
// receiver keep the colour VTK rendered.
//
// PGI_UPSAMPLE_STAGE: 0, one pass with the nearest-sample fallback; with
// the Exact fallback, 1 upsamples and marks the pixels no sample matches
// (their depth set to the quad's own), and 2 shades only the marked ones
// from scratch: drawn with the depth test EQUAL and no depth writes, the
// test runs before the shader, so the fallback's long shader costs only
// where pixels take it (a branch in one shader costs its whole length on
// SIMD rasterisers such as llvmpipe). pgiISRestoreDepthFS puts the depth
// back.

in vec2 texCoord;
uniform sampler2D pgiGColor;
uniform sampler2D pgiGPosition;
uniform sampler2D pgiGNormal;
uniform sampler2D pgiGAlbedo;
uniform sampler2D pgiGDepth;
uniform sampler2D pgiReceiverPosition;
uniform sampler2D pgiReceiverNormal;
//PGI::Input::Dec
uniform int pgiScale;
uniform int pgiBilateral;
uniform int pgiShadows;
uniform int pgiIndirect;
uniform float pgiIndirectExpansion;
uniform sampler2D pgiProxyAlbedo; // same layout as pgiProxyTexture
uniform float pgiDepthEpsilon;
uniform float pgiNormalPower;
uniform float pgiFallbackThreshold;
uniform mat4 pgiVCToWC;
uniform mat3 pgiNormalVCToWC;
uniform float pgiExposure;
uniform int pgiSRGBOutput;

// pgiEncodeSRGB: in the library (pgiSRGB.glsl).

#if PGI_UPSAMPLE_STAGE == 2
// A pixel from scratch: its own visibility and indirect light.
vec3 pgiShadeExact(vec3 p, vec3 n)
{
  float g[PGI_SH_N2];
  int used = pgiVisibility(p, n, g);
  vec3 rgb = used > 0 ? pgiShade(n, g) : max(pgiShadeUnshadowed(n), vec3(0.0));
  if (pgiIndirect != 0)
  {
    vec4 sum = vec4(0.0);
    for (int s = 0; s < pgiNumProxies; ++s)
    {
      ivec2 at = ivec2(s % pgiProxyTextureWidth, s / pgiProxyTextureWidth);
      sum += pgiProxyIndirect(p, n, texelFetch(pgiProxyTexture, at, 0),
        texelFetch(pgiProxyAlbedo, at, 0).rgb, pgiIndirectExpansion);
    }
    rgb += pgiResolveIndirect(p, n, sum, g[0]);
  }
  return rgb;
}
#endif

void main()
{
  ivec2 px = ivec2(texCoord * vec2(textureSize(pgiGColor, 0)));
  vec4 color = texelFetch(pgiGColor, px, 0);
  float depth = texelFetch(pgiGDepth, px, 0).r;
  vec4 pv = texelFetch(pgiGPosition, px, 0);
#if PGI_UPSAMPLE_STAGE != 2
  gl_FragDepth = depth;
#endif
  if (!(depth < 1.0) || !(pv.w > 0.5))
  {
    gl_FragData[0] = color;
    return;
  }
  vec3 p = (pgiVCToWC * vec4(pv.xyz, 1.0)).xyz;
  vec3 n = pgiNormalVCToWC * texelFetch(pgiGNormal, px, 0).xyz;
  float nlen = length(n);
  n = nlen > 0.0 ? n / nlen : vec3(0.0, 0.0, 1.0);
  float z = max(-pv.z, 1.0e-6);
  vec3 rgb;
  if (pgiShadows == 0)
  {
    rgb = pgiShadeUnshadowed(n);
  }
  else
  {
#if PGI_UPSAMPLE_STAGE == 2
    rgb = pgiShadeExact(p, n);
#else
    // Sample i of the receiver buffer sits at full-resolution pixel
    // i * scale + scale / 2.
    vec2 q = (vec2(px) - float(pgiScale / 2)) / float(pgiScale);
    vec2 base = floor(q);
    vec2 t = q - base;
    ivec2 i0 = ivec2(base);
    ivec2 last = textureSize(pgiReceiverPosition, 0) - ivec2(1);
    // Interpolated: the shadowed incident radiance (pgiISShadowedLightFS),
    // 3 * PGI_SHADE_ROWS floats, and the indirect light, 3 more.
    float c[3 * PGI_SHADE_ROWS + 3];
    for (int i = 0; i < 3 * PGI_SHADE_ROWS + 3; ++i)
    {
      c[i] = 0.0;
    }
    float wsum = 0.0;
    float bestMatch = -1.0; // the best sample by receiver-plane x normal weight
    ivec2 best = ivec2(0);
    for (int k = 0; k < 4; ++k)
    {
      ivec2 o = ivec2(k & 1, k >> 1);
      ivec2 s = clamp(i0 + o, ivec2(0), last);
      float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
      if (!(w > 0.0))
      {
        continue;
      }
      vec4 rn = texelFetch(pgiReceiverNormal, s, 0);
      if (!(rn.w > 0.5))
      {
        continue;
      }
      vec3 ps = texelFetch(pgiReceiverPosition, s, 0).xyz;
      float dz = abs(dot(ps - p, n)) / z;
      float match = pgiDepthEpsilon / (pgiDepthEpsilon + dz) *
        pow(max(0.0, dot(n, rn.xyz)), pgiNormalPower);
      if (match > bestMatch)
      {
        bestMatch = match;
        best = s;
      }
      if (pgiBilateral != 0)
      {
        w *= match;
      }
      if (!(w > 0.0))
      {
        continue;
      }
      float v[3 * PGI_SHADE_ROWS + 3 + 3];
      //PGI::Input::Impl
      for (int i = 0; i < 3 * PGI_SHADE_ROWS + 3; ++i)
      {
        c[i] += w * v[i];
      }
      wsum += w;
    }
    if (wsum > pgiFallbackThreshold)
    {
      vec3 lg[PGI_SH_N2];
      for (int i = 0; i < PGI_SH_N2; ++i)
      {
        lg[i] = i < PGI_SHADE_ROWS ? vec3(c[3 * i], c[3 * i + 1], c[3 * i + 2]) / wsum : vec3(0.0);
      }
      rgb = pgiShadeShadowedLight(n, lg, PGI_SHADE_ROWS);
      rgb += vec3(c[3 * PGI_SHADE_ROWS], c[3 * PGI_SHADE_ROWS + 1], c[3 * PGI_SHADE_ROWS + 2]) / wsum;
    }
    else if (bestMatch >= 0.0)
    {
      // No sample matches well: the best one as it is (cheap; no per-pixel
      // recomputation code in the shader).
      ivec2 s = best;
      float v[3 * PGI_SHADE_ROWS + 3 + 3];
      //PGI::Input::Impl
      vec3 lg[PGI_SH_N2];
      for (int i = 0; i < PGI_SH_N2; ++i)
      {
        lg[i] = i < PGI_SHADE_ROWS ? vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]) : vec3(0.0);
      }
      rgb = pgiShadeShadowedLight(n, lg, PGI_SHADE_ROWS);
      rgb += vec3(v[3 * PGI_SHADE_ROWS], v[3 * PGI_SHADE_ROWS + 1], v[3 * PGI_SHADE_ROWS + 2]);
    }
    else
    {
      rgb = max(pgiShadeUnshadowed(n), vec3(0.0));
    }
#if PGI_UPSAMPLE_STAGE == 1
    if (!(wsum > pgiFallbackThreshold))
    {
      gl_FragDepth = gl_FragCoord.z; // for stage 2
    }
#endif
#endif
  }
  rgb *= texelFetch(pgiGAlbedo, px, 0).rgb * pgiExposure;
  if (pgiSRGBOutput != 0)
  {
    rgb = pgiEncodeSRGB(rgb);
  }
  gl_FragData[0] = vec4(rgb, 1.0);
}
