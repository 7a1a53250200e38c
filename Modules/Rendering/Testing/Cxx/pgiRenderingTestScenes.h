/**
 * @file pgiRenderingTestScenes.h
 * @brief Small scene pieces the Rendering tests share: sphere proxies, a
 * coloured synthetic sky with a sun (no data files needed).
 */
#ifndef pgiRenderingTestScenes_h
#define pgiRenderingTestScenes_h

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <cmath>
#include <vector>

namespace pgitest
{
/// Proxies: x, y, z, radius per sphere.
inline vtkSmartPointer<vtkPolyData> Spheres(const std::vector<std::array<double, 4>>& s)
{
  auto proxies = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  for (const auto& x : s)
  {
    points->InsertNextPoint(x[0], x[1], x[2]);
    radius->InsertNextValue(x[3]);
  }
  proxies->SetPoints(points);
  proxies->GetPointData()->AddArray(radius);
  return proxies;
}

/// A lat-long (2:1) sky: blue above, brown below, a warm sun towards
/// (0.5, -0.3, 0.81).
inline vtkSmartPointer<vtkImageData> Sky(int height = 64)
{
  const double pi = 3.14159265358979323846;
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int w = 2 * height, h = height;
  image->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetName("Radiance");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(w * h);
  const double sun[3] = { 0.5, -0.3, 0.81 };
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      // VTK rows run bottom-up: row h - 1 is the top (+z).
      const double theta = pi * (h - 1 - j + 0.5) / h, phi = 2 * pi * (i + 0.5) / w;
      const double d[3] = { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
        std::cos(theta) };
      const double up = d[2];
      double c[3] = { 0.3 + 0.2 * up, 0.45 + 0.3 * up, 0.9 + 0.5 * up };
      if (up < 0)
      {
        c[0] = 0.35;
        c[1] = 0.25;
        c[2] = 0.15;
      }
      const double s = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
      const double glow = s > 0.9 ? 12.0 * (s - 0.9) / 0.1 : 0.0;
      rgb->SetTuple3(j * w + i, c[0] + glow, c[1] + 0.8 * glow, c[2] + 0.5 * glow);
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}
} // namespace pgitest

#endif
