/**
 * @class   vtkPGIGlobalIllumination
 * @brief   Per-vertex global illumination on the CPU from sphere proxies and
 *          SH lighting: the reference implementation the GPU paths match.
 *
 * Input 0: the receivers (vtkPolyData; point normals used if present, else
 * computed). Input 1 (optional): the proxies, points with a "Radius" array
 * (vtkPGISphereSetApproximation's output or any such polydata). Light: a
 * vtkPGILighting (its environment is projected to SH once per change).
 * Infinite blocker planes (a ground) can be added with AddBlockerPlane,
 * bounded to a parallelogram for what they reflect (a finite ground). Their
 * bounce averages their shadowed light, tabulated once per update, over
 * each receiver's view of them (settings PlaneBounceDirections,
 * pgiPlaneLightMap.h); past a bounded plane's edges the receivers see the
 * environment below its horizon (in DirectShadowed).
 *
 * Output: the receivers with point arrays (3 floats each unless said):
 *  - DirectShadowed: environment light through SH soft shadows (exit radiance),
 *    the sky past a bounded plane's edges included;
 *  - IndirectProxy: one bounce from the proxies and blocker planes as
 *    secondary lights (unshadowed, Sloan 2007);
 *  - IndirectShadowed: one bounce from the proxies as spherical lights,
 *    shadowed on both legs (Guerrero 2008);
 *  - IndirectSelf: the bounce of an object onto itself, gathered from its
 *    traced mesh (receivers with a self-visibility, below; else 0);
 *  - LocalLights: spherical and point lights of the vtkPGILighting, shadowed
 *    by the same visibility;
 *  - IndirectLocal: the point lights' indirect light from a light cloud
 *    (SetLocalLightTransfer, e.g. vtkPGILightCloudTransfer; settings
 *    LightCloud), 0 without one;
 *  - Radiance: the sum of the effects that ran;
 *  - Visibility (n^2): the SH visibility vector (relight without recomputing);
 *  - RadianceSRGB (3 bytes): ColorExposure x Radiance encoded sRGB, the
 *    picture the GPU paths draw (in ParaView: colour by it with Map Scalars
 *    off);
 * and a
 * field-data string array "Plan": which effects ran and why.
 *
 * The knobs are a vtkPGIGISettings (GetSettings; SetSettings shares one
 * with the GPU mapper or the image-space pass). This filter honours every
 * one of them: it is the reference the GPU paths are measured against.
 * The precompute (blockers, light, responses, local and spherical lights)
 * is a vtkPGIGIBake, reused while the proxies, lighting, planes and
 * settings are unchanged (GetBake()->GetNumberOfBuilds()).
 *
 * Rigid objects' own shadows, traced once: receivers that carry
 * vtkPGISelfVisibility's arrays (SelfLogVisibility at the accumulation
 * order, SelfVisibilityRest, ObjectId, the SelfBounce field arrays) take
 * their own object's visibility from them, added in log space to the other
 * objects' proxies, and their own object's bounce from the traced hits
 * (IndirectSelf); the proxies whose ObjectId is theirs neither shadow them
 * nor light them (they still dim the planes' light by their overlap). Where
 * the points are no longer where they were traced (moved or deformed), the
 * order differs, an array is missing or SelfVisibility is off, the
 * self-shadow rules run, and the plan says why. The rules stand for a
 * receiver's own surface cutting its own proxies: receivers with their own
 * visibility traced, and receivers whose "ObjectId" point array (without
 * the traced arrays) names no proxy's object, such as a ground plane, see
 * every sphere whole, so that where an object stands on them its contact
 * shadow stays dark.
 *
 * Bright lights (settings BrightLights, on by default): where the
 * environment has compact peaks holding enough of its power (a sun, lamps:
 * pgiBrightLights.h), they are taken out of the map and shaded as distant
 * disk lights with their own sharp shadows and penumbrae, added to
 * DirectShadowed; the SH carries the rest. The shadows come from rays
 * against the real meshes when an occluder is set (SetOccluder, e.g. a
 * vtkPGIMeshOccluder holding the scene's meshes; one ray per direction,
 * BrightLightRays directions per light and receiver), else from the proxies analytically (the
 * light's cone against each sphere's cap). The bounce keeps the whole map.
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
 * Distributed (Controller, default the global controller, with more than
 * one process): each rank shades its own piece of the receivers against the
 * global proxies. Proxies that are not yet global (vtkPGISphereSetApproximation
 * gathers its own) are all-gathered in rank order, so every rank bakes the
 * same scene and a point shared by two pieces gets the same result on both
 * (given the same normal: give point normals computed before the split, or
 * a ghost layer; the Plan says when normals were computed per piece). A rank
 * with an empty piece takes part and outputs an empty polydata with the
 * arrays. An error on one rank (bad input) is an error on every rank, with
 * that rank's reason: no rank waits forever. Per receiver the shading needs
 * no communication. Hierarchy cuts are per receiver cluster; under MPI the
 * clusters are cells of a grid over all ranks' receivers (split by normal
 * axis) instead of Lloyd clusters of the piece, so that a point on a
 * partition boundary gets the same cut, hence the same result, on both ranks.
 *
 * Errors: no receivers, NaN/Inf in receiver points or proxies, proxies
 * without a Radius array, a bad environment. A zero, NaN or Inf normal (as
 * vtkPolyDataNormals gives degenerate triangles) is not an error: that
 * receiver is shaded as if it faced +z.
 */
