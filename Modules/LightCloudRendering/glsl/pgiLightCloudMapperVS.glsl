//VTK::Color::Dec
// ProxyGI light cloud: each receiver's code (compressed: its mean, first
// basis vector, vector count and first PCA weight; dense: its point id),
// the frame's vectors and the cloud's static data.
//PGI::Cloud::Defines
in vec4 pgiCloudCodeMC;
uniform samplerBuffer pgiCloudVectors;
uniform samplerBuffer pgiCloudData;
uniform int pgiCloudCompressed;
uniform int pgiCloudDenseCount;
uniform int pgiCloudReceivers;
uniform vec3 pgiCloudCamera;
uniform vec3 pgiCloudVBOScale;
uniform mat3 pgiCloudModelToWorld;
out vec3 pgiCloudToViewer;
out vec3 pgiCloudRGB[PGI_CLOUD_VARYINGS];
//PGI::SHBasis

// The GLSL twin of vtkPGILightCloudRelight's per-receiver sums. Compressed:
// a = x_m + sum_i z_i b_i, vectors Stride floats each. Dense: a = sum_j w_j
// X_j, the frame's entries (light, r, g, b), responses light-major.
void pgiCloudReconstruct(vec4 code, out float a[PGI_CLOUD_STRIDE])
{
  for (int c = 0; c < PGI_CLOUD_STRIDE; ++c)
  {
    a[c] = 0.0;
  }
  if (pgiCloudCompressed != 0)
  {
    int mean = int(code.x), first = int(code.y), count = int(code.z), z = int(code.w);
    for (int c = 0; c < PGI_CLOUD_STRIDE; ++c)
    {
      a[c] = texelFetch(pgiCloudVectors, mean * PGI_CLOUD_STRIDE + c).r;
    }
    for (int v = 0; v < count; ++v)
    {
      float zv = texelFetch(pgiCloudData, z + v).r;
      int base = (first + v) * PGI_CLOUD_STRIDE;
      for (int c = 0; c < PGI_CLOUD_STRIDE; ++c)
      {
        a[c] += zv * texelFetch(pgiCloudVectors, base + c).r;
      }
    }
    return;
  }
  int receiver = int(code.x);
  for (int q = 0; q < pgiCloudDenseCount; ++q)
  {
    int light = int(texelFetch(pgiCloudVectors, 4 * q).r);
    vec3 w = vec3(texelFetch(pgiCloudVectors, 4 * q + 1).r,
      texelFetch(pgiCloudVectors, 4 * q + 2).r, texelFetch(pgiCloudVectors, 4 * q + 3).r);
    int base = (light * pgiCloudReceivers + receiver) * PGI_CLOUD_STRIDE;
    for (int c = 0; c < PGI_CLOUD_STRIDE; ++c)
    {
      a[c] += w[c % 3] * texelFetch(pgiCloudData, base + c).r;
    }
  }
}

// The unit vector toward the viewer; (0, 0, 1) at the viewer itself, as the
// CPU filter has it.
vec3 pgiCloudViewDirection(vec3 d)
{
  float l = length(d);
  return l > 0.0 ? d / l : vec3(0.0, 0.0, 1.0);
}
