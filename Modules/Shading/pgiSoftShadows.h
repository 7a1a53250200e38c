/**
 * @file pgiSoftShadows.h
 * @brief SHEXP soft shadows at one receiver: the blockers' log-visibility
 * vectors summed, then exponentiated (Ren et al. 2006, sections 6.1-6.2).
 *
 * Blockers are spheres (the proxies) and infinite planes (a ground plane seen
 * from above is a cap of half-angle 90 degrees). Self-shadow replacement
 * (section 6.2), made continuous:
 *  - sphere entirely behind the receiver's tangent plane T_p: dropped;
 *  - receiver inside the sphere: dropped if the centre is behind T_p, else
 *    shrunk to the sphere of the same centre tangent to T_p;
 *  - receiver outside, sphere cut by T_p: replaced by the sphere whose
 *    diameter runs from the sphere's highest point q0 down to T_p (q1);
 *  - both replacements are scaled by a ramp in the receiver's distance rho
 *    (along T_p) to the circle where T_p cuts the sphere, radius delta:
 *    inside by min(1, (delta - rho) / (delta/2)), outside by
 *    min(1, (rho - delta) / delta) (the paper's continuity scaling), so both
 *    vanish where the receiver leaves the sphere and nothing jumps.
 * The rules stand for the receiver's own surface cutting its own proxies. A
 * receiver whose own object is known (SelfVisibility::Object: its own
 * spheres are left out) or that belongs to no sphere's object
 * (SelfVisibility::OwnsNoSpheres: a plane) sees every sphere it sums as
 * another object's, whole: where another object touches it the shadow is
 * dark, as the mesh's is, where the ramp would fade the sphere to nothing.
 * Blockers that subtend less than MinAngle are skipped (they would add
 * nothing the exp could resolve). A plane blocks the half-space beneath it
 * for every receiver above it (a 90-degree cap); receivers on it are not
 * blocked by it.
 */
#ifndef pgiSoftShadows_h
#define pgiSoftShadows_h

#include "ProxyGIShadingModule.h"

#include "pgiSHExp.h"

#include <vector>

namespace proxygi
{

/// Sphere blockers in structure-of-arrays form, plus infinite planes.
struct PROXYGISHADING_EXPORT Blockers
{
  std::vector<float> X, Y, Z, R;
  /// Optional per-band ratio vectors (SHEXP eq. 37), Order values per sphere;
  /// empty: all 1. Hierarchy cuts set them.
  std::vector<float> Ratio;
  /// RGB albedo per sphere (3 floats each), for indirect light; may stay empty.
  std::vector<float> Albedo;
  /// Scene object per sphere (the proxies' "ObjectId"; -1: none), for
  /// receivers that carry their own object's visibility (SelfVisibility).
  std::vector<int> Object;
  std::vector<float> PlaneOrigin, PlaneNormal, PlaneAlbedo; // 3 floats each per plane
  /// Per plane, 6 floats: two half-edge vectors e1, e2 in the plane; the
  /// plane reflects light from origin + a e1 + b e2, |a|, |b| <= 1, only
  /// (PlaneLightMap). All 0: unbounded. Its blocking is the infinite plane's.
  std::vector<float> PlaneExtent;
  void AddSphere(
    float x, float y, float z, float r, const float* albedo = nullptr, int object = -1);
  void AddPlane(const float origin[3], const float normal[3], const float* albedo = nullptr,
    const float* halfEdges = nullptr);
  std::size_t Spheres() const { return this->X.size(); }
  std::size_t Planes() const { return this->PlaneOrigin.size() / 3; }
  /// Whether p lies strictly above every plane: the receivers whose light
  /// carries the planes (LightAbovePlanes). GLSL twin: pgiAboveEveryPlane.
  bool AboveEveryPlane(const float p[3]) const;
};

struct PROXYGISHADING_EXPORT SoftShadowSettings
{
  int Order = 4;
  /// Accumulate and exponentiate at this order, then truncate (0: Order).
  int AccumulationOrder = 0;
  sh::ExpOptions Exp;
  /// Cosine window on the visibility (h; 0 = none, < 0 = 2n).
  double WindowH = 0.0;
  /// Blockers subtending less than this (radians) are skipped.
  float MinAngle = 0.002f;
  bool SelfShadowRules = true;
  /// Planes as 90-degree caps in log space (true), or only reported as seen
  /// (false: the light carries them, see LightAbovePlanes).
  bool PlanesInLogSpace = true;
};

/**
 * A sphere hierarchy over the leaf proxies (Level 0 = leaves; every parent
 * bounds its children), as the Proxies module writes it.
 */
struct PROXYGISHADING_EXPORT ProxyHierarchy
{
  std::vector<float> X, Y, Z, R;
  std::vector<float> Albedo; // 3 per node (parents: their leaves' mean), may be empty
  std::vector<int> Level, Parent;
  std::vector<int> Object;                // scene object per node, may be empty (-1 each)
  std::vector<std::vector<int>> Children; // filled by Finish()
  std::vector<int> Roots;
  /// Builds children and roots from Parent; false if the links are broken.
  bool Finish();
};

/**
 * The blockers one receiver cluster uses (SHEXP section 6.3): the cut of
 * the hierarchy whose nodes subtend less than maxAngle from the cluster's
 * bounding sphere (centre pR, radius rR), each with the per-band ratio vector
 * that best scales its bounding log-visibility to the summed log-visibility
 * of its leaves, both seen from the cluster's central receiver (p, n), then
 * scaled down where the leaves overlap: by the solid angle of their union
 * (the share of 128 directions in the node's cap that meet a leaf) over
 * the sum of theirs. Below the SH's resolution the exp of summed logs adds
 * overlapping caps instead of joining them (a bunny's 64 spheres seen from
 * 3 m: 3.3% of the sphere, their union 0.36%).
 * Leaves in the cut keep ratio 1. `nodes`, if given, receives the hierarchy
 * index of each sphere of the cut.
 */
PROXYGISHADING_EXPORT Blockers CutHierarchy(const ProxyHierarchy& hierarchy, const float pR[3],
  float rR, const float p[3], const float n[3], float maxAngle, int order, bool selfShadowRules,
  std::vector<int>* nodes = nullptr);

/**
 * Applies the replacement rules to one sphere for receiver p, normal n (unit).
 * Returns false when the sphere is dropped; otherwise c and r hold the
 * sphere to accumulate.
 */
PROXYGISHADING_EXPORT bool ReplaceBlocker(const float p[3], const float n[3], float c[3], float& r);

/// A blocker as one receiver sees it after the rules (shared with indirect light).
struct SeenBlocker
{
  int Index;    // into Blockers' spheres; -1 - k for plane k
  float Theta;  // angular radius
  float Dir[3]; // unit, receiver -> centre (planes: -normal)
};

/**
 * A receiver's own object's visibility, precomputed (vtkPGISelfVisibility):
 * the spheres of Object are listed as seen (the indirect light still wants
 * them) but not accumulated, and Log (accumulation order^2 floats per
 * receiver, null: none) is added to the sum before the exp instead.
 */
struct SelfVisibility
{
  int Object = -1;
  const float* Log = nullptr;
  /// The receiver is on no sphere's object (a plane): no rules either.
  bool OwnsNoSpheres = false;
};

class PROXYGISHADING_EXPORT SoftShadows
{
public:
  explicit SoftShadows(const SoftShadowSettings& settings);

