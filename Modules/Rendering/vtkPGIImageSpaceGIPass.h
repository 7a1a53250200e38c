/**
 * @class   vtkPGIImageSpaceGIPass
 * @brief   Image-space soft shadows and one-bounce light from sphere
 *          proxies (Sloan et al. 2007, "Image-based proxy accumulation"):
 *          vtkPGIGIPolyDataMapper's per-vertex SHEXP shadows (and the CPU
 *          filter's IndirectProxy, averaged operator) computed per pixel of a
 *          receiver buffer at 1/1, 1/2, 1/4 or 1/8 of the window.
 *
 * A render pass: set it on a renderer (renderer->SetPass(pass)); it renders
 * the scene through its delegate (a vtkRenderStepsPass by default) once into
 * full-resolution receiver targets (view-space position, normal, depth,
 * albedo = the actor's diffuse colour, VTK's own colour), then:
 *
 * | pass | what |
 * |---|---|
 * | receiver setup | the scene into the receiver targets; one sample per ReceiverScale^2 block into
 * the receiver buffer (world position, eye depth, normal) | | splatting | each proxy drawn
 * (instanced) as the box bounding its sphere of influence (radius x ExpansionFactor); receivers
 * inside it add the proxy's log-visibility vector (self-shadow rules, cap-log table), smoothly
 * clamped to 0 at the boundary, with additive blending into ceil(Order^2/4) RGBA32F targets | |
 * exponentiation | blocker planes added, HYB exp (pgiExpHybrid) per receiver: the visibility vector
 * g (GetVisibilityBuffer); then M_L g and, with Indirect, the resolved indirect light | | indirect
 * | (Indirect on) each proxy's one-bounce light and solid angle splatted over its sphere of
 * influence (IndirectExpansionFactor) into one RGBA32F target; per receiver, planes added and xi
 * applied | | upsampling | per window pixel, the 2x2 receiver-buffer samples' shadowed light M_L g
 * (bands 0..2, linear in the visibility g) and indirect light interpolated (Bilateral: bilinear x
 * receiver-plane x normal weights; Bilinear: bilinear only), shaded with the pixel's own normal
 * (H(N)), times albedo; a pixel no sample matches takes the Fallback |
 *
 * All GLSL formulas are the per-vertex kernel's (pgiGILibrary.glsl), so at
 * ReceiverScale 1 the result is per-pixel SHEXP shading; the only
 * differences from per-vertex shading on a fine mesh are the interpolation
 * across triangles and the smooth clamp of the sphere of influence (below
 * about 1/210 of the brightest unshadowed radiance for an expansion of 15 under
 * a uniform sky, about 1/74 under a delta light at order 4; see
 * LightingExpansionFactor).
 *
 * | property | default | meaning |
 * |---|---|---|
 * | ReceiverScale | 2 | receiver buffer at 1/1, 1/2, 1/4 or 1/8 of the window |
 * | Upsampling | Bilateral | Bilateral or Bilinear |
 * | ExpansionFactor | 15 | sphere-of-influence radius over proxy radius (the paper's value
 * for order 4) |
 * | AutomaticExpansionFactor | off | on: the factor of the actual light
 * (LightingExpansionFactor at ExpansionTolerance, 1/256) |
 * | IndirectExpansionFactor | 10 | sphere of influence of the indirect splat |
 * | NormalPower | 32 | exponent of the bilateral normal weight |
 * | DepthEpsilon | 0.01 | bilateral receiver-plane weight eps / (eps + distance / depth) |
 * | FallbackThreshold | 1e-3 | summed weight below which a pixel takes the fallback |
 * | Fallback | Exact | Exact: shaded from scratch over all proxies (a depth-tested draw
 * of its own, so it costs only where pixels take it); NearestSample: the best-matching
 * sample |
 * | Exposure, SRGBOutput | 1, on | display |
 * | MeasurePassTimes | off | glFinish after each pass and wall-clock times (GetPassTime) |
 *
 * The GI knobs are a vtkPGIGISettings (GetSettings; SetSettings shares one
 * with the CPU filter or the mapper): Order, Shadows, Indirect (needs
 * Shadows), the kernel knobs and DefaultProxyAlbedo/AlbedoArrayName. What
 * this pass cannot honour (GetSupport: orders above 4, exp methods other
 * than HYB, the shadowed bounce, indirect operators other than AVERAGED,
 * planes in the light, local lights, the receivers' DefaultAlbedo: the
 * actor's colour is the albedo here) is replaced, with a warning and a
 * line in GetStatus(). The precompute is the shared vtkPGIGIBake.
 *
 * Inputs as vtkPGIGIPolyDataMapper: proxies (points + "Radius", Level 0 only
 * when a "Level" array is present, world coordinates), lighting, up to 8
 * blocker planes. Receivers are the opaque surfaces rendered with lighting
 * on (VTK's shader must have a view-space position and normal); other
 * pixels keep VTK's colour. The renderer's viewport must start at the
 * window's (or tile's) origin; no stereo.
 *
 * Not done here: translucent receivers.
 */
