// The 8-bit sRGB levels by search against the curve they stand for, and the
// albedo reader against the one-point lookup.
#include "pgiMaterial.h"
#include "pgiSRGB.h"
#include "pgiTesting.h"

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

namespace
{
double NextUp(double x, int ulps)
{
  for (int k = 0; k < ulps; ++k)
  {
    x = std::nextafter(x, 2.0);
  }
  return x;
}
double NextDown(double x, int ulps)
{
  for (int k = 0; k < ulps; ++k)
  {
    x = std::nextafter(x, -1.0);
  }
  return x;
}
} // namespace

int TestSRGBAndAlbedo(int, char*[])
{
  using proxygi::ToSRGB8;
  using proxygi::ToSRGB8ByCurve;
  // Every level's edges to the ulp, then random values over [-0.1, 1.1] and
  // the extremes: the search gives the curve's level everywhere.
  int mismatches = 0, levelsSeen = 0;
  for (int level = 1; level < 256; ++level)
  {
    // The edge where the curve steps to `level`, by bisection on a fine grid.
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 200; ++it)
    {
      const double mid = 0.5 * (lo + hi);
      (ToSRGB8ByCurve(mid) >= level ? hi : lo) = mid;
    }
    for (int ulps = 0; ulps < 4; ++ulps)
    {
      for (double x : { NextUp(hi, ulps), NextDown(hi, ulps), NextDown(lo, ulps) })
      {
        mismatches += ToSRGB8(x) != ToSRGB8ByCurve(x) ? 1 : 0;
      }
    }
    levelsSeen += ToSRGB8(hi) == level ? 1 : 0;
  }
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-0.1, 1.1);
  for (int i = 0; i < 1000000; ++i)
  {
    const double x = value(random);
    mismatches += ToSRGB8(x) != ToSRGB8ByCurve(x) ? 1 : 0;
  }
  for (double x : { 0.0, -0.0, 1.0, 1e-300, 0.0031308, 2.0, 1e300,
         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() })
  {
    mismatches += ToSRGB8(x) != ToSRGB8ByCurve(x) ? 1 : 0;
  }
  PGI_CHECK(mismatches == 0);
  PGI_CHECK(levelsSeen == 255);
  PGI_CHECK(ToSRGB8(std::numeric_limits<double>::quiet_NaN()) == 0);
  PGI_CHECK(ToSRGB8(1.0) == 255 && ToSRGB8(0.5) == 188 && ToSRGB8(0.0) == 0);

  // Albedo: a float array, an unsigned char array, a missing one and a
  // short one read the same through the reader as through AlbedoOf.
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(3);
  mesh->SetPoints(points);
  vtkNew<vtkFloatArray> floats;
  floats->SetName("Albedo");
  floats->SetNumberOfComponents(3);
  const float values[9] = { 0.2f, 1.5f, -1.0f, std::nanf(""), 0.5f, 0.25f, 0.0f, 0.0f, 1.0f };
  for (int i = 0; i < 3; ++i)
  {
    floats->InsertNextTypedTuple(values + 3 * i);
  }
  mesh->GetPointData()->AddArray(floats);
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName("Bytes");
  bytes->SetNumberOfComponents(3);
  for (int i = 0; i < 3; ++i)
  {
    const unsigned char b[3] = { static_cast<unsigned char>(51 * i), 255, 0 };
    bytes->InsertNextTypedTuple(b);
  }
  mesh->GetPointData()->AddArray(bytes);
  const double fallback[3] = { 0.1, 0.2, 0.3 };
  const double expected[4][3][3] = {
    { { 0.2, 1.0, 0.0 }, { 0.0, 0.5, 0.25 }, { 0.0, 0.0, 1.0 } },
    { { 0.0, 1.0, 0.0 }, { 0.2, 1.0, 0.0 }, { 0.4, 1.0, 0.0 } },
    { { 0.1, 0.2, 0.3 }, { 0.1, 0.2, 0.3 }, { 0.1, 0.2, 0.3 } },
    { { 0.1, 0.2, 0.3 }, { 0.1, 0.2, 0.3 }, { 0.1, 0.2, 0.3 } },
  };
  const char* names[4] = { "Albedo", "Bytes", "Missing", nullptr };
  for (int a = 0; a < 4; ++a)
  {
    const proxygi::AlbedoReader reader(mesh, names[a], fallback);
    for (vtkIdType i = 0; i < 4; ++i) // point 3 is past the arrays: the default
    {
      double viaReader[3], viaPoint[3];
      reader.Get(i, viaReader);
      proxygi::AlbedoOf(mesh, names[a], i, fallback, viaPoint);
      for (int k = 0; k < 3; ++k)
      {
        const double want = i < 3 ? expected[a][i][k] : fallback[k];
        PGI_NEAR(viaReader[k], want, 1e-7);
        PGI_CHECK(viaReader[k] == viaPoint[k]);
      }
    }
  }
  return pgitest::Result();
}
