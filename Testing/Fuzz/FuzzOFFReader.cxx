// libFuzzer harness: OFF text through vtkPGIOFFReader, and small meshes on
// through the sphere proxies (what `proxygi proxies` does with a file).
// Findings: a crash, a hang, an allocation the input's size does not
// justify, non-finite spheres, or a used vertex that no sphere of its
// object contains.
#include "pgiFuzz.h"

#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPGIOFFReader.h"
#include "vtkPGISphereSetApproximation.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const bool quiet = pgiFuzz::Quiet();
  (void)quiet;
  vtkNew<vtkPGIOFFReader> reader;
  reader->ReadFromInputStringOn();
  reader->SetInputString(std::string(reinterpret_cast<const char*>(data), size));
  reader->Update();
  vtkPolyData* mesh = reader->GetOutput();
  if (mesh->GetNumberOfPolys() == 0 || mesh->GetNumberOfPoints() > 2000 ||
    mesh->GetPolys()->GetNumberOfConnectivityIds() > 8000)
  {
    return 0;
  }
  vtkNew<vtkPGISphereSetApproximation> proxies;
  proxies->SetInputData(mesh);
  // The input's length picks the method: all three meet hostile meshes.
  proxies->SetMethod(static_cast<int>(size % 3));
  proxies->SetNumberOfSpheres(4);
  proxies->SetVolumeResolution(16);
  proxies->SetInteriorResolution(8);
  proxies->SetMetricResolution(16);
  proxies->SetMaximumIterations(5);
  proxies->Update();
  vtkPolyData* spheres = proxies->GetOutput();
  if (spheres->GetNumberOfPoints() == 0)
  {
    return 0; // refused (NaN coordinates, no area, ...)
  }
  if (!pgiFuzz::Finite(spheres->GetPoints()) || !pgiFuzz::Finite(spheres->GetPointData()))
  {
    pgiFuzz::Finding("non-finite sphere");
  }
  vtkDataArray* radius = spheres->GetPointData()->GetArray("Radius");
  if (!radius)
  {
    pgiFuzz::Finding("no Radius array");
  }
  // Every corner of every polygon of three or more points lies in a sphere
  // (faces of one or two points are not surfaces: the proxies ignore them).
  double bounds[6];
  mesh->GetBounds(bounds);
  const double scale = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2],
    bounds[5] - bounds[4], std::abs(bounds[0]), std::abs(bounds[2]), std::abs(bounds[4]) });
  const double slack = 1e-5 * scale;
  vtkNew<vtkIdList> cell;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(cell);)
  {
    if (cell->GetNumberOfIds() < 3)
    {
      continue;
    }
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      double p[3];
      mesh->GetPoint(cell->GetId(k), p);
      bool inside = false;
      for (vtkIdType s = 0; s < spheres->GetNumberOfPoints() && !inside; ++s)
      {
        double c[3];
        spheres->GetPoint(s, c);
        const double d = std::sqrt(vtkMath::Distance2BetweenPoints(p, c));
        inside = d <= radius->GetTuple1(s) + slack;
      }
      if (!inside)
      {
        pgiFuzz::Finding("a mesh vertex outside every sphere");
      }
    }
  }
  return 0;
}
