/**
 * @file pgiGIShaders.h
 * @brief The GPU side of per-vertex GI, shared by vtkPGIGIPolyDataMapper and
 * the tests: GLSL assembly (the encoded .glsl files plus the SH square
 * generated from the triple-product tensor), the tables and light uploaded as
 * textures and uniforms (GIResources), and a transform-feedback harness that
 * runs any GLSL helper per vertex and reads the results back (GLSLHarness).
 *
 * The GLSL twins and their C++ originals (pgiGILibrary.glsl; the indirect
 * ones in pgiISLibrary.glsl), each pair compared in TestRenderingGLSLTwins:
 * | GLSL | C++ |
 * |---|---|
 * | pgiSHBasis | sh::EvaluateBasis (both from the same generator script) |
 * | pgiCapLog | sh::CapTables::CapLog (float path) |
 * | pgiCapVisibility | sh::CapTables::CapVisibility (float path) |
 * | pgiAveragedIndirect, pgiAveragedRadiance | sh::IndirectTables (float path) |
 * | pgiRotateScaledZonal | sh::RotateScaledZonal |
 * | pgiOptimalLinear | sh::CapTables::OptimalLinear |
 * | pgiSHSquare | sh::TripleProduct::Square (generated from its Terms()) |
 * | pgiExpHybrid, pgiGuardRange | sh::Exp (HYB), sh::GuardRange |
 * | pgiReplaceBlocker | proxygi::ReplaceBlocker |
 * | pgiVisibility, pgiVisibilityOf | SoftShadows::Visibility (PlanesInLogSpace on, off) |
 * | pgiShade(Of), pgiShadeUnshadowed(Of) | EnvironmentShading (product matrix) of L, or
 *   (light 1) of the light above the planes that LightAbovePlanes built |
 * | pgiProxyIndirectTerm(H), pgiResolveIndirect(Scaled) | IndirectExitRadiance (averaged) |
 * | pgiPlaneShadowScale | proxygi::PlaneShadowScale |
 * | pgiAboveEveryPlane | proxygi::Blockers::AboveEveryPlane |
 * | pgiLocalLights | proxygi::LocalLightsRadiance |
 * | pgiAnalyticLight, pgiAnalyticLightLookup | sh::AnalyticLightTables::Evaluate, Lookup |
 * | pgiSphericalLightRadiance (pgiGISphericalLights.glsl) | IndirectTables::SphericalLightRadiance
 * | | pgiShadowedIndirect (pgiGISphericalLights.glsl) | ShadowedIndirect::ExitRadiance |
 */
#ifndef pgiGIShaders_h
#define pgiGIShaders_h

#include "ProxyGIRenderingModule.h"

#include "vtkPGIGISettings.h" // for Support
#include "vtkSmartPointer.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkPolyData;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

