// How well the accuracy budget predicts and chooses, from the measurements of
// `proxygi calibrate --measurements` (every candidate on every scene, with
// its time and its error against Embree):
//  - prediction quality on scenes the model was not fitted on: each training
//    scene left out of the fit in turn, and the held-out scenes under the
//    model fitted on all training scenes;
//  - the regret: the measured time (error) of the chosen settings against the
//    fastest (most accurate) candidate that meets the same budget, found by
//    the exhaustive sweep, and how often the choice misses the budget;
//  - per scene, the Pareto front (error against time) with the chosen points
//    and Embree's curve beside it;
//  - with --variations, the knobs the grid keeps at their defaults (runs of
//    `proxygi calibrate --grid variations`) against those defaults
//    (PREFIX-variations.md).
// Writes a Markdown report and PNG plots (VTK charts: a display or xvfb-run).
//
//   ProxyGIBudgetReport --train A.csv,... --held-out B.csv,... [--grid G,...]
//                       [--embree E.csv,...] [--plots scene,...]
//                       [--variations V.csv,...] --out PREFIX
#include "pgiAccuracyBudget.h"

#include "pgiBenchPlot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace proxygi::budget;

namespace
{
std::string Read(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> Split(const std::string& text)
{
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ','))
  {
    if (!item.empty())
    {
      out.push_back(item);
    }
  }
  return out;
}

std::vector<std::string> Scenes(const std::vector<Measurement>& rows)
{
  std::vector<std::string> names;
  for (const Measurement& m : rows)
  {
    if (std::find(names.begin(), names.end(), m.Scene) == names.end())
    {
      names.push_back(m.Scene);
    }
  }
  return names;
}

std::vector<Measurement> Of(
  const std::vector<Measurement>& rows, const std::string& scene, bool keep)
{
  std::vector<Measurement> out;
  for (const Measurement& m : rows)
  {
    if ((m.Scene == scene) == keep)
    {
      out.push_back(m);
    }
  }
  return out;
}

