/**
 * @class   vtkPGIGlobalIllumination
 * @brief   Per-vertex global illumination on the CPU from sphere proxies and
 *          SH lighting: the reference implementation the GPU paths match.
 *
 * Input 0: the receivers (vtkPolyData; point normals used if present, else
 * computed). Input 1 (optional): the proxies, points with a "Radius" array
 * (vtkPGISphereSetApproximation's output or any such polydata). Light: a
 * vtkPGILighting (its environment is projected to SH once per change).
 * Infinite blocker planes (a ground) can be added with AddBlockerPlane.
 *
 * Output: the receivers with point arrays
 * | array | components | what |
 * |---|---|---|
 * | DirectShadowed | 3 | environment light through SH soft shadows (exit radiance) |
 * | IndirectProxy | 3 | one bounce from the proxies and blocker planes as secondary lights
 * (unshadowed, Sloan 2007) | | IndirectShadowed | 3 | one bounce from the proxies as spherical
 * lights, shadowed on both legs (Guerrero 2008) | | LocalLights | 3 | spherical and point lights of the vtkPGILighting,
 * shadowed by the same visibility | | Radiance | 3 | the sum of the effects that ran | | Visibility
 * | n^2 | the SH visibility vector (relight without recomputing) | and a field-data string array
 * "Plan": which effects ran and why.
 *
 * | property | default | trade |
 * |---|---|---|
 * | Order | 4 | 3-6; cost ~n^2 per blocker, ~n^4-n^5 per receiver for exp |
 * | ExpMethod | HYB | OL faster, PS* more accurate (Documentation/AccuracyTime.md) |
 * | AccumulationOrder | 0 (= Order) | accumulate higher, truncate after exp |
 * | WindowSize | 0 (off) | cosine window h on the visibility; -1 = 2n |
 * | SelfShadowRules | on | SHEXP 6.2 replacement rules, made continuous |
 * | ShadingPath | Table | Table (fixed light) or ProductMatrix (light changing per frame) |
 * | Shadows | on | off: unshadowed environment light |
 * | Indirect | on | one-bounce light from the proxies (albedo from their "Albedo" array, else
 * DefaultAlbedo) and planes | | IndirectOperator | AVERAGED | POINT_SAMPLED (cheapest), AVERAGED
 * (D(theta)), EXACT (M(theta), rotations) | | IndirectMode | UNSHADOWED | which one-bounce
 * model fills Radiance: UNSHADOWED (IndirectProxy), SHADOWED (IndirectShadowed: spherical lights
 * lit at surface samples, from the proxies' SampleOffset/SampleNormal/AlbedoSH arrays written by
 * vtkPGISphereLightSampler, else samples on the spheres themselves; about one exp per light per
 * receiver) or OFF; the other array is all zeros | | SphericalLightBlocking | PER_SPHERE |
 * PER_SPHERE: lights block each other in distance order; PER_OBJECT: in object-distance order
 * (objects from the proxies' ObjectId) | | LocalLights | on | spherical lights (analytic L_H
 * table, fitted lobes) and point lights (as tiny spheres) | | HierarchyAngle | 0 (off) | degrees;
 * with a proxy hierarchy (Level/Parent arrays), receivers are clustered and each cluster uses the
 * hierarchy cut whose nodes subtend less than this, with ratio vectors (SHEXP 6.3); 20-30 is the
 * paper's range | | ReceiversPerCluster | 256 | cluster size for hierarchy cuts |
 *
 * Simulate only what the scene needs: shadows run only when there are
 * blockers; per receiver, the exp runs only when a blocker subtends more than
 * MinBlockerAngle after the self-shadow rules (receivers with none get g = 1
 * at no cost). The Plan array says what ran, what was skipped, and why.
 * Indirect light runs only when some proxy or plane has a nonzero albedo and
 * the environment is not black; local lights only when the lighting has some.
 *
 * IndirectMode SHADOWED (Guerrero et al. 2008, pgiSphericalLights.h): the
 * leaf proxies become spherical lights, lit at their surface samples (first
 * pass, once per update: SHEXP visibility, environment and local lights as
 * uniform spherical lights, Voronoi projection, times the albedo SH) and
 * gathered per receiver (second pass: w_theta average radiance times each
 * light's visibility by the difference of two exps, nearer lights blocking;
 * intersecting lights of one object do not block each other, rule 2 of the
 * sampling has their occlusion). With HierarchyAngle and a hierarchy, each
 * cluster's cut of lights carries reflection ratios. It runs when some light
 * has a nonzero albedo and there is light to bounce.
 *
 * Errors: no receivers, NaN/Inf in receivers or proxies, proxies without a
 * Radius array, a bad environment.
 */
#ifndef vtkPGIGlobalIllumination_h
#define vtkPGIGlobalIllumination_h

#include "ProxyGIShadingModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>
#include <vector>

class vtkPGILighting;

