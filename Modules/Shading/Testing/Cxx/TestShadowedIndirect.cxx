// Shadowed one-bounce light from spherical lights (Guerrero 2008):
//  1. analytic: a sphere mesh of albedo 0.5 in uniform light, its samples
//     found by vtkPGISphereLightSampler, seen from receivers facing it: the
//     exit radiance is 0.5 sin^2(theta) (a uniform disk of radiance 0.5);
//  2. against the Embree reference (real meshes, one bounce): a bright ball
//     and a dark ball on a ground, the ground's indirect light;
//     IndirectShadowed against IndirectProxy (unshadowed, AVERAGED);
//  3. two objects of two intersecting spheres each: per-sphere and
//     per-object blocking both run and stay close to each other and the
//     reference; the Plan says what ran; modes Off and skipped cases;
//  4. a spherical light (black sky) lighting the samples: the bounce
//     against the reference (its mean; see the note on ringing).
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"

#include "pgiTesting.h"
#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGIReferenceIllumination.h"
#include "vtkPGISphereLightSampler.h"
#include "vtkPGISphereSetApproximation.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkTrivialProducer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkPolyData> Ellipsoid(
  const double c[3], const double axes[3], double albedo, int object)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(48);
  source->SetPhiResolution(32);
  source->SetRadius(1.0);
  source->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(source->GetOutput());
  mesh->GetPointData()->SetNormals(nullptr);
  vtkNew<vtkFloatArray> a;
  a->SetName("Albedo");
  a->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> id;
  id->SetName("ObjectId");
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      p[k] = c[k] + axes[k] * p[k];
    }
    mesh->GetPoints()->SetPoint(i, p);
    a->InsertNextTuple3(albedo, albedo, albedo);
    id->InsertNextValue(object);
  }
  mesh->GetPointData()->AddArray(a);
  mesh->GetPointData()->AddArray(id);
  return mesh;
}

vtkSmartPointer<vtkPolyData> Spheres(const std::vector<double>& xyzr,
  const std::vector<int>& object, const std::vector<double>& albedo)
{
  auto proxies = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius, a;
  vtkNew<vtkIntArray> id;
  radius->SetName("Radius");
  a->SetName("Albedo");
  a->SetNumberOfComponents(3);
  id->SetName("ObjectId");
  for (std::size_t i = 0; 4 * i + 3 < xyzr.size(); ++i)
  {
    points->InsertNextPoint(xyzr[4 * i], xyzr[4 * i + 1], xyzr[4 * i + 2]);
    radius->InsertNextValue(xyzr[4 * i + 3]);
    id->InsertNextValue(object[i]);
    a->InsertNextTuple3(albedo[i], albedo[i], albedo[i]);
  }
  proxies->SetPoints(points);
  proxies->GetPointData()->AddArray(radius);
  proxies->GetPointData()->AddArray(id);
  proxies->GetPointData()->AddArray(a);
  return proxies;
}

using pgitest::RelativeRMSE;

// int_disk H dw for a disk of angular radius asin(s) straight above, with H
// the order-4 (bands 0-2; band 3 is 0) clamped cosine / pi: what SH order 4
// can give. 6.25% over sin^2 for small disks.
double DiskOrder4(double s)
{
  const double c = std::sqrt(1 - s * s);
  const double p2 = (3 * c * c - 1) / 2, p3 = (5 * c * c * c - 3 * c) / 2;
  return (1 - c) / 2 + (1 - p2) / 3 + (c - p3) / 8;
}

// Two spheres' meshes, each without the triangles inside the other: their
// union's surface, which two proxies fit exactly.
vtkSmartPointer<vtkPolyData> Peanut(
  const double a[3], const double b[3], double r, double albedo, int object)
{
  const double axes[3] = { r, r, r };
  vtkNew<vtkAppendPolyData> append;
  const double* c[2] = { a, b };
  for (int k = 0; k < 2; ++k)
  {
    vtkSmartPointer<vtkPolyData> ball = Ellipsoid(c[k], axes, albedo, object);
    const double* other = c[1 - k];
    vtkNew<vtkCellArray> kept;
    vtkIdType npts;
    const vtkIdType* ids;
    for (ball->GetPolys()->InitTraversal(); ball->GetPolys()->GetNextCell(npts, ids);)
    {
      double m[3] = { 0, 0, 0 };
      for (vtkIdType q = 0; q < npts; ++q)
      {
        double x[3];
        ball->GetPoint(ids[q], x);
        for (int j = 0; j < 3; ++j)
        {
          m[j] += x[j] / npts;
        }
      }
      const double d2 =
        std::pow(m[0] - other[0], 2) + std::pow(m[1] - other[1], 2) + std::pow(m[2] - other[2], 2);
      if (d2 > r * r)
      {
        kept->InsertNextCell(npts, ids);
      }
    }
    ball->SetPolys(kept);
    append->AddInputData(ball);
  }
  append->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(append->GetOutput());
  return out;
}

double Mean(vtkDataArray* a, vtkIdType count)
{
  double sum = 0;
  for (vtkIdType i = 0; i < count; ++i)
  {
    sum += a->GetComponent(i, 0);
  }
  return sum / count;
}