int IndexOf(const Model& model, const Knobs& k)
{
  for (std::size_t i = 0; i < model.Candidates.size(); ++i)
  {
    if (model.Candidates[i].Settings == k)
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}

double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Evaluation
{
  std::string Scene;
  bool HeldOut = false;
  std::vector<double> ErrorRatio, TimeRatio; // predicted / measured per candidate
  std::vector<Route> Routes;                 // each candidate's
};

struct Outcome
{
  std::string Chosen;
  double PredictedError = 0, PredictedSeconds = 0, MeasuredError = 0, MeasuredSeconds = 0;
  double CheckError = -1; // what the check estimated of it
  bool PredictedMet = false;
};

struct Regret
{
  std::string Scene, Budget;
  bool ErrorBudget = true;
  double Asked = 0.0;
  Outcome Model, Checked;                  // the model alone; after the check (--check 16)
  double BestError = -1, BestSeconds = -1; // the exhaustive sweep's answer; -1: none meets it
};

const double ErrorBudgets[] = { 0.05, 0.075, 0.10, 0.15 };
const double TimeBudgets[] = { 0.1, 0.25, 0.5, 1.0 };

void Evaluate(const Model& model, const std::vector<Measurement>& scene, bool heldOut,
  std::vector<Evaluation>& evaluations, std::vector<Regret>& regrets)
{
  Evaluation e;
  e.Scene = scene.front().Scene;
  e.HeldOut = heldOut;
  for (const Measurement& m : scene)
  {
    const int k = IndexOf(model, m.Settings);
    if (k >= 0)
    {
      e.ErrorRatio.push_back(model.PredictError(k, m.Features) / m.Error);
      e.TimeRatio.push_back(model.PredictSeconds(k, m.Features) / m.Seconds);
      e.Routes.push_back(m.Settings.Backend);
    }
  }
  evaluations.push_back(e);
  // The features as proxygi render has them before it builds proxies: the
  // scene's own (any row's), no sphere count (each candidate's, ProxySpheres).
  SceneFeatures f = scene.front().Features;
  f.Spheres = 0.0;
  auto outcome = [&](const Choice& c)
  {
    Outcome o;
    o.Chosen = c.Settings.Describe();
    o.PredictedError = c.PredictedError;
    o.PredictedSeconds = c.PredictedSeconds;
    o.PredictedMet = c.Met;
    for (const Measurement& m : scene)
    {
      if (m.Settings == c.Settings)
      {
        o.MeasuredError = m.Error;
        o.MeasuredSeconds = m.Seconds;
        o.CheckError = m.CheckError;
      }
    }
    return o;
  };
  auto add = [&](bool errorBudget, double asked)
  {
    Budget b;
    errorBudget ? b.SetError(asked) : b.SetSeconds(asked);
    const Choice c = Choose(model, f, b);
    Regret r;
    r.Scene = e.Scene;
    r.ErrorBudget = errorBudget;
    r.Asked = asked;
    r.Model = outcome(c);
    // The check, as proxygi render --check 16 does it: the choice's error
    // as Embree at 16 samples estimates it (calibrate recorded it per
    // candidate) and its time scale this scene's predictions; a new choice
    // is run and checked too, and the one serving the budget better kept.
    const Measurement* ran = nullptr;
    for (const Measurement& m : scene)
    {
      ran = m.Settings == c.Settings ? &m : ran;
    }
    Choice kept = c;
    // As proxygi render --mode auto: both routes, the mapper's choices read back.
    if (ran && ran->CheckError > 0.0)
    {
      SceneFeatures checked = f;
      const Choice again = Recheck(model, checked, b, c, ran->CheckError, ran->Seconds);
      const Measurement* second = nullptr;
      for (const Measurement& m : scene)
      {
        second = m.Settings == again.Settings ? &m : second;
      }
      if (second && second != ran &&
        !FirstServesBetter(
          b, ran->CheckError, ran->Seconds, second->CheckError, second->Seconds, model.CheckMargin))
      {
        kept = again;
      }
    }
    r.Checked = outcome(kept);
    for (const Measurement& m : scene)
    {
      if (errorBudget && m.Error <= asked && (r.BestSeconds < 0 || m.Seconds < r.BestSeconds))
      {
        r.BestSeconds = m.Seconds;
        r.BestError = m.Error;
      }
      if (!errorBudget && m.Seconds <= asked && (r.BestError < 0 || m.Error < r.BestError))
      {
        r.BestSeconds = m.Seconds;
        r.BestError = m.Error;
      }
    }
    regrets.push_back(r);
  };
  for (double asked : ErrorBudgets)
  {
    add(true, asked);
  }
  for (double asked : TimeBudgets)
  {
    add(false, asked);
  }
}

std::string Percent(double v)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f%%", 100.0 * v);
  return text;
}

// `proxygi calibrate --grid variations` runs against the same candidates
// with every knob at its default (the default grid's runs of that scene):
// per varied knob, time and error over the default's, and how often the
// variation is both faster and more accurate. Markdown, or "" without runs.
std::string VariationTable(
  const std::vector<Measurement>& variations, const std::vector<Measurement>& defaults)
{
  const Knobs plain;
  std::map<std::string, std::array<std::vector<double>, 2>> ratios;
  std::map<std::string, int> dominates;
  std::vector<std::string> order;
  for (const Measurement& v : variations)
  {
    Knobs base = v.Settings;
    base.HierarchyAngle = plain.HierarchyAngle;
    base.ExpMethod = plain.ExpMethod;
    base.Blocking = plain.Blocking;
    base.BrightLightRays = plain.BrightLightRays;
    const auto found = std::find_if(defaults.begin(), defaults.end(),
      [&](const Measurement& d) { return d.Scene == v.Scene && d.Settings == base; });
    if (found == defaults.end() || v.Settings == base)
    {
      continue;
    }
    // The one knob off its default, as Describe says it.
    const std::string all = v.Settings.Describe(), common = base.Describe();
    const std::string knob = all.substr(std::min(all.size(), common.size() + 2));
    if (ratios.find(knob) == ratios.end())
    {
      order.push_back(knob);
    }
    ratios[knob][0].push_back(v.Seconds / found->Seconds);
    ratios[knob][1].push_back(v.Error / found->Error);
    dominates[knob] += v.Seconds < found->Seconds && v.Error < found->Error ? 1 : 0;
  }
  if (order.empty())
  {
    return std::string();
  }
  std::string text = "| knob off its default | runs | time / default: median | range | error / "
                     "default: median | range | faster and more accurate |\n"
                     "|---|---:|---:|---:|---:|---:|---:|\n";
  char line[512];
  for (const std::string& knob : order)
  {
    const auto& r = ratios[knob];
    const auto t = std::minmax_element(r[0].begin(), r[0].end());
    const auto e = std::minmax_element(r[1].begin(), r[1].end());
    std::snprintf(line, sizeof(line), "| %s | %zu | %.2f | %.2f-%.2f | %.3f | %.3f-%.3f | %d |\n",
      knob.c_str(), r[0].size(), Median(r[0]), *t.first, *t.second, Median(r[1]), *e.first,
      *e.second, dominates[knob]);
    text += line;
  }
  return text;
}
} // namespace

