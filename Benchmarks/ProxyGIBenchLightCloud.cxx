// The light cloud's accuracy and cost (Documentation/AccuracyTime.md, "Light
// cloud"): each knob against the Embree reference of the same user lights,
// placed at random off the grid (a fixed seed no setting is tuned to), in
// one run:
//   ProxyGIBenchLightCloud [--out PREFIX] [--quick] [--reference-spp N] [scene.json]
// Default scene: Testing/Data/cornell-box.json. The cloud's grid has cubic
// cells, "N cells across" the region's shortest axis. Per setting: cloud lights
// (after clustering, per zone), coefficients per receiver, memory,
// precompute seconds (dense + compression), CPU relighting milliseconds per
// frame, the relative RMSE of the indirect light (mean over the test lights)
// and of the total light when the direct light is exact (Embree's).
// The cloud's region is the scene's "light_cloud" region, else the objects'
// bounds. Writes PREFIX.md, PREFIX.csv and PREFIX.png (error against
// coefficients per receiver).
//
// With --glossy the receivers are glossy (Phong, ks 0.5, exponent 12, the
// paper's bunny) and the sweep is over the SH order instead: the error of
// the radiance seen from three view points inside the region, against the
// exact glossy radiance of the same light (direct by a shadow ray, one
// bounce by --reference-spp gather rays lit by the light), over the
// receivers facing each viewer. Writes PREFIX.md and PREFIX.csv.
#include "pgiBenchPlot.h"
#include "pgiLightCloudGlossy.h"
#include "pgiMaterial.h"
#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"
#include "pgiScene.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPrecompute.h"
#include "vtkPGILightCloudRelight.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"
#include "vtkPGIReferenceIllumination.h"

