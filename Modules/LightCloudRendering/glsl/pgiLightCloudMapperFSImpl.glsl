  {
    // ProxyGI light cloud: added to VTK's lighting, or replacing it.
    vec3 pgiCloud = pgiCloudExposure * pgiCloudRadiance();
    if (pgiCloudSRGBOutput != 0)
    {
      pgiCloud = pgiEncodeSRGB(pgiCloud);
    }
    gl_FragData[0].rgb =
      pgiCloudCombineWithVTKLighting != 0 ? gl_FragData[0].rgb + pgiCloud : pgiCloud;
  }