#ifndef vtkPGIGlobalIllumination_h
#define vtkPGIGlobalIllumination_h

#include "ProxyGIShadingModule.h"
#include "vtkNew.h"
#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkFloatArray;
class vtkUnsignedCharArray;
class vtkMultiProcessController;
class vtkPGILighting;
class vtkPGILocalLightTransfer;
class vtkPGIOccluder;
namespace proxygi
{
namespace budget
{
class Planner;
}
}

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

  /// The GI knobs (never null); SetSettings(nullptr) restores a private default set.
  vtkPGIGISettings* GetSettings() { return this->Settings; }
  virtual void SetSettings(vtkPGIGISettings* settings);
  /// What this filter honours (everything).
  static const vtkPGIGISettings::Support& GetSupport();
  /// The precompute this filter reuses between executions.
  vtkPGIGIBake* GetBake() { return this->Bake; }

  /// Infinite planes that block the half-space beneath them (a ground); with
  /// an albedo they also reflect light (indirect).
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);
  /**
   * A plane of finite extent, the parallelogram origin + a e1 + b e2 with
   * |a|, |b| <= 1 (e1, e2 its half edges, in the plane): it still blocks as
   * the infinite plane, but with PlaneBounceDirections > 0 it reflects from
   * that area only and past its edges the receivers see the environment
   * below its horizon, as they would over a finite ground.
   */
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3],
    const double halfEdge1[3], const double halfEdge2[3]);
  /// The same with plain numbers: origin, normal, albedo (ParaView).
  void AddBlockerPlane(double ox, double oy, double oz, double nx, double ny, double nz, double ar,
    double ag, double ab);
  void RemoveAllBlockerPlanes();

  /// Real geometry for the bright lights' shadow rays (null: the proxies'
  /// cones shadow them).
  virtual void SetOccluder(vtkPGIOccluder* occluder);
  vtkGetObjectMacro(Occluder, vtkPGIOccluder);

  /// The point lights' indirect light through precomputed transfer (a light
  /// cloud: vtkPGILightCloudTransfer), run while the settings' LightCloud is
  /// on and the lighting has point lights; null: none.
  virtual void SetLocalLightTransfer(vtkPGILocalLightTransfer* transfer);
  vtkGetObjectMacro(LocalLightTransfer, vtkPGILocalLightTransfer);

  /// Scale of the radiance in the RadianceSRGB colours (default 1).
  vtkSetClampMacro(ColorExposure, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ColorExposure, double);

  /**
   * Accuracy budget: with ErrorBudget > 0 (relative RMSE against the truth,
   * 0.05 for 5%) each update runs the fastest order, bounce order, bounce
   * model and hierarchy angle the budget model predicts to stay within it;
   * with TimeBudget > 0 (seconds per update) the most accurate predicted to
   * fit in it; with both, the fastest meeting both. The proxies and the
   * receivers' self-visibility are inputs, so only the candidates of their
   * sphere count and self-visibility are considered. The Plan says what was
   * chosen, the prediction and what was traded away; a budget that cannot
   * be met runs the closest candidate and says so. 0: no budget (default);
   * negative: a warning and the closest candidate.
   */
  vtkSetMacro(ErrorBudget, double);
  vtkGetMacro(ErrorBudget, double);
  vtkSetMacro(TimeBudget, double);
  vtkGetMacro(TimeBudget, double);
  /// The model from `proxygi calibrate` (null or empty: the one that ships).
  vtkSetStringMacro(BudgetModelFileName);
  vtkGetStringMacro(BudgetModelFileName);

  /// The ranks the receivers are spread over (null: this process alone).
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// Seconds and bytes received in the last execution's collectives (0 serially).
  vtkGetMacro(CommunicationTime, double);
  vtkGetMacro(CommunicationBytes, double);

  /// The plan of the last execution, one line per decision.
  const std::vector<std::string>& GetPlan() const { return this->Plan; }

  vtkMTimeType GetMTime() override;

