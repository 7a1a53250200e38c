/**
 * @class   vtkPGIGIBake
 * @brief   The CPU precompute every GI consumer shares: proxies, blocker
 *          planes, lighting and settings in; blockers, the light in SH, the
 *          light above the planes, the planes' visibility, the secondary
 *          lights' response, the local lights and the spherical lights after
 *          their first pass out, with the plan of what the scene needs.
 *
 * vtkPGIGlobalIllumination, vtkPGIGIPolyDataMapper and
 * vtkPGIImageSpaceGIPass each own one and call Update() before shading;
 * it rebuilds only when an input changed (the proxies' or the lighting's
 * MTime, the settings' MTime, the planes), the way vtkShadowMapBakerPass
 * feeds vtkShadowMapPass, so a camera move or a new receiver mesh costs no
 * precompute. The settings it reads are the consumer's effective ones
 * (vtkPGIGISettings::Resolve).
 *
 * The stages of a build, in order: ReadBlockers (leaf proxies with albedo,
 * the hierarchy when HierarchyAngle asks, the planes), ProjectLight (the
 * environment in SH, LightAbovePlanes when the planes ride in the light;
 * reused from the last build when only the proxies or the kernel's knobs
 * changed, see GetNumberOfLightProjections),
 * PlanEffects (what the scene needs, one plan line per decision),
 * PrepareLocalLights, PrepareSphericalLights (the shadowed bounce's first
 * pass).
 *
 * Bright lights (settings BrightLights): ProjectLight takes the map's
 * compact peaks out (pgiBrightLights.h). The direct light's SH (Light,
 * Shading, OpenShading) is then the residual's; the bounce keeps the whole
 * map (IndirectShading, Secondary, the spherical lights' first pass), where
 * a blurred sun costs little; the consumer shades the
 * lights themselves with their own shadows (pgiBrightLightShadows.h).
 */
#ifndef vtkPGIGIBake_h
#define vtkPGIGIBake_h

#include "ProxyGIShadingModule.h"
#include "vtkObject.h"
#include "vtkPGIGISettings.h"
#include "vtkSmartPointer.h"

#include "pgiBrightLights.h"
#include "pgiEnvironmentShading.h"
#include "pgiIndirectLight.h"
#include "pgiSoftShadows.h"
#include "pgiSphericalLights.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkPGILighting;
class vtkPolyData;
class vtkPolyDataNormals;

namespace proxygi
{
class EnvironmentMap;
/// What a bake computed (read-only for the consumers).
struct PROXYGISHADING_EXPORT BakedScene
{
  int Order = 0;
  /// Leaf proxies (centre, radius, albedo) and planes (origin, unit normal, albedo).
  Blockers SceneBlockers;
  /// The proxies' point ids of Scene's spheres.
  std::vector<vtkIdType> LeafIds;
  bool UseHierarchy = false;
  ProxyHierarchy Hierarchy;
  /// L, 3 x n^2 channel-major (R, G, B rows).
  std::vector<double> Light;
  /// The whole map L came from (the lighting's; valid until it changes,
  /// which rebuilds), for what the SH cannot carry: the sky just below a
  /// bounded plane's horizon (PlaneLightMap::SetSky).
  const EnvironmentMap* Environment = nullptr;
  /// Planes carried by the light: L times the planes' steps and the planes'
  /// visibility (n^2); otherwise LightAbovePlanes is L and the visibility 0.
  bool PlanesInLight = false;
  std::vector<double> LightAbovePlanes;
  std::vector<double> PlaneVisibility;
  /// Shading of L (receivers without shadows or under a plane) and of the
  /// light above the planes.
  std::shared_ptr<const EnvironmentShading> OpenShading, Shading;
  /// The bright lights taken out of the map (L is the residual), the share
  /// of the map's power in its brightest compact peak and in those taken.
  std::vector<DistantLight> BrightLights;
  double BrightestFraction = 0.0, BrightFraction = 0.0;
  std::shared_ptr<const SecondaryLights> Secondary;
  /// The response interleaved (RGB per coefficient), as the GLSL reads it.
  std::vector<float> InterleavedResponse;
  /// The kernel settings of this scene (PlanesInLogSpace = !PlanesInLight).
  SoftShadowSettings Kernel;
  /// The shadowed bounce's order (settings IndirectOrder; Order when not
  /// below it), its kernel (Kernel at that order) and its light: the whole
  /// map's light above the planes, bright lights included, truncated to
  /// that order (Shading itself when the orders agree and no light was
  /// taken out). The spherical lights' Radiance has this order.
  int IndirectOrder = 0;
  SoftShadowSettings IndirectKernel;
  std::shared_ptr<const EnvironmentShading> IndirectShading;
  LocalEmitters Locals;
  /// Shadowed bounce: every light (with a hierarchy: every node, with Level)
  /// after its first pass; LeafLights the leaves alone (hierarchy only).
  SphericalLights Lights, LeafLights;
  std::map<std::size_t, int> LeafOfNode;
  std::string SphericalLightsSummary;

  // What the scene needs.
  bool AnyBlockers = false, AnyAlbedo = false, PlanesReflect = false, Dark = false;
  bool RunShadows = false, RunIndirect = false, RunPlaneBounce = false, RunShadowed = false,
       RunLocal = false, RunBrightLights = false, NeedVisibility = false;
  /// One line per decision.
  std::vector<std::string> Plan;

