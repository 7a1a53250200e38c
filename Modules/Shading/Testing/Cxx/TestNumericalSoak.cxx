// Numerical soak of vtkPGIGlobalIllumination: randomized hard
// configurations, each one receiver against a randomized scene (proxies and
// planes at scales from 1e-6 to 1e6, coincident, nested, zero-radius and
// huge spheres, receivers on, inside and at the centre of spheres, zero,
// tiny and huge normals, random settings), with NaN and Inf sprinkled into
// some scenes. A scene with a non-finite point, centre or radius must be
// refused (no output); a non-finite normal faces +z; every output value must be finite, not
// negative and bounded by 4 x albedo x (sky + sphere light) (the light a receiver can see, with
// room for SH ringing). The counts are printed.
//
//   TestNumericalSoak [--configurations N] [--receivers-per-scene M] [--seed S]
//
// The default run shades 2 x 10^4 configurations; the labelled soak target
// (ctest -L soak) 10^6.
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"

#include "pgiHardScenes.h"
#include "pgiTesting.h"

#include "vtkCellArray.h"
#include "vtkLogger.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

namespace
{
struct Counts
{
  long long Configurations = 0, Scenes = 0, PoisonedScenes = 0, Refused = 0, PoisonedAccepted = 0,
            NormalPoisonAccepted = 0, CleanRefused = 0, Values = 0, NonFinite = 0, Negative = 0,
            AboveBound = 0;
  double Peak = 0.0; // largest output over its bound
};

const double Albedo = 0.8, Sky = 1.0, LightRadiance = 3.0;

struct Generator
{
  std::mt19937_64 Random;
  explicit Generator(unsigned long long seed)
    : Random(seed)
  {
  }
  double Uniform(double a, double b)
  {
    return std::uniform_real_distribution<double>(a, b)(Random);
  }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }
  int Integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(Random); }
  void Direction(double d[3])
  {
    const double z = Uniform(-1.0, 1.0), phi = Uniform(0.0, 2.0 * M_PI);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    d[0] = s * std::cos(phi);
    d[1] = s * std::sin(phi);
    d[2] = z;
  }
  double Poison()
  {
    const int k = Integer(0, 2);
    return k == 0 ? std::numeric_limits<double>::quiet_NaN() : (k == 1 ? HUGE_VAL : -HUGE_VAL);
  }
};