int main(int argc, char* argv[])
{
  std::string train, heldOut, out = "budget", embreeFiles, plotScenes, variationFiles, grids;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string a = argv[i];
    (a == "--train"           ? train
        : a == "--held-out"   ? heldOut
        : a == "--embree"     ? embreeFiles
        : a == "--plots"      ? plotScenes
        : a == "--variations" ? variationFiles
        : a == "--grid"       ? grids
                              : out) = argv[i + 1];
  }
  std::vector<Measurement> trainRows, heldRows;
  std::string error;
  // Each of --train and --held-out: CSV files, comma separated.
  if (!ReadMeasurementFiles(Split(train), trainRows, error) ||
    !ReadMeasurementFiles(Split(heldOut), heldRows, error) || trainRows.empty())
  {
    std::fprintf(stderr, "ProxyGIBudgetReport: %s\n",
      error.empty() ? "no measurements (--train, --held-out)" : error.c_str());
    return 1;
  }
  // As proxygi calibrate --fit --grid: only those candidates' runs.
  if (!grids.empty())
  {
    std::vector<Knobs> grid;
    if (!NamedGrids(Split(grids), grid, error))
    {
      std::fprintf(stderr, "ProxyGIBudgetReport: --grid: %s\n", error.c_str());
      return 1;
    }
    trainRows = InGrid(trainRows, grid);
    heldRows = InGrid(heldRows, grid);
  }
  // Embree's curve per scene: spp, seconds, error.
  std::map<std::string, std::vector<std::array<double, 3>>> embree;
  for (const std::string& file : Split(embreeFiles))
  {
    std::stringstream text(Read(file));
    std::string line;
    std::getline(text, line);
    while (std::getline(text, line))
    {
      std::vector<std::string> cells = Split(line);
      if (cells.size() == 4)
      {
        embree[cells[0]].push_back(
          { { std::stod(cells[1]), std::stod(cells[2]), std::stod(cells[3]) } });
      }
    }
  }

  std::vector<Evaluation> evaluations;
  std::vector<Regret> regrets;
  for (const std::string& scene : Scenes(trainRows))
  {
    Model without;
    if (!without.Fit(Of(trainRows, scene, false), error))
    {
      std::fprintf(stderr, "ProxyGIBudgetReport: %s\n", error.c_str());
      return 1;
    }
    Evaluate(without, Of(trainRows, scene, true), false, evaluations, regrets);
  }
  Model all;
  if (!all.Fit(trainRows, error))
  {
    std::fprintf(stderr, "ProxyGIBudgetReport: %s\n", error.c_str());
    return 1;
  }
  for (const std::string& scene : Scenes(heldRows))
  {
    Evaluate(all, Of(heldRows, scene, true), true, evaluations, regrets);
  }

  std::ofstream md(out + ".md");
  if (!md)
  {
    std::fprintf(stderr, "ProxyGIBudgetReport: cannot write %s.md\n", out.c_str());
    return 1;
  }
  md << "Measurements: " << trainRows.size() << " runs on " << Scenes(trainRows).size()
     << " training scenes, " << heldRows.size() << " on " << Scenes(heldRows).size()
     << " held-out scenes; " << all.Candidates.size()
     << " candidates. Each training scene is predicted by the model fitted on the others "
        "(leave one out); each held-out scene by the model fitted on every training scene. "
        "Ratios are predicted / measured over the scene's candidates: the median and the "
        "worst (farthest from 1).\n\n";
  md << "| scene | fit | error ratio: median | worst | time ratio: median | worst |\n"
        "|---|---|---:|---:|---:|---:|\n";
  std::vector<double> allLogError, allLogTime, heldLogError, heldLogTime;
  for (const Evaluation& e : evaluations)
  {
    auto worst = [](const std::vector<double>& v)
    {
      double w = 1.0;
      for (double x : v)
      {
        w = std::fabs(std::log(x)) > std::fabs(std::log(w)) ? x : w;
      }
      return w;
    };
    for (double x : e.ErrorRatio)
    {
      (e.HeldOut ? heldLogError : allLogError).push_back(std::fabs(std::log(x)));
    }
    for (double x : e.TimeRatio)
    {
      (e.HeldOut ? heldLogTime : allLogTime).push_back(std::fabs(std::log(x)));
    }
    char line[512];
    std::snprintf(line, sizeof(line), "| %s | %s | %.2f | %.2f | %.2f | %.2f |\n", e.Scene.c_str(),
      e.HeldOut ? "held out" : "left out", Median(e.ErrorRatio), worst(e.ErrorRatio),
      Median(e.TimeRatio), worst(e.TimeRatio));
    md << line;
  }
  char summary[512];
  std::snprintf(summary, sizeof(summary),
    "\nMedian |log(predicted/measured)|: error %.2f (x%.2f) left out, %.2f (x%.2f) held out; "
    "time %.2f (x%.2f) left out, %.2f (x%.2f) held out.\n\n",
    Median(allLogError), std::exp(Median(allLogError)), Median(heldLogError),
    std::exp(Median(heldLogError)), Median(allLogTime), std::exp(Median(allLogTime)),
    Median(heldLogTime), std::exp(Median(heldLogTime)));
  md << summary;
  if (all.HasRoute(Route::Mapper))
  {
    // The same per route: the mapper's error has no bright-light term.
    for (Route route : { Route::Filter, Route::Mapper })
    {
      std::vector<double> logs[4]; // error, time; left out, held out
      for (const Evaluation& e : evaluations)
      {
        for (std::size_t i = 0; i < e.Routes.size(); ++i)
        {
          if (e.Routes[i] == route)
          {
            logs[e.HeldOut ? 1 : 0].push_back(std::fabs(std::log(e.ErrorRatio[i])));
            logs[e.HeldOut ? 3 : 2].push_back(std::fabs(std::log(e.TimeRatio[i])));
          }
        }
      }
      std::snprintf(summary, sizeof(summary),
        "%s: error x%.2f left out, x%.2f held out; time x%.2f left out, x%.2f held out.\n",
        route == Route::Mapper ? "The GPU mapper's candidates" : "The CPU filter's candidates",
        std::exp(Median(logs[0])), std::exp(Median(logs[1])), std::exp(Median(logs[2])),
        std::exp(Median(logs[3])));
      md << summary;
    }
    md << "\n";
  }

  // The regret.
  md << "The choice per budget (error budgets: the fastest predicted to meet it; time "
        "budgets: the most accurate predicted to fit). *Best* is the exhaustive sweep's "
        "answer from the measurements; the regret is chosen/best time (error budgets) or "
        "chosen/best error (time budgets); *missed* when the chosen settings' measured "
        "error or time is over the budget.\n\n";
  md << "| scene | budget | chosen by the model | measured | with the check | measured | best "
        "| regret: model | with check |\n"
        "|---|---|---|---|---|---|---|---:|---:|\n";
  struct Tally
  {
    int Misses = 0, Counted = 0;
    std::vector<double> ErrorRegret, TimeRegret;
  } tally[2];
  int noneMeets = 0;
  for (const Regret& r : regrets)
  {
    std::string cells[2];
    for (int which = 0; which < 2; ++which)
    {
      const Outcome& o = which == 0 ? r.Model : r.Checked;
      const bool missed = r.ErrorBudget ? o.MeasuredError > r.Asked : o.MeasuredSeconds > r.Asked;
      if (r.BestError >= 0.0)
      {
        const double v =
          r.ErrorBudget ? o.MeasuredSeconds / r.BestSeconds : o.MeasuredError / r.BestError;
        (r.ErrorBudget ? tally[which].ErrorRegret : tally[which].TimeRegret).push_back(v);
        char text[64];
        std::snprintf(text, sizeof(text), "%.2f%s", v, missed ? " **missed**" : "");
        cells[which] = text;
        ++tally[which].Counted;
        tally[which].Misses += missed ? 1 : 0;
      }
      else if (which == 0)
      {
        cells[which] = o.PredictedMet ? "predicted met" : "said: not met";
      }
      else
      {
        // After the check the program says what the check estimated.
        const bool estimatedMet =
          r.ErrorBudget ? o.CheckError <= r.Asked : o.MeasuredSeconds <= r.Asked;
        cells[which] = estimatedMet ? "estimated met" : "said: not met";
      }
    }
    noneMeets += r.BestError < 0.0 ? 1 : 0;
    auto measured = [](const Outcome& o)
    {
      return Percent(o.MeasuredError) + ", " +
        std::to_string(std::lround(1e3 * o.MeasuredSeconds)) + " ms";
    };
    const std::string same = r.Checked.Chosen == r.Model.Chosen ? "same" : r.Checked.Chosen;
    md << "| " << r.Scene << " | "
       << (r.ErrorBudget ? "error " + Percent(r.Asked)
                         : "time " + std::to_string(std::lround(1e3 * r.Asked)) + " ms")
       << " | " << r.Model.Chosen << " | " << measured(r.Model) << " | " << same << " | "
       << measured(r.Checked) << " | "
       << (r.BestError < 0 ? std::string("none meets it")
                           : Percent(r.BestError) + ", " +
                std::to_string(std::lround(1e3 * r.BestSeconds)) + " ms")
       << " | " << cells[0] << " | " << cells[1] << " |\n";
  }
  std::string summaryText;
  for (int which = 0; which < 2; ++which)
  {
    const Tally& t = tally[which];
    std::snprintf(summary, sizeof(summary),
      "%s: over the %d budgets some candidate meets, the regret is median %.2f, worst %.2f "
      "for error budgets (the choice's time over the fastest meeting it) and median %.2f, "
      "worst %.2f for time budgets (its error over the most accurate fitting); the choice's "
      "measured result missed the budget in %d of %d.\n",
      which == 0 ? "\nThe model alone" : "\nWith the check", t.Counted, Median(t.ErrorRegret),
      t.ErrorRegret.empty() ? 0.0 : *std::max_element(t.ErrorRegret.begin(), t.ErrorRegret.end()),
      Median(t.TimeRegret),
      t.TimeRegret.empty() ? 0.0 : *std::max_element(t.TimeRegret.begin(), t.TimeRegret.end()),
      t.Misses, t.Counted);
    summaryText += summary;
  }
  std::vector<double> checkRatio;
  for (const std::vector<Measurement>* rows : { &trainRows, &heldRows })
  {
    for (const Measurement& m : *rows)
    {
      if (m.CheckError > 0.0)
      {
        checkRatio.push_back(std::fabs(std::log(m.CheckError / m.Error)));
      }
    }
  }
  std::snprintf(summary, sizeof(summary),
    "%d budgets no candidate meets. The check's estimate (Embree at 16 samples, noise taken "
    "out) against the error measured at 1024: median |log ratio| %.3f (x%.3f), worst x%.2f.\n",
    noneMeets, Median(checkRatio), std::exp(Median(checkRatio)),
    checkRatio.empty() ? 1.0 : std::exp(*std::max_element(checkRatio.begin(), checkRatio.end())));
  summaryText += summary;
  md << summaryText;
  std::printf("%s", summaryText.c_str());

  // The knobs the grid keeps at their defaults, measured around it.
  std::vector<Measurement> variations, defaults = trainRows;
  defaults.insert(defaults.end(), heldRows.begin(), heldRows.end());
  if (!ReadMeasurementFiles(Split(variationFiles), variations, error))
  {
    std::fprintf(stderr, "ProxyGIBudgetReport: %s\n", error.c_str());
    return 1;
  }
  const std::string table = VariationTable(variations, defaults);
  if (!table.empty())
  {
    std::ofstream variationsFile(out + "-variations.md");
    if (!(variationsFile << table))
    {
      std::fprintf(stderr, "ProxyGIBudgetReport: cannot write %s-variations.md\n", out.c_str());
      return 1;
    }
    std::printf("%s", table.c_str());
  }

  // Pareto fronts.
  const std::vector<std::string> plots = Split(plotScenes);
  int plotIndex = 0;
  for (const std::string& scene : plots)
  {
    std::vector<Measurement> rows = Of(trainRows, scene, true);
    const bool held = rows.empty();
    if (held)
    {
      rows = Of(heldRows, scene, true);
    }
    if (rows.empty())
    {
      std::fprintf(stderr, "ProxyGIBudgetReport: no scene '%s'\n", scene.c_str());
      continue;
    }
    pgibench::Series points{ "every candidate", {}, {}, false };
    pgibench::Series front{ "Pareto front", {}, {}, true };
    pgibench::Series chosen{ "chosen for 5, 7.5, 10, 15% (checked)", {}, {}, false };
    pgibench::Series curve{ "Embree 16, 64, 256 spp", {}, {}, true };
    std::vector<Measurement> sorted = rows;
    std::sort(sorted.begin(), sorted.end(),
      [](const Measurement& a, const Measurement& b) { return a.Seconds < b.Seconds; });
    double bestError = 1e300;
    for (const Measurement& m : sorted)
    {
      points.X.push_back(m.Seconds);
      points.Y.push_back(100.0 * m.Error);
      if (m.Error < bestError)
      {
        bestError = m.Error;
        front.X.push_back(m.Seconds);
        front.Y.push_back(100.0 * m.Error);
      }
    }
    for (const Regret& r : regrets)
    {
      if (r.Scene == scene && r.ErrorBudget)
      {
        chosen.X.push_back(r.Checked.MeasuredSeconds);
        chosen.Y.push_back(100.0 * r.Checked.MeasuredError);
      }
    }
    for (const auto& p : embree[scene])
    {
      curve.X.push_back(p[1]);
      curve.Y.push_back(100.0 * p[2]);
    }
    pgibench::PlotAxes axes;
    axes.Title = scene + (held ? " (held out)" : " (left out of the fit)");
    axes.X = "seconds per update (2 threads)";
    axes.Y = "relative RMSE against Embree 1024 spp (%)";
    std::vector<pgibench::Series> series = { points, front, chosen };
    if (!curve.X.empty())
    {
      series.push_back(curve);
    }
    const std::string png = out + "-pareto-" + std::to_string(++plotIndex) + ".png";
    pgibench::WritePlot(png, axes, series);
    // Linked as Documentation/AccuracyTime.md includes the text.
    md << "\n![" << scene << "](figures/" << png.substr(png.rfind('/') + 1) << ")\n";
    std::printf("wrote %s (%s)\n", png.c_str(), scene.c_str());
  }
  md.flush();
  if (!md)
  {
    std::fprintf(stderr, "ProxyGIBudgetReport: cannot write %s.md\n", out.c_str());
    return 1;
  }
  std::printf("wrote %s.md\n", out.c_str());
  return 0;
}
