/**
 * @file pgiPlaneLightMap.h
 * @brief The light a blocker plane reflects where the proxies (and the
 * bright lights' shadows) dim it, on a grid, and its mean over the part of
 * the plane a receiver sees.
 *
 * A ground lit by the environment reflects albedo/pi E(x), with E dimmed
 * under the objects. A receiver above it gathers
 *   int_{w meets the plane} L(x(w)) max(n.w, 0) dw,
 * so the factor the plane's uniform light is scaled by (PlaneShadowScale's
 * meaning) is the mean of s(x) = E(x) / E_open over the directions that meet
 * the plane, weighted by max(n.w, 0). One plane point per receiver (the one
 * along n - m) takes the darkest spot under an object for the whole view and
 * leaves the objects' undersides far too dark; this map averages instead.
 *
 * s is tabulated once per update on a grid over the region the proxies can
 * shadow: their footprints widened by 2.5 times their height above the plane
 * (an environment's shadow of a sphere fades as its solid angle; at that
 * distance it is below 1%), stretched along each bright light's shadow
 * (at most 20 heights). Outside the grid s = 1. A receiver averages
 * `directions` bilinear look-ups along uniform directions over the
 * half-space below the plane, fixed in the plane's frame, so the result is
 * continuous in the receiver's position and normal.
 *
 * Given the receiver's visibility g (the other blockers and its own object,
 * without the plane), each direction is also weighted by V(w) = g . y(w),
 * clamped to [0, 1]: the plane seen past what stands in front of it, so the
 * overlap normalisation need not guess it (IndirectExitRadiance's
 * planesSeenPast). A receiver on a bunny's back whose view of the ground is
 * its own body then gathers that body's bounce, not the ground's.
 *
 * A plane of finite extent (Blockers::PlaneExtent) reflects only inside it:
 * a direction that meets the plane outside it sees the environment below
 * the horizon instead, which the infinite plane blocks in the direct light;
 * Scale returns that light too (the gap past the plane's edges), so a ground
 * of 6 x 6 metres is not lit, nor lights, as an endless one.
 */
#ifndef pgiPlaneLightMap_h
#define pgiPlaneLightMap_h

#include "ProxyGIShadingModule.h"

#include "pgiBrightLights.h"
#include "pgiEnvironmentMap.h"
#include "pgiSoftShadows.h"

#include <vector>

class vtkPGIOccluder;

namespace proxygi
{
struct BakedScene;
struct BrightLightSet;

class PROXYGISHADING_EXPORT PlaneLightMap
{
public:
  /**
   * Lays the grid out on plane `plane` of `blockers` over the region its
   * spheres (and `lights`' shadows of them) can darken, with at most
   * `resolution` cells along its longer side, and sets `directions` look-up
   * directions (with the SH basis of `order` at each, for Scale's g). s
   * starts at 1 everywhere. A plane no sphere stands above gets an empty
   * grid (Scale then gives 1).
   */
  void Layout(const Blockers& blockers, int plane, const std::vector<DistantLight>& lights,
    int resolution, int directions, int order);

  int GetNumberOfPoints() const { return this->Columns * this->Rows; }
  int GetColumns() const { return this->Columns; }
  int GetRows() const { return this->Rows; }
  /// Grid point i (row-major), on the plane.
  void Point(int i, float q[3]) const;
  /// s at the grid points, 3 floats (RGB) each, to be filled in [0, 1].
  float* Scales() { return this->S.data(); }
  const float* Scales() const { return this->S.data(); }

  /// s at plane point x (bilinear; 1 outside the grid).
  void Lookup(const float x[3], float s[3]) const;

  /**
   * The environment below the plane's horizon, for the sky a receiver sees
   * past a bounded plane's edges (order-4 SH would smear the bright sky
   * across the horizon). Tabulated in the plane's frame over SkyBins
   * azimuths and SkyHeights steps of s = sin(angle below the horizon)
   * (uniform in s is uniform in solid angle: dw = ds dphi): per bin and
   * height, the integral of L(w) w dw over the bin from the horizon down to
   * s, as (w.U, w.V, w.m) times RGB (9 floats), from 8 x 4 samples of the
   * map per cell. Kept while the map and the plane's frame stay.
   */
  void SetSky(const EnvironmentMap& map);
  static constexpr int SkyBins = 32, SkyHeights = 64;
  /// Layout's most look-up directions (vtkPGIGISettings::PlaneBounceDirections' range).
  static constexpr int MaxDirections = 1024;
  /// Grid points along a tile's side: each tile is shaded with the blockers
  /// scaled at its centre to block what their union blocks.
  static constexpr int TileSide = 8;
  /// Rows of directions per bin (at s = (r + 0.5) / SkyRows) the visibility is read at.
  static constexpr int SkyRows = 8;
  static_assert(SkyRows >= 2, "the visibility is read between two rows");

  /// Whether plane point x lies on the plane's extent (always if unbounded).
  bool Inside(const float x[3]) const;

  /**
   * The scale of the plane's light a receiver at p (normal n, unit) sees:
   * the sum of max(n.w, 0) s over the look-up directions over that of
   * max(n.w, 0). With g (Layout's order^2 floats), each term of the first
   * sum is also weighted by V(w). Directions that meet the plane off its
   * extent add nothing to it. With `gap`, the sky's exit radiance past the
   * extent (white receiver, 1/pi int L(w) V(w) max(n.w, 0) dw over the
   * directions below the horizon that miss the extent; SkyPastEdges). False
   * (scale 1, gap 0) when the receiver is not above the plane or sees none
   * of it.
   */
  bool Scale(const float p[3], const float n[3], float scale[3], const float* g = nullptr,
    float gap[3] = nullptr) const;