void Shade(Generator& g, int receiversPerScene, Counts& counts)
{
  const double scale = std::pow(10.0, g.Uniform(-6.0, 6.0));
  // Proxies: random spheres, and the hard kinds among them.
  std::vector<std::array<double, 5>> spheres;
  const int count = g.Integer(0, 24);
  for (int i = 0; i < count; ++i)
  {
    std::array<double, 5> s = { g.Uniform(-scale, scale), g.Uniform(-scale, scale),
      g.Uniform(-scale, scale), scale * std::pow(10.0, g.Uniform(-3.0, 0.5)),
      double(g.Integer(0, 3)) };
    const int kind = g.Integer(0, 9);
    if (kind == 0)
    {
      s[3] = 0.0; // zero radius
    }
    else if (kind == 1 && !spheres.empty())
    {
      s = spheres[g.Integer(0, int(spheres.size()) - 1)]; // coincident
    }
    else if (kind == 2 && !spheres.empty())
    {
      const auto& outer = spheres[g.Integer(0, int(spheres.size()) - 1)];
      s = outer; // nested
      s[3] = outer[3] * g.Uniform(0.0, 1.0);
    }
    else if (kind == 3)
    {
      s[3] = scale * 1e3; // everything inside
    }
    spheres.push_back(s);
  }
  // Receivers: random, on a sphere, inside one, at a centre; any normal.
  auto receivers = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> verts;
  for (int r = 0; r < receiversPerScene; ++r)
  {
    double p[3] = { g.Uniform(-scale, scale), g.Uniform(-scale, scale), g.Uniform(-scale, scale) };
    double n[3];
    g.Direction(n);
    const int kind = g.Integer(0, 9);
    if (kind <= 2 && !spheres.empty())
    {
      const auto& s = spheres[g.Integer(0, int(spheres.size()) - 1)];
      const double t = kind == 0 ? 1.0 : (kind == 1 ? g.Uniform(0.0, 1.0) : 0.0);
      double d[3];
      g.Direction(d);
      for (int k = 0; k < 3; ++k)
      {
        p[k] = s[k] + t * s[3] * d[k]; // on, inside, at the centre
      }
    }
    const int normalKind = g.Integer(0, 9);
    const double length =
      normalKind == 0 ? 0.0 : (normalKind == 1 ? 1e-30 : (normalKind == 2 ? 1e30 : 1.0));
    for (double& c : n)
    {
      c *= length;
    }
    verts->InsertNextCell(1);
    verts->InsertCellPoint(points->InsertNextPoint(p));
    normals->InsertNextTuple(n);
  }
  receivers->SetPoints(points);
  receivers->SetVerts(verts);
  receivers->GetPointData()->SetNormals(normals);

  vtkSmartPointer<vtkPolyData> proxies = pgitest::HardProxies(spheres);
  // Poison: one non-finite number somewhere in the input.
  const bool poisoned = g.Chance(0.05) && (receiversPerScene > 0);
  int where = -1;
  if (poisoned)
  {
    where = spheres.empty() ? g.Integer(0, 1) : g.Integer(0, 3);
    const vtkIdType r = g.Integer(0, receiversPerScene - 1);
    if (where == 0)
    {
      double p[3];
      points->GetPoint(r, p);
      p[g.Integer(0, 2)] = g.Poison();
      points->SetPoint(r, p);
    }
    else if (where == 1)
    {
      normals->SetComponent(r, g.Integer(0, 2), g.Poison());
    }
    else if (where == 2)
    {
      proxies->GetPointData()->GetArray("Radius")->SetComponent(
        g.Integer(0, int(spheres.size()) - 1), 0, g.Poison());
    }
    else
    {
      double c[3];
      const vtkIdType s = g.Integer(0, int(spheres.size()) - 1);
      proxies->GetPoint(s, c);
      c[g.Integer(0, 2)] = g.Poison();
      proxies->GetPoints()->SetPoint(s, c);
    }
  }

  vtkNew<vtkPGILighting> lighting;
  lighting->SetUniformRadiance(Sky, Sky, Sky);
  if (g.Chance(0.5))
  {
    double c[3];
    g.Direction(c);
    const double at = scale * g.Uniform(0.5, 3.0);
    lighting->AddSphereLight(c[0] * at, c[1] * at, c[2] * at, scale * g.Uniform(0.01, 0.5),
      LightRadiance, LightRadiance, LightRadiance);
  }
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputData(receivers);
  gi->SetProxiesData(proxies);
  gi->SetLighting(lighting);
  for (int k = g.Integer(0, 2); k > 0; --k)
  {
    double origin[3] = { g.Uniform(-scale, scale), g.Uniform(-scale, scale),
      g.Uniform(-scale, scale) },
           normal[3];
    g.Direction(normal);
    const double grey[3] = { 0.5, 0.5, 0.5 };
    gi->AddBlockerPlane(origin, normal, grey);
  }
  vtkPGIGISettings* settings = gi->GetSettings();
  settings->SetOrder(g.Integer(2, 6));
  settings->SetExpMethod(g.Integer(vtkPGIGISettings::EXP_PS, vtkPGIGISettings::EXP_HYB));
  settings->SetIndirect(g.Chance(0.7));
  settings->SetIndirectMode(g.Chance(0.5) ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
                                          : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  settings->SetDefaultAlbedo(Albedo, Albedo, Albedo);
  gi->Update();

  ++counts.Scenes;
  counts.PoisonedScenes += poisoned ? 1 : 0;
  vtkPolyData* out = gi->GetOutput();
  if (out->GetNumberOfPoints() == 0)
  {
    ++counts.Refused;
    counts.CleanRefused += poisoned ? 0 : 1;
    return;
  }
  if (poisoned && where == 1)
  {
    ++counts.NormalPoisonAccepted; // such a receiver faces +z
  }
  else if (poisoned)
  {
    ++counts.PoisonedAccepted;
    std::printf("soak: a scene with a non-finite %s was accepted\n",
      where == 0     ? "receiver point"
        : where == 2 ? "radius"
                     : "centre");
  }
  counts.Configurations += out->GetNumberOfPoints();
  const double bound = 4.0 * Albedo * (Sky + LightRadiance);
  for (int a = 0; a < out->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = out->GetPointData()->GetArray(a);
    if (!array || !array->GetName() || !std::strcmp(array->GetName(), "Normals") ||
      !std::strcmp(array->GetName(), "RadianceSRGB"))
    {
      continue;
    }
    // Visibility is an SH vector (signed); radiance arrays are bounded.
    const bool radiance = std::strcmp(array->GetName(), "Visibility") != 0;
    const vtkIdType n = array->GetNumberOfValues();
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double v = array->GetVariantValue(i).ToDouble();
      ++counts.Values;
      if (!std::isfinite(v))
      {
        ++counts.NonFinite;
      }
      else if (radiance && v < -1e-9)
      {
        ++counts.Negative;
      }
      else if (radiance && v > bound)
      {
        ++counts.AboveBound;
      }
      if (radiance && std::isfinite(v))
      {
        counts.Peak = std::max(counts.Peak, v / bound);
      }
    }
  }
}
} // namespace