namespace proxygi
{
struct Blockers;
class PlaneLightMap;
struct SphericalLights;
namespace gpu
{

/// SH orders the GLSL supports (the generated basis has bands 0..5).
constexpr int MinOrder = 2;
constexpr int MaxOrder = 6;
/// Infinite blocker planes the kernel takes.
constexpr int MaxPlanes = 8;

/// The bake's leaf spheres as the kernel reads them: x, y, z, r each.
PROXYGIRENDERING_EXPORT std::vector<float> PackSpheres(const Blockers& blockers);
/// The bake's planes as the kernel reads them: origin, unit normal (6 each).
PROXYGIRENDERING_EXPORT std::vector<float> PackPlanes(const Blockers& blockers);
/// The planes' albedo as the pgiPlaneAlbedo uniform (MaxPlanes RGB, zero-padded).
PROXYGIRENDERING_EXPORT std::vector<float> PackPlaneAlbedos(const Blockers& blockers);

/**
 * The leaf spheres' albedo (the bake's, 3 per sphere) as RGBA texels laid
 * out as GIResources lays out the spheres (rows of up to 1024), kept in
 * `texels` and uploaded as a float texture that replaces `texture`.
 */
PROXYGIRENDERING_EXPORT void UploadProxyAlbedos(vtkOpenGLRenderWindow* window,
  const Blockers& blockers, std::vector<float>& texels, vtkSmartPointer<vtkTextureObject>& texture);

/**
 * The planes' light maps (BuildPlaneLightMaps) as pgiPlaneLightScale in the
 * GI mapper's compute shader reads them: the grids stacked in one float
 * texture, the look-up directions (world vector, steps) in another, the
 * sky past the planes' edges (SetSky's tables) in a third, and the
 * per-plane uniforms (MaxPlanes each, zero-padded).
 */
struct PROXYGIRENDERING_EXPORT PlaneLightMapsGL
{
  int Directions = 0; // 0: no maps (one plane point)
  vtkSmartPointer<vtkTextureObject> Grid, Table, Sky;
  std::vector<float> U, V, Frame, Size, Dual; // 3, 3, 4, 4, 4 per plane
  int Points = 0;
};

/// Uploads `maps` (all with the same directions) into `gl`, releasing what
/// it held; empty maps or no directions leave it off.
PROXYGIRENDERING_EXPORT void UploadPlaneLightMaps(
  vtkOpenGLRenderWindow* window, const std::vector<PlaneLightMap>& maps, PlaneLightMapsGL& gl);
/// Binds them to `program` (textures activated; Release deactivates).
PROXYGIRENDERING_EXPORT void BindPlaneLightMaps(vtkShaderProgram* program, PlaneLightMapsGL& gl);
PROXYGIRENDERING_EXPORT void ReleasePlaneLightMaps(PlaneLightMapsGL& gl);
/// Frees their textures and empties `gl` (a new upload, or the mapper's
/// ReleaseGraphicsResources).
PROXYGIRENDERING_EXPORT void FreePlaneLightMaps(vtkWindow* window, PlaneLightMapsGL& gl);

/// The indirect-light GLSL (pgiISLibrary.glsl: pgiProxyIndirectTerm,
/// pgiResolveIndirect and their uniforms), to go after LibrarySource.
PROXYGIRENDERING_EXPORT std::string IndirectLibrarySource();

/// The shadowed one-bounce GLSL (pgiGISphericalLights.glsl: the second pass
/// of ShadowedIndirect) sized for `lights` spherical lights (rounded up to
/// a multiple of 32, so few program variants), to go after LibrarySource.
PROXYGIRENDERING_EXPORT std::string SphericalLightsLibrarySource(int lights);

/// GLSL statements of TripleProduct::Square for one order (o = f * f).
PROXYGIRENDERING_EXPORT std::string SquareSource(int order);

/// The GI library for one order: #defines, the SH basis, pgiGILibrary.glsl.
PROXYGIRENDERING_EXPORT std::string LibrarySource(int order);

/// Knobs of the kernel that are uniforms (SoftShadowSettings' twins).
struct KernelSettings
{
  /// Blockers subtending less than this (radians) are skipped.
  double MinBlockerAngle = 0.002;
  bool SelfShadowRules = true;
  /// HYB threshold; <= 0: sh::DefaultHybridMaxNorm(order).
  double HybridMaxNorm = 0.0;
  /// Range guard tolerance of sh::Exp; < 0 switches the guard off.
  double RangeTolerance = 0.5;
};

/// The kernel's uniforms from (effective) settings: one fill for both GPU consumers.
PROXYGIRENDERING_EXPORT KernelSettings KernelSettingsOf(vtkPGIGISettings* settings);

/**
 * What the GPU kernels (pgiGILibrary.glsl) honour, for a GPU backend's
 * vtkPGIGISettings::Support: orders MinOrder..maxOrder, HYB only, the
 * product-matrix path, no accumulation order, windowing or hierarchy cuts,
 * the averaged indirect operator. Backends narrow it further.
 */
PROXYGIRENDERING_EXPORT vtkPGIGISettings::Support KernelSupport(const char* backend, int maxOrder);

/**
 * Tables, light and blockers on the GPU for one order: the cap log-visibility,
 * cap visibility and optimal-linear tables of sh::CapTables, the averaged
 * indirect D(theta) of sh::IndirectTables, the light's product matrix
 * (sh::TripleProduct::ProductMatrix, per channel), the light vector, the
 * scaled ZH of the diffuse transfer, the proxies as a float texture.
 */
class PROXYGIRENDERING_EXPORT GIResources
{
public:
  GIResources();
  ~GIResources();
  GIResources(const GIResources&) = delete;
  GIResources& operator=(const GIResources&) = delete;

  /// Builds the table textures for this order in this context (cached).
  bool SetOrder(vtkOpenGLRenderWindow* window, int order);
  int GetOrder() const;
  /// Light: order^2 SH coefficients per channel (radiance), in double.
  void SetLight(const double* red, const double* green, const double* blue);
  /**
   * The light above the blocker planes (light 1 of pgiShadeOf and
   * pgiShadeUnshadowedOf): L times the planes' steps as LightAbovePlanes
   * built it. Null pointers: light 1 is L again (also the default; call
   * after SetLight when both change).
   */
  void SetLightAbovePlanes(const double* red, const double* green, const double* blue);
  /// Spheres as x, y, z, r (4 floats each); planes as origin, unit normal (6 each).
  void SetBlockers(const std::vector<float>& spheres, const std::vector<float>& planes);
  void SetSettings(const KernelSettings& settings);
  /// Uploads (on the next Bind) AnalyticLightTables' lobe table for the
  /// local lights (pgiAnalyticLight); off by default (built on demand).
  void SetAnalyticLightTable(bool use);
  /// The table's first theta node, below which the filter scales L_H.
  double GetAnalyticLightMinTheta() const;
  /**
   * The spherical lights of the shadowed bounce after their first pass
   * (PrepareSphericalLights), uploaded on the next Bind with the w_theta
   * table; null: none (pgiNumSphericalLights 0).
   */
  void SetSphericalLights(const SphericalLights* lights, bool perObject);

  /// Activates the textures and sets every uniform on a bound program.
  void Bind(vtkShaderProgram* program);
  /// Frees the texture units Bind took.
  void Unbind();
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/**
 * Runs GLSL per vertex with transform feedback: `inputs` vec4 attributes
 * pgiIn0.. (one row of 4 * inputs floats per vertex), `outputs` vec4
 * varyings pgiOut0.. captured and read back. `body` is the main() code;
 * `declarations` go before main (helper functions). The GI library of the
 * order is included, with Resources() bound.
 */
class PROXYGIRENDERING_EXPORT GLSLHarness
{
public:
  explicit GLSLHarness(vtkOpenGLRenderWindow* window);
  ~GLSLHarness();
  GLSLHarness(const GLSLHarness&) = delete;
  GLSLHarness& operator=(const GLSLHarness&) = delete;

  GIResources& Resources();
  /// uniforms: sets the declarations' own uniforms on the bound program.
  bool Run(int order, const std::string& declarations, const std::string& body, int inputs,
    int outputs, const std::vector<float>& in, std::vector<float>& out,
    const std::function<void(vtkShaderProgram*)>& uniforms = {});
  const std::string& GetError() const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace gpu
} // namespace proxygi

#endif
