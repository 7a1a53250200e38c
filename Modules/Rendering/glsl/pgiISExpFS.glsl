//VTK::System::Dec
//PGI::Library
//VTK::Output::Dec

// ProxyGI image-space GI, exponentiation pass over the receiver buffer: the
// accumulated log visibility plus the blocker planes, HYB exp (the
// per-vertex kernel's pgiExpHybrid), written as the visibility vector g,
// four coefficients per target. No blocker: g = 1 (as pgiVisibility).

in vec2 texCoord;
uniform sampler2D pgiReceiverPosition;
uniform sampler2D pgiReceiverNormal;
//PGI::Input::Dec

void main()
{
  ivec2 px = ivec2(texCoord * vec2(textureSize(pgiReceiverNormal, 0)));
  float f[PGI_SH_N2];
  float g[PGI_SH_N2];
  vec4 rn = texelFetch(pgiReceiverNormal, px, 0);
  if (!(rn.w > 0.5))
  {
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      g[i] = 0.0;
    }
  }
  else
  {
    //PGI::Input::Impl
    bool any = false;
    for (int i = 0; i < PGI_SH_N2; ++i)
    {
      any = any || f[i] != 0.0;
    }
    vec3 p = texelFetch(pgiReceiverPosition, px, 0).xyz;
    for (int k = 0; k < pgiNumPlanes; ++k)
    {
      vec3 pn = pgiPlaneNormal[k];
      float height = pgiPlaneHeight(k, p);
      if (height > pgiPlaneTolerance)
      {
        pgiAccumulateCap(0.5 * pgiPi, -pn, f);
        any = true;
      }
    }
    if (!any || !pgiExpHybrid(f, g))
    {
      pgiSetConstantOne(g);
    }
  }
  //PGI::Output::Impl
}