class PROXYGISHADING_EXPORT vtkPGIGlobalIllumination : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIGlobalIllumination* New();
  vtkTypeMacro(vtkPGIGlobalIllumination, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);

  void SetProxiesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetProxiesData(vtkDataObject* data) { this->SetInputData(1, data); }

  vtkSetClampMacro(Order, int, 2, 8);
  vtkGetMacro(Order, int);
  enum
  {
    EXP_PS = 0,
    EXP_PS_STAR = 1,
    EXP_OL = 2,
    EXP_HYB = 3
  };
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
  vtkSetClampMacro(MinBlockerAngle, double, 0.0, 0.5);
  vtkGetMacro(MinBlockerAngle, double);
  enum
  {
    SHADING_TABLE = 0,
    SHADING_PRODUCT_MATRIX = 1
  };
  vtkSetClampMacro(ShadingPath, int, SHADING_TABLE, SHADING_PRODUCT_MATRIX);
  vtkGetMacro(ShadingPath, int);
  vtkSetClampMacro(HierarchyAngle, double, 0.0, 89.0);
  vtkGetMacro(HierarchyAngle, double);
  vtkSetClampMacro(ReceiversPerCluster, int, 1, 1 << 20);
  vtkGetMacro(ReceiversPerCluster, int);
  vtkSetMacro(Indirect, bool);
  vtkGetMacro(Indirect, bool);
  vtkBooleanMacro(Indirect, bool);
  enum
  {
    INDIRECT_POINT_SAMPLED = 0,
    INDIRECT_AVERAGED = 1,
    INDIRECT_EXACT = 2
  };
  vtkSetClampMacro(IndirectOperator, int, INDIRECT_POINT_SAMPLED, INDIRECT_EXACT);
  vtkGetMacro(IndirectOperator, int);
  /// Which one-bounce model runs; Indirect off means none whatever this says.
  enum
  {
    INDIRECT_MODE_UNSHADOWED = 0,
    INDIRECT_MODE_SHADOWED = 1,
    INDIRECT_MODE_OFF = 2
  };
  vtkSetClampMacro(IndirectMode, int, INDIRECT_MODE_UNSHADOWED, INDIRECT_MODE_OFF);
  vtkGetMacro(IndirectMode, int);
  void SetIndirectModeToUnshadowed() { this->SetIndirectMode(INDIRECT_MODE_UNSHADOWED); }
  void SetIndirectModeToShadowed() { this->SetIndirectMode(INDIRECT_MODE_SHADOWED); }
  void SetIndirectModeToOff() { this->SetIndirectMode(INDIRECT_MODE_OFF); }
  enum
  {
    BLOCKING_PER_SPHERE = 0,
    BLOCKING_PER_OBJECT = 1
  };
  vtkSetClampMacro(SphericalLightBlocking, int, BLOCKING_PER_SPHERE, BLOCKING_PER_OBJECT);
  vtkGetMacro(SphericalLightBlocking, int);
  vtkSetMacro(LocalLights, bool);
  vtkGetMacro(LocalLights, bool);
  vtkBooleanMacro(LocalLights, bool);
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  /// How blocker planes shadow: PLANES_IN_LIGHT (default) multiplies the
  /// light of receivers above every plane by the planes' step functions
  /// (exact, free per receiver); PLANES_IN_LOG_SPACE accumulates each plane
  /// as a 90-degree cap log like a sphere (what the GPU mapper does; its exp
  /// darkens the open hemisphere by ~10% at order 4).
  enum
  {
    PLANES_IN_LIGHT = 0,
    PLANES_IN_LOG_SPACE = 1
  };
  vtkSetClampMacro(PlaneBlocking, int, PLANES_IN_LIGHT, PLANES_IN_LOG_SPACE);
  vtkGetMacro(PlaneBlocking, int);
  /// Planes reflect less where the proxies shadow them (on by default): the
  /// plane light a receiver gets is scaled by the shadowing at the plane
  /// point it mostly sees (pgiIndirectLight.h PlaneShadowScale); one more
  /// visibility per receiver that sees a reflecting plane.
  vtkSetMacro(PlaneBounceShadows, bool);
  vtkGetMacro(PlaneBounceShadows, bool);
  vtkBooleanMacro(PlaneBounceShadows, bool);
  vtkSetVector3Macro(DefaultAlbedo, double);
  vtkGetVector3Macro(DefaultAlbedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);

  /// Infinite planes that block the half-space beneath them (a ground); with
  /// an albedo they also reflect light (indirect).
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);
  void RemoveAllBlockerPlanes();

  /// The plan of the last execution, one line per decision.
  const std::vector<std::string>& GetPlan() const { return this->Plan; }

  vtkMTimeType GetMTime() override;

protected:
  vtkPGIGlobalIllumination();
  ~vtkPGIGlobalIllumination() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkPGILighting* Lighting = nullptr;
  int Order = 4;
  int ExpMethod = EXP_HYB;
  int ExpDegree = 2;
  int AccumulationOrder = 0;
  double WindowSize = 0.0;
  bool SelfShadowRules = true;
  double MinBlockerAngle = 0.002;
  int ShadingPath = SHADING_TABLE;
  bool Shadows = true;
  bool Indirect = true;
  int IndirectOperator = INDIRECT_AVERAGED;
  int IndirectMode = INDIRECT_MODE_UNSHADOWED;
  int SphericalLightBlocking = BLOCKING_PER_SPHERE;
  bool LocalLights = true;
  double HierarchyAngle = 0.0;
  int ReceiversPerCluster = 256;
  int PlaneBlocking = PLANES_IN_LIGHT;
  bool PlaneBounceShadows = true;
  double DefaultAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;
  std::vector<double> BlockerPlanes; // origin, normal, albedo
  std::vector<std::string> Plan;

private:
  vtkPGIGlobalIllumination(const vtkPGIGlobalIllumination&) = delete;
  void operator=(const vtkPGIGlobalIllumination&) = delete;
};

#endif
