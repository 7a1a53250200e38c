/**
 * @file pgiHardScenes.h
 * @brief The hard cases every GI route is run on (the CPU filter's
 * TestGlobalIlluminationHardCases and the GPU's TestRenderingHardCases):
 * receivers inside 1-50 proxies, under and inside 1000 overlapping proxies,
 * zero-radius, coincident and receiver-hugging proxies, spheres cut by the
 * receivers' tangent plane; a sweep of receivers through spheres; the light
 * (a uniform sky, a spherical and a point light).
 */
#ifndef pgiHardScenes_h
#define pgiHardScenes_h

#include "vtkPGILighting.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace pgitest
{
struct HardScene
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Receivers; // with point normals
  vtkSmartPointer<vtkPolyData> Proxies;   // "Radius", "ObjectId"
};

/// Proxies from x, y, z, r, object rows.
inline vtkSmartPointer<vtkPolyData> HardProxies(const std::vector<std::array<double, 5>>& s)
{
  auto proxies = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  vtkNew<vtkFloatArray> object;
  object->SetName("ObjectId");
  for (const auto& x : s)
  {
    points->InsertNextPoint(x[0], x[1], x[2]);
    radius->InsertNextValue(x[3]);
    object->InsertNextValue(static_cast<float>(x[4]));
  }
  proxies->SetPoints(points);
  proxies->GetPointData()->AddArray(radius);
  proxies->GetPointData()->AddArray(object);
  return proxies;
}

inline vtkSmartPointer<vtkPolyData> HardSphereMesh(double x, double y, double z, double r, int res)
{
  vtkNew<vtkSphereSource> s;
  s->SetCenter(x, y, z);
  s->SetRadius(r);
  s->SetThetaResolution(2 * res);
  s->SetPhiResolution(res);
  s->Update();
  return s->GetOutput();
}

inline vtkSmartPointer<vtkPolyData> HardPlane(double half, double z, int res)
{
  vtkNew<vtkPlaneSource> p;
  p->SetOrigin(-half, -half, z);
  p->SetPoint1(half, -half, z);
  p->SetPoint2(-half, half, z);
  p->SetResolution(res, res);
  p->Update();
  return p->GetOutput();
}

inline vtkSmartPointer<vtkPolyData> HardAppend(
  const std::vector<vtkSmartPointer<vtkPolyData>>& parts)
{
  vtkNew<vtkAppendPolyData> all;
  for (const auto& p : parts)
  {
    all->AddInputData(p);
  }
  all->Update();
  return all->GetOutput();
}

/// The scenes; a ground blocker plane at z = -1.5 goes with each.
inline std::vector<HardScene> HardScenes()
{
  std::vector<HardScene> scenes;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  {
    // 50 spheres that all contain the origin; receivers on a small sphere
    // and a patch through it: each inside 1 to 50 proxies.
    std::vector<std::array<double, 5>> s;
    for (int k = 0; k < 50; ++k)
    {
      const double c[3] = { 0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng) };
      const double d = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      s.push_back({ c[0], c[1], c[2], d + 0.02 + 0.5 * std::fabs(u(rng)), double(k % 3) });
    }
    scenes.push_back({ "receivers inside 1-50 proxies",
      HardAppend({ HardSphereMesh(0, 0, 0, 0.3, 12), HardPlane(1.0, 0.0, 12) }), HardProxies(s) });
  }
  {
    // 1000 overlapping spheres over a ground, a receiver sphere inside them.
    std::vector<std::array<double, 5>> s;
    s.reserve(1000);
    for (int k = 0; k < 1000; ++k)
    {
      s.push_back(
        { 2 * u(rng), 2 * u(rng), 2.0 + u(rng), 0.3 + 0.2 * std::fabs(u(rng)), double(k % 4) });
    }
    scenes.push_back({ "1000 overlapping proxies",
      HardAppend({ HardPlane(3.0, 0.0, 12), HardSphereMesh(0, 0, 2, 0.4, 8) }), HardProxies(s) });
  }
  {
    // A zero-radius proxy, two coincident ones, and receivers lying on a
    // proxy's own surface.
    const std::vector<std::array<double, 5>> s = { { 0, 0, 1, 0.0, 0 }, { 0.2, 0, 1.2, 0.5, 0 },
      { 0.2, 0, 1.2, 0.5, 0 }, { -0.8, 0.5, 0.7, 0.4, 1 } };
    scenes.push_back({ "zero-radius, coincident, on the surface",
      HardAppend({ HardPlane(2.5, 0.0, 24), HardSphereMesh(-0.8, 0.5, 0.7, 0.4, 16) }),
      HardProxies(s) });
  }
  {
    // Spheres cut by the ground's tangent plane at several heights.
    const std::vector<std::array<double, 5>> s = { { -2.4, 0, -0.5, 1, 0 }, { -0.8, 0, 0, 1, 1 },
      { 0.8, 0, 0.6, 1, 2 }, { 2.4, 0, 0.95, 1, 3 } };
    scenes.push_back(
      { "spheres cut by the tangent plane", HardPlane(3.5, 0.0, 40), HardProxies(s) });
  }
  return scenes;
}