int TestNumericalSoak(int argc, char* argv[])
{
  long long configurations = 20000;
  int perScene = 100;
  unsigned long long seed = 20261202;
  for (int a = 1; a + 1 < argc; ++a)
  {
    if (!std::strcmp(argv[a], "--configurations"))
    {
      configurations = std::atoll(argv[++a]);
    }
    else if (!std::strcmp(argv[a], "--receivers-per-scene"))
    {
      perScene = std::atoi(argv[++a]);
    }
    else if (!std::strcmp(argv[a], "--seed"))
    {
      seed = std::strtoull(argv[++a], nullptr, 10);
    }
  }
  // Refusals of poisoned scenes are expected: their messages are not news.
  vtkObject::GlobalWarningDisplayOff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  Generator generator(seed);
  Counts counts;
  const auto start = std::chrono::steady_clock::now();
  while (counts.Configurations < configurations)
  {
    Shade(generator, perScene, counts);
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("soak: %lld configurations shaded in %lld scenes (%d receivers each, seed %llu), "
              "%.1f s\n",
    counts.Configurations, counts.Scenes, perScene, seed, seconds);
  std::printf("soak: %lld output values: %lld NaN/Inf, %lld negative, %lld above the bound "
              "(largest at %.3f of it)\n",
    counts.Values, counts.NonFinite, counts.Negative, counts.AboveBound, counts.Peak);
  std::printf("soak: %lld scenes with a NaN/Inf input: %lld refused, %lld with a NaN/Inf normal "
              "shaded (facing +z), %lld others accepted; %lld clean scenes refused\n",
    counts.PoisonedScenes, counts.Refused - counts.CleanRefused, counts.NormalPoisonAccepted,
    counts.PoisonedAccepted, counts.CleanRefused);
  PGI_CHECK(counts.NonFinite == 0);
  PGI_CHECK(counts.Negative == 0);
  PGI_CHECK(counts.AboveBound == 0);
  PGI_CHECK(counts.PoisonedAccepted == 0);
  PGI_CHECK(counts.CleanRefused == 0);
  return pgitest::Result();
}
