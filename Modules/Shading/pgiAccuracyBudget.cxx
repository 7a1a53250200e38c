#include "pgiAccuracyBudget.h"

#include "pgiBrightLights.h"
#include "pgiDefaultBudgetModel.h"
#include "pgiEnvironmentMap.h"
#include "vtkPGIGISettings.h"
#include "vtkPGILighting.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace proxygi
{
namespace budget
{
namespace
{
// Units of the time model's terms, so its coefficients are of order one.
constexpr double ReceiverUnit = 1e4, SphereUnit = 1e2;

std::string Percent(double fraction)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f%%", 100.0 * fraction);
  return text;
}

std::string Milliseconds(double seconds)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f ms", 1e3 * seconds);
  return text;
}

// Dense least squares by the normal equations (a few unknowns), with a
// ridge per column (empty: none) so collinear terms stay finite.
bool SolveLeastSquares(const std::vector<std::vector<double>>& rows,
  const std::vector<double>& values, const std::vector<double>& weights, std::size_t unknowns,
  const std::vector<double>& ridge, std::vector<double>& x)
{
  std::vector<double> a(unknowns * unknowns, 0.0), b(unknowns, 0.0);
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    for (std::size_t i = 0; i < unknowns; ++i)
    {
      b[i] += weights[r] * rows[r][i] * values[r];
      for (std::size_t j = 0; j < unknowns; ++j)
      {
        a[i * unknowns + j] += weights[r] * rows[r][i] * rows[r][j];
      }
    }
  }
  for (std::size_t i = 0; i < ridge.size() && i < unknowns; ++i)
  {
    a[i * unknowns + i] += ridge[i];
  }
  // Gaussian elimination with partial pivoting.
  for (std::size_t c = 0; c < unknowns; ++c)
  {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < unknowns; ++r)
    {
      if (std::fabs(a[r * unknowns + c]) > std::fabs(a[pivot * unknowns + c]))
      {
        pivot = r;
      }
    }
    if (!(std::fabs(a[pivot * unknowns + c]) > 1e-300))
    {
      return false;
    }
    if (pivot != c)
    {
      for (std::size_t j = 0; j < unknowns; ++j)
      {
        std::swap(a[c * unknowns + j], a[pivot * unknowns + j]);
      }
      std::swap(b[c], b[pivot]);
    }
    for (std::size_t r = c + 1; r < unknowns; ++r)
    {
      const double f = a[r * unknowns + c] / a[c * unknowns + c];
      for (std::size_t j = c; j < unknowns; ++j)
      {
        a[r * unknowns + j] -= f * a[c * unknowns + j];
      }
      b[r] -= f * b[c];
    }
  }
  x.assign(unknowns, 0.0);
  for (std::size_t c = unknowns; c-- > 0;)
  {
    double s = b[c];
    for (std::size_t j = c + 1; j < unknowns; ++j)
    {
      s -= a[c * unknowns + j] * x[j];
    }
    x[c] = s / a[c * unknowns + c];
  }
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

// vtkPGIGISettings::ExpMethodName's inverse; -1 for no method.
int ExpMethodFromName(const std::string& name)
{
  for (int m = vtkPGIGISettings::EXP_PS; m <= vtkPGIGISettings::EXP_HYB; ++m)
  {
    if (name == vtkPGIGISettings::ExpMethodName(m))
    {
      return m;
    }
  }
  return -1;
}

constexpr int TimeTermCount = 5;
std::array<double, TimeTermCount> TimeTerms(const SceneFeatures& f, const Knobs& k)
{
  const double r = f.Receivers / ReceiverUnit;
  return { { 1.0, f.Map, r, r * ProxySpheres(f, k) / SphereUnit, r * f.BrightLights } };
}

double Evaluate(const std::array<double, TimeTermCount>& c, const SceneFeatures& f, const Knobs& k)
{
  const auto terms = TimeTerms(f, k);
  double t = 0.0;
  for (int i = 0; i < TimeTermCount; ++i)
  {
    t += c[i] * terms[i];
  }
  return t;
}

// The time law with non-negative coefficients, least squares on relative
// error: the best of the subsets of terms whose solution is non-negative.
std::array<double, TimeTermCount> FitTime(const std::vector<const Measurement*>& rows)
{
  std::array<double, TimeTermCount> best{};
  double bestResidual = std::numeric_limits<double>::infinity();
  for (int subset = 1; subset < (1 << TimeTermCount); ++subset)
  {
    std::vector<int> terms;
    for (int t = 0; t < TimeTermCount; ++t)
    {
      if (subset & (1 << t))
      {
        terms.push_back(t);
      }
    }
    std::vector<std::vector<double>> design;
    std::vector<double> values, weights;
    for (const Measurement* m : rows)
    {
      const auto all = TimeTerms(m->Features, m->Settings);
      std::vector<double> row;
      row.reserve(terms.size());
      for (int t : terms)
      {
        row.push_back(all[t]);
      }
      design.push_back(row);
      values.push_back(m->Seconds);
      weights.push_back(1.0 / std::max(1e-6, m->Seconds * m->Seconds));
    }
    std::vector<double> x;
    if (!SolveLeastSquares(design, values, weights, terms.size(), {}, x) ||
      std::any_of(x.begin(), x.end(), [](double v) { return v < 0.0; }))
    {
      continue;
    }
    std::array<double, TimeTermCount> c{};
    for (std::size_t i = 0; i < terms.size(); ++i)
    {
      c[terms[i]] = x[i];
    }
    double residual = 0.0;
    for (const Measurement* m : rows)
    {
      const double e =
        (Evaluate(c, m->Features, m->Settings) - m->Seconds) / std::max(1e-6, m->Seconds);
      residual += e * e;
    }
    // A term whose column is all zero (no map anywhere) solves to 0: the
    // smaller subset wins ties.
    if (residual < bestResidual * (1.0 - 1e-9))
    {
      bestResidual = residual;
      best = c;
    }
  }
  return best;
}

