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
 * filter does), the proxies (input port 1, SetProxiesConnection, as
 * vtkGlyph3DMapper takes its source, or SetProxies for a data object:
 * points with a "Radius" array; only Level 0 when a "Level" array is
 * present), the light (SetLighting; a uniform white sky if none), infinite
 * blocker planes (AddBlockerPlane, at most 8). Proxies and planes are in
 * world coordinates; the mesh follows its actor's matrix.
 *
 * The GI knobs are a vtkPGIGISettings (GetSettings; SetSettings shares one
 * with the CPU filter or the image-space pass). What this mapper cannot
 * honour (GetSupport: orders above 6, exp methods other than HYB,
 * AccumulationOrder, windowing, hierarchy cuts, indirect operators other
 * than AVERAGED) is replaced by what it can, with a warning and a line in
 * GetGIStatus(). The precompute is the vtkPGIGIBake every consumer shares,
 * rebuilt only when the proxies, lighting, planes or settings change.
 *
 * | property | default | meaning |
 * |---|---|---|
 * | GlobalIllumination | on | off: a plain vtkOpenGLPolyDataMapper |
 * | Exposure | 1 | scale of the radiance written to the image |
 * | SRGBOutput | on | encode the image sRGB (the project's PNGs are sRGB) |
 * | CombineWithVTKLighting | off | on: GI is added to VTK's own lighting (e.g. specular
 * highlights, lights GI does not cover); off: GI replaces it |
 * | CaptureVisibility | off | also keep the per-vertex SH visibility (read back with
 * GetPerVertexResults) |
 * | AlwaysRecompute | off | run the GI pass every frame even if nothing changed |
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
#include "pgiVertexGI.h" // for the shared GPU implementation
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"

#include <string>

class vtkFloatArray;
class vtkPGILighting;
class vtkPolyData;

class PROXYGIRENDERING_EXPORT vtkPGIGIPolyDataMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkPGIGIPolyDataMapper* New();
  vtkTypeMacro(vtkPGIGIPolyDataMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sphere proxies: points with a "Radius" point array (world coordinates),
  /// as data (SetProxies) or from a pipeline (SetProxiesConnection, port 1).
  virtual void SetProxies(vtkPolyData* proxies);
  vtkPolyData* GetProxies();
  void SetProxiesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  virtual void SetLighting(vtkPGILighting* lighting);
  vtkPGILighting* GetLighting() { return this->Scene.Lighting; }

  /// The GI knobs (never null); SetSettings(nullptr) restores a private default set.
  vtkPGIGISettings* GetSettings() { return this->Scene.Settings; }
  virtual void SetSettings(vtkPGIGISettings* settings);
  /// What this mapper honours.
  static const vtkPGIGISettings::Support& GetSupport();
  /// The precompute this mapper reuses between GI passes.
  vtkPGIGIBake* GetBake() { return this->Scene.Bake; }

  /// Infinite planes blocking the half-space beneath them (at most 8);
  /// albedo (default 0) for the indirect light they reflect.
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);
  /// A plane of finite extent (vtkPGIGlobalIllumination::AddBlockerPlane):
  /// with PlaneBounceDirections > 0 it reflects from that area only.
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3],
    const double halfEdge1[3], const double halfEdge2[3]);
  void RemoveAllBlockerPlanes();
  static constexpr int MaxLocalLights = proxygi::gpu::VertexGI::MaxLocalLights;

  void SetGlobalIllumination(bool on);
  bool GetGlobalIllumination() const { return this->Options.GlobalIllumination; }
  vtkBooleanMacro(GlobalIllumination, bool);
  void SetExposure(double exposure);
  double GetExposure() const { return this->Options.Exposure; }
  void SetSRGBOutput(bool on);
  bool GetSRGBOutput() const { return this->Options.SRGBOutput; }
  vtkBooleanMacro(SRGBOutput, bool);
  void SetCombineWithVTKLighting(bool on);
  bool GetCombineWithVTKLighting() const { return this->Options.CombineWithVTKLighting; }
  vtkBooleanMacro(CombineWithVTKLighting, bool);
  void SetCaptureVisibility(bool on);
  bool GetCaptureVisibility() const { return this->Options.CaptureVisibility; }
  vtkBooleanMacro(CaptureVisibility, bool);
  void SetAlwaysRecompute(bool on);
  bool GetAlwaysRecompute() const { return this->Options.AlwaysRecompute; }
  vtkBooleanMacro(AlwaysRecompute, bool);

  /**
   * Accuracy budget (proxygi::budget, as vtkPGIGlobalIllumination's): with
   * ErrorBudget > 0 (relative RMSE against the truth, e.g. 0.05) the fastest
   * of the model's GPU-mapper candidates predicted to meet it, with
   * TimeBudget > 0 (seconds per GI pass) the most accurate predicted to fit;
   * both: the fastest meeting both. It chooses the order and the bounce
   * among the candidates of the proxies' sphere count, on a copy of the
   * settings (the settings object is left as set), and says the choice,
   * its prediction and what it traded in GetGIStatus(). The times are those
   * of the GL renderer the model was calibrated on (`proxygi calibrate
   * --routes filter,mapper`); the status says when that is another kind of
   * renderer. 0: no budget (default); negative: a warning, the closest
   * candidate. BudgetModelFileName: a model from `proxygi calibrate`
   * (default: the one that ships).
   */
  void SetErrorBudget(double fraction);
  double GetErrorBudget() const { return this->Scene.ErrorBudget; }
  void SetTimeBudget(double seconds);
  double GetTimeBudget() const { return this->Scene.TimeBudget; }
  void SetBudgetModelFileName(const char* fileName);
  const char* GetBudgetModelFileName() const { return this->Scene.BudgetModelFileName.c_str(); }

  vtkMTimeType GetMTime() override;

  /**
   * Reads back the results of the last GI pass, in point order: radiance
   * (3 components, exit radiance with albedo, as DirectShadowed) and, with
   * CaptureVisibility, the SH visibility (order^2 components, as Visibility).
   * Needs a rendered frame; false if there is none.
   */
  bool GetPerVertexResults(vtkFloatArray* radiance, vtkFloatArray* visibility = nullptr);

  /// How many times the GI pass ran (it is skipped when nothing changed).
  int GetNumberOfGIUpdates() const { return this->GI.GetNumberOfUpdates(); }
  /// What the last frame did and why, one line (e.g. for logs).
  const std::string& GetGIStatus() const { return this->GI.GetStatus(); }
  /// Whether the last GI pass ran past llvmpipe's loop limit, so its results
  /// may be cut short (GetGIStatus says so too).
  bool GetGICutShort() const { return this->GI.GetCutShort(); }

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkPGIGIPolyDataMapper();
  ~vtkPGIGIPolyDataMapper() override;

  void RenderPieceStart(vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// Runs the GI pass if anything it depends on changed; false if GI is off.
  bool UpdateGI(vtkRenderer* ren, vtkActor* act);

  proxygi::gpu::MapperScene Scene;
  proxygi::gpu::VertexGI GI;
  proxygi::gpu::VertexGIOptions Options;

private:
  vtkPGIGIPolyDataMapper(const vtkPGIGIPolyDataMapper&) = delete;
  void operator=(const vtkPGIGIPolyDataMapper&) = delete;
};

#endif