  int GetOrder() const { return this->Settings.Order; }
  /// The order blockers are summed at (SelfVisibility::Log rows: its square).
  int GetAccumulationOrder() const { return this->AccOrder; }

  /**
   * Visibility vector g (Order^2 floats) at receiver p with normal n.
   * Returns the number of blockers accumulated; 0 means g = 1 exactly (no exp
   * run). status reports NaN/Inf met on the way. `seen`, if given, receives
   * the blockers as this receiver sees them (for indirect light).
   */
  int Visibility(const float p[3], const float n[3], const Blockers& blockers, float* g,
    sh::Status& status, std::vector<SeenBlocker>* seen = nullptr,
    const SelfVisibility& self = SelfVisibility()) const;

  /**
   * Visibility of `count` receivers against the same blockers: points p and
   * unit normals n (3 floats each), g (count rows of Order^2), status and
   * used (count each) as Visibility gives them. Runs sh::BatchWidth
   * receivers at once through the batched kernels (pgiSHBatch.h) where they
   * are enabled and the accumulation order is at most 6; receivers one at a
   * time otherwise. `seen`, if given, is `count` lists that receive each
   * receiver's blockers as Visibility's `seen` does. Allocates nothing
   * beyond those lists' growth. `self` applies to every receiver (its Log
   * has `count` rows); a nonzero Log row counts as one blocker in `used`.
   */
  void VisibilityBatch(int count, const float* p, const float* n, const Blockers& blockers,
    float* g, sh::Status* status, int* used, std::vector<SeenBlocker>* seen = nullptr,
    const SelfVisibility& self = SelfVisibility()) const;

private:
  /// The window, applied to a visibility vector of the output order.
  void Finish(float* g) const;

  SoftShadowSettings Settings;
  int AccOrder;
};

/**
 * Scales the ratio vectors of `cut` (made 1 where it has none) so that its
 * SH visibility, seen by a receiver at p (normal n, unit) that owns none of
 * its spheres, blocks as much of the cosine-weighted hemisphere as the
 * union of `leaves` does (`directions` spherical-Fibonacci directions). Heavily
 * overlapping spheres near the receiver (an arch's tube over the ground)
 * are each still too small for the SH, and the exp of summed logs blocks
 * far more than their union: under the arch's middle 60% of the
 * cosine-weighted hemisphere against 42% for the union. Returns the scale,
 * 1 when the cut
 * blocks no more than the union or the kernel does not apply ratios.
 */
/**
 * The share of `directions` cosine-weighted spherical-Fibonacci directions
 * about n from p that meet a sphere of `leaves` (the union's cosine-weighted
 * blocked share). Each sphere tests only the directions whose polar angle
 * its cone can reach; everyPair tests every direction against every sphere
 * (the reference the tests hold it to: the same count).
 */
PROXYGISHADING_EXPORT double UnionCoveredShare(const Blockers& leaves, const float p[3],
  const float n[3], int directions, bool everyPair = false);

PROXYGISHADING_EXPORT float ScaleCutToUnion(Blockers& cut, const Blockers& leaves,
  const SoftShadows& kernel, const float p[3], const float n[3], int directions = 2048);

} // namespace proxygi

#endif
