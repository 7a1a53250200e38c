/**
 * @file pgiSphericalLights.h
 * @brief Shadowed one-bounce indirect light from spherical lights (Guerrero,
 * Jeschke and Wimmer 2008, sections 5-7): each proxy is a spherical light
 * (SL) whose radiance, as a function of the direction from its centre, is an
 * SH vector updated from sample points on the object's surface.
 *
 * First pass (UpdateRadiance), per SL i: at each of its surface samples p_j
 * (normal n_j) the diffuse exit radiance of a white surface under the
 * environment with SHEXP visibility from all proxies and planes (and the
 * local lights, treated as SLs of uniform radiance); projected with the
 * Voronoi basis sums, L_i = sum_j L_pj Y_j (eq. 10); times the albedo SH,
 * Lc_i = L_i * c_i (eq. 11).
 *
 * Second pass (ExitRadiance), per receiver p, normal n: the SLs after the
 * self-shadow rules (ReplaceBlocker), ordered by distance (per sphere) or by
 * object distance, then distance (per object). SL k contributes
 *   Lbar_k Vbar_k,  Lbar_k = w_theta . Lc_k  (average radiance, eq. 16-18),
 *   Vbar_k = H(n) . (exp(F_k) - exp(F_k + G_k))  (eq. 23-24),
 * F_k the summed log-visibility of the planes and of the SLs before k,
 * without the SLs of k's object that intersect it (their occlusion is in
 * Lc_k already: rule 2 of the sampling). H(n) includes 1/pi, so the sum is
 * the exit radiance of a white receiver.
 *
 * Per-sphere and per-object blocking differ only in the order (so in who
 * blocks whom); F is accumulated incrementally in both, and exp(F_k + G_k)
 * is reused as the next exp(F_k+1) whenever the blocker sets match, so a
 * receiver costs about one exp per SL it sees.
 */
#ifndef pgiSphericalLights_h
#define pgiSphericalLights_h

#include "ProxyGIShadingModule.h"

#include "pgiSoftShadows.h"

#include "vtkType.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkDataArray;
class vtkPGILighting;
class vtkPolyData;

namespace proxygi
{
class EnvironmentShading;
namespace sh
{
class AnalyticLightTables;
}

enum class SphericalLightBlocking
{
  PerSphere,
  PerObject
};

/// The SLs: geometry, object, intersections and (after the first pass) radiance.
struct PROXYGISHADING_EXPORT SphericalLights
{
  int Order = 4;
  std::vector<float> X, Y, Z, R;
  std::vector<int> Object;
  /// Lc per SL: 3 x Order^2 (R, G, B), radiance by direction from the centre.
  std::vector<float> Radiance;
  /// Count x Count flags: same object and overlapping (filled by Finish()).
  std::vector<char> Intersects;
  /// Hierarchy reflection ratio per SL (empty: 1).
  std::vector<float> ReflectionRatio;
  /// Hierarchy level per SL (may stay empty): with it, only SLs of one level
  /// and object count as intersecting.
  std::vector<int> Level;
  void Add(float x, float y, float z, float r, int object);
  std::size_t Count() const { return this->X.size(); }
  void Finish();
};

/// Local lights as SLs of uniform radiance that do not block.
struct PROXYGISHADING_EXPORT LocalEmitters
{
  std::vector<float> X, Y, Z, R, Radiance; // Radiance: 3 per light
  std::vector<char> Point;                 // point light: Radiance holds the intensity
  void Add(const double c[3], double r, const double rgb[3], bool point);
  /// Every sphere light and point light of `lighting`.
  void AddLights(const vtkPGILighting& lighting);
  std::size_t Count() const { return this->X.size(); }
};

/**
 * The local lights' direct exit radiance at a white receiver at p with
 * normal n, shadowed by the visibility g (nullptr: unshadowed), at the
 * order of `tables`: vtkPGIGlobalIllumination's LocalLights array before
 * the albedo. GLSL twin: pgiLocalLights. Below the table's first node L_H
 * grows as sin^2(theta) with a fixed shape, so it is evaluated there and
 * scaled (point lights: theta -> 0, radiance I / (pi d^2 sin^2 theta)).
 */
PROXYGISHADING_EXPORT void LocalLightsRadiance(const LocalEmitters& lights,
  const sh::AnalyticLightTables& tables, const double p[3], const float n[3], const float* g,
  float lit[3]);

/// Surface samples of the SLs (m per SL, in the directions Directions).
struct PROXYGISHADING_EXPORT SphericalLightSamples
{
  int Directions = 0;
  std::vector<float> Position; // Count x m x 3, world
  std::vector<float> Normal;   // Count x m x 3; (0, 0, 0): no sample
  std::vector<float> AlbedoSH; // Count x 3 x Order^2
  std::vector<float> Voronoi;  // m x Order^2, sh::VoronoiBasisSums
};

/// Per-thread scratch for ExitRadiance (no allocation per receiver).
struct SphericalLightScratch
{
  struct Seen
  {
    int Index; // SL index, or -1 - k for local light k
    float Key, Theta, Dir[3];
  };
  std::vector<Seen> List, Sorted;
  std::vector<float> ObjectKey;
  std::vector<std::size_t> Rank;
  std::vector<float> Logs;  // Order^2 per entry of List
  std::vector<float> Basis; // the SH basis at each entry's direction
  std::vector<int> Excluded;
  // The distinct blocker sets the lights need the exp of (Order^2 each), their
  // keys (a bit per sorted entry; cacheable ones are looked up), their exps
  // and statuses; per emitting light, the sets before and after it.
  std::vector<float> Sets, SetExp;
  std::vector<std::uint64_t> SetKey;
  std::vector<char> SetCacheable;
  std::vector<int> SetStatus;
  struct Job
  {
    int Before, After; // set indices, -1: exactly 1 (nothing blocks)
    int Entry;
    float Lbar[3];
  };
  std::vector<Job> Jobs;
};

class PROXYGISHADING_EXPORT ShadowedIndirect
{
public:
  ShadowedIndirect(const SoftShadowSettings& settings, SphericalLightBlocking blocking);