/// `count` receivers on the line y = 0.1, z = 0, x in [-3, 3], facing +z
/// (vertex cells), and spheres of radius 1 at x = 0 and the given heights
/// relative to the line: each cuts the receivers' tangent plane.
inline HardScene HardSweep(int count, double height)
{
  auto line = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> verts;
  for (int k = 0; k <= count; ++k)
  {
    points->InsertNextPoint(-3.0 + 6.0 * k / count, 0.1, 0.0);
    normals->InsertNextTuple3(0, 0, 1);
    verts->InsertNextCell(1);
    verts->InsertCellPoint(k);
  }
  line->SetPoints(points);
  line->SetVerts(verts);
  line->GetPointData()->SetNormals(normals);
  return { "sweep", line, HardProxies({ { 0.0, 0.0, height, 1.0, 0 } }) };
}

/// The scene scaled by `scale` about the origin (receivers, proxy centres
/// and radii).
inline HardScene HardScaled(const HardScene& base, double scale)
{
  HardScene scaled = base;
  scaled.Receivers = vtkSmartPointer<vtkPolyData>::New();
  scaled.Receivers->DeepCopy(base.Receivers);
  scaled.Proxies = vtkSmartPointer<vtkPolyData>::New();
  scaled.Proxies->DeepCopy(base.Proxies);
  for (vtkPolyData* data : { scaled.Receivers.Get(), scaled.Proxies.Get() })
  {
    for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    {
      double x[3];
      data->GetPoint(i, x);
      data->GetPoints()->SetPoint(i, scale * x[0], scale * x[1], scale * x[2]);
    }
  }
  vtkDataArray* radius = scaled.Proxies->GetPointData()->GetArray("Radius");
  for (vtkIdType i = 0; i < radius->GetNumberOfTuples(); ++i)
  {
    radius->SetTuple1(i, scale * radius->GetTuple1(i));
  }
  return scaled;
}

/// A uniform white sky, a spherical light and a point light.
inline vtkSmartPointer<vtkPGILighting> HardLighting()
{
  auto lighting = vtkSmartPointer<vtkPGILighting>::New();
  const double c1[3] = { 1.5, -1.0, 3.0 }, e1[3] = { 3.0, 2.5, 2.0 };
  const double c2[3] = { -1.0, 1.5, 2.5 }, e2[3] = { 2.0, 2.0, 3.0 };
  lighting->AddSphereLight(c1, 0.4, e1);
  lighting->AddPointLight(c2, e2);
  return lighting;
}

/// Largest |a| over every component of every tuple; NaN/Inf -> +inf.
inline double HardPeak(vtkDataArray* a, double* lowest = nullptr)
{
  double peak = 0.0, low = 0.0;
  for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      const double v = a->GetComponent(i, c);
      peak = std::isfinite(v) ? std::max(peak, std::fabs(v)) : HUGE_VAL;
      low = std::min(low, v);
    }
  }
  if (lowest)
  {
    *lowest = low;
  }
  return peak;
}
/// The name of the first point array of `a` that differs from `b`'s in a
/// single bit (or is missing there), or ""; arrays named in `skip` aside.
inline std::string FirstDifference(
  vtkPolyData* a, vtkPolyData* b, const std::vector<std::string>& skip = {})
{
  vtkPointData* pa = a->GetPointData();
  vtkPointData* pb = b->GetPointData();
  if (pa->GetNumberOfArrays() != pb->GetNumberOfArrays())
  {
    return "(number of arrays)";
  }
  for (int k = 0; k < pa->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* x = pa->GetArray(k);
    vtkDataArray* y = x ? pb->GetArray(x->GetName()) : nullptr;
    if (!x || (x->GetName() && std::count(skip.begin(), skip.end(), x->GetName())))
    {
      continue;
    }
    if (!y || x->GetDataType() != y->GetDataType() ||
      x->GetNumberOfValues() != y->GetNumberOfValues() ||
      std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0),
        static_cast<std::size_t>(x->GetNumberOfValues()) * x->GetDataTypeSize()) != 0)
    {
      return x->GetName() ? x->GetName() : "(unnamed)";
    }
  }
  return std::string();
}
} // namespace pgitest

#endif
