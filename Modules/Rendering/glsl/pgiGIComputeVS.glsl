//VTK::System::Dec

// Per-vertex GI, one GL point per mesh point: vtkPGIGIPolyDataMapper draws
// the points with rasterisation off and captures pgiRadiance (and, when
// asked, the visibility vector) by transform feedback, once per change of
// the scene; the surface pass then reads the captured buffer as a vertex
// attribute.

//PGI::Defines

//PGI::Library

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

// rgb: exit radiance (albedo included); a: blockers accumulated.
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
  if (pgiShadows != 0)
  {
    used = pgiVisibility(p, n, g);
    rgb = used > 0 ? pgiShade(n, g) : max(pgiShadeUnshadowed(n), vec3(0.0));
  }
  else
  {
    pgiSetConstantOne(g);
    rgb = pgiShadeUnshadowed(n);
  }
  pgiRadiance = vec4(rgb * pgiAlbedoMC, float(used));
  //PGI::Capture::Impl
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