protected:
  vtkPGIGlobalIllumination();
  ~vtkPGIGlobalIllumination() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The stages of RequestData.
  // An empty string when fine, else the reason.
  std::string CheckReceivers(vtkPolyData* receivers);
  std::string PrepareBake(vtkPolyData* proxies, vtkPolyData* receivers);
  // The budget's knobs on Effective (after Resolve), with their plan lines.
  std::string ApplyBudget(vtkPolyData* proxies, vtkPolyData* receivers);
  bool ClusterReceivers(vtkPolyData* receivers, vtkDataArray* normals);
  void ShadeReceivers(vtkPolyData* receivers, vtkDataArray* normals, vtkPolyData* output);

  vtkPGILighting* Lighting = nullptr;
  vtkPGIOccluder* Occluder = nullptr;
  vtkPGILocalLightTransfer* LocalLightTransfer = nullptr;
  vtkPGIGISettings* Settings = nullptr;
  vtkNew<vtkPGIGISettings> Effective;
  vtkNew<vtkPGIGIBake> Bake;
  struct Clusters;
  std::unique_ptr<Clusters> ReceiverClusters;
  struct ShadeBuffers;
  std::unique_ptr<ShadeBuffers> Scratch;
  std::vector<std::string> Plan;
  double ColorExposure = 1.0;
  double ErrorBudget = 0.0, TimeBudget = 0.0;
  char* BudgetModelFileName = nullptr;
  std::unique_ptr<proxygi::budget::Planner> Budget;
  std::string BudgetPlan;
  vtkMultiProcessController* Controller = nullptr;
  double CommunicationTime = 0.0, CommunicationBytes = 0.0;
  // Per-stage milliseconds of the last update (normals, precompute, clusters,
  // shading, and within shading the visibility and the spherical lights
  // summed over threads), and the precompute's build count then.
  double StageMs[6] = {};
  // The output arrays, reused by the next update when nobody else holds them.
  vtkSmartPointer<vtkFloatArray> OutputArrays[8];
  // The light cloud's part of the output (ShadeReceivers).
  void AddTransferredLight(vtkPolyData* receivers, vtkFloatArray* cloud, vtkFloatArray* total);
  vtkSmartPointer<vtkUnsignedCharArray> ColorArray;
  int BuildsSeen = -1;

private:
  vtkPGIGlobalIllumination(const vtkPGIGlobalIllumination&) = delete;
  void operator=(const vtkPGIGlobalIllumination&) = delete;
};

#endif