double ObjectsTerm(const SceneFeatures& f)
{
  return std::log2(std::max(1.0, f.Objects));
}
constexpr double SlopeRidge = 0.1, SharedRidge = 1e-3;

bool Finite(double v)
{
  return std::isfinite(v);
}
} // namespace

const char* RouteName(Route route)
{
  return route == Route::Mapper ? "mapper" : "filter";
}

std::string Knobs::Describe() const
{
  std::ostringstream s;
  const bool mapper = this->Backend == Route::Mapper;
  s << (mapper ? "GPU mapper: " : "") << "order " << this->Order;
  if (this->ShadowedIndirect && this->IndirectOrder > 0 && this->IndirectOrder < this->Order)
  {
    s << " (bounce " << this->IndirectOrder << ")";
  }
  s << ", " << this->Spheres << " spheres, "
    << (this->SelfVisibility > 0 ? "traced self-visibility" : "self-shadow rules") << ", "
    << (this->ShadowedIndirect ? "shadowed" : "unshadowed") << " bounce";
  if (!mapper && this->HierarchyAngle != 25.0)
  {
    s << ", hierarchy " << this->HierarchyAngle << " deg";
  }
  const Knobs defaults;
  if (this->ExpMethod != defaults.ExpMethod)
  {
    s << ", exp " << vtkPGIGISettings::ExpMethodName(this->ExpMethod);
  }
  if (this->Blocking != defaults.Blocking)
  {
    s << ", per-object blocking";
  }
  if (this->BrightLightRays != defaults.BrightLightRays)
  {
    s << ", " << this->BrightLightRays << " rays per bright light";
  }
  return s.str();
}