  /**
   * First pass: lights.Radiance from the samples. `blockers` are what shadows
   * the samples (the proxies and planes, as for direct light). Returns the
   * number of samples whose exp failed (they count as unlit).
   */
  long UpdateRadiance(SphericalLights& lights, const SphericalLightSamples& samples,
    const Blockers& blockers, const EnvironmentShading& environment,
    const LocalEmitters* locals) const;

  /**
   * Second pass: exit radiance of a white receiver at p (normal n, unit)
   * from the SLs (emitting, blocking) and, if given, local emitters
   * (emitting only). `planes` adds its planes as blockers. Returns false if
   * an exp failed (that SL is left out). `contributions`, if given, receives
   * each SL's share (R + G + B; lights.Count() values), for reflection ratios.
   * The SLs of object `ownObject` (when >= 0) neither emit nor block: the
   * receiver has its own object's bounce and visibility precomputed.
   */
  bool ExitRadiance(const SphericalLights& lights, bool emitLights, const LocalEmitters* locals,
    const Blockers* planes, const float p[3], const float n[3], float rgb[3],
    SphericalLightScratch& scratch, float* contributions = nullptr, int ownObject = -1) const;

private:
  SoftShadowSettings Settings;
  SphericalLightBlocking Blocking;
};

/**
 * The spherical lights of the shadowed bounce from the proxies and their
 * first pass (vtkPGIGlobalIllumination and vtkPGIGIPolyDataMapper share
 * it). `leafIds`: the proxies that are lights; `levels` (may be null): their
 * Level array. Surface samples come from the proxies' SampleOffset and
 * SampleNormal arrays (vtkPGISphereLightSampler) or else lie on the spheres;
 * albedo from AlbedoSH, else `albedoArray`, else `defaultAlbedo`. `shading`
 * lights the samples, `blockers` shadow them, `emitters` (may be null) add
 * local lights. Returns "" when the lights are ready, else why the bounce is
 * skipped; `error` is set for bad input; `summary` says what ran.
 */
PROXYGISHADING_EXPORT std::string PrepareSphericalLights(vtkPolyData* proxies,
  const std::vector<vtkIdType>& leafIds, vtkDataArray* levels, int order, const char* albedoArray,
  const double defaultAlbedo[3], const EnvironmentShading& shading, bool dark,
  const Blockers& blockers, const LocalEmitters* emitters, const ShadowedIndirect& kernel,
  SphericalLights& lights, std::string& summary, std::string& error);

} // namespace proxygi

#endif
