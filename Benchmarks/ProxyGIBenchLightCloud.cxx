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
#include "pgiBenchPlot.h"
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
#include <vtkPolyData.h>
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
};

struct Result
{
  double Lights = 0, Coefficients = 0, MegaBytes = 0, Precompute = 0, RelightMs = 0;
  // Over the lights clear of surfaces; NearError over those near them.
  double Error = 0, Worst = 0, TotalError = 0, NearError = 0;
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
  precompute->SetSamples(s.Samples);
  precompute->SetCompress(s.Compress);
  precompute->SetMergeTolerance(s.MergeTolerance);
  precompute->SetZoneSize(s.ZoneSize);
  precompute->SetVectorsPerReceiver(s.Vectors);
  precompute->SetMergedResponse(s.Merged);
  precompute->Update();
  vtkPGILightCloud* cloud = precompute->GetOutput();
  r.Precompute = precompute->GetSeconds();
  r.Lights = s.Compress ? precompute->GetCompressedLights() : cloud->GetNumberOfLights();
  r.Coefficients = cloud->GetCoefficientsPerReceiver();
  r.MegaBytes = cloud->GetActualMemorySize() / 1024.0;
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
} // namespace

int main(int argc, char* argv[])
{
  std::string out = "lightcloud-sweep", scenePath = PROXYGI_BENCH_SCENE;
  bool quick = false;
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