#ifndef vtkPGIImageSpaceGIPass_h
#define vtkPGIImageSpaceGIPass_h

#include "ProxyGIRenderingModule.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <string>
#include <vector>

class vtkAlgorithmOutput;
class vtkFloatArray;
class vtkOpenGLRenderWindow;
class vtkPGILighting;
class vtkPolyData;
class vtkRenderPass;

class PROXYGIRENDERING_EXPORT vtkPGIImageSpaceGIPass : public vtkOpenGLRenderPass
{
public:
  static vtkPGIImageSpaceGIPass* New();
  vtkTypeMacro(vtkPGIImageSpaceGIPass, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum UpsamplingMode
  {
    Bilinear = 0,
    Bilateral = 1
  };
  /// What a pixel no receiver-buffer sample matches gets.
  enum FallbackMode
  {
    NearestSampleFallback = 0,
    ExactFallback = 1
  };
  /// The passes GetPassTime reports.
  enum Pass
  {
    ReceiverSetupPass = 0,
    SplattingPass,
    ExponentiationPass,
    IndirectPass,
    UpsamplingPass,
    NumberOfPasses
  };

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  /// The pass that renders the scene (default: a vtkRenderStepsPass).
  virtual void SetDelegatePass(vtkRenderPass* pass);
  vtkGetObjectMacro(DelegatePass, vtkRenderPass);

  /// Sphere proxies: points with a "Radius" point array (world coordinates),
  /// as data, or from a pipeline that Render updates (a change upstream
  /// re-executes it), as vtkGlyph3DMapper takes its source.
  virtual void SetProxies(vtkPolyData* proxies);
  void SetProxiesConnection(vtkAlgorithmOutput* output);
  /// The proxies the last frame used (from the connection when there is one).
  vtkPolyData* GetProxies();
  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);
  /// Infinite planes blocking the half-space beneath them (at most 8); with
  /// an albedo they also bounce light (Indirect), as in the CPU filter.
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);
  void RemoveAllBlockerPlanes();

  /// The GI knobs (never null); SetSettings(nullptr) restores a private default set.
  vtkPGIGISettings* GetSettings() { return this->Settings; }
  virtual void SetSettings(vtkPGIGISettings* settings);
  /// What this pass honours.
  static const vtkPGIGISettings::Support& GetSupport();
  /// The precompute this pass reuses between frames.
  vtkPGIGIBake* GetBake() { return this->Bake; }

  /// 1, 2, 4 or 8 (other values: vtkErrorMacro, unchanged).
  void SetReceiverScale(int scale);
  vtkGetMacro(ReceiverScale, int);
  vtkSetClampMacro(Upsampling, int, Bilinear, Bilateral);
  vtkGetMacro(Upsampling, int);
  void SetUpsamplingToBilinear() { this->SetUpsampling(Bilinear); }
  void SetUpsamplingToBilateral() { this->SetUpsampling(Bilateral); }
  vtkSetClampMacro(ExpansionFactor, double, 1.0, 1000.0);
  vtkGetMacro(ExpansionFactor, double);
  vtkSetClampMacro(IndirectExpansionFactor, double, 1.0, 1000.0);
  vtkGetMacro(IndirectExpansionFactor, double);
  vtkSetClampMacro(NormalPower, double, 0.0, 1024.0);
  vtkGetMacro(NormalPower, double);
  vtkSetClampMacro(DepthEpsilon, double, 1e-6, 1e6);
  vtkGetMacro(DepthEpsilon, double);
  vtkSetClampMacro(FallbackThreshold, double, 0.0, 1.0);
  vtkGetMacro(FallbackThreshold, double);
  /// Exact (default): shaded from scratch over all proxies, as the paper's
  /// robust solution, in a draw of its own that a depth test limits to the
  /// pixels taking it. NearestSample: the best-matching sample as it is.
  vtkSetClampMacro(Fallback, int, NearestSampleFallback, ExactFallback);
  vtkGetMacro(Fallback, int);
  vtkSetClampMacro(Exposure, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Exposure, double);
  vtkSetMacro(SRGBOutput, bool);
  vtkGetMacro(SRGBOutput, bool);
  vtkBooleanMacro(SRGBOutput, bool);
  vtkSetMacro(MeasurePassTimes, bool);
  vtkGetMacro(MeasurePassTimes, bool);
  vtkBooleanMacro(MeasurePassTimes, bool);

  /**
   * The lighting-specific expansion factor (Sloan et al. 2007, 4.1): the
   * smallest eta such that a blocker of sin(angular radius) = 1/eta, in the
   * worst direction over a Fibonacci set with the receiver normal facing it,
   * changes diffuse shading by at most `tolerance` of the brightest
   * unshadowed shading. Light: order^2 SH coefficients per channel. At
   * order 4 and 1/256 this gives about 28 for the "peakiest" light (a
   * delta; the paper quotes 15, which by this measure is a 1/74 loss) and
   * about 16.5 for a uniform sky: smoother light needs smaller splats.
   */
  static double LightingExpansionFactor(int order, const double* red, const double* green,
    const double* blue, double tolerance = 1.0 / 256.0);

  /// On: ExpansionFactor is ignored and LightingExpansionFactor of the
  /// current light is used (recomputed when the light changes).
  vtkSetMacro(AutomaticExpansionFactor, bool);
  vtkGetMacro(AutomaticExpansionFactor, bool);
  vtkBooleanMacro(AutomaticExpansionFactor, bool);
  /// The tolerance AutomaticExpansionFactor uses (default 1/256).
  vtkSetClampMacro(ExpansionTolerance, double, 1e-6, 0.5);
  vtkGetMacro(ExpansionTolerance, double);
  /// The expansion factor the last frame used.
  double GetUsedExpansionFactor() const;

  /// Seconds the pass took in the last frame (MeasurePassTimes on; else 0).
  double GetPassTime(int pass) const;
  /// What the last frame did, one line.
  const std::string& GetStatus() const { return this->Status; }
  /// Receiver-buffer size of the last frame.
  void GetReceiverBufferSize(int size[2]) const;

  /**
   * Reads back the receiver buffer of the last frame: the visibility
   * vectors (Order^2 components per sample, rows bottom-up, 0 where there is
   * no receiver) and, if given, a 0/1 receiver mask. False without a frame.
   */
  bool GetVisibilityBuffer(vtkFloatArray* visibility, vtkFloatArray* mask = nullptr);

  // vtkOpenGLRenderPass: the receiver outputs in VTK's fragment shaders.
  bool PreReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool PostReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool SetShaderParameters(vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp* prop,
    vtkOpenGLVertexArrayObject* VAO = nullptr) override;