void Knobs::Apply(vtkPGIGISettings* settings) const
{
  settings->SetOrder(this->Order);
  settings->SetIndirectOrder(this->IndirectOrder);
  settings->SetIndirectMode(this->ShadowedIndirect ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
                                                   : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  settings->SetHierarchyAngle(this->HierarchyAngle);
  settings->SetExpMethod(this->ExpMethod);
  settings->SetSphericalLightBlocking(this->Blocking);
  settings->SetBrightLightRays(this->BrightLightRays);
}

bool Knobs::operator==(const Knobs& o) const
{
  return this->Order == o.Order && this->IndirectOrder == o.IndirectOrder &&
    this->Spheres == o.Spheres && this->SelfVisibility == o.SelfVisibility &&
    this->ShadowedIndirect == o.ShadowedIndirect && this->HierarchyAngle == o.HierarchyAngle &&
    this->Backend == o.Backend && this->ExpMethod == o.ExpMethod && this->Blocking == o.Blocking &&
    this->BrightLightRays == o.BrightLightRays;
}

std::vector<Knobs> DefaultGrid()
{
  std::vector<Knobs> grid;
  for (int order : { 3, 4, 6, 8 })
  {
    for (int spheres : { 16, 64 })
    {
      for (int self : { 0, 256 })
      {
        for (bool shadowed : { false, true })
        {
          Knobs k;
          k.Order = order;
          k.IndirectOrder = std::min(order, 4);
          k.Spheres = spheres;
          k.SelfVisibility = self;
          k.ShadowedIndirect = shadowed;
          grid.push_back(k);
        }
      }
    }
  }
  return grid;
}

// Knobs' defaults are the settings' (the header does not include them).
static_assert(Knobs().ExpMethod == vtkPGIGISettings::EXP_HYB &&
    Knobs().Blocking == vtkPGIGISettings::BLOCKING_PER_SPHERE,
  "Knobs' defaults");

std::vector<Knobs> VariationGrid()
{
  std::vector<Knobs> grid;
  for (const Knobs& base : DefaultGrid())
  {
    if ((base.Order != 4 && base.Order != 6) || base.SelfVisibility == 0)
    {
      continue;
    }
    for (double angle : { 0.0, 45.0 })
    {
      Knobs k = base;
      k.HierarchyAngle = angle;
      grid.push_back(k);
    }
    for (int method : { vtkPGIGISettings::EXP_OL, vtkPGIGISettings::EXP_PS_STAR })
    {
      Knobs k = base;
      k.ExpMethod = method;
      grid.push_back(k);
    }
    if (base.ShadowedIndirect)
    {
      Knobs k = base;
      k.Blocking = vtkPGIGISettings::BLOCKING_PER_OBJECT;
      grid.push_back(k);
    }
    for (int rays : { 4, 64 })
    {
      Knobs k = base;
      k.BrightLightRays = rays;
      grid.push_back(k);
    }
  }
  return grid;
}

std::vector<Knobs> TradeGrid()
{
  std::vector<Knobs> grid;
  for (const Knobs& k : VariationGrid())
  {
    if (k.HierarchyAngle == 45.0 || k.BrightLightRays == 4)
    {
      grid.push_back(k);
    }
  }
  return grid;
}

bool NamedGrids(const std::vector<std::string>& names, std::vector<Knobs>& grid, std::string& error)
{
  grid.clear();
  error = names.empty() ? "no grid named" : "";
  for (const std::string& name : names)
  {
    const std::vector<Knobs> some = name == "default" ? DefaultGrid()
      : name == "trades"                              ? TradeGrid()
      : name == "variations"                          ? VariationGrid()
                                                      : std::vector<Knobs>();
    if (some.empty())
    {
      error = "unknown grid '" + name + "' (default, trades, variations)";
      return false;
    }
    for (const Knobs& k : some)
    {
      if (std::find(grid.begin(), grid.end(), k) == grid.end())
      {
        grid.push_back(k);
      }
    }
  }
  return !grid.empty();
}

bool ReadMeasurementFiles(
  const std::vector<std::string>& paths, std::vector<Measurement>& rows, std::string& error)
{
  for (const std::string& path : paths)
  {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::vector<Measurement> some;
    if (!in)
    {
      error = path + ": cannot read";
      return false;
    }
    if (!ReadMeasurements(text.str(), some, error))
    {
      error.insert(0, path + ": ");
      return false;
    }
    rows.insert(rows.end(), some.begin(), some.end());
  }
  return true;
}

std::vector<Measurement> InGrid(
  const std::vector<Measurement>& rows, const std::vector<Knobs>& grid)
{
  std::vector<Measurement> kept;
  for (const Measurement& m : rows)
  {
    if (m.Settings.Backend == Route::Mapper ||
      std::find(grid.begin(), grid.end(), m.Settings) != grid.end())
    {
      kept.push_back(m);
    }
  }
  return kept;
}

std::vector<Knobs> MapperGrid()
{
  std::vector<Knobs> grid;
  for (int order : { 3, 4, 6 })
  {
    for (int spheres : { 16, 64 })
    {
      for (bool shadowed : { false, true })
      {
        Knobs k;
        k.Backend = Route::Mapper;
        k.Order = order;
        k.IndirectOrder = 0;
        k.Spheres = spheres;
        k.SelfVisibility = 0;
        k.ShadowedIndirect = shadowed;
        k.HierarchyAngle = 0.0;
        grid.push_back(k);
      }
    }
  }
  return grid;
}

void SceneFeatures::SetLight(const EnvironmentMap* map)
{
  this->PeakFraction = 0.0;
  this->Directionality = 0.0;
  this->BrightLights = 0.0;
  this->Map = map ? 1.0 : 0.0;
  if (!map)
  {
    return;
  }
  BrightLightResult bright;
  ExtractBrightLights(*map, BrightLightOptions(), bright);
  this->PeakFraction = bright.BrightestFraction;
  this->BrightLights = static_cast<double>(bright.Lights.size());
  double r[9], g[9], b[9];
  map->ProjectSH(3, r, g, b);
  double y[9];
  for (int i = 0; i < 9; ++i)
  {
    y[i] = 0.2126 * r[i] + 0.7152 * g[i] + 0.0722 * b[i];
  }
  double higher = 0.0;
  for (int i = 1; i < 9; ++i)
  {
    higher += y[i] * y[i];
  }
  this->Directionality = std::fabs(y[0]) > 0.0 ? std::sqrt(higher) / std::fabs(y[0]) : 0.0;
}

bool SceneFeatures::SetLight(vtkPGILighting* lighting, std::string& error)
{
  if (!lighting)
  {
    error = "no lighting";
    return false;
  }
  const bool hasMap = lighting->GetEnvironmentImage() ||
    (lighting->GetEnvironmentFileName() && *lighting->GetEnvironmentFileName());
  if (!hasMap)
  {
    this->SetLight(nullptr);
    return true;
  }
  const EnvironmentMap* map = nullptr;
  if (!lighting->GetEnvironment(map, error) || !map)
  {
    return false;
  }
  this->SetLight(map);
  return true;
}

std::array<double, NumberOfErrorFeatures> ErrorFeatures(const SceneFeatures& f)
{
  return { { f.PeakFraction, f.Directionality, std::log2(std::max(1.0, f.Objects)) } };
}

std::string WriteMeasurements(const std::vector<Measurement>& rows)
{
  std::ostringstream s;
  s.precision(9);
  s << "scene,receivers,spheres_total,objects,peak_fraction,directionality,order,indirect_order,"
       "spheres,self_visibility,shadowed_indirect,hierarchy_angle,seconds,error,bright_lights,map,"
       "check_error,route,exp_method,blocking,bright_light_rays\n";
  for (const Measurement& m : rows)
  {
    std::string scene = m.Scene;
    std::replace(scene.begin(), scene.end(), ',', ';');
    s << scene << "," << m.Features.Receivers << "," << m.Features.Spheres << ","
      << m.Features.Objects << "," << m.Features.PeakFraction << "," << m.Features.Directionality
      << "," << m.Settings.Order << "," << m.Settings.IndirectOrder << "," << m.Settings.Spheres
      << "," << m.Settings.SelfVisibility << "," << (m.Settings.ShadowedIndirect ? 1 : 0) << ","
      << m.Settings.HierarchyAngle << "," << m.Seconds << "," << m.Error << ","
      << m.Features.BrightLights << "," << m.Features.Map << "," << m.CheckError << ","
      << RouteName(m.Settings.Backend) << ","
      << vtkPGIGISettings::ExpMethodName(m.Settings.ExpMethod) << "," << m.Settings.Blocking << ","
      << m.Settings.BrightLightRays << "\n";
  }
  return s.str();
}

bool ReadMeasurements(const std::string& text, std::vector<Measurement>& rows, std::string& error)
{
  std::istringstream in(text);
  std::string line;
  int number = 0;
  rows.clear();
  while (std::getline(in, line))
  {
    ++number;
    if (number == 1 || line.empty())
    {
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream cellStream(line);
    std::string cell;
    while (std::getline(cellStream, cell, ','))
    {
      cells.push_back(cell);
    }
    // 17 fields: written before the route column (the filter's runs); 18:
    // before the exp method, blocking and bright-light rays (their defaults).
    const bool route = cells.size() >= 18, knobs = cells.size() == 21;
    const int method = knobs ? ExpMethodFromName(cells[18]) : Knobs().ExpMethod;
    if ((cells.size() != 17 && cells.size() != 18 && !knobs) ||
      (route && cells[17] != RouteName(Route::Filter) && cells[17] != RouteName(Route::Mapper)) ||
      method < 0)
    {
      error = "line " + std::to_string(number) +
        ": 17, 18 or 21 fields expected (the 18th: " + RouteName(Route::Filter) + " or " +
        RouteName(Route::Mapper) + "; the 19th an exp method: PS, PS*, OL, HYB)";
      return false;
    }
    Measurement m;
    try
    {
      m.Scene = cells[0];
      m.Features.Receivers = std::stod(cells[1]);
      m.Features.Spheres = std::stod(cells[2]);
      m.Features.Objects = std::stod(cells[3]);
      m.Features.PeakFraction = std::stod(cells[4]);
      m.Features.Directionality = std::stod(cells[5]);
      m.Settings.Order = std::stoi(cells[6]);
      m.Settings.IndirectOrder = std::stoi(cells[7]);
      m.Settings.Spheres = std::stoi(cells[8]);
      m.Settings.SelfVisibility = std::stoi(cells[9]);
      m.Settings.ShadowedIndirect = std::stoi(cells[10]) != 0;
      m.Settings.HierarchyAngle = std::stod(cells[11]);
      m.Seconds = std::stod(cells[12]);
      m.Error = std::stod(cells[13]);
      m.Features.BrightLights = std::stod(cells[14]);
      m.Features.Map = std::stod(cells[15]);
      m.CheckError = std::stod(cells[16]);
      m.Settings.Backend =
        route && cells[17] == RouteName(Route::Mapper) ? Route::Mapper : Route::Filter;
      m.Settings.ExpMethod = method;
      if (knobs)
      {
        m.Settings.Blocking = std::stoi(cells[19]);
        m.Settings.BrightLightRays = std::stoi(cells[20]);
      }
    }
    catch (const std::exception&)
    {
      error = "line " + std::to_string(number) + ": not a number";
      return false;
    }
    rows.push_back(m);
  }
  return true;
}

bool Model::Fit(const std::vector<Measurement>& rows, std::string& error)
{
  // Candidates in first-seen order, with their usable rows.
  std::vector<Knobs> knobs;
  std::vector<std::vector<const Measurement*>> byCandidate;
  std::set<std::string> scenes;
  for (const Measurement& m : rows)
  {
    if (!(m.Seconds > 0.0) || !(m.Error > 0.0) || !Finite(m.Seconds) || !Finite(m.Error))
    {
      continue;
    }
    auto it = std::find(knobs.begin(), knobs.end(), m.Settings);
    if (it == knobs.end())
    {
      knobs.push_back(m.Settings);
      byCandidate.emplace_back();
      it = knobs.end() - 1;
    }
    byCandidate[it - knobs.begin()].push_back(&m);
    scenes.insert(m.Scene);
  }
  std::vector<Candidate> fitted;
  std::vector<const Measurement*> used;
  std::vector<std::size_t> usedCandidate;
  for (std::size_t k = 0; k < knobs.size(); ++k)
  {
    std::set<std::string> own;
    for (const Measurement* m : byCandidate[k])
    {
      own.insert(m->Scene);
    }
    if (own.size() < 2)
    {
      continue;
    }
    Candidate c;
    c.Settings = knobs[k];
    c.Time = FitTime(byCandidate[k]);
    for (const Measurement* m : byCandidate[k])
    {
      used.push_back(m);
      usedCandidate.push_back(fitted.size());
    }
    fitted.push_back(c);
  }
  if (fitted.empty())
  {
    error = "no candidate has measurements on two scenes or more";
    return false;
  }
  // log e = u_k + v_k log2(objects) + w . x: K intercepts, K slopes (how a
  // candidate fares as objects shadow each other: fewer spheres do better
  // there, more on one object), then the weights each route's candidates
  // share (filter, mapper). The ridge pulls the slopes towards the shared one.
  const std::size_t count = fitted.size();
  const std::size_t unknowns = 2 * count + 2 * NumberOfErrorFeatures;
  const auto weightsAt = [&](std::size_t k)
  {
    return 2 * count +
      (fitted[k].Settings.Backend == Route::Mapper ? NumberOfErrorFeatures : std::size_t(0));
  };
  std::vector<std::vector<double>> design;
  std::vector<double> values, weights;
  for (std::size_t r = 0; r < used.size(); ++r)
  {
    std::vector<double> row(unknowns, 0.0);
    row[usedCandidate[r]] = 1.0;
    row[count + usedCandidate[r]] = ObjectsTerm(used[r]->Features);
    const auto x = ErrorFeatures(used[r]->Features);
    std::copy(x.begin(), x.end(), row.begin() + weightsAt(usedCandidate[r]));
    design.push_back(row);
    values.push_back(std::log(used[r]->Error));
    weights.push_back(1.0);
  }
  std::vector<double> solution;
  std::vector<double> ridge(unknowns, SharedRidge);
  std::fill(ridge.begin(), ridge.begin() + count, 0.0);
  std::fill(ridge.begin() + count, ridge.begin() + 2 * count, SlopeRidge);
  if (!SolveLeastSquares(design, values, weights, unknowns, ridge, solution))
  {
    error = "the error model's least squares has no solution";
    return false;
  }
  for (std::size_t k = 0; k < count; ++k)
  {
    fitted[k].ErrorIntercept = solution[k];
    fitted[k].ErrorObjectsSlope = solution[count + k];
  }
  for (int j = 0; j < NumberOfErrorFeatures; ++j)
  {
    this->ErrorWeights[j] = solution[2 * count + j];
    this->MapperErrorWeights[j] = solution[2 * count + NumberOfErrorFeatures + j];
  }
  this->Candidates = fitted;
  double sum = 0.0;
  for (std::size_t r = 0; r < used.size(); ++r)
  {
    const double e =
      std::log(this->PredictError(usedCandidate[r], used[r]->Features)) - std::log(used[r]->Error);
    sum += e * e;
  }
  this->ErrorSpread = std::sqrt(sum / std::max<std::size_t>(1, used.size()));
  // The check's transfer: each scene's mean log residual per family, and
  // the slope of one family's on another's over the scenes with both.
  std::map<std::string, std::map<int, std::pair<double, int>>> residuals;
  for (std::size_t r = 0; r < used.size(); ++r)
  {
    auto& cell =
      residuals[used[r]->Scene][CheckFamily(this->Candidates[usedCandidate[r]].Settings)];
    cell.first +=
      std::log(used[r]->Error / this->PredictError(usedCandidate[r], used[r]->Features));
    ++cell.second;
  }
  double xy = 0.0, xx = 0.0;
  int pairs = 0;
  for (const auto& scene : residuals)
  {
    for (const auto& a : scene.second)
    {
      for (const auto& b : scene.second)
      {
        if (a.first != b.first)
        {
          const double x = a.second.first / a.second.second;
          xy += x * (b.second.first / b.second.second);
          xx += x * x;
          ++pairs;
        }
      }
    }
  }
  this->CheckTransfer = pairs >= 6 && xx > 0.0 ? std::clamp(xy / xx, 0.0, 1.0) : 1.0;
  // The check's estimate has its own error (the cheap run's noise is known
  // to a few percent, and it is most of the sum at a few samples).
  std::vector<double> underestimate;
  for (const Measurement& m : rows)
  {
    if (m.CheckError > 0.0 && m.Error > 0.0 && Finite(m.CheckError))
    {
      underestimate.push_back(m.Error / m.CheckError);
    }
  }
  this->CheckMargin = 1.0;
  if (underestimate.size() >= 8)
  {
    const auto at = underestimate.begin() + (3 * (underestimate.size() - 1)) / 4;
    std::nth_element(underestimate.begin(), at, underestimate.end());
    this->CheckMargin = std::clamp(*at, 1.0, 1.5);
  }
  this->Scenes = static_cast<int>(scenes.size());
  return true;
}

int CheckFamily(const Knobs& k)
{
  return 2 * static_cast<int>(k.Backend) + (k.SelfVisibility > 0 ? 1 : 0);
}

std::string CheckFamilyName(const Knobs& k)
{
  return std::string(k.Backend == Route::Mapper ? "of the GPU mapper" : "of the CPU filter") +
    (k.SelfVisibility > 0 ? " with traced self-visibility" : " with the self-shadow rules");
}

double ProxySpheres(const SceneFeatures& f, const Knobs& k)
{
  return f.Spheres > 0.0 ? f.Spheres : k.Spheres * std::max(1.0, f.Objects);
}

double Model::PredictSeconds(std::size_t k, const SceneFeatures& f) const
{
  return f.TimeScale * Evaluate(this->Candidates[k].Time, f, this->Candidates[k].Settings);
}

double Model::PredictError(std::size_t k, const SceneFeatures& f) const
{
  const auto x = ErrorFeatures(f);
  double s =
    this->Candidates[k].ErrorIntercept + this->Candidates[k].ErrorObjectsSlope * ObjectsTerm(f);
  for (int j = 0; j < NumberOfErrorFeatures; ++j)
  {
    s += (this->Candidates[k].Settings.Backend == Route::Mapper ? this->MapperErrorWeights
                                                                : this->ErrorWeights)[j] *
      x[j];
  }
  const bool scaled =
    f.ScaledFamily < 0 || CheckFamily(this->Candidates[k].Settings) == f.ScaledFamily;
  return (scaled ? f.ErrorScale : f.OtherErrorScale) * std::exp(s);
}

std::string Model::Write() const
{
  std::ostringstream s;
  s.precision(9);
  s << "# ProxyGI accuracy budget model (proxygi calibrate)\n"
    << "version 2\n"
    << "machine " << (this->Machine.empty() ? "unknown" : this->Machine) << "\n";
  if (!this->MapperRenderer.empty())
  {
    s << "mapper_renderer " << this->MapperRenderer << "\n";
  }
  s << "scenes " << this->Scenes << "\n"
    << "error_weights";
  for (double w : this->ErrorWeights)
  {
    s << " " << w;
  }
  if (this->HasRoute(Route::Mapper))
  {
    s << "\nmapper_error_weights";
    for (double w : this->MapperErrorWeights)
    {
      s << " " << w;
    }
  }
  s << "\nerror_spread " << this->ErrorSpread << "\n";
  if (this->CheckMargin != 1.0)
  {
    s << "check_margin " << this->CheckMargin << "\n";
  }
  if (this->CheckTransfer != 1.0)
  {
    s << "check_transfer " << this->CheckTransfer << "\n";
  }
  s << "# order indirect_order spheres self_visibility shadowed hierarchy | a m b c d (s) | u v "
       "| route [exp=M] [blocking=object] [bright_rays=N] (knobs off their defaults)\n";
  for (const Candidate& c : this->Candidates)
  {
    const Knobs& k = c.Settings;
    s << "candidate " << k.Order << " " << k.IndirectOrder << " " << k.Spheres << " "
      << k.SelfVisibility << " " << (k.ShadowedIndirect ? 1 : 0) << " " << k.HierarchyAngle << " "
      << c.Time[0] << " " << c.Time[1] << " " << c.Time[2] << " " << c.Time[3] << " " << c.Time[4]
      << " " << c.ErrorIntercept << " " << c.ErrorObjectsSlope << " " << RouteName(k.Backend);
    const Knobs defaults;
    if (k.ExpMethod != defaults.ExpMethod)
    {
      s << " exp=" << vtkPGIGISettings::ExpMethodName(k.ExpMethod);
    }
    if (k.Blocking != defaults.Blocking)
    {
      s << " blocking=object";
    }
    if (k.BrightLightRays != defaults.BrightLightRays)
    {
      s << " bright_rays=" << k.BrightLightRays;
    }
    s << "\n";
  }
  return s.str();
}

bool Model::Read(const std::string& text, std::string& error)
{
  Model m;
  std::istringstream in(text);
  std::string line;
  bool version = false;
  int number = 0;
  while (std::getline(in, line))
  {
    ++number;
    if (line.empty() || line[0] == '#')
    {
      continue;
    }
    std::istringstream words(line);
    std::string key;
    words >> key;
    bool ok = true;
    if (key == "version")
    {
      int v = 0;
      ok = static_cast<bool>(words >> v) && v == 2;
      version = ok;
    }
    else if (key == "machine")
    {
      std::getline(words >> std::ws, m.Machine);
    }
    else if (key == "mapper_renderer")
    {
      std::getline(words >> std::ws, m.MapperRenderer);
    }
    else if (key == "scenes")
    {
      ok = static_cast<bool>(words >> m.Scenes);
    }
    else if (key == "error_weights")
    {
      for (double& w : m.ErrorWeights)
      {
        ok = ok && static_cast<bool>(words >> w) && Finite(w);
      }
    }
    else if (key == "mapper_error_weights")
    {
      for (double& w : m.MapperErrorWeights)
      {
        ok = ok && static_cast<bool>(words >> w) && Finite(w);
      }
    }
    else if (key == "error_spread")
    {
      ok = static_cast<bool>(words >> m.ErrorSpread) && Finite(m.ErrorSpread);
    }
    else if (key == "check_transfer")
    {
      ok = static_cast<bool>(words >> m.CheckTransfer) && m.CheckTransfer >= 0.0 &&
        m.CheckTransfer <= 1.0;
    }
    else if (key == "check_margin")
    {
      ok =
        static_cast<bool>(words >> m.CheckMargin) && m.CheckMargin >= 1.0 && m.CheckMargin <= 2.0;
    }
    else if (key == "candidate")
    {
      Candidate c;
      int shadowed = 0;
      ok = static_cast<bool>(words >> c.Settings.Order >> c.Settings.IndirectOrder >>
             c.Settings.Spheres >> c.Settings.SelfVisibility >> shadowed >>
             c.Settings.HierarchyAngle >> c.Time[0] >> c.Time[1] >> c.Time[2] >> c.Time[3] >>
             c.Time[4] >> c.ErrorIntercept >> c.ErrorObjectsSlope) &&
        c.Settings.Order >= 2 && c.Settings.Order <= 8 && c.Settings.Spheres > 0 &&
        std::all_of(c.Time.begin(), c.Time.end(), [](double t) { return t >= 0.0 && Finite(t); }) &&
        Finite(c.ErrorIntercept) && Finite(c.ErrorObjectsSlope);
      c.Settings.ShadowedIndirect = shadowed != 0;
      // Without a route word: a filter candidate (models written before).
      std::string route;
      if (ok && words >> route)
      {
        ok = route == RouteName(Route::Filter) ||
          (route == RouteName(Route::Mapper) && c.Settings.Order <= 6);
        c.Settings.Backend = route == RouteName(Route::Mapper) ? Route::Mapper : Route::Filter;
      }
      // Then the knobs off their defaults.
      std::string knob;
      while (ok && words >> knob)
      {
        const std::size_t eq = knob.find('=');
        const std::string name = knob.substr(0, eq),
                          value = eq == std::string::npos ? "" : knob.substr(eq + 1);
        if (name == "exp")
        {
          c.Settings.ExpMethod = ExpMethodFromName(value);
          ok = c.Settings.ExpMethod >= 0;
        }
        else if (name == "blocking")
        {
          c.Settings.Blocking = vtkPGIGISettings::BLOCKING_PER_OBJECT;
          ok = value == "object";
        }
        else if (name == "bright_rays")
        {
          c.Settings.BrightLightRays = std::atoi(value.c_str());
          ok = c.Settings.BrightLightRays >= 1 && c.Settings.BrightLightRays <= 256;
        }
        else
        {
          ok = false;
        }
      }
      m.Candidates.push_back(c);
    }
    else
    {
      ok = false;
    }
    if (!ok)
    {
      error = "budget model, line " + std::to_string(number) + ": cannot read '" + line + "'";
      return false;
    }
  }
  if (!version || m.Candidates.empty())
  {
    error = "not a budget model (version 2 with candidates expected)";
    return false;
  }
  *this = m;
  return true;
}

bool Model::Save(const std::string& path, std::string& error) const
{
  std::ofstream out(path);
  out << this->Write();
  if (!out)
  {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

bool Model::Load(const std::string& path, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot read " + path;
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  return this->Read(text.str(), error) || (error = path + ": " + error, false);
}

bool Model::HasRoute(Route route) const
{
  return std::any_of(this->Candidates.begin(), this->Candidates.end(),
    [route](const Candidate& c) { return c.Settings.Backend == route; });
}

const Model& Model::Default()
{
  static const Model model = []()
  {
    Model m;
    std::string error;
    m.Read(pgiDefaultBudgetModel, error);
    return m;
  }();
  return model;
}

Choice Choose(const Model& model, const SceneFeatures& scene, const Budget& budget,
  const std::function<bool(const Knobs&)>& allowed)
{
  Choice choice;
  std::vector<std::size_t> ks;
  for (std::size_t k = 0; k < model.Candidates.size(); ++k)
  {
    if (!allowed || allowed(model.Candidates[k].Settings))
    {
      ks.push_back(k);
    }
  }
  if (ks.empty())
  {
    choice.Valid = false;
    choice.Reason = "the budget model has no candidate for these inputs";
    return choice;
  }
  std::vector<double> error(model.Candidates.size()), seconds(model.Candidates.size());
  std::size_t fastest = ks[0], mostAccurate = ks[0];
  for (std::size_t k : ks)
  {
    error[k] = model.PredictError(k, scene);
    seconds[k] = model.PredictSeconds(k, scene);
    fastest = seconds[k] < seconds[fastest] ? k : fastest;
    mostAccurate = error[k] < error[mostAccurate] ? k : mostAccurate;
  }
  const bool hasError = budget.HasError, hasTime = budget.HasTime;
  std::string problem;
  if (hasError && !(budget.Error > 0.0 && Finite(budget.Error)))
  {
    problem = "an error budget must be a positive fraction (5% or 0.05)";
  }
  if (hasTime && !(budget.Seconds > 0.0 && Finite(budget.Seconds)))
  {
    problem += std::string(problem.empty() ? "" : "; ") + "a time budget must be positive";
  }
  const double errorCap = hasError ? budget.Error : std::numeric_limits<double>::infinity();
  const double timeCap = hasTime ? budget.Seconds : std::numeric_limits<double>::infinity();

  std::ostringstream why;
  std::size_t chosen = ks[0];
  if (!problem.empty() || !budget.Any())
  {
    // Closest reachable: the most accurate for a bad error budget, the
    // fastest for a bad time budget.
    choice.Valid = budget.Any() ? false : true;
    chosen = (hasError && !(budget.Error > 0.0 && Finite(budget.Error))) ? mostAccurate
      : hasTime                                                          ? fastest
                                                                         : mostAccurate;
    why << (problem.empty() ? "no budget given" : problem) << ": the "
        << (chosen == fastest ? "fastest" : "most accurate") << " candidate instead";
  }
  else
  {
    // Fastest among those meeting both; with a time budget only, the most
    // accurate that fits in it.
    int best = -1;
    for (std::size_t k : ks)
    {
      if (error[k] > errorCap || seconds[k] > timeCap)
      {
        continue;
      }
      const bool better = best < 0 ||
        (hasError
            ? seconds[k] < seconds[best]
            : (error[k] < error[best] || (error[k] == error[best] && seconds[k] < seconds[best])));
      best = better ? static_cast<int>(k) : best;
    }
    if (best >= 0)
    {
      chosen = static_cast<std::size_t>(best);
      choice.Met = true;
      why << (hasError ? "the fastest predicted to stay within " + Percent(budget.Error)
                       : "the most accurate predicted to fit in " + Milliseconds(budget.Seconds));
      if (hasError && hasTime)
      {
        why << " and " << Milliseconds(budget.Seconds);
      }
    }
    else if (hasTime && seconds[fastest] > timeCap)
    {
      chosen = fastest;
      why << "no candidate is predicted to fit in " << Milliseconds(budget.Seconds)
          << ": the fastest instead";
    }
    else
    {
      // The error budget is out of reach (within the time budget, if any).
      int best2 = -1;
      for (std::size_t k : ks)
      {
        if (seconds[k] <= timeCap && (best2 < 0 || error[k] < error[best2]))
        {
          best2 = static_cast<int>(k);
        }
      }
      chosen = static_cast<std::size_t>(best2);
      why << "no candidate" << (hasTime ? " that fits in " + Milliseconds(budget.Seconds) : "")
          << " is predicted to stay within " << Percent(budget.Error)
          << ": the most accurate instead";
    }
  }
  choice.Candidate = static_cast<int>(chosen);
  choice.Settings = model.Candidates[chosen].Settings;
  choice.PredictedError = error[chosen];
  choice.PredictedSeconds = seconds[chosen];
  why << "; traded away: ";
  if (chosen == mostAccurate)
  {
    why << "nothing in accuracy";
  }
  else
  {
    char points[32];
    std::snprintf(points, sizeof(points), "%.1f", 100.0 * (error[chosen] - error[mostAccurate]));
    why << points << " points of error against the most accurate (" << Percent(error[mostAccurate])
        << " in " << Milliseconds(seconds[mostAccurate]) << ")";
  }
  if (chosen != fastest)
  {
    why << ", " << Milliseconds(seconds[chosen] - seconds[fastest]) << " against the fastest ("
        << Milliseconds(seconds[fastest]) << ", " << Percent(error[fastest]) << ")";
  }
  choice.Reason = why.str();
  return choice;
}

Choice Recheck(const Model& model, SceneFeatures& scene, const Budget& budget, const Choice& ran,
  double measuredError, double measuredSeconds, const std::function<bool(const Knobs&)>& allowed)
{
  if (measuredError > 0.0 && ran.PredictedError > 0.0 && Finite(measuredError))
  {
    // A knob that fails on this scene's meshes (the rules on thin limbs)
    // says less about the other families than about its own.
    const double ratio = measuredError / ran.PredictedError;
    if (scene.ScaledFamily < 0)
    {
      scene.OtherErrorScale = scene.ErrorScale;
    }
    scene.ScaledFamily = CheckFamily(ran.Settings);
    scene.ErrorScale *= ratio;
    scene.OtherErrorScale *= std::pow(ratio, model.CheckTransfer);
  }
  if (measuredSeconds > 0.0 && ran.PredictedSeconds > 0.0 && Finite(measuredSeconds))
  {
    scene.TimeScale *= measuredSeconds / ran.PredictedSeconds;
  }
  return Choose(model, scene, budget, allowed);
}

bool FirstServesBetter(const Budget& budget, double errorA, double secondsA, double errorB,
  double secondsB, double errorMargin)
{
  const auto meets = [&](double e, double t)
  {
    return (!budget.HasError || e * errorMargin <= budget.Error) &&
      (!budget.HasTime || t <= budget.Seconds);
  };
  const bool a = meets(errorA, secondsA), b = meets(errorB, secondsB);
  if (a != b)
  {
    return a;
  }
  if (a)
  {
    return budget.HasError ? secondsA <= secondsB : errorA <= errorB;
  }
  return budget.HasError ? errorA <= errorB : secondsA <= secondsB;
}

namespace
{
// A number and one of `units` (name, scale); no unit means scale 1.
bool ParseScaled(const std::string& text,
  std::initializer_list<std::pair<const char*, double>> units, double& value)
{
  value = 0.0;
  try
  {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    const std::string unit = text.substr(used);
    double scale = unit.empty() ? 1.0 : 0.0;
    for (const auto& u : units)
    {
      scale = unit == u.first ? u.second : scale;
    }
    value = v * scale;
    return scale != 0.0 && Finite(v);
  }
  catch (const std::exception&)
  {
    return false;
  }
}
} // namespace

bool SoftwareRenderer(const std::string& renderer)
{
  std::string lower = renderer;
  std::transform(lower.begin(), lower.end(), lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("llvmpipe") != std::string::npos ||
    lower.find("softpipe") != std::string::npos || lower.find("swrast") != std::string::npos ||
    lower.find("software") != std::string::npos;
}

bool MapperTimesApply(const Model& model, const std::string& renderer, std::string& why)
{
  if (!model.HasRoute(Route::Mapper))
  {
    why = "the budget model has no GPU-mapper candidates ('proxygi calibrate --routes "
          "filter,mapper' measures them)";
    return false;
  }
  if (SoftwareRenderer(model.MapperRenderer) != SoftwareRenderer(renderer))
  {
    why = "the budget model's GPU-mapper times were measured on " +
      (model.MapperRenderer.empty() ? std::string("an unnamed renderer") : model.MapperRenderer) +
      ", not on this kind of renderer (" + renderer +
      "): 'proxygi calibrate --routes filter,mapper' measures them here";
    return false;
  }
  why.clear();
  return true;
}

bool Planner::Plan(const std::string& modelFile, Route route, vtkPolyData* proxies,
  double receivers, bool tracedSelf, vtkPGILighting* lighting, const Budget& budget,
  vtkPGIGISettings* settings, Choice& choice, std::string& line, std::string& error)
{
  if (!this->Loaded || this->FileName != modelFile)
  {
    this->Used = Model::Default();
    if (!modelFile.empty() && !this->Used.Load(modelFile, error))
    {
      this->Loaded = false;
      error = "Budget model: " + error;
      return false;
    }
    this->FileName = modelFile;
    this->Loaded = true;
  }
  SceneFeatures features;
  features.Receivers = receivers;
  // Spheres per object from the leaves (Level 0, or all without levels).
  vtkDataArray* level = proxies ? proxies->GetPointData()->GetArray("Level") : nullptr;
  vtkDataArray* object = proxies ? proxies->GetPointData()->GetArray("ObjectId") : nullptr;
  std::set<long long> objects;
  double leaves = 0.0;
  for (vtkIdType i = 0; proxies && i < proxies->GetNumberOfPoints(); ++i)
  {
    if (!level || level->GetComponent(i, 0) == 0.0)
    {
      leaves += 1.0;
      objects.insert(object ? static_cast<long long>(object->GetComponent(i, 0)) : 0);
    }
  }
  features.Objects = std::max<double>(1.0, static_cast<double>(objects.size()));
  features.Spheres = leaves;
  vtkImageData* image = lighting ? lighting->GetEnvironmentImage() : nullptr;
  const vtkMTimeType lightTime =
    !lighting ? 0 : std::max(lighting->GetMTime(), image ? image->GetMTime() : vtkMTimeType(0));
  if (!this->LightKnown || this->Light != lighting || this->LightTime != lightTime)
  {
    // No lighting: the consumers' uniform white sky.
    if (!lighting)
    {
      this->LightFeatures.SetLight(static_cast<const EnvironmentMap*>(nullptr));
    }
    else if (!this->LightFeatures.SetLight(lighting, error))
    {
      this->LightKnown = false;
      error = "Budget: " + error;
      return false;
    }
    this->Light = lighting;
    this->LightTime = lightTime;
    this->LightKnown = true;
  }
  features.PeakFraction = this->LightFeatures.PeakFraction;
  features.Directionality = this->LightFeatures.Directionality;
  features.BrightLights = this->LightFeatures.BrightLights;
  features.Map = this->LightFeatures.Map;
  const Model& model = this->Used;
  const double perObject = leaves / features.Objects;
  // The route's sphere count nearest to the proxies' (in ratio).
  double nearest = 0.0;
  for (const auto& c : model.Candidates)
  {
    const double d = std::fabs(std::log(c.Settings.Spheres / std::max(1.0, perObject)));
    if (c.Settings.Backend == route &&
      (nearest == 0.0 || d < std::fabs(std::log(nearest / std::max(1.0, perObject)))))
    {
      nearest = c.Settings.Spheres;
    }
  }
  const bool selfChosen = route == Route::Filter;
  choice = Choose(model, features, budget,
    [&](const Knobs& k)
    {
      return k.Backend == route && k.Spheres == nearest &&
        (!selfChosen || (k.SelfVisibility > 0) == tracedSelf);
    });
  // A model without these inputs' candidates (a calibration of other
  // settings) is used as it is, and the line says so.
  const bool matched = choice.Candidate >= 0;
  if (!matched)
  {
    choice = Choose(model, features, budget, [&](const Knobs& k) { return k.Backend == route; });
  }
  if (choice.Candidate < 0)
  {
    error = "Budget: " + choice.Reason + " (route: " + RouteName(route) + ")";
    return false;
  }
  choice.Settings.Apply(settings);
  std::ostringstream s;
  s.precision(3);
  s << "budget: " << choice.Settings.Describe() << " (the proxies' " << perObject
    << " spheres per object as " << nearest;
  if (selfChosen)
  {
    s << ", self-visibility " << (tracedSelf ? "given" : "by the rules");
  }
  s << (matched ? "" : "; the model has no candidate for these inputs: its nearest")
    << "); predicted error " << 100.0 * choice.PredictedError << "%, "
    << 1e3 * choice.PredictedSeconds << " ms on "
    << (route == Route::Mapper ? model.MapperRenderer : model.Machine) << "; "
    << (choice.Met ? "" : "NOT MET: ") << choice.Reason;
  line = s.str();
  return true;
}

bool ParseErrorBudget(const std::string& text, double& fraction)
{
  return ParseScaled(text, { { "%", 0.01 } }, fraction);
}

bool ParseTimeBudget(const std::string& text, double& seconds)
{
  return ParseScaled(text, { { "ms", 1e-3 }, { "s", 1.0 } }, seconds);
}

} // namespace budget
} // namespace proxygi
