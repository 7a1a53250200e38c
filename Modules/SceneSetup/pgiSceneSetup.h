/**
 * @file pgiSceneSetup.h
 * @brief What every program that renders a scene does the same way: sphere
 * proxies for the scene's meshes (built once, cached on disk), the GI filter
 * configured from the scene, the Embree reference of the same receivers
 * (cached), and the error metric of the accuracy/time report.
 */
#ifndef pgiSceneSetup_h
#define pgiSceneSetup_h

#include "ProxyGISceneSetupModule.h"

#include "pgiScene.h"
#include "vtkSmartPointer.h"

#include <array>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkPGIGISettings;
class vtkPGIGlobalIllumination;
class vtkPGIOccluder;
class vtkPolyData;

namespace proxygi
{

/**
 * Watches the long filters of a scene's set-up (proxy building, the
 * reference's tracing): Begin before a filter updates, End after it. End
 * returning false (the user stopped it) makes the set-up fail with
 * "interrupted" and cache nothing of that filter.
 */
class PROXYGISCENESETUP_EXPORT SetupMonitor
{
public:
  virtual ~SetupMonitor();
  virtual void Begin(vtkAlgorithm* filter, const std::string& what) = 0;
  virtual bool End(vtkAlgorithm* filter) = 0;
};

/// What a mesh's sphere radii are fitted for.
enum class ProxyFit
{
  Bounding,  ///< every point of the mesh inside a sphere (vtkPGISphereSetApproximation)
  Occlusion, ///< then scaled to block what the mesh blocks (vtkPGIOcclusionFit)
};

struct SceneProxies
{
  /// Leaves of every mesh (vtkPGISphereSetApproximation) and every scene
  /// sphere (exact), then the hierarchy above them (vtkPGISphereHierarchy):
  /// "Radius", "Albedo", "ObjectId" (scene object index), "Level", "Parent".
  vtkSmartPointer<vtkPolyData> Spheres;
  /// Scene planes as blocker planes: origin (their centre), normal, albedo,
  /// then their two half edges (AddBlockerPlane's extent).
  std::vector<std::array<double, 15>> Planes;
  vtkIdType Leaves = 0;
  ProxyFit Fit = ProxyFit::Bounding;
  /// With ProxyFit::Occlusion, per mesh: vtkPGIOcclusionFit's held-out
  /// occlusion error and bias, before and after the fit.
  struct OcclusionFit
  {
    std::string Object;
    double ErrorBefore = 0.0, ErrorAfter = 0.0, BiasBefore = 0.0, BiasAfter = 0.0;
  };
  std::vector<OcclusionFit> Fits;
  double Seconds = 0.0; // building (or reading) them
  bool Cached = false;  // every mesh's set came from the cache
};

/// Proxies of a loaded scene, `spheresPerMesh` per mesh, their radii fitted
/// for `fit`; the sets are cached in `cacheDir` (created if missing; "" = no
/// cache). False with a message.
PROXYGISCENESETUP_EXPORT bool BuildSceneProxies(const SceneDescription& scene,
  const LoadedScene& loaded, int spheresPerMesh, const std::string& cacheDir, SceneProxies& proxies,
  std::string& error, SetupMonitor* monitor = nullptr, ProxyFit fit = ProxyFit::Bounding);

/// Everything a scene's cached results depend on (objects, their placement
/// and albedo, the environment with its rotation and scale, the lights), as
/// one string for cache keys.
PROXYGISCENESETUP_EXPORT std::string DescribeScene(const SceneDescription& scene);

/// The receivers of a scene: every object with point normals (unsplit) and
/// an "ObjectId" point array (its index, as the proxies' ObjectId names it).
PROXYGISCENESETUP_EXPORT std::vector<vtkSmartPointer<vtkPolyData>> SceneReceivers(
  const LoadedScene& loaded);

/**
 * Each mesh receiver's own visibility (vtkPGISelfVisibility: `samples` rays
 * per vertex, SH of `order`), added to `receivers` as point arrays, with
 * "ObjectId" the object's index so that the GI filter leaves its own proxies
 * out. Planes and exact spheres get none (nothing of them shadows them).
 * Cached in `cacheDir` by object, vertex count, order and samples; `seconds`
 * is the tracing time of this call (0 when all came from the cache).
 */
PROXYGISCENESETUP_EXPORT bool AddSelfVisibility(const SceneDescription& scene,
  std::vector<vtkSmartPointer<vtkPolyData>>& receivers, int order, int samples,
  const std::string& cacheDir, double& seconds, std::string& error,
  SetupMonitor* monitor = nullptr);

/**
 * The scene's meshes (every receiver: meshes, planes and spheres as drawn)
 * as an occluder for the GI filter's bright lights (vtkPGIMeshOccluder,
 * Embree): their shadows come from the real geometry, as the reference's.
 */
PROXYGISCENESETUP_EXPORT vtkSmartPointer<vtkPGIOccluder> SceneOccluder(
  const std::vector<vtkSmartPointer<vtkPolyData>>& receivers);

/// The scene's effect switches (shadows, indirect, local lights) on GI
/// settings; the knobs (order, method, ...) are left to the caller.
PROXYGISCENESETUP_EXPORT void ConfigureSettings(
  vtkPGIGISettings* settings, const SceneDescription& scene);

/// Sets the filter's lighting, proxies, planes and (ConfigureSettings) the
/// scene's effect switches on its settings.
PROXYGISCENESETUP_EXPORT void ConfigureGlobalIllumination(vtkPGIGlobalIllumination* gi,
  const SceneDescription& scene, const LoadedScene& loaded, const SceneProxies& proxies);

/// Shades each receiver in turn with the one filter `gi`, so its bake is
/// built once for the scene, and returns shallow copies of its outputs (each
/// with its Plan field array): the filter gives an update new arrays while
/// the last ones are held elsewhere, so each copy keeps its own.
PROXYGISCENESETUP_EXPORT std::vector<vtkSmartPointer<vtkPolyData>> ShadeEach(
  vtkPGIGlobalIllumination* gi, const std::vector<vtkSmartPointer<vtkPolyData>>& receivers);

/**
 * Embree reference of every receiver (object k is the receiver, the others
 * block and reflect), `spp` samples, one bounce; with `proxies` the meshes
 * of the other objects are replaced by their sphere proxies (the reference's
 * proxy mode: it separates proxy-geometry error from SH error). Cached in
 * `cacheDir` by scene name, object, vertex count, spp and mode; `seconds`
 * is the tracing time (read back from the cache when cached). Runs meant to
 * be compared with each other take different seeds (independent noise).
 * With `traceMissing` false nothing is traced: empty (error "not cached")
 * unless every receiver's reference is in the cache. Empty on error.
 */
PROXYGISCENESETUP_EXPORT std::vector<vtkSmartPointer<vtkPolyData>> SceneReference(
  const SceneDescription& scene, const LoadedScene& loaded,
  const std::vector<vtkSmartPointer<vtkPolyData>>& receivers, int spp, const std::string& cacheDir,
  const SceneProxies* proxies, double& seconds, std::string& error, unsigned int seed = 1,
  bool traceMissing = true, SetupMonitor* monitor = nullptr);

/// Relative RMSE sqrt(sum |a-b|^2 / sum |b|^2) of two RGB point arrays over
/// the given objects (all when `objects` is empty); 0 when b is all zero.
PROXYGISCENESETUP_EXPORT double RelativeRMSE(const std::vector<vtkSmartPointer<vtkPolyData>>& a,
  const char* arrayA, const std::vector<vtkSmartPointer<vtkPolyData>>& b, const char* arrayB,
  const std::vector<std::size_t>& objects = {});

/// Relative RMS of an array (a reference's standard error) against another
/// (its value), the noise floor of RelativeRMSE.
PROXYGISCENESETUP_EXPORT double RelativeRMS(const std::vector<vtkSmartPointer<vtkPolyData>>& a,
  const char* arrayA, const char* arrayValue, const std::vector<std::size_t>& objects = {});

/**
 * The relative RMSE of `a`'s "Radiance" against a reference of `targetSpp`
 * samples, estimated from a cheap one of `cheapSpp` samples ("Radiance",
 * "RadianceStdErr"): the cheap run's extra noise taken out of both sums.
 * Over tens of thousands of receivers the noise's sum is known to a few
 * percent, so 16 samples estimate a 1024-sample comparison (the budget's
 * check; AccuracyTime.md section 22 measures how well).
 */
PROXYGISCENESETUP_EXPORT double EstimatedRelativeRMSE(
  const std::vector<vtkSmartPointer<vtkPolyData>>& a,
  const std::vector<vtkSmartPointer<vtkPolyData>>& cheap, int cheapSpp, int targetSpp);

} // namespace proxygi

#endif
