/**
 * @file pgiAccuracyBudget.h
 * @brief The accuracy budget: a cost and error model of the CPU filter's
 * knobs, fitted from measurements against Embree, and the choice of the
 * knobs that meet a user's error or time budget.
 *
 * The model has one row per candidate (a point of the knob grid, Knobs):
 *  - time: t = a + m M + b R + c R P + d R L (M 1 with a map, R receivers
 *    in 1e4, P the leaf spheres in 1e2 (ProxySpheres), L the map's bright
 *    lights),
 *    fitted per candidate by non-negative least squares on relative error;
 *  - error: log e = u_k + v_k log2(objects) + w . x(scene), an intercept
 *    and a slope on the objects per candidate (the ridge pulls the slopes to
 *    0) and weights shared by the candidates of a route, x the scene's light
 *    and geometry (ErrorFeatures).
 * Both are cheap to evaluate from SceneFeatures, which the CLI and the filter
 * compute before shading. The times belong to the machine they were measured
 * on: `proxygi calibrate` refits them (and the error) on the user's own.
 *
 * A candidate runs on one of two routes: the CPU filter
 * (vtkPGIGlobalIllumination) or the GPU mapper (vtkPGIGIPolyDataMapper,
 * whose times are those of the GL renderer named in the model). A Planner
 * chooses for one consumer between its updates.
 */
#ifndef pgiAccuracyBudget_h
#define pgiAccuracyBudget_h

#include "ProxyGIShadingModule.h"
#include "vtkType.h" // for vtkMTimeType

#include <array>
#include <functional>
#include <string>
#include <vector>

class vtkPGIGISettings;
class vtkPGILighting;
class vtkPolyData;

namespace proxygi
{
class EnvironmentMap;

namespace budget
{

/// Where a candidate shades: the CPU filter (bright lights taken out and
/// shadowed by rays, traced self-visibility or the rules, hierarchy cuts) or
/// the GPU mapper (the map whole in the SH, the rules, every leaf sphere,
/// the bounce at the shadows' order).
enum class Route
{
  Filter,
  Mapper
};
/// "filter" or "mapper" (the model and CSV files' word).
PROXYGISHADING_EXPORT const char* RouteName(Route route);

/// One point of the knob grid the budget chooses from (occlusion-fitted
/// proxies; the rest at the route's defaults).
struct PROXYGISHADING_EXPORT Knobs
{
  int Order = 6;
  int IndirectOrder = 4;    ///< the shadowed bounce's order (0: Order)
  int Spheres = 64;         ///< leaf spheres per mesh (proxies are built upstream)
  int SelfVisibility = 256; ///< rays per vertex of the meshes' own visibility (0: the rules)
  bool ShadowedIndirect = true;
  double HierarchyAngle = 25.0;
  Route Backend = Route::Filter;
  /// vtkPGIGISettings' ExpMethod, SphericalLightBlocking, BrightLightRays
  /// (the defaults: HYB, per sphere, 16; VariationGrid measures others).
  int ExpMethod = 3;
  int Blocking = 0;
  int BrightLightRays = 16;

