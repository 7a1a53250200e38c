//VTK::Color::Impl
  {
    // ProxyGI light cloud: the receiver's light, per vertex.
    float pgiA[PGI_CLOUD_STRIDE];
    pgiCloudReconstruct(pgiCloudCodeMC, pgiA);
    // Camera minus vertex in model coordinates (both in the VBO's shifted
    // and scaled frame), then to world: linear in position, so it
    // interpolates exactly over a face.
    pgiCloudToViewer = pgiCloudModelToWorld * ((pgiCloudCamera - vertexMC.xyz) / pgiCloudVBOScale);
#if PGI_CLOUD_VARYINGS * 3 == PGI_CLOUD_STRIDE
    for (int k = 0; k < PGI_CLOUD_VARYINGS; ++k)
    {
      pgiCloudRGB[k] = vec3(pgiA[3 * k], pgiA[3 * k + 1], pgiA[3 * k + 2]);
    }
#else
    // Glossy, per vertex: the SH evaluated toward the camera here.
    float pgiY[PGI_SH_N2];
    pgiSHBasis(pgiCloudViewDirection(pgiCloudToViewer), pgiY);
    vec3 pgiSeen = vec3(0.0);
    for (int k = 0; k < PGI_SH_N2; ++k)
    {
      pgiSeen += pgiY[k] * vec3(pgiA[3 * k], pgiA[3 * k + 1], pgiA[3 * k + 2]);
    }
    pgiCloudRGB[0] = pgiSeen;
#endif
  }