  /**
   * The sky past a bounded plane's edges at a receiver whose foot is (x, y)
   * in plane coordinates, at height h > 0, normal n, visibility g (or null):
   * per azimuth bin, the heights below the horizon whose rays miss the
   * extent (the bin's centre ray), intersected with where its n.w > 0, are
   * read off the SetSky table (linear in s), weighted by V at their middle
   * (linear between the bin's two SkyRows directions around it, each
   * clamped to [0, 1], so that it moves continuously); the sum over pi.
   * Exact for a map constant over each cell, up to the bins' width.
   */
  void SkyPastEdges(
    float x, float y, float h, const float n[3], const float* g, float gap[3]) const;

  // What the GPU mapper uploads (its GLSL twin, pgiPlaneLightScale).
  const float* GetU() const { return this->U; }
  const float* GetV() const { return this->V; }
  /// U0, V0 (the grid's first point in plane coordinates) and the cell size.
  void GetGrid(float& u0, float& v0, float& cell) const
  {
    u0 = this->U0;
    v0 = this->V0;
    cell = this->Cell;
  }
  bool GetBounded() const { return this->Bounded; }
  const float* GetDual1() const { return this->Dual1; }
  const float* GetDual2() const { return this->Dual2; }
  int GetNumberOfDirections() const { return static_cast<int>(this->Directions.size() / 3); }
  /// Direction k's world vector, and its steps on the plane per unit height.
  const float* GetDirection(int k) const { return &this->Directions[3 * k]; }
  float GetStepU(int k) const { return this->StepU[k]; }
  float GetStepV(int k) const { return this->StepV[k]; }
  /// SetSky's table: bin b's (SkyHeights + 1) x 9 floats from 9 b (SkyHeights + 1).
  const float* GetSkyTable() const
  {
    return this->SkyTable.empty() ? nullptr : this->SkyTable.data();
  }

private:
  float Origin[3] = { 0, 0, 0 }, Normal[3] = { 0, 0, 1 }, U[3] = { 1, 0, 0 }, V[3] = { 0, 1, 0 };
  // The grid's first point in plane coordinates, its cell size, its size.
  float U0 = 0, V0 = 0, Cell = 1;
  int Columns = 0, Rows = 0;
  std::vector<float> S;
  // Per direction: the world direction and its step on the plane per unit
  // height, (w.U, w.V) / (-w.m); the steps padded with zeros to
  // DirectionStride.
  std::vector<float> Directions, StepU, StepV;
  int Coefficients = 0;
  // The basis at the directions, coefficient-major: coefficient i of
  // direction k at i * DirectionStride + k (the stride a multiple of
  // DotLanes, zeros past the last direction), so V at every direction is
  // one product with the directions side by side.
  std::vector<float> Basis;
  int DirectionStride = 0;
  // SetSky's table, what it was built from, and the basis at each bin's
  // SkyRows directions (b * SkyRows + r), coefficient-major as Basis.
  std::vector<float> SkyTable, SkyBasis;
  // Per bin: its centre's (cos, sin) in (U, V) and its steps in the
  // extent's coordinates (dual 1, dual 2) per unit of distance.
  std::vector<float> SkyAxes;
  struct SkyKey
  {
    const void* Texels = nullptr;
    double Rotation = 0.0, Checksum = 0.0;
    int Width = 0, Height = 0, Coefficients = 0;
    float Frame[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    bool operator==(const SkyKey& o) const;
  } SkyBuiltFor;
  // A bounded plane: its half edges' dual vectors in (U, V), so that a
  // point's extent coordinates are its plane coordinates dotted with them.
  bool Bounded = false;
  float Dual1[2] = { 0, 0 }, Dual2[2] = { 0, 0 };
};

/// What shades the planes' light maps (BuildPlaneLightMaps).
struct PROXYGISHADING_EXPORT PlaneLightMapShading
{
  /// The receivers' kernel (planes carried by the light or not, as theirs).
  const SoftShadows* Shadows = nullptr;
  /// The bright lights taken out of the map (null: none) and their shadows'
  /// route: rays through Occluder, else the proxies' cones.
  const BrightLightSet* Bright = nullptr;
  const vtkPGIOccluder* Occluder = nullptr;
  float RayOffset = 0.0f, MinAngle = 0.0f;
  bool ShadowsOn = true;
  /// Cells along a grid's longer side.
  int Resolution = 128;
};

/**
 * One map per blocker plane of `scene`, laid out and filled: the proxies'
 * visibility at each grid point (every leaf sphere, the plane's normal;
 * per tile of TileSide x TileSide points the spheres scaled to block what
 * their union blocks at its centre, ScaleCutToUnion) and
 * the bright lights' shadows there, blended by their shares of the plane's
 * light (as PlaneShadowScale and BrightLightsOnPlane do per receiver), and
 * the sky below the horizon along `directions` look-up directions. Threaded
 * (vtkSMPTools). Returns the grid points of all maps. The CPU filter and
 * the GPU mapper (which uploads them) share it.
 */
PROXYGISHADING_EXPORT int BuildPlaneLightMaps(const BakedScene& scene,
  const PlaneLightMapShading& how, int directions, std::vector<PlaneLightMap>& maps);

} // namespace proxygi

#endif