  /// "order 6 (bounce 4), 64 spheres, traced self, shadowed bounce", then
  /// any knob off its default ("exp OL"); the mapper's begin with "GPU
  /// mapper: ".
  std::string Describe() const;
  /// Sets order, indirect order and mode, hierarchy angle, exp method,
  /// blocking and bright-light rays on `settings` (sphere count and
  /// self-visibility are the caller's: they are upstream).
  void Apply(vtkPGIGISettings* settings) const;
  bool operator==(const Knobs& other) const;
};

/// The grid `proxygi calibrate` measures by default: orders 3, 4, 6, 8
/// (bounce at min(order, 4)), 16 or 64 spheres, traced self-visibility or the
/// rules, shadowed or unshadowed bounce.
PROXYGISHADING_EXPORT std::vector<Knobs> DefaultGrid();
/// The knobs the default grid keeps at their defaults, each varied alone
/// (`proxygi calibrate --variations`) around the default grid's order 4 and
/// 6 candidates with traced self-visibility: hierarchy angle 0 (no cuts)
/// and 45 degrees, exp OL and PS*, per-object blocking (shadowed bounce
/// only), 4 and 64 rays per bright light.
PROXYGISHADING_EXPORT std::vector<Knobs> VariationGrid();
/// The variations that trade time for error (AccuracyTime.md section 22):
/// hierarchy cuts at 45 degrees and 4 rays per bright light, around the
/// same candidates as VariationGrid.
PROXYGISHADING_EXPORT std::vector<Knobs> TradeGrid();
/// The filter's candidates of the grids named (default, trades,
/// variations; repeats counted once). False, with the name, for an unknown
/// one.
PROXYGISHADING_EXPORT bool NamedGrids(
  const std::vector<std::string>& names, std::vector<Knobs>& grid, std::string& error);
/// The GPU mapper's grid (`proxygi calibrate --routes mapper`): orders 3, 4,
/// 6 (its most), 16 or 64 spheres, shadowed or unshadowed bounce; the rules,
/// no hierarchy cuts, the bounce at the order.
PROXYGISHADING_EXPORT std::vector<Knobs> MapperGrid();

/// What the model predicts from; cheap to compute before any shading.
struct PROXYGISHADING_EXPORT SceneFeatures
{
  double Receivers = 0.0; ///< points shaded (all receivers of a frame)
  /// Leaf proxy spheres of the scene's proxies where they are built (a
  /// measurement, the filter's and mappers' own proxies: every candidate
  /// chosen among shades with these); 0 where the choice builds them (the
  /// CLI: each candidate's count times Objects). See ProxySpheres.
  double Spheres = 0.0;
  double Objects = 1.0; ///< meshes that cast shadows
  /// The brightest compact peak's share of the light's power (a sun).
  double PeakFraction = 0.0;
  /// |SH bands 1-2| / band 0 of the light's luminance: how directional it is.
  double Directionality = 0.0;
  /// The map's compact peaks a filter takes out as distant lights (each
  /// costs its shadow rays per receiver), and whether there is a map at all
  /// (its projection is a fixed cost).
  double BrightLights = 0.0, Map = 0.0;
  /// Measured over predicted error and time on this scene, from a check
  /// (Recheck; 1: none). TimeScale scales every prediction, ErrorScale the
  /// errors of the checked candidate's family (CheckFamily; all where
  /// ScaledFamily is -1), OtherErrorScale the other families'.
  double ErrorScale = 1.0, TimeScale = 1.0, OtherErrorScale = 1.0;
  int ScaledFamily = -1;

