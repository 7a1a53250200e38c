/**
 * @class   vtkPGIGIPolyDataMapper
 * @brief   Per-vertex global illumination on the GPU: SHEXP soft shadows from
 *          sphere proxies under SH environment light, the GPU twin of
 *          vtkPGIGlobalIllumination's DirectShadowed array.
 *
 * A vtkOpenGLPolyDataMapper that, before drawing, runs a GI pass: one GL
 * point per mesh point through a vertex shader (rasterisation off) that sums
 * the proxies' log-visibility vectors (cap-log table texture, ZH rotation
 * with the SH basis in GLSL, self-shadow rules), exponentiates them (HYB:
 * optimal-linear table texture, SH squares generated from the triple-product
 * tensor, range guard) and shades with the light's product matrix. The
 * results are captured by transform feedback into a buffer that the surface
 * pass reads as a per-vertex attribute and interpolates. The GI pass runs
 * only when something it depends on changed (mesh, proxies, light, actor
 * matrix, knobs), so camera moves cost no GI; AlwaysRecompute forces it every
 * frame (for timing). Tables come from the SphericalHarmonics module, the
 * GLSL from .glsl files encoded at build time (see pgiGIShaders.h).
 *
 * Inputs: the mesh (point normals used if present, else computed as the CPU
 * filter does), the proxies (SetProxies: points with a "Radius" array; only
 * Level 0 when a "Level" array is present), the light (SetLighting; a
 * uniform white sky if none), infinite blocker planes (AddBlockerPlane).
 * Proxies and planes are in world coordinates; the mesh follows its actor's
 * matrix.
 *
 * | property | default | meaning |
 * |---|---|---|
 * | GlobalIllumination | on | off: a plain vtkOpenGLPolyDataMapper |
 * | Shadows | on | off: unshadowed environment light |
 * | Order | 4 | SH order 2..6; cost ~n^2 per proxy and ~n^4 per vertex |
 * | Albedo | 0.8 0.8 0.8 | diffuse albedo where the mesh has no AlbedoArrayName array |
 * | AlbedoArrayName | "Albedo" | per-point albedo (3 components, 0..1 or 0..255 bytes) |
 * | SelfShadowRules | on | SHEXP 6.2 replacement rules, made continuous |
 * | MinBlockerAngle | 0.002 | radians; smaller blockers are skipped |
 * | HybridMaxNorm | 0 | HYB threshold; 0: sh::DefaultHybridMaxNorm(order) |
 * | RangeTolerance | 0.5 | sh::Exp's range guard; < 0 switches it off |
 * | Exposure | 1 | scale of the radiance written to the image |
 * | SRGBOutput | on | encode the image sRGB (the project's PNGs are sRGB) |
 * | CombineWithVTKLighting | off | on: GI is added to VTK's own lighting (e.g. specular
 * highlights, lights GI does not cover); off: GI replaces it |
 * | CaptureVisibility | off | also keep the per-vertex SH visibility (read back with
 * GetPerVertexResults) |
 * | AlwaysRecompute | off | run the GI pass every frame even if nothing changed |
 * | PlaneBlocking | PLANES_IN_LIGHT | as vtkPGIGlobalIllumination: receivers above every
 * plane get L times the planes' steps (LightAbovePlanes, built on the CPU) and no planes in
 * log space; PLANES_IN_LOG_SPACE accumulates the planes' 90-degree caps in log space |
 * | Indirect | off | one-bounce indirect light from the proxies and planes |
 * | IndirectMode | INDIRECT_MODE_UNSHADOWED | the filter's two models: UNSHADOWED (Sloan
 * 2007: AVERAGED operator, overlap normalisation xi) or SHADOWED (Guerrero 2008: the proxies
 * as spherical lights, first pass on the CPU per proxy, second pass per vertex on the GPU,
 * about one HYB exp per light a vertex sees; planes still reflect as in UNSHADOWED) |
 * | SphericalLightBlocking | BLOCKING_PER_SPHERE | SHADOWED: who blocks whom, per sphere or
 * per object (the filter's knob) |
 * | PlaneBounceShadows | on | with Indirect: planes reflect less where the proxies shadow
 * them (the filter's PlaneShadowScale; one more visibility per receiver and plane) |
 * | DefaultProxyAlbedo | 0.8 0.8 0.8 | proxies' albedo where they have no
 * ProxyAlbedoArrayName ("Albedo") array; planes' albedo: AddBlockerPlane (default 0) |
 * | LocalLights | on | the lighting's spherical and point lights (at most 16), analytic
 * L_H lobes (AnalyticLightTables, uploaded) shadowed by the proxies' visibility |
 *
 * The captured radiance is direct + indirect + local exit radiance, the
 * filter's Radiance.
 *
 * Not on the GPU yet (the CPU filter has them): exp methods other than HYB,
 * AccumulationOrder, windowing, hierarchy cuts (and with them the spherical
 * lights' reflection ratios), the indirect operators other than AVERAGED.
 * The surface pass needs no geometry shader (no wide lines or edges).
 *
 * Errors: proxies without "Radius" or with NaN/Inf/negative values
 * (vtkErrorMacro; GI goes on without the proxies), a bad environment
 * (vtkErrorMacro; the mesh is then drawn with VTK's lighting).
 *
 * On Mesa's llvmpipe a shader invocation stops all its loops once they ran
 * 65535 iterations together; past about 1000 proxies, 600 with the bounce
 * or 96 spherical lights the results may be cut short, which GetGIStatus()
 * and a warning say. Hardware drivers have no such limit.
 */
