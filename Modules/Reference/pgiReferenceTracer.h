/**
 * @file pgiReferenceTracer.h
 * @brief Monte Carlo ground truth for diffuse scenes on Embree.
 *
 * Geometry: triangle meshes (per-vertex or per-object albedo) and spheres
 * (the proxies, to split proxy-geometry error from SH error). Light: an
 * environment map (importance sampled, combined with cosine sampling by the
 * balance heuristic), spherical area lights (sampled by solid angle; they
 * emit but do not block) and point lights.
 *
 * Estimates at a surface point x with normal n, per sample:
 *  - direct: E_d = int L(w) V(x, w) max(n.w, 0) dw over all lights;
 *  - indirect: one cosine-sampled ray; at its hit y the exit radiance
 *    rho(y)/pi (E_d(y) + further bounces up to MaxBounces) times pi.
 * Exit radiance = albedo(x)/pi E. Every receiver draws from its own seeded
 * random stream, so results do not depend on threading. The standard error
 * of each estimate is returned with it.
 */
#ifndef pgiReferenceTracer_h
#define pgiReferenceTracer_h

#include "ProxyGIReferenceModule.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace proxygi
{
class EnvironmentMap;
struct TracerAccess;

class PROXYGIREFERENCE_EXPORT ReferenceTracer
{
public:
  ReferenceTracer();
  ~ReferenceTracer();
  ReferenceTracer(const ReferenceTracer&) = delete;
  ReferenceTracer& operator=(const ReferenceTracer&) = delete;

  /**
   * Adds a triangle mesh. albedo: per-vertex RGB (3 x points) or null for
   * objectAlbedo. Degenerate (zero-area) triangles are skipped and counted;
   * NaN/Inf coordinates or out-of-range indices fail with a message.
   */
  bool AddMesh(const std::vector<float>& points, const std::vector<unsigned>& triangles,
    const float* albedo, const float objectAlbedo[3], std::string& error);
  /// Adds a sphere (a proxy) with a uniform albedo.
  bool AddSphere(const double center[3], double radius, const float albedo[3], std::string& error);
  /// The environment (kept by pointer; the caller keeps it alive). Null: black.
  void SetEnvironment(const EnvironmentMap* environment);
  void AddSphereLight(const double center[3], double radius, const float radiance[3]);
  void AddPointLight(const double position[3], const float intensity[3]);
  /// Builds the Embree scene; fails for an empty scene.
  bool Commit(std::string& error);

  /// Diagonal of the scene's bounding box (sets the ray offset).
  double GetSceneSize() const { return this->SceneSize; }
  std::size_t GetSkippedTriangles() const { return this->SkippedTriangles; }
  /// Rays traced so far (intersection and occlusion), for throughput.
  std::uint64_t GetRayCount() const;

  struct Settings
  {
    int Samples = 256;
    /// 0: direct light only; 1: one-bounce indirect (the default); more for tests.
    int MaxBounces = 1;
    std::uint64_t Seed = 1;
  };

  struct Estimate
  {
    double Direct[3] = { 0, 0, 0 };   // irradiance
    double Indirect[3] = { 0, 0, 0 }; // irradiance
    double DirectStdErr[3] = { 0, 0, 0 };
    double IndirectStdErr[3] = { 0, 0, 0 };
    double TotalStdErr[3] = { 0, 0, 0 };
  };

  /// Irradiance at x (normal n, unit), from random stream `stream`.
  void EstimateIrradiance(const double x[3], const double n[3], std::uint64_t stream,
    const Settings& settings, Estimate& out) const;

  struct RadianceEstimate
  {
    bool Hit = false;
    double Direct[3] = { 0, 0, 0 };   // exit radiance from direct light
    double Indirect[3] = { 0, 0, 0 }; // exit radiance from bounced light
    double Total[3] = { 0, 0, 0 };
    double TotalStdErr[3] = { 0, 0, 0 };
  };
  /**
   * Exit radiance seen along a camera ray: the first hit's albedo/pi times
   * its estimated irradiance, split into direct and indirect; where nothing
   * is hit, the environment (counted as direct).
   */
  void EstimateRadianceAlongRay(const double origin[3], const double direction[3],
    std::uint64_t stream, const Settings& settings, RadianceEstimate& out) const;

  /**
   * The first hit on a mesh of the ray from x (offset along the unit normal
   * n by the scene's ray epsilon) in unit direction d: the mesh's point ids
   * of the hit triangle (as AddMesh numbered them) and their barycentric
   * weights. False for a miss or a hit on a sphere. For visibility
   * precomputes (vtkPGISelfVisibility).
   */
  bool HitVertices(const double x[3], const double n[3], const double d[3], unsigned ids[3],
    double weights[3]) const;

  /**
   * Shadow rays: for `count` rays from origins along unit directions (3
   * floats each), blocked[i] = 1 when anything lies between tnear and
   * lengths[i] (null lengths: infinity). For the GI filter's bright lights
   * and the light cloud's visibility tests (vtkPGIMeshOccluder). Thread-safe.
   */
  void OccludedRays(int count, const float* origins, const float* directions, float tnear,
    const float* lengths, unsigned char* blocked) const;

  /// Whether anything blocks the segment from a to b (a kept off a surface
  /// by the caller; the far end is shortened by the ray offset).
  bool SegmentBlocked(const double a[3], const double b[3]) const;
  /// The offset rays start at off a surface (1e-4 of the scene size).
  double GetRayOffset() const;

  /// A surface point seen from a receiver: where one gather ray hit.
  struct GatherHit
  {
    float Position[3]; // offset off the surface along Normal by GetRayOffset()
    float Normal[3];   // unit, facing the receiver's side
    float Albedo[3];
  };
  /**
   * The first hits of `count` cosine-sampled rays from x (unit normal n),
   * stratified (a Fibonacci lattice shifted by random stream `stream` of
   * `seed`); misses are left out, so a
   * one-bounce estimate divides by `count`: E_ind(x) = pi/count sum over
   * hits of L(hit). For precomputes that light one set of hits by many
   * lights (the light cloud). Thread-safe.
   */
  void GatherHits(const double x[3], const double n[3], std::uint64_t seed, std::uint64_t stream,
    int count, std::vector<GatherHit>& hits) const;

  /**
   * Where a point lies, from `rays` rays spread over the sphere: Inside a
   * solid when every ray hits and most hit a triangle from behind (its
   * normal by the mesh's vertex order, (p1 - p0) x (p2 - p0), along the
   * ray: closed meshes face out); otherwise its distance to the nearest hit.
   * Spheres count as solids. For placing light-cloud lights.
   */
  struct PointPlace
  {
    bool Inside = false;
    double NearestHit = 0.0;                  // infinity when every ray escapes
    double NearestDirection[3] = { 0, 0, 0 }; // the ray that hit nearest
  };
  PointPlace PlacePoint(const double p[3], int rays) const;

  /// Albedo and geometric normal of the first hit along a ray, for tests.
  bool FirstHit(const double origin[3], const double direction[3], double& t, double normal[3],
    float albedo[3]) const;

  struct Internal;

private:
  friend struct TracerAccess;
  std::unique_ptr<Internal> Impl;
  double SceneSize = 1.0;
  std::size_t SkippedTriangles = 0;
  // The ray count in per-thread shards: one counter bumped per ray by every
  // thread serialised the tracing on its cache line (the light cloud's
  // precompute ran no faster on two threads than on one).
  struct alignas(64) RayShard
  {
    std::atomic<std::uint64_t> Count{ 0 };
  };
  static constexpr int RayShards = 32;
  mutable std::array<RayShard, RayShards> Rays;
  std::atomic<std::uint64_t>& RayCounter() const;
};

} // namespace proxygi

#endif