  /// Receivers, spheres and objects as given, the light's terms from `map`
  /// (nullptr: a uniform sky, both 0).
  void SetLight(const EnvironmentMap* map);
  /// Both light terms from a vtkPGILighting (its map, or its uniform sky).
  bool SetLight(vtkPGILighting* lighting, std::string& error);
};

/// Candidates whose errors a check's surprise carries over to in full: the
/// same route and the same self-shadowing (traced or the rules). Across
/// families it carries over by Model::CheckTransfer.
PROXYGISHADING_EXPORT int CheckFamily(const Knobs& k);
/// In words: "of the CPU filter with traced self-visibility", ...
PROXYGISHADING_EXPORT std::string CheckFamilyName(const Knobs& k);

/// The leaf spheres a candidate shades with on a scene, P of the time law:
/// the proxies' own count where the features have it (a mesh that is a
/// sphere is one sphere, whatever the candidate asks), else the candidate's
/// count per mesh times the meshes.
PROXYGISHADING_EXPORT double ProxySpheres(const SceneFeatures& f, const Knobs& k);

constexpr int NumberOfErrorFeatures = 3;
/// x(scene) of the error model: peak fraction, directionality, log2 objects.
PROXYGISHADING_EXPORT std::array<double, NumberOfErrorFeatures> ErrorFeatures(
  const SceneFeatures& f);

/// One run of one candidate on one scene, against the reference.
struct PROXYGISHADING_EXPORT Measurement
{
  std::string Scene;
  SceneFeatures Features;
  Knobs Settings;
  double Seconds = 0.0; ///< one filter update over every receiver
  double Error = 0.0;   ///< relative RMSE against Embree
  /// The same error as a check estimates it from a cheap Embree run
  /// (EstimatedRelativeRMSE; -1: not measured).
  double CheckError = -1.0;
};

/// Measurements as CSV (one header line), and back.
PROXYGISHADING_EXPORT std::string WriteMeasurements(const std::vector<Measurement>& rows);
PROXYGISHADING_EXPORT bool ReadMeasurements(
  const std::string& text, std::vector<Measurement>& rows, std::string& error);
/// The measurements of CSV files, appended in order. False, with the
/// file's name, for one that cannot be read or parsed.
PROXYGISHADING_EXPORT bool ReadMeasurementFiles(
  const std::vector<std::string>& paths, std::vector<Measurement>& rows, std::string& error);
/// `rows` without the filter's runs of candidates not in `grid` (the
/// mapper's are kept).
PROXYGISHADING_EXPORT std::vector<Measurement> InGrid(
  const std::vector<Measurement>& rows, const std::vector<Knobs>& grid);

class PROXYGISHADING_EXPORT Model
{
public:
  struct Candidate
  {
    Knobs Settings;
    std::array<double, 5> Time{ { 0.0, 0.0, 0.0, 0.0, 0.0 } }; ///< a, m, b, c, d
    double ErrorIntercept = 0.0;                               ///< u_k
    double ErrorObjectsSlope = 0.0;                            ///< v_k, on log2 of the objects
  };
  std::vector<Candidate> Candidates;
  std::array<double, NumberOfErrorFeatures> ErrorWeights{ { 0.0, 0.0, 0.0 } };
  /// The GPU mapper's candidates' own weights: its route keeps a sun in the
  /// SH, so the light's features weigh otherwise than on the filter's.
  std::array<double, NumberOfErrorFeatures> MapperErrorWeights{ { 0.0, 0.0, 0.0 } };
  /// RMS of the fit's log-error residuals: exp(+-spread) brackets ~2/3 of
  /// the scenes.
  double ErrorSpread = 0.0;
  /// How far the check's cheap estimate (Embree at a few samples,
  /// EstimatedRelativeRMSE) may sit below the error it estimates: the 75th
  /// percentile of measured / estimated over the fit's runs (1: none
  /// recorded). A checked run meets an error budget only within it.
  double CheckMargin = 1.0;
  /// How much of a check's log(measured / predicted) error on one family
  /// (CheckFamily) holds for the others: the slope, through 0, of one
  /// family's mean log residual per scene on another's over the fit's
  /// scenes, in [0, 1] (1: none recorded, every candidate scaled alike).
  double CheckTransfer = 1.0;
  std::string Machine; ///< where the times were measured
  /// The GL renderer the GPU mapper's times were measured on (empty: the
  /// model has no mapper candidates).
  std::string MapperRenderer;
  int Scenes = 0; ///< scenes it was fitted on

  bool HasRoute(Route route) const;

  /// Fits every candidate that has measurements on at least two scenes.
  /// False with a message when none has.
  bool Fit(const std::vector<Measurement>& rows, std::string& error);
  double PredictSeconds(std::size_t candidate, const SceneFeatures& f) const;
  double PredictError(std::size_t candidate, const SceneFeatures& f) const;