#ifndef vtkPGIGIPolyDataMapper_h
#define vtkPGIGIPolyDataMapper_h

#include "ProxyGIRenderingModule.h"
#include "vtkOpenGLPolyDataMapper.h"

#include <memory>
#include <string>
#include <vector>

class vtkFloatArray;
class vtkPGILighting;
class vtkPolyData;

class PROXYGIRENDERING_EXPORT vtkPGIGIPolyDataMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkPGIGIPolyDataMapper* New();
  vtkTypeMacro(vtkPGIGIPolyDataMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sphere proxies: points with a "Radius" point array (world coordinates).
  virtual void SetProxies(vtkPolyData* proxies);
  vtkGetObjectMacro(Proxies, vtkPolyData);

  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);

  /// Infinite planes blocking the half-space beneath them (at most 8);
  /// albedo (default 0) for the indirect light they reflect.
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);

  /// How blocker planes shadow (vtkPGIGlobalIllumination's values).
  enum
  {
    PLANES_IN_LIGHT = 0,
    PLANES_IN_LOG_SPACE = 1
  };
  vtkSetClampMacro(PlaneBlocking, int, PLANES_IN_LIGHT, PLANES_IN_LOG_SPACE);
  vtkGetMacro(PlaneBlocking, int);

  /// One-bounce unshadowed indirect light (averaged operator).
  vtkSetMacro(Indirect, bool);
  vtkGetMacro(Indirect, bool);
  vtkBooleanMacro(Indirect, bool);
  /// The indirect model (vtkPGIGlobalIllumination's values).
  enum
  {
    INDIRECT_MODE_UNSHADOWED = 0,
    INDIRECT_MODE_SHADOWED = 1
  };
  vtkSetClampMacro(IndirectMode, int, INDIRECT_MODE_UNSHADOWED, INDIRECT_MODE_SHADOWED);
  vtkGetMacro(IndirectMode, int);
  void SetIndirectModeToUnshadowed() { this->SetIndirectMode(INDIRECT_MODE_UNSHADOWED); }
  void SetIndirectModeToShadowed() { this->SetIndirectMode(INDIRECT_MODE_SHADOWED); }
  /// SHADOWED: per-sphere or per-object blocking of the spherical lights.
  enum
  {
    BLOCKING_PER_SPHERE = 0,
    BLOCKING_PER_OBJECT = 1
  };
  vtkSetClampMacro(SphericalLightBlocking, int, BLOCKING_PER_SPHERE, BLOCKING_PER_OBJECT);
  vtkGetMacro(SphericalLightBlocking, int);
  /// With Indirect: the planes reflect less where the proxies shadow them
  /// (one more visibility per receiver and plane; the filter's knob).
  vtkSetMacro(PlaneBounceShadows, bool);
  vtkGetMacro(PlaneBounceShadows, bool);
  vtkBooleanMacro(PlaneBounceShadows, bool);
  /// Proxies' albedo: their ProxyAlbedoArrayName point array, else this.
  vtkSetVector3Macro(DefaultProxyAlbedo, double);
  vtkGetVector3Macro(DefaultProxyAlbedo, double);
  vtkSetStringMacro(ProxyAlbedoArrayName);
  vtkGetStringMacro(ProxyAlbedoArrayName);
  /// The lighting's spherical and point lights (at most MaxLocalLights).
  vtkSetMacro(LocalLights, bool);
  vtkGetMacro(LocalLights, bool);
  vtkBooleanMacro(LocalLights, bool);
  static constexpr int MaxLocalLights = 16;
  void RemoveAllBlockerPlanes();

  vtkSetMacro(GlobalIllumination, bool);
  vtkGetMacro(GlobalIllumination, bool);
  vtkBooleanMacro(GlobalIllumination, bool);
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  vtkSetClampMacro(Order, int, 2, 6);
  vtkGetMacro(Order, int);
  vtkSetVector3Macro(Albedo, double);
  vtkGetVector3Macro(Albedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);
  vtkSetMacro(SelfShadowRules, bool);
  vtkGetMacro(SelfShadowRules, bool);
  vtkBooleanMacro(SelfShadowRules, bool);
  vtkSetClampMacro(MinBlockerAngle, double, 0.0, 0.5);
  vtkGetMacro(MinBlockerAngle, double);
  vtkSetClampMacro(HybridMaxNorm, double, 0.0, 10.0);
  vtkGetMacro(HybridMaxNorm, double);
  vtkSetMacro(RangeTolerance, double);
  vtkGetMacro(RangeTolerance, double);
  vtkSetClampMacro(Exposure, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Exposure, double);
  vtkSetMacro(SRGBOutput, bool);
  vtkGetMacro(SRGBOutput, bool);
  vtkBooleanMacro(SRGBOutput, bool);
  vtkSetMacro(CombineWithVTKLighting, bool);
  vtkGetMacro(CombineWithVTKLighting, bool);
  vtkBooleanMacro(CombineWithVTKLighting, bool);
  vtkSetMacro(CaptureVisibility, bool);
  vtkGetMacro(CaptureVisibility, bool);
  vtkBooleanMacro(CaptureVisibility, bool);
  vtkSetMacro(AlwaysRecompute, bool);
  vtkGetMacro(AlwaysRecompute, bool);
  vtkBooleanMacro(AlwaysRecompute, bool);

  /**
   * Reads back the results of the last GI pass, in point order: radiance
   * (3 components, exit radiance with albedo, as DirectShadowed) and, with
   * CaptureVisibility, the SH visibility (order^2 components, as Visibility).
   * Needs a rendered frame; false if there is none.
   */
  bool GetPerVertexResults(vtkFloatArray* radiance, vtkFloatArray* visibility = nullptr);

  /// How many times the GI pass ran (it is skipped when nothing changed).
  vtkGetMacro(NumberOfGIUpdates, int);
  /// What the last frame did and why, one line (e.g. for logs).
  const std::string& GetGIStatus() const { return this->GIStatus; }

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkPGIGIPolyDataMapper();
  ~vtkPGIGIPolyDataMapper() override;

  void RenderPieceStart(vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;

  /// Runs the GI pass if anything it depends on changed; false if GI is off.
  bool UpdateGI(vtkRenderer* ren, vtkActor* act);
  // The shadowed bounce's spherical lights and their first pass (CPU).
  bool UpdateSphericalLights(vtkPGILighting* lighting);

  vtkPolyData* Proxies = nullptr;
  vtkPGILighting* Lighting = nullptr;
  std::vector<double> BlockerPlanes; // origin, normal
  std::vector<double> PlaneAlbedos;  // 3 per plane
  int PlaneBlocking = PLANES_IN_LIGHT;
  bool Indirect = false;
  int IndirectMode = INDIRECT_MODE_UNSHADOWED;
  int SphericalLightBlocking = BLOCKING_PER_SPHERE;
  bool PlaneBounceShadows = true;
  double DefaultProxyAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* ProxyAlbedoArrayName = nullptr;
  bool LocalLights = true;
  bool GlobalIllumination = true;
  bool Shadows = true;
  int Order = 4;
  double Albedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;
  bool SelfShadowRules = true;
  double MinBlockerAngle = 0.002;
  double HybridMaxNorm = 0.0;
  double RangeTolerance = 0.5;
  double Exposure = 1.0;
  bool SRGBOutput = true;
  bool CombineWithVTKLighting = false;
  bool CaptureVisibility = false;
  bool AlwaysRecompute = false;
  int NumberOfGIUpdates = 0;
  std::string GIStatus;

private:
  struct Internals;
  std::unique_ptr<Internals> GPU;

  vtkPGIGIPolyDataMapper(const vtkPGIGIPolyDataMapper&) = delete;
  void operator=(const vtkPGIGIPolyDataMapper&) = delete;
};

#endif