bool PlanHas(vtkPGIGlobalIllumination* gi, const std::string& text)
{
  for (const std::string& line : gi->GetPlan())
  {
    if (line.find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

void PrintPlan(vtkPGIGlobalIllumination* gi)
{
  for (const std::string& line : gi->GetPlan())
  {
    std::printf("  plan: %s\n", line.c_str());
  }
}

// A ground patch (compared) with a skirt out to 100 (not compared), as in
// TestIndirectLight, so the reference ground is as infinite as the plane.
struct Ground
{
  vtkNew<vtkPlaneSource> Patch;
  vtkNew<vtkAppendPolyData> All;
  Ground()
  {
    this->Patch->SetOrigin(-3, -3, 0);
    this->Patch->SetPoint1(5, -3, 0);
    this->Patch->SetPoint2(-3, 3, 0);
    this->Patch->SetResolution(32, 24);
    this->All->AddInputConnection(this->Patch->GetOutputPort());
    const double skirts[4][4] = { { -100, 100, 3, 100 }, { -100, 100, -100, -3 },
      { -100, -3, -3, 3 }, { 5, 100, -3, 3 } };
    for (const auto& k : skirts)
    {
      vtkNew<vtkPlaneSource> skirt;
      skirt->SetOrigin(k[0], k[2], 0);
      skirt->SetPoint1(k[1], k[2], 0);
      skirt->SetPoint2(k[0], k[3], 0);
      this->All->AddInputConnection(skirt->GetOutputPort());
    }
  }
};

struct Run
{
  double Seconds;
  vtkSmartPointer<vtkPolyData> Output;
  std::vector<std::string> Plan;
};

// Shade's mode for no indirect light.
constexpr int IndirectNone = -1;

Run Shade(vtkAlgorithmOutput* receivers, vtkPolyData* proxies, int mode, int blocking)
{
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputConnection(receivers);
  gi->SetProxiesData(proxies);
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
  gi->AddBlockerPlane(origin, up);
  gi->GetSettings()->SetIndirect(mode != IndirectNone);
  gi->GetSettings()->SetIndirectMode(mode == IndirectNone ? 0 : mode);
  gi->GetSettings()->SetSphericalLightBlocking(blocking);
  const auto start = std::chrono::steady_clock::now();
  gi->Update();
  Run run;
  run.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.Output = gi->GetOutput();
  run.Plan = gi->GetPlan();
  return run;
}
} // namespace

namespace
{
// The measurement (label slow, argument --timing): six peanuts (12 spheres)
// and a dark ball on a ground; error against the reference on 825
// receivers, time per receiver on 14641, for the unshadowed AVERAGED bounce
// and the shadowed one with per-sphere and per-object blocking; then the cow
// with 16 variational spheres, on the ground and on its own vertices.
int Timing()
{
  vtkNew<vtkAppendPolyData> meshes;
  std::vector<double> spheres;
  std::vector<int> objects;
  std::vector<double> albedos;
  int object = 0;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 2; ++j, ++object)
    {
      const double x = -2.0 + 2.2 * i, y = -1.2 + 2.4 * j;
      const double a[3] = { x, y, 0.6 }, b[3] = { x + 0.3, y, 1.45 };
      const double albedo = 0.5 + 0.08 * object;
      meshes->AddInputData(Peanut(a, b, 0.55, albedo, object));
      spheres.insert(spheres.end(), { a[0], a[1], a[2], 0.555, b[0], b[1], b[2], 0.555 });
      objects.insert(objects.end(), { object, object });
      albedos.insert(albedos.end(), { albedo, albedo });
    }
  }
  const double darkC[3] = { 1.2, 0, 0.5 }, small[3] = { 0.45, 0.45, 0.45 };
  meshes->AddInputData(Ellipsoid(darkC, small, 0.0, object));
  spheres.insert(spheres.end(), { darkC[0], darkC[1], darkC[2], 0.455 });
  objects.push_back(object);
  albedos.push_back(0.0);
  meshes->Update();
  vtkNew<vtkPGISphereLightSampler> sampler;
  sampler->SetInputConnection(meshes->GetOutputPort());
  sampler->SetProxiesData(Spheres(spheres, objects, albedos));
  auto start = std::chrono::steady_clock::now();
  sampler->Update();
  std::printf("sampler: %d spheres in %.3f s\n", static_cast<int>(objects.size()),
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  Ground ground;
  vtkNew<vtkPGIReferenceIllumination> reference;
  reference->SetInputConnection(ground.All->GetOutputPort());
  reference->AddSceneObjectConnection(meshes->GetOutputPort());
  reference->SetSamples(1024);
  reference->Update();
  vtkDataArray* ref = reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
  const Run unshadowed = Shade(ground.Patch->GetOutputPort(), sampler->GetOutput(),
    vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED, 0);
  const Run perSphere = Shade(ground.Patch->GetOutputPort(), sampler->GetOutput(),
    vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_SPHERE);
  const Run perObject = Shade(ground.Patch->GetOutputPort(), sampler->GetOutput(),
    vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_OBJECT);
  const double eu = RelativeRMSE(unshadowed.Output->GetPointData()->GetArray("IndirectProxy"), ref);
  const double es =
    RelativeRMSE(perSphere.Output->GetPointData()->GetArray("IndirectShadowed"), ref);
  const double eo =
    RelativeRMSE(perObject.Output->GetPointData()->GetArray("IndirectShadowed"), ref);

  vtkNew<vtkPlaneSource> fine;
  fine->SetOrigin(-3, -3, 0);
  fine->SetPoint1(5, -3, 0);
  fine->SetPoint2(-3, 3, 0);
  fine->SetResolution(120, 120);
  fine->Update();
  const double n = fine->GetOutput()->GetNumberOfPoints();
  auto best = [&](int mode, int blocking)
  {
    double t = 1e30;
    for (int k = 0; k < 3; ++k)
    {
      t = std::min(t, Shade(fine->GetOutputPort(), sampler->GetOutput(), mode, blocking).Seconds);
    }
    return t;
  };
  const double tOff = best(IndirectNone, 0);
  const double tU = best(vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED, 0);
  const double tS =
    best(vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_SPHERE);
  const double tO =
    best(vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_OBJECT);
  std::printf("6 peanuts + dark ball (13 spheres, 7 objects), order 4, HYB, ground of %d "
              "receivers (error on 825, reference 1024 samples), vtkSMPTools %s, %d threads:\n",
    static_cast<int>(n), vtkSMPTools::GetBackend(), vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("  mode off (direct light only): %.3f s\n", tOff);
  std::printf("  unshadowed AVERAGED: relative RMSE %.1f%%, +%.2f us per receiver\n", 100 * eu,
    1e6 * (tU - tOff) / n);
  std::printf("  shadowed per sphere: relative RMSE %.1f%%, +%.2f us per receiver\n", 100 * es,
    1e6 * (tS - tOff) / n);
  std::printf("  shadowed per object: relative RMSE %.1f%%, +%.2f us per receiver\n", 100 * eo,
    1e6 * (tO - tOff) / n);
  for (const std::string& line : perSphere.Plan)
  {
    std::printf("  plan: %s\n", line.c_str());
  }
  // Measured 24.7% for both (unshadowed 26.2%).
  PGI_BELOW(es, 0.35);
  PGI_BELOW(eo, 0.35);

  // A real object: the cow (3 long), 16 variational spheres, on the ground.
  vtkNew<vtkPGIOFFReader> reader;
  reader->SetFileName((std::string(PROXYGI_DATA_DIR) + "/meshes/cow.off").c_str());
  reader->Update();
  vtkNew<vtkPolyData> cow;
  cow->DeepCopy(reader->GetOutput());
  for (vtkIdType i = 0; i < cow->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cow->GetPoint(i, p);
    const double q[3] = { 3 * p[0], -3 * p[2], 3 * (p[1] + 0.306243) + 0.01 }; // y up -> z up
    cow->GetPoints()->SetPoint(i, q);
  }
  vtkNew<vtkPGISphereSetApproximation> approximation;
  approximation->SetInputData(cow);
  approximation->SetNumberOfSpheres(16);
  start = std::chrono::steady_clock::now();
  approximation->Update();
  const double buildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkNew<vtkPGISphereLightSampler> cowSampler;
  cowSampler->SetInputData(cow);
  cowSampler->SetProxiesConnection(approximation->GetOutputPort());
  start = std::chrono::steady_clock::now();
  cowSampler->Update();
  const double sampleSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkDataArray* rules = cowSampler->GetOutput()->GetFieldData()->GetArray("SampleRules");
  vtkNew<vtkPGIReferenceIllumination> cowReference;
  cowReference->SetInputConnection(ground.All->GetOutputPort());
  cowReference->AddSceneObjectData(cow);
  cowReference->SetSamples(1024);
  cowReference->Update();
  vtkDataArray* cowRef = cowReference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
  const double cowU = RelativeRMSE(Shade(ground.Patch->GetOutputPort(), cowSampler->GetOutput(),
                                     vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED, 0)
                                     .Output->GetPointData()
                                     ->GetArray("IndirectProxy"),
    cowRef);
  const double cowS =
    RelativeRMSE(Shade(ground.Patch->GetOutputPort(), cowSampler->GetOutput(),
                   vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_SPHERE)
                   .Output->GetPointData()
                   ->GetArray("IndirectShadowed"),
      cowRef);
  auto bestCow = [&](int mode, int blocking)
  {
    double t = 1e30;
    for (int k = 0; k < 3; ++k)
    {
      t =
        std::min(t, Shade(fine->GetOutputPort(), cowSampler->GetOutput(), mode, blocking).Seconds);
    }
    return t;
  };
  const double cOff = bestCow(IndirectNone, 0);
  const double cU = bestCow(vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED, 0);
  const double cS =
    bestCow(vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_SPHERE);
  std::printf("cow, 16 variational spheres (%.2f s), samples (%.3f s; rule 1 %g, rule 2 %g, rule 3 "
              "%g, none %g):\n",
    buildSeconds, sampleSeconds, rules->GetTuple1(0), rules->GetTuple1(1), rules->GetTuple1(2),
    rules->GetTuple1(3));
  std::printf("  unshadowed AVERAGED: relative RMSE %.1f%%, +%.2f us per receiver\n", 100 * cowU,
    1e6 * (cU - cOff) / n);
  std::printf("  shadowed per sphere: relative RMSE %.1f%%, +%.2f us per receiver\n", 100 * cowS,
    1e6 * (cS - cOff) / n);
  // Measured 81% against 86%: both bounce about twice the reference's light
  // under the cow, where 16 spheres stand for legs and belly with far more
  // area than they have; away from it (1 to 10 beyond its outline) the
  // shadowed bounce errs 35-50%, the unshadowed one 53-112%.
  PGI_BELOW(cowS, 0.9);
  PGI_CHECK(cowS < cowU);

  // The cow lit by itself: its own vertices as receivers (the ground black,
  // so only the cow bounces, as in the model).
  {
    vtkNew<vtkFloatArray> grey;
    grey->SetName("Albedo");
    grey->SetNumberOfComponents(3);
    for (vtkIdType i = 0; i < cow->GetNumberOfPoints(); ++i)
    {
      grey->InsertNextTuple3(0.8, 0.8, 0.8);
    }
    vtkNew<vtkPolyData> greyCow;
    greyCow->ShallowCopy(cow);
    greyCow->GetPointData()->AddArray(grey);
    vtkNew<vtkPGIReferenceIllumination> self;
    self->SetInputData(greyCow);
    self->AddSceneObjectConnection(ground.All->GetOutputPort());
    self->SetDefaultAlbedo(0, 0, 0);
    self->SetSamples(512);
    self->Update();
    vtkDataArray* selfRef = self->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
    vtkNew<vtkPGISphereLightSampler> greySampler;
    greySampler->SetInputData(greyCow);
    greySampler->SetProxiesConnection(approximation->GetOutputPort());
    greySampler->Update();
    vtkNew<vtkPolyData> receivers;
    receivers->ShallowCopy(greyCow);
    vtkNew<vtkTrivialProducer> source;
    source->SetOutput(receivers);
    double err[3];
    for (int k = 0; k < 3; ++k)
    {
      const Run run = Shade(source->GetOutputPort(), greySampler->GetOutput(),
        k == 0 ? vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED
               : vtkPGIGISettings::INDIRECT_MODE_SHADOWED,
        k == 2 ? vtkPGIGISettings::BLOCKING_PER_OBJECT : vtkPGIGISettings::BLOCKING_PER_SPHERE);
      vtkDataArray* a =
        run.Output->GetPointData()->GetArray(k == 0 ? "IndirectProxy" : "IndirectShadowed");
      err[k] = RelativeRMSE(a, selfRef);
      PGI_CHECK(a->GetRange(0)[0] >= 0.0 && std::isfinite(a->GetRange(0)[1]));
    }
    std::printf("the cow's own vertices (%d, reference 512 samples, mean %.4f): unshadowed "
                "AVERAGED %.1f%%, shadowed per sphere %.1f%%, per object %.1f%%\n",
      static_cast<int>(cow->GetNumberOfPoints()), Mean(selfRef, selfRef->GetNumberOfTuples()),
      100 * err[0], 100 * err[1], 100 * err[2]);
    // Measured 153.7% against 76.5%: on the object itself occlusion is what
    // matters (legs and belly hide one another), and only the shadowed
    // bounce has it.
    PGI_CHECK(err[1] < 0.7 * err[0]);
    // An empty shadowed output scores 100%, which the ratio alone allows.
    PGI_BELOW(err[1], 0.9);
    PGI_BELOW(err[2], 0.9);
  }
  return pgitest::Result();
}
} // namespace

int TestShadowedIndirect(int argc, char* argv[])
{
  using GI = vtkPGIGlobalIllumination;
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--timing")
    {
      return Timing();
    }
  }
  // 1. Analytic: receivers facing a ball of albedo 0.5 in uniform light 1.
  {
    const double c[3] = { 0, 0, 0 }, axes[3] = { 1, 1, 1 };
    vtkSmartPointer<vtkPolyData> ball = Ellipsoid(c, axes, 0.5, 0);
    vtkNew<vtkPGISphereLightSampler> sampler;
    sampler->SetInputData(ball);
    sampler->SetProxiesData(Spheres({ 0, 0, 0, 1.02 }, { 0 }, { 0.0 }));
    vtkNew<vtkPolyData> receivers;
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> normals;
    normals->SetNumberOfComponents(3);
    const double distances[4] = { 1.1, 1.6, 3.0, 5.0 };
    const double dirs[4][3] = { { 0, 0, 1 }, { 0.6, 0.8, 0 }, { -0.48, 0.6, -0.64 }, { 0, -1, 0 } };
    for (int k = 0; k < 4; ++k)
    {
      points->InsertNextPoint(
        distances[k] * dirs[k][0], distances[k] * dirs[k][1], distances[k] * dirs[k][2]);
      normals->InsertNextTuple3(-dirs[k][0], -dirs[k][1], -dirs[k][2]);
    }
    receivers->SetPoints(points);
    receivers->GetPointData()->SetNormals(normals);
    vtkNew<GI> gi;
    gi->SetInputData(receivers);
    gi->SetProxiesConnection(sampler->GetOutputPort());
    gi->GetSettings()->SetDefaultAlbedo(
      1, 1, 1); // receivers; the ball's 0.5 comes from its AlbedoSH
    gi->GetSettings()->SetDefaultProxyAlbedo(1, 1, 1);
    gi->GetSettings()->SetIndirectModeToShadowed();
    gi->Update();
    PrintPlan(gi);
    PGI_CHECK(PlanHas(gi, "92 surface samples of 92 (SampleOffset/SampleNormal arrays), AlbedoSH"));
    vtkDataArray* bounce = gi->GetOutput()->GetPointData()->GetArray("IndirectShadowed");
    vtkDataArray* unshadowed = gi->GetOutput()->GetPointData()->GetArray("IndirectProxy");
    vtkDataArray* total = gi->GetOutput()->GetPointData()->GetArray("Radiance");
    vtkDataArray* direct = gi->GetOutput()->GetPointData()->GetArray("DirectShadowed");
    for (int k = 0; k < 4; ++k)
    {
      const double s = 1.02 / distances[k];
      const double exact = 0.5 * s * s, order4 = 0.5 * DiskOrder4(s);
      std::printf("distance %.1f: IndirectShadowed %.5f, exact %.5f (%+.2f%%), order-4 H %.5f "
                  "(%+.2f%%)\n",
        distances[k], bounce->GetComponent(k, 0), exact,
        100 * (bounce->GetComponent(k, 0) / exact - 1), order4,
        100 * (bounce->GetComponent(k, 0) / order4 - 1));
      // A disk of 68 degrees: the SH exp of its cap log comes out 7% low.
      const double tolerance = distances[k] < 1.5 ? 0.08 : 0.02;
      PGI_NEAR(bounce->GetComponent(k, 0), order4, tolerance * order4);
      PGI_NEAR(bounce->GetComponent(k, 1), bounce->GetComponent(k, 0), 1e-6);
      PGI_NEAR(unshadowed->GetComponent(k, 0), 0.0, 0.0); // only one model runs
      PGI_NEAR(
        total->GetComponent(k, 0), direct->GetComponent(k, 0) + bounce->GetComponent(k, 0), 1e-5);
    }
    // The bounce at order 4 under order-6 shadows (IndirectOrder): the
    // uniform light has no band above 0, so it is the order-4 bounce; the
    // whole order-6 bounce differs (its H and exp run at 6).
    auto bounceAt = [&](int order, int indirectOrder)
    {
      vtkNew<GI> at;
      at->SetInputData(receivers);
      at->SetProxiesConnection(sampler->GetOutputPort());
      at->GetSettings()->SetDefaultAlbedo(1, 1, 1);
      at->GetSettings()->SetDefaultProxyAlbedo(1, 1, 1);
      at->GetSettings()->SetIndirectModeToShadowed();
      at->GetSettings()->SetOrder(order);
      at->GetSettings()->SetIndirectOrder(indirectOrder);
      at->Update();
      PGI_CHECK(PlanHas(at, "the bounce at SH order 4 (shadows at 6)") ==
        (order == 6 && indirectOrder == 4));
      vtkNew<vtkFloatArray> copy;
      copy->DeepCopy(at->GetOutput()->GetPointData()->GetArray("IndirectShadowed"));
      return vtkSmartPointer<vtkFloatArray>(copy.Get());
    };
    vtkSmartPointer<vtkFloatArray> six = bounceAt(6, 0), sixFour = bounceAt(6, 4),
                                   sixEight = bounceAt(6, 8);
    double farthest = 0.0;
    for (int k = 0; k < 4; ++k)
    {
      const double four = bounce->GetComponent(k, 0);
      PGI_NEAR(sixFour->GetComponent(k, 0), four, 1e-5 * four);
      PGI_NEAR(sixEight->GetComponent(k, 0), six->GetComponent(k, 0), 0.0); // 8 > 6: runs at 6
      farthest = std::max(farthest, std::abs(six->GetComponent(k, 0) / four - 1));
    }
    std::printf("order 6 bounce against order 4: at most %.2f%% apart\n", 100 * farthest);
    PGI_CHECK(farthest > 1e-3);
    // Without the sampler's arrays the samples lie on the proxy itself.
    vtkNew<GI> own;
    own->SetInputData(receivers);
    own->SetProxiesData(Spheres({ 0, 0, 0, 1.0 }, { 0 }, { 0.5 }));
    own->GetSettings()->SetDefaultAlbedo(1, 1, 1);
    own->GetSettings()->SetDefaultProxyAlbedo(1, 1, 1);
    own->GetSettings()->SetIndirectModeToShadowed();
    own->Update();
    PGI_CHECK(PlanHas(own, "on the spheres themselves"));
    vtkDataArray* ownBounce = own->GetOutput()->GetPointData()->GetArray("IndirectShadowed");
    for (int k = 0; k < 4; ++k)
    {
      const double order4 = 0.5 * DiskOrder4(1.0 / distances[k]);
      PGI_NEAR(ownBounce->GetComponent(k, 0), order4, (distances[k] < 1.5 ? 0.08 : 0.02) * order4);
    }
    // Skipped: albedo 0 everywhere; mode off.
    vtkNew<GI> black;
    black->SetInputData(receivers);
    black->SetProxiesData(Spheres({ 0, 0, 0, 1.0 }, { 0 }, { 0.0 }));
    black->GetSettings()->SetIndirectModeToShadowed();
    black->Update();
    PGI_CHECK(PlanHas(black, "skipped (every spherical light has albedo 0)"));
    PGI_CHECK(
      black->GetOutput()->GetPointData()->GetArray("IndirectShadowed")->GetRange(0)[1] == 0);
    vtkNew<GI> none;
    none->SetInputData(receivers);
    none->GetSettings()->SetIndirectModeToShadowed();
    none->Update();
    PGI_CHECK(PlanHas(none, "skipped (no proxies to act as spherical lights)"));
    vtkNew<GI> off;
    off->SetInputData(receivers);
    off->SetProxiesData(Spheres({ 0, 0, 0, 1.0 }, { 0 }, { 0.5 }));
    off->GetSettings()->IndirectOff();
    off->Update();
    PGI_CHECK(PlanHas(off, "indirect light: off"));
    // Hard cases: receivers inside the sphere and a coincident second sphere.
    vtkNew<vtkPolyData> inside;
    vtkNew<vtkPoints> insidePoints;
    insidePoints->InsertNextPoint(0, 0, 0);
    insidePoints->InsertNextPoint(0.99, 0, 0);
    insidePoints->InsertNextPoint(0, 1.0, 0);
    inside->SetPoints(insidePoints);
    vtkNew<vtkFloatArray> insideNormals;
    insideNormals->SetNumberOfComponents(3);
    insideNormals->InsertNextTuple3(0, 0, 1);
    insideNormals->InsertNextTuple3(1, 0, 0);
    insideNormals->InsertNextTuple3(0, 1, 0);
    inside->GetPointData()->SetNormals(insideNormals);
    vtkNew<GI> hard;
    hard->SetInputData(inside);
    hard->SetProxiesData(Spheres({ 0, 0, 0, 1.0, 0, 0, 0, 1.0 }, { 0, 1 }, { 0.5, 0.5 }));
    hard->GetSettings()->SetIndirectModeToShadowed();
    hard->Update();
    vtkDataArray* h = hard->GetOutput()->GetPointData()->GetArray("IndirectShadowed");
    for (vtkIdType i = 0; i < 3; ++i)
    {
      PGI_CHECK(std::isfinite(h->GetComponent(i, 0)) && h->GetComponent(i, 0) >= 0.0);
    }
  }

  // 2. Against the reference: a bright ball (0.9) and a dark ball (0) on a ground.
  Ground ground;
  const double brightC[3] = { 0, 0, 1.1 }, darkC[3] = { 1.8, 0, 0.7 }, one[3] = { 1, 1, 1 },
               small[3] = { 0.6, 0.6, 0.6 };
  vtkSmartPointer<vtkPolyData> bright = Ellipsoid(brightC, one, 0.9, 0);
  vtkSmartPointer<vtkPolyData> dark = Ellipsoid(darkC, small, 0.0, 1);
  vtkNew<vtkPGIReferenceIllumination> reference;
  reference->SetInputConnection(ground.All->GetOutputPort());
  reference->AddSceneObjectData(bright);
  reference->AddSceneObjectData(dark);
  reference->SetSamples(1024);
  reference->Update();
  vtkDataArray* refIndirect = reference->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
  vtkNew<vtkAppendPolyData> meshes;
  meshes->AddInputData(bright);
  meshes->AddInputData(dark);
  vtkNew<vtkPGISphereLightSampler> sampler;
  sampler->SetInputConnection(meshes->GetOutputPort());
  sampler->SetProxiesData(Spheres({ 0, 0, 1.1, 1.0, 1.8, 0, 0.7, 0.6 }, { 0, 1 }, { 0.9, 0.0 }));
  sampler->Update();
  // Receivers behind the dark ball (x > 2.4, |y| < 1.2) see the bright one partly hidden.
  std::vector<char> behind;
  {
    vtkPolyData* patch = ground.Patch->GetOutput();
    ground.Patch->Update();
    for (vtkIdType i = 0; i < patch->GetNumberOfPoints(); ++i)
    {
      double x[3];
      patch->GetPoint(i, x);
      behind.push_back(x[0] > 2.4 && std::fabs(x[1]) < 1.2 ? 1 : 0);
    }
  }
  const Run unshadowed = Shade(ground.Patch->GetOutputPort(), sampler->GetOutput(),
    vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED, 0);
  const Run shadowed = Shade(ground.Patch->GetOutputPort(), sampler->GetOutput(),
    vtkPGIGISettings::INDIRECT_MODE_SHADOWED, 0);
  vtkDataArray* u = unshadowed.Output->GetPointData()->GetArray("IndirectProxy");
  vtkDataArray* s = shadowed.Output->GetPointData()->GetArray("IndirectShadowed");
  const double eu = RelativeRMSE(u, refIndirect), es = RelativeRMSE(s, refIndirect);
  const double eub = RelativeRMSE(u, refIndirect, &behind),
               esb = RelativeRMSE(s, refIndirect, &behind);
  const double receivers = static_cast<double>(u->GetNumberOfTuples());
  std::printf("two balls on a ground, %d receivers, reference %s relative stderr:\n",
    static_cast<int>(receivers),
    std::to_string(
      reference->GetOutput()->GetFieldData()->GetArray("RelativeRMSStdErr")->GetTuple1(0))
      .c_str());
  std::printf("  unshadowed (AVERAGED): relative RMSE %.1f%% (behind the dark ball %.1f%%)\n",
    100 * eu, 100 * eub);
  std::printf("  shadowed (per sphere): relative RMSE %.1f%% (behind the dark ball %.1f%%)\n",
    100 * es, 100 * esb);
  for (const std::string& line : shadowed.Plan)
  {
    std::printf("  plan: %s\n", line.c_str());
  }
  // Measured 23.6% (behind the dark ball 81%) against 29.0% (159%) unshadowed.
  PGI_BELOW(es, 0.26);
  PGI_CHECK(es < eu);
  PGI_CHECK(esb < 0.6 * eub); // occlusion of the bright ball by the dark one
  PGI_CHECK(s->GetRange(0)[0] >= 0.0);

  // 3. Two objects of two intersecting spheres each (standing peanuts).
  {
    const double a0[3] = { 0, 0, 0.6 }, a1[3] = { 0, 0, 1.5 }, b0[3] = { 1.9, 0.3, 0.6 },
                 b1[3] = { 1.9, 0.3, 1.5 };
    vtkSmartPointer<vtkPolyData> a = Peanut(a0, a1, 0.55, 0.9, 0);
    vtkSmartPointer<vtkPolyData> b = Peanut(b0, b1, 0.55, 0.6, 1);
    vtkNew<vtkPGIReferenceIllumination> ref2;
    ref2->SetInputConnection(ground.All->GetOutputPort());
    ref2->AddSceneObjectData(a);
    ref2->AddSceneObjectData(b);
    ref2->SetSamples(512);
    ref2->Update();
    vtkDataArray* r2 = ref2->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
    vtkNew<vtkAppendPolyData> both;
    both->AddInputData(a);
    both->AddInputData(b);
    vtkNew<vtkPGISphereLightSampler> sampler2;
    sampler2->SetInputConnection(both->GetOutputPort());
    sampler2->SetProxiesData(
      Spheres({ 0, 0, 0.6, 0.555, 0, 0, 1.5, 0.555, 1.9, 0.3, 0.6, 0.555, 1.9, 0.3, 1.5, 0.555 },
        { 0, 0, 1, 1 }, { 0.9, 0.9, 0.6, 0.6 }));
    sampler2->Update();
    const Run perSphere = Shade(ground.Patch->GetOutputPort(), sampler2->GetOutput(),
      vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_SPHERE);
    const Run perObject = Shade(ground.Patch->GetOutputPort(), sampler2->GetOutput(),
      vtkPGIGISettings::INDIRECT_MODE_SHADOWED, vtkPGIGISettings::BLOCKING_PER_OBJECT);
    const Run flat = Shade(ground.Patch->GetOutputPort(), sampler2->GetOutput(),
      vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED, 0);
    vtkDataArray* ps = perSphere.Output->GetPointData()->GetArray("IndirectShadowed");
    vtkDataArray* po = perObject.Output->GetPointData()->GetArray("IndirectShadowed");
    vtkDataArray* un = flat.Output->GetPointData()->GetArray("IndirectProxy");
    const double eps = RelativeRMSE(ps, r2), epo = RelativeRMSE(po, r2), eun = RelativeRMSE(un, r2),
                 diff = RelativeRMSE(po, ps);
    std::printf("two objects of two spheres each (timings: the --timing run):\n"
                "  per sphere: relative RMSE %.1f%%\n"
                "  per object: relative RMSE %.1f%%\n"
                "  unshadowed (AVERAGED): relative RMSE %.1f%%\n"
                "  per object vs per sphere: %.2f%%\n",
      100 * eps, 100 * epo, 100 * eun, 100 * diff);
    std::printf("  means: reference %.5f, per sphere %.5f, unshadowed %.5f\n",
      Mean(r2, ps->GetNumberOfTuples()), Mean(ps, ps->GetNumberOfTuples()),
      Mean(un, un->GetNumberOfTuples()));
    for (const std::string& line : perObject.Plan)
    {
      std::printf("  plan: %s\n", line.c_str());
    }
    PGI_CHECK(ps->GetRange(0)[0] >= 0.0 && po->GetRange(0)[0] >= 0.0);
    PGI_CHECK(std::isfinite(ps->GetRange(0)[1]) && std::isfinite(po->GetRange(0)[1]));
    // A hierarchy over them (a parent per object): cuts with reflection ratios.
    {
      vtkNew<vtkPolyData> tree;
      tree->DeepCopy(Spheres({ 0, 0, 0.6, 0.555, 0, 0, 1.5, 0.555, 1.9, 0.3, 0.6, 0.555, 1.9, 0.3,
                               1.5, 0.555, 0, 0, 1.05, 1.01, 1.9, 0.3, 1.05, 1.01 },
        { 0, 0, 1, 1, 0, 1 }, { 0.9, 0.9, 0.6, 0.6, 0.9, 0.6 }));
      vtkNew<vtkIntArray> level, parent;
      level->SetName("Level");
      parent->SetName("Parent");
      for (int v : { 0, 0, 0, 0, 1, 1 })
      {
        level->InsertNextValue(v);
      }
      for (int v : { 4, 4, 5, 5, -1, -1 })
      {
        parent->InsertNextValue(v);
      }
      tree->GetPointData()->AddArray(level);
      tree->GetPointData()->AddArray(parent);
      vtkNew<vtkPGISphereLightSampler> treeSampler;
      treeSampler->SetInputConnection(both->GetOutputPort());
      treeSampler->SetProxiesData(tree);
      vtkNew<GI> cut;
      cut->SetInputConnection(ground.Patch->GetOutputPort());
      cut->SetProxiesConnection(treeSampler->GetOutputPort());
      const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
      cut->AddBlockerPlane(origin, up);
      cut->GetSettings()->SetIndirectModeToShadowed();
      cut->GetSettings()->SetHierarchyAngle(25);
      cut->GetSettings()->SetReceiversPerCluster(32);
      cut->Update();
      PrintPlan(cut);
      PGI_CHECK(PlanHas(cut, "spherical lights cut alike, with reflection ratios"));
      vtkDataArray* hc = cut->GetOutput()->GetPointData()->GetArray("IndirectShadowed");
      const double eh = RelativeRMSE(hc, r2), dh = RelativeRMSE(hc, ps);
      std::printf("  hierarchy cuts at 25 degrees: relative RMSE %.1f%%, %.2f%% from the leaves\n",
        100 * eh, 100 * dh);
      PGI_CHECK(hc->GetRange(0)[0] >= 0.0 && std::isfinite(hc->GetRange(0)[1]));
      PGI_BELOW(dh, 0.10);
    }
    // Measured 31.0% and 31.0% (unshadowed 24.9%): the shadowed bounce is
    // better away from the objects but too bright right under them, where
    // the 92 piecewise-constant samples of the dark underside ring at order 4.
    PGI_BELOW(eps, 0.36);
    PGI_BELOW(epo, 0.36);
    PGI_BELOW(diff, 0.05);
    // The two blockings differ (a filter ignoring the setting gives 0), and
    // the plan says which ran.
    PGI_CHECK(diff > 1e-4);
    auto says = [](const Run& run, const char* text)
    {
      return std::any_of(run.Plan.begin(), run.Plan.end(),
        [&](const std::string& line) { return line.find(text) != std::string::npos; });
    };
    PGI_CHECK(says(perObject, "per-object") && !says(perObject, "per-sphere"));
    PGI_CHECK(says(perSphere, "per-sphere") && !says(perSphere, "per-object"));
  }

  // 4. Local lights as spherical lights: a black sky, a spherical light over
  // the bright ball; the ground's one bounce against the reference.
  {
    vtkNew<vtkPGILighting> lighting;
    lighting->SetUniformRadiance(0, 0, 0);
    const double lc[3] = { -1.5, 0.5, 3.0 }, lr[3] = { 20, 20, 20 };
    lighting->AddSphereLight(lc, 0.3, lr);
    vtkNew<vtkPGIReferenceIllumination> ref4;
    ref4->SetInputConnection(ground.All->GetOutputPort());
    ref4->AddSceneObjectData(bright);
    ref4->SetLighting(lighting);
    ref4->SetSamples(2048);
    ref4->Update();
    vtkNew<vtkPGISphereLightSampler> sampler4;
    sampler4->SetInputData(bright);
    sampler4->SetProxiesData(Spheres({ 0, 0, 1.1, 1.0 }, { 0 }, { 0.9 }));
    vtkNew<GI> gi;
    gi->SetInputConnection(ground.Patch->GetOutputPort());
    gi->SetProxiesConnection(sampler4->GetOutputPort());
    gi->SetLighting(lighting);
    const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
    gi->AddBlockerPlane(origin, up);
    gi->GetSettings()->SetIndirectModeToShadowed();
    gi->Update();
    PGI_CHECK(PlanHas(gi, "(with local lights)"));
    vtkDataArray* lit = gi->GetOutput()->GetPointData()->GetArray("IndirectShadowed");
    vtkDataArray* ref = ref4->GetOutput()->GetPointData()->GetArray("IndirectOneBounce");
    const double e = RelativeRMSE(lit, ref);
    std::printf("spherical light over the ball, black sky: ground bounce up to %.4f (reference "
                "%.4f), relative RMSE %.1f%%\n",
      lit->GetRange(0)[1], ref->GetRange(0)[1], 100 * e);
    const double meanLit = Mean(lit, lit->GetNumberOfTuples()),
                 meanRef = Mean(ref, lit->GetNumberOfTuples());
    // Away from the ball (beyond 1.5 of its axis), where no ringing reaches.
    std::vector<char> away(lit->GetNumberOfTuples(), 0);
    vtkPolyData* patch = gi->GetOutput();
    for (vtkIdType i = 0; i < patch->GetNumberOfPoints(); ++i)
    {
      double x[3];
      patch->GetPoint(i, x);
      away[i] = x[0] * x[0] + x[1] * x[1] > 1.5 * 1.5;
    }
    const double eAway = RelativeRMSE(lit, ref, &away);
    std::printf("  mean over the patch %.5f, reference %.5f; relative RMSE beyond 1.5 of the "
                "ball's axis %.1f%%\n",
      meanLit, meanRef, 100 * eAway);
    // Measured: mean 0.00062 against 0.00053; RMSE 100%, all of it right
    // under the ball, where the order-4 SH of its lit side leaks ~6% of the
    // peak to the dark antipode (the clamped cosine truncated at order 4);
    // away from it 33.6% (an all-zero output scores 100% on both).
    PGI_NEAR(meanLit, meanRef, 0.25 * meanRef);
    PGI_BELOW(e, 1.2);
    PGI_BELOW(eAway, 0.45);
    gi->GetSettings()->SetLocalLights(false);
    gi->Update();
    PGI_CHECK(PlanHas(gi, "skipped (the environment is black and there are no local lights)"));
  }
  return pgitest::Result();
}
