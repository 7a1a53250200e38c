/**
 * @class   vtkPGIGISettings
 * @brief   The GI knobs, one set of names for every consumer: the CPU
 *          filter (vtkPGIGlobalIllumination), the per-vertex GPU mapper
 *          (vtkPGIGIPolyDataMapper) and the image-space pass
 *          (vtkPGIImageSpaceGIPass).
 *
 * Each consumer owns one (GetSettings) or shares one (SetSettings), and
 * declares what it can honour (a vtkPGIGISettings::Support). Resolve()
 * turns the requested settings into what a backend runs: every value it
 * cannot honour is replaced by the nearest one it can, and each
 * replacement is said in one line (the consumer warns once and puts the
 * line in its plan or status). Nothing is replaced silently.
 *
 * | knob | default | meaning |
 * |---|---|---|
 * | Shadows | on | off: unshadowed environment light |
 * | Order | 4 | SH order 2..8; cost ~n^2 per blocker, ~n^4..n^5 per receiver |
 * | ExpMethod | EXP_HYB | PS, PS*, OL, HYB (Documentation/AccuracyTime.md) |
 * | ExpDegree | 2 | series degree of PS and PS* |
 * | AccumulationOrder | 0 (= Order) | accumulate higher, truncate after the exp |
 * | WindowSize | 0 (off) | cosine window h on the visibility; -1 = 2n |
 * | SelfShadowRules | on | SHEXP 6.2 replacement rules, made continuous |
 * | SelfVisibility | on | traced own visibility (vtkPGISelfVisibility); CPU filter |
 * | MinBlockerAngle | 0.002 | radians; smaller blockers are skipped |
 * | HybridMaxNorm | 0 | HYB threshold; 0: sh::DefaultHybridMaxNorm(order) |
 * | RangeTolerance | 0.5 | sh::Exp's range guard; < 0 switches it off |
 * | ShadingPath | SHADING_TABLE | TABLE (L*H(N) tabulated) or PRODUCT_MATRIX (M_L) |
 * | HierarchyAngle | 0 (off) | degrees; hierarchy cuts per receiver cluster (SHEXP 6.3) |
 * | ReceiversPerCluster | 256 | cluster size for hierarchy cuts |
 * | Indirect | on | one-bounce light from the proxies and planes |
 * | IndirectMode | UNSHADOWED | UNSHADOWED (Sloan 2007) or SHADOWED (Guerrero 2008) |
 * | IndirectOperator | AVERAGED | POINT_SAMPLED, AVERAGED (D(theta)), EXACT (M(theta)) |
 * | SphericalLightBlocking | PER_SPHERE | SHADOWED: lights block per sphere or per object |
 * | IndirectOrder | 0 (= Order) | the shadowed bounce's SH order, at most Order; CPU filter |
 * | PlaneBounceShadows | on | planes reflect less where the proxies shadow them |
 * | PlaneBounceDirections | 64 | planes' light averaged per receiver (pgiPlaneLightMap.h) |
 * | PlaneBlocking | PLANES_IN_LIGHT | planes as steps in the light, or caps in log space |
 * | LocalLights | on | the lighting's spherical and point lights |
 * | LightCloud | on | point lights' indirect light from a light cloud (SetLocalLightTransfer) |
 * | BrightLights | on | the map's compact peaks (a sun) as distant lights; CPU filter |
 * | BrightLightFraction | 0.02 | a peak holding less of the map's power stays in the SH |
 * | BrightLightCount | 4 | at most this many peaks are taken out |
 * | BrightLightRays | 16 | directions per light and receiver over its disk (or occluder rays) |
 * | DefaultAlbedo | 0.8 0.8 0.8 | receivers' albedo without an AlbedoArrayName array |
 * | DefaultProxyAlbedo | 0.8 0.8 0.8 | proxies' albedo without an AlbedoArrayName array |
 * | AlbedoArrayName | "Albedo" | per-point albedo of receivers and proxies (0..1 or bytes) |
 */
#ifndef vtkPGIGISettings_h
#define vtkPGIGISettings_h

#include "ProxyGIShadingModule.h"
#include "vtkObject.h"

#include <string>
#include <vector>

