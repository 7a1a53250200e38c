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
 * | Order | 4 | SH order 2..4 (one RGBA32F target per 4 coefficients) |
 * | ExpansionFactor | 15 | sphere-of-influence radius over proxy radius (the paper's value for
 * order 4) | | AutomaticExpansionFactor | off | on: the factor of the actual light
 * (LightingExpansionFactor at ExpansionTolerance, 1/256) | | Shadows | on | off: unshadowed
 * environment light (no splatting) | | Indirect | off | one-bounce light from proxies (averaged
 * operator) and albedo planes, normalised by xi | | IndirectExpansionFactor | 10 | sphere of
 * influence of the indirect splat | | DefaultProxyAlbedo, ProxyAlbedoArrayName | 0.8, "Albedo" |
 * the proxies' albedo | | SelfShadowRules, MinBlockerAngle, HybridMaxNorm, RangeTolerance | as the
 * mapper | kernel knobs | | NormalPower | 32 | exponent of the bilateral normal weight | |
 * DepthEpsilon | 0.01 | bilateral receiver-plane weight eps / (eps + distance / depth) | |
 * FallbackThreshold | 1e-3 | summed weight below which a pixel takes the fallback | | Fallback |
 * Exact | Exact: shaded from scratch over all proxies; NearestSample: the best-matching sample
 * (cheap on llvmpipe) | | Exposure, SRGBOutput | 1, on | display | | MeasurePassTimes | off |
 * glFinish after each pass and wall-clock times (GetPassTime) |
 *
 * Inputs as vtkPGIGIPolyDataMapper: proxies (points + "Radius", Level 0 only
 * when a "Level" array is present, world coordinates), lighting, up to 8
 * blocker planes. Receivers are the opaque surfaces rendered with lighting
 * on (VTK's shader must have a view-space position and normal); other
 * pixels keep VTK's colour. The renderer's viewport must start at the
 * window's (or tile's) origin; no stereo.
 *
 * Not done here (CPU only): the point-sampled and exact indirect operators,
 * shadowed indirect light, exp methods other than HYB, orders above 4,
 * translucent receivers.
 */
#ifndef vtkPGIImageSpaceGIPass_h
#define vtkPGIImageSpaceGIPass_h

#include "ProxyGIRenderingModule.h"
#include "vtkOpenGLRenderPass.h"

#include <memory>
#include <string>
#include <vector>

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

  /// Sphere proxies: points with a "Radius" point array (world coordinates).
  virtual void SetProxies(vtkPolyData* proxies);
  vtkGetObjectMacro(Proxies, vtkPolyData);
  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);
  /// Infinite planes blocking the half-space beneath them (at most 8); with
  /// an albedo they also bounce light (Indirect), as in the CPU filter.
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);
  void RemoveAllBlockerPlanes();

  /// 1, 2, 4 or 8 (other values: vtkErrorMacro, unchanged).
  void SetReceiverScale(int scale);
  vtkGetMacro(ReceiverScale, int);
  vtkSetClampMacro(Upsampling, int, Bilinear, Bilateral);
  vtkGetMacro(Upsampling, int);
  void SetUpsamplingToBilinear() { this->SetUpsampling(Bilinear); }
  void SetUpsamplingToBilateral() { this->SetUpsampling(Bilateral); }
  vtkSetClampMacro(Order, int, 2, 4);
  vtkGetMacro(Order, int);
  vtkSetClampMacro(ExpansionFactor, double, 1.0, 1000.0);
  vtkGetMacro(ExpansionFactor, double);
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  /// One-bounce light from the proxies and planes (needs Shadows on).
  vtkSetMacro(Indirect, bool);
  vtkGetMacro(Indirect, bool);
  vtkBooleanMacro(Indirect, bool);
  vtkSetClampMacro(IndirectExpansionFactor, double, 1.0, 1000.0);
  vtkGetMacro(IndirectExpansionFactor, double);
  /// Proxies' albedo: their ProxyAlbedoArrayName point array, else this.
  vtkSetVector3Macro(DefaultProxyAlbedo, double);
  vtkGetVector3Macro(DefaultProxyAlbedo, double);
  vtkSetStringMacro(ProxyAlbedoArrayName);
  vtkGetStringMacro(ProxyAlbedoArrayName);
  vtkSetMacro(SelfShadowRules, bool);
  vtkGetMacro(SelfShadowRules, bool);
  vtkBooleanMacro(SelfShadowRules, bool);
  vtkSetClampMacro(MinBlockerAngle, double, 0.0, 0.5);
  vtkGetMacro(MinBlockerAngle, double);
  vtkSetClampMacro(HybridMaxNorm, double, 0.0, 10.0);
  vtkGetMacro(HybridMaxNorm, double);
  vtkSetMacro(RangeTolerance, double);
  vtkGetMacro(RangeTolerance, double);
  vtkSetClampMacro(NormalPower, double, 0.0, 1024.0);
  vtkGetMacro(NormalPower, double);
  vtkSetClampMacro(DepthEpsilon, double, 1e-6, 1e6);
  vtkGetMacro(DepthEpsilon, double);
  vtkSetClampMacro(FallbackThreshold, double, 0.0, 1.0);
  vtkGetMacro(FallbackThreshold, double);
  /// Exact (default): shaded from scratch over all proxies, as the paper's
  /// robust solution. NearestSample: the best-matching sample as it is; much
  /// cheaper on CPU rasterisers (llvmpipe pays for untaken branches).
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
  vtkPGILighting* Lighting = nullptr;
  std::vector<double> BlockerPlanes; // origin, normal
  std::vector<double> PlaneAlbedos;  // 3 per plane
  int ReceiverScale = 2;
  int Upsampling = Bilateral;
  int Order = 4;
  double ExpansionFactor = 15.0;
  bool AutomaticExpansionFactor = false;
  double ExpansionTolerance = 1.0 / 256.0;
  bool Shadows = true;
  bool Indirect = false;
  double IndirectExpansionFactor = 10.0;
  double DefaultProxyAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* ProxyAlbedoArrayName = nullptr;
  bool SelfShadowRules = true;
  double MinBlockerAngle = 0.002;
  double HybridMaxNorm = 0.0;
  double RangeTolerance = 0.5;
  double NormalPower = 32.0;
  double DepthEpsilon = 0.01;
  double FallbackThreshold = 1e-3;
  int Fallback = ExactFallback;
  double Exposure = 1.0;
  bool SRGBOutput = true;
  bool MeasurePassTimes = false;
  std::string Status;

private:
  void Splat(vtkOpenGLRenderWindow* window, const std::string& vs, const std::string& fs,
    double expansion, float planeTolerance, const float wcdc[16], int proxies, bool albedo);
  void SetIndirectUniforms(vtkShaderProgram* program, float planeTolerance);

  struct Internals;
  std::unique_ptr<Internals> GPU;

  vtkPGIImageSpaceGIPass(const vtkPGIImageSpaceGIPass&) = delete;
  void operator=(const vtkPGIImageSpaceGIPass&) = delete;
};

#endif