  /// The leaf lights the receivers use without a hierarchy cut.
  const SphericalLights& ShadowedLeaves() const
  {
    return this->UseHierarchy ? this->LeafLights : this->Lights;
  }
};

/// Point normals of receivers (computed unsplit when missing, as every
/// consumer does); null when they cannot be computed.
PROXYGISHADING_EXPORT vtkSmartPointer<vtkDataArray> ReceiverNormals(vtkPolyData* receivers);

/// Updates a normals filter on one thread: VTK's threaded cell links sum a
/// point's polygons in an order that varies from run to run, and the
/// normals (so every result) with it in the last bits.
PROXYGISHADING_EXPORT void UpdateNormals(vtkPolyDataNormals* filter);
} // namespace proxygi

class PROXYGISHADING_EXPORT vtkPGIGIBake : public vtkObject
{
public:
  static vtkPGIGIBake* New();
  vtkTypeMacro(vtkPGIGIBake, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sphere proxies: points with "Radius" (Level/Parent for a hierarchy).
  virtual void SetProxies(vtkPolyData* proxies);
  vtkGetObjectMacro(Proxies, vtkPolyData);
  /// The light (null: a uniform white sky).
  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);
  /// The effective settings (never null; shared, not copied).
  virtual void SetSettings(vtkPGIGISettings* settings);
  vtkGetObjectMacro(Settings, vtkPGIGISettings);

  /// Infinite planes blocking the half-space beneath them; albedo for the
  /// bounce. With half edges e1, e2 (in the plane) the plane reflects from
  /// origin + a e1 + b e2, |a|, |b| <= 1, only (Blockers::PlaneExtent).
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3],
    const double* halfEdges = nullptr);
  void RemoveAllBlockerPlanes();
  int GetNumberOfBlockerPlanes() const { return static_cast<int>(this->Planes.size() / 9); }
  /// origin, normal, albedo: 9 values per plane, as given.
  const std::vector<double>& GetBlockerPlanes() const { return this->Planes; }

  vtkMTimeType GetMTime() override;

  /**
   * Rebuilds if an input changed since the last build. False on bad input
   * (GetError says why): a bad environment leaves no scene; bad proxies
   * leave a scene without them (GetProxyError), which the filter refuses
   * and the GPU consumers draw without proxies.
   */
  bool Update();
  /**
   * A GPU consumer's step before drawing: resolves `requested` for
   * `support` (with this bake's planes and local lights) into its settings, warns through
   * `owner` when the notes differ from `said` (then updates it), updates
   * the bake, and reports a bad environment or bad proxies through
   * `owner`'s error once per rebuild. False without a usable scene (bad
   * environment); bad proxies leave a scene without them.
   */
  bool UpdateFor(vtkObject* owner, vtkPGIGISettings* requested,
    const vtkPGIGISettings::Support& support, std::vector<std::string>& said);

  const proxygi::BakedScene& GetScene() const { return this->Scene; }
  /// A sentence: "Bad environment: ..." (or the proxies' error).
  const std::string& GetError() const { return this->Error; }
  const std::string& GetProxyError() const { return this->ProxyError; }
  /// How many times Update() rebuilt (the rest reused).
  vtkGetMacro(NumberOfBuilds, int);
  /// When the last build finished (consumers compare it to re-upload).
  vtkMTimeType GetBuildTime() const { return this->BuildTime.GetMTime(); }
  /// How many builds projected the environment (the others reused it).
  vtkGetMacro(NumberOfLightProjections, int);

protected:
  vtkPGIGIBake();
  ~vtkPGIGIBake() override;

  bool ReadBlockers();
  bool ProjectLight(vtkPGILighting* lighting, proxygi::BakedScene& previous);
  void ProjectEnvironment(const proxygi::EnvironmentMap& environment);
  void SetKernel();
  void PlanEffects(vtkPGILighting* lighting);
  void PrepareLocalLights(vtkPGILighting* lighting);
  bool PrepareSphericalLights();

  vtkPolyData* Proxies = nullptr;
  vtkPGILighting* Lighting = nullptr;
  vtkPGIGISettings* Settings = nullptr;
  std::vector<double> Planes;
  std::vector<double> PlaneExtents; // 6 per plane, 0: unbounded
  proxygi::BakedScene Scene;
  std::string Error, ProxyError;
  int NumberOfBuilds = 0;
  vtkTimeStamp BuildTime;
  vtkPolyData* BuiltProxies = nullptr;
  vtkPGILighting* BuiltLighting = nullptr;
  bool BuiltOk = false;
  // What the last projection of the light depended on: the environment, its
  // time, the order, the shading path and the planes.
  struct LightKey
  {
    const void* Environment = nullptr;
    vtkMTimeType Time = 0;
    int Order = 0, IndirectOrder = 0, Path = -1, PlaneBlocking = -1;
    std::vector<double> Planes;
    std::vector<double> Bright; // on, fraction, count
    bool operator==(const LightKey& o) const
    {
      return this->Environment == o.Environment && this->Time == o.Time && this->Order == o.Order &&
        this->IndirectOrder == o.IndirectOrder && this->Path == o.Path &&
        this->PlaneBlocking == o.PlaneBlocking && this->Planes == o.Planes &&
        this->Bright == o.Bright;
    }
  };
  LightKey LastLight;
  vtkSmartPointer<vtkPGILighting> DefaultLighting;
  int NumberOfLightProjections = 0;

private:
  vtkPGIGIBake(const vtkPGIGIBake&) = delete;
  void operator=(const vtkPGIGIBake&) = delete;
};

#endif