class PROXYGISHADING_EXPORT vtkPGIGISettings : public vtkObject
{
public:
  static vtkPGIGISettings* New();
  vtkTypeMacro(vtkPGIGISettings, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ExpMethods
  {
    EXP_PS = 0,
    EXP_PS_STAR = 1,
    EXP_OL = 2,
    EXP_HYB = 3
  };
  enum ShadingPaths
  {
    SHADING_TABLE = 0,
    SHADING_PRODUCT_MATRIX = 1
  };
  enum IndirectModes
  {
    INDIRECT_MODE_UNSHADOWED = 0,
    INDIRECT_MODE_SHADOWED = 1
  };
  enum IndirectOperators
  {
    INDIRECT_POINT_SAMPLED = 0,
    INDIRECT_AVERAGED = 1,
    INDIRECT_EXACT = 2
  };
  enum SphericalLightBlockings
  {
    BLOCKING_PER_SPHERE = 0,
    BLOCKING_PER_OBJECT = 1
  };
  enum PlaneBlockings
  {
    PLANES_IN_LIGHT = 0,
    PLANES_IN_LOG_SPACE = 1
  };

  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  vtkSetClampMacro(Order, int, 2, 8);
  vtkGetMacro(Order, int);
  vtkSetClampMacro(ExpMethod, int, EXP_PS, EXP_HYB);
  vtkGetMacro(ExpMethod, int);
  vtkSetClampMacro(ExpDegree, int, 1, 16);
  vtkGetMacro(ExpDegree, int);
  vtkSetClampMacro(AccumulationOrder, int, 0, 8);
  vtkGetMacro(AccumulationOrder, int);
  vtkSetMacro(WindowSize, double);
  vtkGetMacro(WindowSize, double);
  vtkSetMacro(SelfShadowRules, bool);
  vtkGetMacro(SelfShadowRules, bool);
  vtkBooleanMacro(SelfShadowRules, bool);
  vtkSetMacro(SelfVisibility, bool);
  vtkGetMacro(SelfVisibility, bool);
  vtkBooleanMacro(SelfVisibility, bool);
  vtkSetClampMacro(MinBlockerAngle, double, 0.0, 0.5);
  vtkGetMacro(MinBlockerAngle, double);
  vtkSetClampMacro(HybridMaxNorm, double, 0.0, 10.0);
  vtkGetMacro(HybridMaxNorm, double);
  vtkSetMacro(RangeTolerance, double);
  vtkGetMacro(RangeTolerance, double);
  vtkSetClampMacro(ShadingPath, int, SHADING_TABLE, SHADING_PRODUCT_MATRIX);
  vtkGetMacro(ShadingPath, int);
  vtkSetClampMacro(HierarchyAngle, double, 0.0, 89.0);
  vtkGetMacro(HierarchyAngle, double);
  vtkSetClampMacro(ReceiversPerCluster, int, 1, 1 << 20);
  vtkGetMacro(ReceiversPerCluster, int);
  vtkSetMacro(Indirect, bool);
  vtkGetMacro(Indirect, bool);
  vtkBooleanMacro(Indirect, bool);
  vtkSetClampMacro(IndirectMode, int, INDIRECT_MODE_UNSHADOWED, INDIRECT_MODE_SHADOWED);
  vtkGetMacro(IndirectMode, int);
  void SetIndirectModeToUnshadowed() { this->SetIndirectMode(INDIRECT_MODE_UNSHADOWED); }
  void SetIndirectModeToShadowed() { this->SetIndirectMode(INDIRECT_MODE_SHADOWED); }
  vtkSetClampMacro(IndirectOperator, int, INDIRECT_POINT_SAMPLED, INDIRECT_EXACT);
  vtkGetMacro(IndirectOperator, int);
  vtkSetClampMacro(SphericalLightBlocking, int, BLOCKING_PER_SPHERE, BLOCKING_PER_OBJECT);
  vtkGetMacro(SphericalLightBlocking, int);
  /// The shadowed bounce's SH order: 0 (or >= Order) runs it at Order.
  /// The bounce is low-frequency, and its second pass (an exp per light
  /// and receiver) costs ~n^4: order 6 shadows with an order-4 bounce.
  vtkSetClampMacro(IndirectOrder, int, 0, 8);
  vtkGetMacro(IndirectOrder, int);
  /// What runs: IndirectOrder if set and below Order, else Order.
  int GetEffectiveIndirectOrder() const
  {
    return this->IndirectOrder > 0 && this->IndirectOrder < this->Order ? this->IndirectOrder
                                                                        : this->Order;
  }
  vtkSetMacro(PlaneBounceShadows, bool);
  vtkGetMacro(PlaneBounceShadows, bool);
  vtkBooleanMacro(PlaneBounceShadows, bool);
  /// With PlaneBounceShadows: how many directions each receiver averages
  /// the planes' shadowed light over (a grid of it per update,
  /// pgiPlaneLightMap.h); 0: the one plane point along n - m.
  vtkSetClampMacro(PlaneBounceDirections, int, 0, 1024);
  vtkGetMacro(PlaneBounceDirections, int);
  vtkSetClampMacro(PlaneBlocking, int, PLANES_IN_LIGHT, PLANES_IN_LOG_SPACE);
  vtkGetMacro(PlaneBlocking, int);
  vtkSetMacro(LocalLights, bool);
  vtkGetMacro(LocalLights, bool);
  vtkBooleanMacro(LocalLights, bool);
  /// The point lights' indirect light from a light cloud (a
  /// vtkPGILocalLightTransfer given to the consumer; none: skipped).
  vtkSetMacro(LightCloud, bool);
  vtkGetMacro(LightCloud, bool);
  vtkBooleanMacro(LightCloud, bool);
  /// Bright lights out of the map (pgiBrightLights.h): each gets its own
  /// sharp shadow (rays against the meshes through the filter's occluder,
  /// else the proxies' cones), the SH carries the rest.
  vtkSetMacro(BrightLights, bool);
  vtkGetMacro(BrightLights, bool);
  vtkBooleanMacro(BrightLights, bool);
  vtkSetClampMacro(BrightLightFraction, double, 0.0, 1.0);
  vtkGetMacro(BrightLightFraction, double);
  vtkSetClampMacro(BrightLightCount, int, 0, 16);
  vtkGetMacro(BrightLightCount, int);
  vtkSetClampMacro(BrightLightRays, int, 1, 256);
  vtkGetMacro(BrightLightRays, int);
  vtkSetVector3Macro(DefaultAlbedo, double);
  vtkGetVector3Macro(DefaultAlbedo, double);
  vtkSetVector3Macro(DefaultProxyAlbedo, double);
  vtkGetVector3Macro(DefaultProxyAlbedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);

  /**
   * A consumer's SetSettings: `slot` (owned by `owner`, never null) takes
   * `next`, or a fresh default set for null. True when it changed (the
   * caller then calls Modified()).
   */
  static bool Share(vtkObject* owner, vtkPGIGISettings*& slot, vtkPGIGISettings* next);

  /// Every knob from `other` (Modified only if something changed).
  void DeepCopy(vtkPGIGISettings* other);

  /// The names the knobs' values print as (e.g. "HYB", "shadowed").
  static const char* ExpMethodName(int method);
  static const char* IndirectModeName(int mode);
  static const char* IndirectOperatorName(int op);
  static const char* PlaneBlockingName(int blocking);
  static const char* SphericalLightBlockingName(int blocking);
  static const char* ShadingPathName(int path);

  /**
   * What a backend can honour. Bit sets are indexed by the enums above;
   * a knob a backend does not read at all is a false flag.
   */
  struct Support
  {
    const char* Backend = "";
    int MinOrder = 2, MaxOrder = 8;
    unsigned ExpMethods = 0xF;
    bool ExpDegree = true;
    bool AccumulationOrder = true;
    bool WindowSize = true;
    unsigned ShadingPaths = 0x3;
    bool Hierarchy = true; // HierarchyAngle, ReceiversPerCluster
    unsigned IndirectModes = 0x3;
    unsigned IndirectOperators = 0x7;
    bool SphericalLightBlocking = true;
    bool IndirectOrder = true; // false: the bounce runs at Order
    bool PlaneBounceShadows = true;
    bool PlaneBounceDirections = true; // and the planes' extent; false: one point
    unsigned PlaneBlockings = 0x3;
    bool LocalLights = true;
    bool LightCloud = true;     // a vtkPGILocalLightTransfer for the point lights
    bool BrightLights = true;   // BrightLights and its three knobs
    bool SelfVisibility = true; // receivers' SelfLogVisibility arrays
    bool ReceiverAlbedo = true; // DefaultAlbedo and AlbedoArrayName on receivers
    bool ExpGuards = true;      // HybridMaxNorm, RangeTolerance
  };

  /**
   * Copies these settings into `effective` with every value `support`
   * cannot honour replaced (the nearest supported value, or the default
   * for a knob it does not read), one line per replacement in `notes`
   * ("Order 8: the GPU mapper supports 2..6; using 6"). `planes`, `localLights`:
   * how many blocker planes and local lights the scene has (PlaneBlocking and
   * LocalLights only matter with some).
   * Knobs a backend does not read are noted only when set away from their
   * default. Returns whether nothing was replaced.
   */
  bool Resolve(const Support& support, int planes, vtkPGIGISettings* effective,
    std::vector<std::string>& notes, int localLights = 0) const;

protected:
  vtkPGIGISettings();
  ~vtkPGIGISettings() override;

  bool Shadows = true;
  int Order = 4;
  int ExpMethod = EXP_HYB;
  int ExpDegree = 2;
  int AccumulationOrder = 0;
  double WindowSize = 0.0;
  bool SelfShadowRules = true;
  bool SelfVisibility = true;
  double MinBlockerAngle = 0.002;
  double HybridMaxNorm = 0.0;
  double RangeTolerance = 0.5;
  int ShadingPath = SHADING_TABLE;
  double HierarchyAngle = 0.0;
  int ReceiversPerCluster = 256;
  bool Indirect = true;
  int IndirectMode = INDIRECT_MODE_UNSHADOWED;
  int IndirectOperator = INDIRECT_AVERAGED;
  int SphericalLightBlocking = BLOCKING_PER_SPHERE;
  int IndirectOrder = 0;
  bool PlaneBounceShadows = true;
  int PlaneBounceDirections = 64;
  int PlaneBlocking = PLANES_IN_LIGHT;
  bool LocalLights = true;
  bool LightCloud = true;
  bool BrightLights = true;
  double BrightLightFraction = 0.02;
  int BrightLightCount = 4;
  int BrightLightRays = 16;
  double DefaultAlbedo[3] = { 0.8, 0.8, 0.8 };
  double DefaultProxyAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;

private:
  vtkPGIGISettings(const vtkPGIGISettings&) = delete;
  void operator=(const vtkPGIGISettings&) = delete;
};

#endif