  std::string Write() const;
  bool Read(const std::string& text, std::string& error);
  bool Save(const std::string& path, std::string& error) const;
  bool Load(const std::string& path, std::string& error);
  /// The model that ships with ProxyGI (fitted on the project's scenes on
  /// its 2-core CI machine, see Documentation/AccuracyTime.md).
  static const Model& Default();
};

/// A budget: relative RMSE against the truth and seconds per filter update,
/// each only where its Has flag is set (a given 0 is a bad budget, not none).
struct PROXYGISHADING_EXPORT Budget
{
  double Error = 0.0;
  double Seconds = 0.0;
  bool HasError = false, HasTime = false;
  bool Any() const { return this->HasError || this->HasTime; }
  void SetError(double fraction)
  {
    this->Error = fraction;
    this->HasError = true;
  }
  void SetSeconds(double seconds)
  {
    this->Seconds = seconds;
    this->HasTime = true;
  }
  /// As the filter's and mappers' SetErrorBudget / SetTimeBudget take
  /// them: each given where it is not 0.
  static Budget FromSetters(double error, double seconds)
  {
    Budget b;
    if (error != 0.0)
    {
      b.SetError(error);
    }
    if (seconds != 0.0)
    {
      b.SetSeconds(seconds);
    }
    return b;
  }
};

struct PROXYGISHADING_EXPORT Choice
{
  int Candidate = -1; ///< index into the model; -1 when the model is empty
  Knobs Settings;
  double PredictedError = 0.0, PredictedSeconds = 0.0;
  bool Met = false;   ///< the prediction meets every budget given
  bool Valid = true;  ///< the budget made sense (> 0, finite)
  std::string Reason; ///< what it chose, why, and what it traded away
};

/**
 * The settings for `budget` on a scene: with an error budget the fastest
 * candidate predicted to meet it; with a time budget the most accurate
 * predicted to fit in it; with both, the fastest that meets both. A budget
 * nothing meets (or a bad one: zero, negative, not finite) gives the closest
 * reachable candidate, Met false and the reason. `allowed` restricts the
 * candidates (a filter cannot change its proxies or self-visibility).
 */
PROXYGISHADING_EXPORT Choice Choose(const Model& model, const SceneFeatures& scene,
  const Budget& budget, const std::function<bool(const Knobs&)>& allowed = {});

/**
 * The check: `ran` was run on the scene and its error (estimated against
 * Embree, EstimatedRelativeRMSE) and time measured. Scales the scene's
 * predictions by measured / predicted (ErrorScale, TimeScale of `scene`)
 * and chooses again.
 */
PROXYGISHADING_EXPORT Choice Recheck(const Model& model, SceneFeatures& scene, const Budget& budget,
  const Choice& ran, double measuredError, double measuredSeconds,
  const std::function<bool(const Knobs&)>& allowed = {});

/// Of two runs measured (error, seconds), the one that serves `budget`
/// better: one that meets it over one that does not; of two that do, the
/// faster for an error budget, the more accurate for a time budget; of two
/// that do not, the more accurate (error budget) or the faster. An error
/// meets the budget when error * errorMargin does (Model::CheckMargin for
/// the check's estimates). True: `a`.
PROXYGISHADING_EXPORT bool FirstServesBetter(const Budget& budget, double errorA, double secondsA,
  double errorB, double secondsB, double errorMargin = 1.0);

/// Whether a GL renderer's name (GL_RENDERER, or a description holding it)
/// is a software rasteriser: llvmpipe, softpipe, swrast ("software").
PROXYGISHADING_EXPORT bool SoftwareRenderer(const std::string& renderer);

/// Whether the model's GPU-mapper times describe `renderer`: the model has
/// mapper candidates measured on the same kind of renderer (software or
/// hardware). False with the reason, which says what to run.
PROXYGISHADING_EXPORT bool MapperTimesApply(
  const Model& model, const std::string& renderer, std::string& why);

/**
 * What a consumer (the filter, a GPU mapper) keeps between its updates to
 * choose its knobs for a budget: the model, read once per file name, and
 * the light's features, computed once per light (a bright-light search and
 * a projection of the map), so an update that moves proxies redoes neither.
 */
class PROXYGISHADING_EXPORT Planner
{
public:
  /**
   * Chooses among the `route`'s candidates with the sphere count nearest to
   * the proxies' leaves per object (and, for the filter, traced
   * self-visibility as the receivers have it or not) for `receivers` points
   * (every rank's, under MPI), and sets the choice on `settings`.
   * `modelFile` empty: the model that ships. `line` is the plan's line.
   * False with `error` when the model or the light cannot be read.
   */
  bool Plan(const std::string& modelFile, Route route, vtkPolyData* proxies, double receivers,
    bool tracedSelf, vtkPGILighting* lighting, const Budget& budget, vtkPGIGISettings* settings,
    Choice& choice, std::string& line, std::string& error);
  const Model& GetModel() const { return this->Used; }

private:
  std::string FileName;
  Model Used;
  bool Loaded = false;
  SceneFeatures LightFeatures;
  const vtkPGILighting* Light = nullptr;
  vtkMTimeType LightTime = 0;
  bool LightKnown = false;
};

/// Parses "5%", "0.05", "16ms", "0.2s". False on anything else.
PROXYGISHADING_EXPORT bool ParseErrorBudget(const std::string& text, double& fraction);
PROXYGISHADING_EXPORT bool ParseTimeBudget(const std::string& text, double& seconds);

} // namespace budget
} // namespace proxygi

#endif
