  {
    // ProxyGI: GI replaces VTK's lighting, or adds to it as ambient light.
    vec3 pgiGI = pgiExposure * (pgiRadianceVSOutput + PGI_EXTRA_RADIANCE);
    if (pgiSRGBOutput != 0)
    {
      pgiGI = pgiEncodeSRGB(pgiGI);
    }
    gl_FragData[0].rgb = pgiCombineWithVTKLighting != 0 ? gl_FragData[0].rgb + pgiGI : pgiGI;
  }