#include <vtkAppendPolyData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace
{
struct Setting
{
  std::string Knob, Value;
  int Resolution = 5;
  int Samples = 64;
  bool Compress = false;
  double MergeTolerance = 0.1;
  vtkIdType ZoneSize = 1000;
  double Vectors = 8.0;
  int Merged = vtkPGILightCloudPrecompute::AVERAGED_RESPONSE;
  int GlossyOrder = 0;       // 0: diffuse receivers
  bool AtTestLights = false; // cloud lights on the test lights themselves
  bool GlossyDirect = false; // the cloud carries the direct light too
};

const double GlossySpecular = 0.5, GlossyExponent = 12.0;

struct Result
{
  double Lights = 0, Coefficients = 0, MegaBytes = 0, Precompute = 0, RelightMs = 0;
  // Over the lights clear of surfaces; NearError over those near them.
  double Error = 0, Worst = 0, TotalError = 0, NearError = 0;
  std::vector<double> ViewError; // glossy: per view point
};

struct Bench
{
  vtkSmartPointer<vtkPolyData> Receivers;
  vtkNew<vtkPGIMeshOccluder> Occluder;
  double Region[6];
  std::vector<std::array<double, 3>> Lights;
  std::vector<char> Near; // closer to a surface than half the baseline's spacing
  int NearCount = 0;
  std::vector<vtkSmartPointer<vtkFloatArray>> Truth, TruthDirect;
  // Glossy: view points, receiver normals, exact radiance per light and view.
  std::vector<std::array<double, 3>> Views;
  std::vector<double> Normals;
  std::vector<std::vector<std::vector<float>>> GlossyTruth, GlossyIndirectTruth;
};

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

vtkSmartPointer<vtkFloatArray> Relit(vtkPGILightCloud* cloud, Bench& b, const double* p, double* ms)
{
  vtkNew<vtkPGILightCloudRelight> relight;
  relight->SetInputData(b.Receivers);
  relight->SetCloudData(cloud);
  relight->SetOccluder(b.Occluder);
  relight->AddLight(p[0], p[1], p[2], 1, 1, 1);
  relight->Update();
  if (ms)
  {
    // Frames of a light moving in small steps around p.
    const int frames = 20;
    const double t0 = Now();
    for (int f = 0; f < frames; ++f)
    {
      relight->SetLightPosition(0, p[0] + 0.002 * f, p[1], p[2] - 0.001 * f);
      relight->SetTime(f / 30.0);
      relight->Update();
    }
    *ms = 1000.0 * (Now() - t0) / frames;
    relight->SetLightPosition(0, p[0], p[1], p[2]);
    relight->ResetFade();
    relight->Update();
  }
  auto result = vtkSmartPointer<vtkFloatArray>::New();
  result->DeepCopy(relight->GetOutput()->GetPointData()->GetArray("LightCloudRadiance"));
  return result;
}

// The exact glossy radiance (direct and one bounce) of each clear test
// light seen from each view point; GlossyTruth[light][view], RGB.
void GlossyReference(Bench& b, int samples)
{
  proxygi::ReferenceTracer tracer;
  std::string error;
  const double grey[3] = { 0.8, 0.8, 0.8 };
  if (!proxygi::AddPolyData(tracer, b.Receivers, grey, "Albedo", error) || !tracer.Commit(error) ||
    !proxygi::ReceiverNormals(b.Receivers, b.Normals, error))
  {
    std::fprintf(stderr, "glossy reference: %s\n", error.c_str());
    std::exit(1);
  }
  const vtkIdType n = b.Receivers->GetNumberOfPoints();
  const double offset = tracer.GetRayOffset();
  const std::size_t lights = b.Lights.size(), views = b.Views.size();
  b.GlossyTruth.assign(lights, std::vector<std::vector<float>>(views, std::vector<float>(3 * n)));
  b.GlossyIndirectTruth = b.GlossyTruth;
  vtkSMPTools::For(0, n,
    [&](vtkIdType first, vtkIdType last)
    {
      std::vector<proxygi::ReferenceTracer::GatherHit> hits;
      for (vtkIdType i = first; i < last; ++i)
      {
        double x[3], a[3];
        b.Receivers->GetPoint(i, x);
        proxygi::AlbedoOf(b.Receivers, "Albedo", i, grey, a);
        const double* nrm = &b.Normals[3 * i];
        tracer.GatherHits(x, nrm, 977, static_cast<std::uint64_t>(i), samples, hits);
        const double o[3] = { x[0] + offset * nrm[0], x[1] + offset * nrm[1],
          x[2] + offset * nrm[2] };
        for (std::size_t k = 0; k < lights; ++k)
        {
          const double* p = b.Lights[k].data();
          // Incident irradiance: direction, RGB amount.
          std::vector<std::array<double, 6>> in;
          std::size_t firstBounce = 0;
          double w[3] = { p[0] - x[0], p[1] - x[1], p[2] - x[2] };
          const double d2 = vtkMath::Dot(w, w);
          vtkMath::Normalize(w);
          const double c = vtkMath::Dot(nrm, w);
          if (c > 0.0 && !tracer.SegmentBlocked(o, p))
          {
            in.push_back({ w[0], w[1], w[2], c / d2, c / d2, c / d2 });
            firstBounce = 1;
          }
          for (const auto& hit : hits)
          {
            const double y[3] = { hit.Position[0], hit.Position[1], hit.Position[2] };
            double v[3] = { p[0] - y[0], p[1] - y[1], p[2] - y[2] };
            const double e2 = vtkMath::Dot(v, v);
            const double ch =
              (hit.Normal[0] * v[0] + hit.Normal[1] * v[1] + hit.Normal[2] * v[2]) / std::sqrt(e2);
            if (ch > 0.0 && !tracer.SegmentBlocked(y, p))
            {
              double u[3] = { y[0] - x[0], y[1] - x[1], y[2] - x[2] };
              vtkMath::Normalize(u);
              const double g = ch / e2 / samples;
              in.push_back(
                { u[0], u[1], u[2], hit.Albedo[0] * g, hit.Albedo[1] * g, hit.Albedo[2] * g });
            }
          }
          for (std::size_t v = 0; v < views; ++v)
          {
            double wo[3];
            vtkMath::Subtract(b.Views[v].data(), x, wo);
            vtkMath::Normalize(wo);
            double l[3] = { 0, 0, 0 }, indirect[3] = { 0, 0, 0 };
            for (std::size_t q = 0; q < in.size(); ++q)
            {
              const double f =
                GlossySpecular * proxygi::PhongLobe(nrm, in[q].data(), wo, GlossyExponent);
              for (int ch = 0; ch < 3; ++ch)
              {
                const double value = (a[ch] / vtkMath::Pi() + f) * in[q][3 + ch];
                l[ch] += value;
                indirect[ch] += q >= firstBounce ? value : 0.0;
              }
            }
            for (int ch = 0; ch < 3; ++ch)
            {
              b.GlossyTruth[k][v][3 * i + ch] = static_cast<float>(l[ch]);
              b.GlossyIndirectTruth[k][v][3 * i + ch] = static_cast<float>(indirect[ch]);
            }
          }
        }
      }
    });
}

// Errors of a glossy cloud: Error/Worst over the views (clear lights),
// ViewError per view.
void RunGlossy(vtkPGILightCloud* cloud, Bench& b, bool direct, Result& r)
{
  r.ViewError.assign(b.Views.size(), 0.0);
  int clear = 0;
  for (std::size_t k = 0; k < b.Lights.size(); ++k)
  {
    if (b.Near[k])
    {
      continue;
    }
    ++clear;
    for (std::size_t v = 0; v < b.Views.size(); ++v)
    {
      vtkNew<vtkPGILightCloudRelight> relight;
      relight->SetInputData(b.Receivers);
      relight->SetCloudData(cloud);
      relight->SetOccluder(b.Occluder);
      relight->AddLight(b.Lights[k][0], b.Lights[k][1], b.Lights[k][2], 1, 1, 1);
      relight->SetViewPoint(b.Views[v].data());
      relight->Update();
      if (k == 0 && v == 0)
      {
        // Frames of the light moving in small steps, then back.
        const int frames = 10;
        const double t0 = Now();
        for (int f = 1; f <= frames; ++f)
        {
          relight->SetLightPosition(0, b.Lights[k][0] + 0.002 * f, b.Lights[k][1], b.Lights[k][2]);
          relight->Update();
        }
        r.RelightMs = 1000.0 * (Now() - t0) / frames;
        relight->SetLightPosition(0, b.Lights[k][0], b.Lights[k][1], b.Lights[k][2]);
        relight->ResetFade();
        relight->Update();
      }
      vtkDataArray* seen = relight->GetOutput()->GetPointData()->GetArray("LightCloudRadiance");
      double e2 = 0.0, t2 = 0.0;
      for (vtkIdType i = 0; i < b.Receivers->GetNumberOfPoints(); ++i)
      {
        double x[3], wo[3];
        b.Receivers->GetPoint(i, x);
        vtkMath::Subtract(b.Views[v].data(), x, wo);
        if (vtkMath::Dot(wo, &b.Normals[3 * i]) <= 0.0)
        {
          continue; // facing away from this viewer
        }
        for (int c = 0; c < 3; ++c)
        {
          const double t = (direct ? b.GlossyTruth : b.GlossyIndirectTruth)[k][v][3 * i + c];
          const double d = seen->GetComponent(i, c) - t;
          e2 += d * d;
          t2 += t * t;
        }
      }
      const double e = std::sqrt(e2 / std::max(t2, 1e-300));
      r.ViewError[v] += e;
      r.Worst = std::max(r.Worst, e);
    }
  }
  for (double& e : r.ViewError)
  {
    e /= std::max(1, clear);
    r.Error += e / static_cast<double>(r.ViewError.size());
  }
}

Result Run(const Setting& s, Bench& b)
{
  Result r;
  vtkNew<vtkPGILightCloudPrecompute> precompute;
  precompute->SetInputData(b.Receivers);
  precompute->SetRegionOfInterest(b.Region);
  // Cubic cells: Resolution along the region's shortest axis.
  double shortest = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    shortest = std::min(shortest, b.Region[2 * a + 1] - b.Region[2 * a]);
  }
  int cells[3];
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = std::max(1,
      static_cast<int>(
        std::lround(s.Resolution * (b.Region[2 * a + 1] - b.Region[2 * a]) / shortest)));
  }
  precompute->SetGridResolution(cells);
  if (s.AtTestLights)
  {
    // SH truncation and noise alone: relighting lands on a cloud light.
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (const auto& p : b.Lights)
    {
      points->InsertNextPoint(p.data());
    }
    precompute->SetLightPositions(points);
    precompute->SetSurfaceMargin(0.0);
  }
  precompute->SetSamples(s.Samples);
  precompute->SetCompress(s.Compress);
  precompute->SetMergeTolerance(s.MergeTolerance);
  precompute->SetZoneSize(s.ZoneSize);
  precompute->SetVectorsPerReceiver(s.Vectors);
  precompute->SetMergedResponse(s.Merged);
  if (s.GlossyOrder > 0)
  {
    precompute->SetSpecularAlbedo(GlossySpecular);
    precompute->SetPhongExponent(GlossyExponent);
    precompute->SetGlossyOrder(s.GlossyOrder);
    precompute->SetIncludeDirect(s.GlossyDirect);
  }
  precompute->Update();
  vtkPGILightCloud* cloud = precompute->GetOutput();
  r.Precompute = precompute->GetSeconds();
  r.Lights = s.Compress ? precompute->GetCompressedLights() : cloud->GetNumberOfLights();
  r.Coefficients = cloud->GetCoefficientsPerReceiver();
  r.MegaBytes = cloud->GetActualMemorySize() / 1024.0;
  if (s.GlossyOrder > 0)
  {
    RunGlossy(cloud, b, s.GlossyDirect, r);
    return r;
  }
  for (std::size_t k = 0; k < b.Lights.size(); ++k)
  {
    double ms = 0.0;
    auto a = Relit(cloud, b, b.Lights[k].data(), k == 0 ? &ms : nullptr);
    if (k == 0)
    {
      r.RelightMs = ms;
    }
    double e2 = 0.0, t2 = 0.0, total2 = 0.0;
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      const double d = a->GetValue(i) - b.Truth[k]->GetValue(i);
      const double total =
        static_cast<double>(b.Truth[k]->GetValue(i)) + b.TruthDirect[k]->GetValue(i);
      e2 += d * d;
      t2 += static_cast<double>(b.Truth[k]->GetValue(i)) * b.Truth[k]->GetValue(i);
      total2 += total * total;
    }
    const double e = std::sqrt(e2 / t2);
    if (std::getenv("PGI_VERBOSE"))
    {
      std::printf("  light %zu at (%.3f %.3f %.3f)%s: %.1f%%\n", k, b.Lights[k][0], b.Lights[k][1],
        b.Lights[k][2], b.Near[k] ? " near a surface" : "", 100 * e);
    }
    if (b.Near[k])
    {
      r.NearError += e / b.NearCount;
      continue;
    }
    const double clear = static_cast<double>(b.Lights.size() - b.NearCount);
    r.TotalError += std::sqrt(e2 / total2) / clear;
    r.Error += e / clear;
    r.Worst = std::max(r.Worst, e);
  }
  return r;
}
int GlossySweep(Bench& b, const std::string& name, const std::string& out, bool quick, int spp)
{
  // View points inside the region: a low front corner, high above, a side.
  const double* g = b.Region;
  auto at = [g](double u, double v, double w)
  {
    return std::array<double, 3>{ g[0] + u * (g[1] - g[0]), g[2] + v * (g[3] - g[2]),
      g[4] + w * (g[5] - g[4]) };
  };
  b.Views = { at(0.15, 0.1, 0.3), at(0.5, 0.5, 0.9), at(0.9, 0.6, 0.5) };
  const double t0 = Now();
  GlossyReference(b, spp);
  std::printf("%s, glossy receivers (Phong ks %.2f, exponent %.0f): %lld receivers, %zu test "
              "lights (%d near surfaces, left out), %zu view points; reference %d gather rays "
              "(%.1f s)\n",
    name.c_str(), GlossySpecular, GlossyExponent,
    static_cast<long long>(b.Receivers->GetNumberOfPoints()), b.Lights.size(), b.NearCount,
    b.Views.size(), spp, Now() - t0);
  std::vector<Setting> settings;
  auto orderName = [](int order)
  {
    return "order " + std::to_string(order) + " (" + std::to_string(order * order) + " per colour)";
  };
  for (int order : quick ? std::vector<int>{ 2, 4, 6 } : std::vector<int>{ 2, 3, 4, 5, 6 })
  {
    Setting s;
    s.Knob = "SH order, cloud lights on the test lights";
    s.AtTestLights = true;
    s.GlossyOrder = order;
    s.Value = orderName(order);
    settings.push_back(s);
  }
  for (int order : { 2, 4 })
  {
    Setting s;
    s.Knob = "SH order";
    s.Resolution = quick ? 3 : 4;
    s.GlossyOrder = order;
    s.Value = orderName(order) + ", " + std::to_string(s.Resolution) + " cells across";
    settings.push_back(s);
  }
  for (int res : quick ? std::vector<int>{ 5 } : std::vector<int>{ 3, 5, 6 })
  {
    Setting s;
    s.Knob = "cloud density";
    s.Resolution = res;
    s.GlossyOrder = 4;
    s.Value = orderName(4) + ", " + std::to_string(res) + " cells across";
    settings.push_back(s);
  }
  for (int res : quick ? std::vector<int>{ 3 } : std::vector<int>{ 3, 5 })
  {
    Setting s;
    s.Knob = "direct light in the cloud too";
    s.Resolution = res;
    s.GlossyOrder = 4;
    s.GlossyDirect = true;
    s.Value = orderName(4) + ", " + std::to_string(res) + " cells across";
    settings.push_back(s);
  }
  {
    Setting s;
    s.Knob = "direct light in the cloud too";
    s.AtTestLights = true;
    s.GlossyOrder = 4;
    s.GlossyDirect = true;
    s.Value = orderName(4) + ", cloud lights on the test lights";
    settings.push_back(s);
  }
  Setting compressed;
  compressed.GlossyOrder = 4;
  compressed.Resolution = quick ? 3 : 4;
  compressed.Compress = true;
  compressed.Vectors = 16;
  compressed.Knob = "compressed";
  compressed.Value = "order 4, " + std::to_string(compressed.Resolution) +
    " cells across, tolerance 0.10, 16 vectors";
  settings.push_back(compressed);

  std::ofstream md(out + ".md"), csv(out + ".csv");
  csv << "knob,value,lights,coefficients,megabytes,precompute_s,relight_ms,error,worst";
  char line[1024];
  std::snprintf(line, sizeof(line),
    "Scene: %s, %lld receivers, all glossy (Phong ks %.2f, exponent %.0f, Lambert albedo as "
    "the scene's). Error: relative RMSE of the indirect radiance (direct and indirect where the "
    "knob says so) seen from each view point over the receivers facing it, against the exact "
    "glossy radiance (%d gather rays), mean over %d test lights clear of surfaces.\n\n"
    "| knob | setting | cloud lights | coefficients / receiver | memory (MB) | precompute (s) | "
    "relight (ms / frame) | view 1 | view 2 | view 3 | mean | worst |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    name.c_str(), static_cast<long long>(b.Receivers->GetNumberOfPoints()), GlossySpecular,
    GlossyExponent, spp, static_cast<int>(b.Lights.size()) - b.NearCount);
  for (std::size_t v = 0; v < b.Views.size(); ++v)
  {
    csv << ",view" << v + 1;
  }
  csv << "\n";
  md << line;
  std::printf("%s", line);
  for (const Setting& s : settings)
  {
    const Result r = Run(s, b);
    std::snprintf(line, sizeof(line),
      "| %s | %s | %.1f | %.1f | %.2f | %.2f | %.2f | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% "
      "|\n",
      s.Knob.c_str(), s.Value.c_str(), r.Lights, r.Coefficients, r.MegaBytes, r.Precompute,
      r.RelightMs, 100 * r.ViewError[0], 100 * r.ViewError[1], 100 * r.ViewError[2], 100 * r.Error,
      100 * r.Worst);
    md << line;
    std::printf("%s", line);
    std::fflush(stdout);
    csv << s.Knob << ',' << s.Value << ',' << r.Lights << ',' << r.Coefficients << ','
        << r.MegaBytes << ',' << r.Precompute << ',' << r.RelightMs << ',' << r.Error << ','
        << r.Worst;
    for (double e : r.ViewError)
    {
      csv << ',' << e;
    }
    csv << '\n';
  }
  std::printf("wrote %s.md, %s.csv\n", out.c_str(), out.c_str());
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  // Debian's VTK defaults to the sequential SMP backend: both cores.
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkSMPTools::SetBackend("STDThread");
  }
  std::string out = "lightcloud-sweep", scenePath = PROXYGI_BENCH_SCENE;
  bool quick = false, glossy = false;
  int referenceSamples = 512;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
    {
      out = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else if (!std::strcmp(argv[i], "--glossy"))
    {
      glossy = true;
    }
    else if (!std::strcmp(argv[i], "--reference-spp") && i + 1 < argc)
    {
      referenceSamples = std::atoi(argv[++i]);
    }
    else
    {
      scenePath = argv[i];
    }
  }
  proxygi::SceneDescription description;
  proxygi::LoadedScene scene;
  std::string error;
  if (!proxygi::LoadScene(scenePath, description, error) ||
    !proxygi::BuildScene(description, scene, error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  Bench b;
  vtkNew<vtkAppendPolyData> append;
  for (auto& object : scene.Objects)
  {
    append->AddInputData(object);
    b.Occluder->AddMesh(object);
  }
  append->Update();
  b.Receivers = append->GetOutput();
  b.Receivers->GetBounds(b.Region);
  if (description.HasCloudRegion)
  {
    std::copy(description.CloudRegion, description.CloudRegion + 6, b.Region);
  }
  std::string message;
  b.Occluder->Prepare(message);

  // Test lights: uniform in the region, inset, not inside a solid (a point
  // all of whose six axis rays are blocked), from a fixed seed. Lights
  // closer to a surface than half the baseline grid's cell are counted
  // apart: the cloud's lights are no nearer than that, so there it
  // extrapolates a near field it never saw.
  std::uint64_t state = 0x5EED;
  auto next = [&state]()
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (state >> 11) * (1.0 / 9007199254740992.0);
  };
  vtkNew<vtkStaticCellLocator> surfaces;
  surfaces->SetDataSet(b.Receivers);
  surfaces->BuildLocator();
  double halfCell = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    halfCell = std::min(halfCell, 0.5 * (b.Region[2 * a + 1] - b.Region[2 * a]) / 5.0);
  }
  const int clearLights = quick ? 3 : 6, nearLights = quick ? 2 : 4;
  int clearFound = 0;
  for (int tries = 0; tries < 100000 && (clearFound < clearLights || b.NearCount < nearLights);
       ++tries)
  {
    std::array<double, 3> p;
    for (int a = 0; a < 3; ++a)
    {
      const double lo = b.Region[2 * a], hi = b.Region[2 * a + 1];
      p[a] = lo + (0.1 + 0.8 * next()) * (hi - lo);
    }
    float origins[18], directions[18] = { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 };
    for (int r = 0; r < 6; ++r)
    {
      for (int a = 0; a < 3; ++a)
      {
        origins[3 * r + a] = static_cast<float>(p[a]);
      }
    }
    unsigned char blocked[6];
    b.Occluder->Occluded(6, origins, directions, 0.0f, blocked);
    if (blocked[0] + blocked[1] + blocked[2] + blocked[3] + blocked[4] + blocked[5] == 6)
    {
      continue;
    }
    double closest[3], d2;
    vtkIdType cell;
    int sub;
    surfaces->FindClosestPoint(p.data(), closest, cell, sub, d2);
    const bool near = d2 < halfCell * halfCell;
    if (near ? b.NearCount < nearLights : clearFound < clearLights)
    {
      b.Lights.push_back(p);
      b.Near.push_back(near ? 1 : 0);
      (near ? b.NearCount : clearFound)++;
    }
  }
  if (glossy)
  {
    return GlossySweep(b, description.Name, out, quick, referenceSamples);
  }
  const int testLights = static_cast<int>(b.Lights.size());
  double noise = 0.0, nearNoise = 0.0;
  for (const auto& p : b.Lights)
  {
    const bool isNear = b.Near[b.Truth.size()] != 0;
    vtkNew<vtkPGILighting> lighting;
    lighting->SetUniformRadiance(0.0, 0.0, 0.0);
    lighting->AddPointLight(p[0], p[1], p[2], 1.0, 1.0, 1.0);
    vtkNew<vtkPGIReferenceIllumination> reference;
    reference->SetInputData(b.Receivers);
    reference->SetLighting(lighting);
    reference->SetSamples(referenceSamples);
    reference->Update();
    auto truth = vtkSmartPointer<vtkFloatArray>::New();
    truth->DeepCopy(reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce"));
    b.Truth.push_back(truth);
    auto direct = vtkSmartPointer<vtkFloatArray>::New();
    direct->DeepCopy(reference->GetOutput()->GetPointData()->GetArray("DirectShadowed"));
    b.TruthDirect.push_back(direct);
    vtkDataArray* se = reference->GetOutput()->GetPointData()->GetArray("IndirectStdErr");
    double s2 = 0.0, t2 = 0.0;
    for (vtkIdType i = 0; i < truth->GetNumberOfValues(); ++i)
    {
      s2 += se->GetComponent(i / 3, i % 3) * se->GetComponent(i / 3, i % 3);
      t2 += static_cast<double>(truth->GetValue(i)) * truth->GetValue(i);
    }
    (isNear ? nearNoise : noise) += std::sqrt(s2 / t2);
  }
  noise /= std::max(1, testLights - b.NearCount);
  nearNoise /= std::max(1, b.NearCount);
  std::printf("%s: %lld receivers; %d test lights (%d within %.3f of a surface); Embree %d "
              "samples, its own indirect noise %.2f%% (near: %.2f%%)\n",
    description.Name.c_str(), static_cast<long long>(b.Receivers->GetNumberOfPoints()), testLights,
    b.NearCount, halfCell, referenceSamples, 100 * noise, 100 * nearNoise);

  std::vector<Setting> settings;
  Setting base;
  base.Knob = "baseline";
  base.Value = "5 cells across, 64 samples, dense";
  settings.push_back(base);
  for (int res : quick ? std::vector<int>{ 3, 7 } : std::vector<int>{ 3, 4, 6, 7, 8 })
  {
    Setting s = base;
    s.Knob = "cloud density";
    s.Resolution = res;
    s.Value = std::to_string(res) + " cells across";
    settings.push_back(s);
  }
  for (int spp : quick ? std::vector<int>{ 16, 256 } : std::vector<int>{ 16, 32, 128, 256 })
  {
    Setting s = base;
    s.Knob = "gather samples";
    s.Samples = spp;
    s.Value = std::to_string(spp) + " samples";
    settings.push_back(s);
  }
  Setting compressed = base;
  compressed.Compress = true;
  compressed.Samples = 128;
  compressed.Vectors = 12;
  for (double tol :
    quick ? std::vector<double>{ 0.05, 0.4 } : std::vector<double>{ 0.02, 0.05, 0.1, 0.2, 0.4 })
  {
    Setting s = compressed;
    s.Knob = "clustering (MergeTolerance)";
    s.MergeTolerance = tol;
    char v[64];
    std::snprintf(v, sizeof(v), "tolerance %.2f", tol);
    s.Value = v;
    settings.push_back(s);
  }
  for (vtkIdType zone : quick ? std::vector<vtkIdType>{ 100000, 200 }
                              : std::vector<vtkIdType>{ 100000, 1000, 400, 200 })
  {
    Setting s = compressed;
    s.Knob = "zones (ZoneSize)";
    s.ZoneSize = zone;
    s.Value = zone >= 100000 ? std::string("one zone") : "zones of <= " + std::to_string(zone);
    settings.push_back(s);
  }
  for (double vectors :
    quick ? std::vector<double>{ 4, 16 } : std::vector<double>{ 2, 4, 8, 12, 16, 24 })
  {
    Setting s = compressed;
    s.Knob = "PCA vectors per receiver";
    s.Vectors = vectors;
    s.Value = std::to_string(static_cast<int>(vectors)) + " vectors";
    settings.push_back(s);
  }
  for (int merged : { vtkPGILightCloudPrecompute::AVERAGED_RESPONSE,
         vtkPGILightCloudPrecompute::RECOMPUTED_RESPONSE })
  {
    Setting s = compressed;
    s.Knob = "merged response";
    s.Merged = merged;
    s.MergeTolerance = 0.4;
    s.Value = merged ? "recomputed at the mean" : "averaged";
    settings.push_back(s);
  }

  std::ofstream md(out + ".md"), csv(out + ".csv");
  csv << "knob,value,lights,coefficients,megabytes,precompute_s,relight_ms,indirect_error,worst,"
         "total_error,near_indirect_error\n";
  char line[1024];
  std::snprintf(line, sizeof(line),
    "Scene: %s, %lld receivers; %d test lights at random (seed 0x5EED), %d of them within "
    "%.3f (half the baseline's cell) of a surface; Embree %d samples (its own indirect noise "
    "%.2f%%, near surfaces %.2f%%). Errors are relative RMSE against Embree, mean over the "
    "lights clear of surfaces unless the column says near; the total takes Embree's exact "
    "direct light.\n\n"
    "| knob | setting | cloud lights | coefficients / receiver | memory (MB) | precompute (s) | "
    "relight (ms / frame) | indirect error | worst | total error | indirect error, near "
    "surfaces |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
    description.Name.c_str(), static_cast<long long>(b.Receivers->GetNumberOfPoints()), testLights,
    b.NearCount, halfCell, referenceSamples, 100 * noise, 100 * nearNoise);
  md << line;
  std::printf("%s", line);
  std::vector<pgibench::Series> series;
  for (const Setting& s : settings)
  {
    const Result r = Run(s, b);
    std::snprintf(line, sizeof(line),
      "| %s | %s | %.1f | %.1f | %.2f | %.2f | %.2f | %.1f%% | %.1f%% | %.1f%% | %.1f%% |\n",
      s.Knob.c_str(), s.Value.c_str(), r.Lights, r.Coefficients, r.MegaBytes, r.Precompute,
      r.RelightMs, 100 * r.Error, 100 * r.Worst, 100 * r.TotalError, 100 * r.NearError);
    md << line;
    std::printf("%s", line);
    std::fflush(stdout);
    csv << s.Knob << ',' << s.Value << ',' << r.Lights << ',' << r.Coefficients << ','
        << r.MegaBytes << ',' << r.Precompute << ',' << r.RelightMs << ',' << r.Error << ','
        << r.Worst << ',' << r.TotalError << ',' << r.NearError << '\n';
    auto it = std::find_if(
      series.begin(), series.end(), [&](const pgibench::Series& x) { return x.Name == s.Knob; });
    if (it == series.end())
    {
      series.push_back({ s.Knob, {}, {}, false });
      it = series.end() - 1;
    }
    it->X.push_back(r.Coefficients);
    it->Y.push_back(100 * r.Error);
  }
  pgibench::WritePlot(out + ".png",
    { "Light cloud: indirect error against coefficients per receiver (" + description.Name + ")",
      "coefficients per receiver", "relative RMSE of indirect radiance (%)" },
    series);
  std::printf("wrote %s.md, %s.csv, %s.png\n", out.c_str(), out.c_str(), out.c_str());
  return 0;
}