protected:
  vtkPGIImageSpaceGIPass();
  ~vtkPGIImageSpaceGIPass() override;

  vtkRenderPass* DelegatePass = nullptr;
  vtkPolyData* Proxies = nullptr;
  vtkSmartPointer<vtkAlgorithmOutput> ProxiesConnection;
  vtkPGILighting* Lighting = nullptr;
  vtkPGIGISettings* Settings = nullptr;
  vtkNew<vtkPGIGISettings> Effective;
  vtkNew<vtkPGIGIBake> Bake;
  std::vector<std::string> SettingsNotes;
  int ReceiverScale = 2;
  int Upsampling = Bilateral;
  double ExpansionFactor = 15.0;
  bool AutomaticExpansionFactor = false;
  double ExpansionTolerance = 1.0 / 256.0;
  double IndirectExpansionFactor = 10.0;
  double NormalPower = 32.0;
  double DepthEpsilon = 0.01;
  double FallbackThreshold = 1e-3;
  int Fallback = ExactFallback;
  double Exposure = 1.0;
  bool SRGBOutput = true;
  bool MeasurePassTimes = false;
  std::string Status;

private:
  // The stages of Render.
  bool PrepareInputs(vtkOpenGLRenderWindow* window, std::string& why);
  void AllocateTargets(vtkOpenGLRenderWindow* window);
  bool BuildPrograms(vtkOpenGLRenderWindow* window);
  void SetUpFrame(vtkRenderer* ren);
  void RenderReceivers(const vtkRenderState* s, vtkOpenGLRenderWindow* window);
  void SplatShadows(vtkOpenGLRenderWindow* window);
  void Exponentiate(vtkOpenGLRenderWindow* window);
  void SplatIndirect(vtkOpenGLRenderWindow* window);
  void ShadeReceiverBuffer(vtkOpenGLRenderWindow* window);
  void Upsample(vtkOpenGLRenderWindow* window);
  void ComposeStatus();
  void Splat(vtkOpenGLRenderWindow* window, const std::string& vs, const std::string& fs,
    double expansion, bool albedo);
  void SetIndirectUniforms(vtkShaderProgram* program);
  void Lap(int pass);

  struct Internals;
  std::unique_ptr<Internals> GPU;

  vtkPGIImageSpaceGIPass(const vtkPGIImageSpaceGIPass&) = delete;
  void operator=(const vtkPGIImageSpaceGIPass&) = delete;
};

#endif
