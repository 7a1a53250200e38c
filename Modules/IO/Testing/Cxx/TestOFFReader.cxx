// OFF reader: a small file with polygons and colours, the CGAL bunny, and
// bad files that must give errors, not crashes.
#include "vtkPGIOFFReader.h"

#include "pgiTesting.h"
#include "vtkCellData.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <cstdio>
#include <fstream>
#include <string>

namespace
{
std::string WriteTemp(const char* name, const char* text)
{
  std::string path = std::string("/tmp/pgi-") + name + ".off";
  std::ofstream(path) << text;
  return path;
}
} // namespace

int TestOFFReader(int, char*[])
{
  const std::string good = WriteTemp("good",
    "COFF\n# a quad and a triangle\n5 2 0\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n"
    "0 1 0 1 1 1\n0.5 0.5 1 10 20 30\n4 0 1 2 3\n3 0 1 4 200 100 50\n");
  vtkNew<vtkPGIOFFReader> reader;
  reader->SetFileName(good.c_str());
  reader->Update();
  vtkPolyData* mesh = reader->GetOutput();
  PGI_CHECK(mesh->GetNumberOfPoints() == 5);
  PGI_CHECK(mesh->GetNumberOfPolys() == 2);
  PGI_CHECK(mesh->GetCell(0)->GetNumberOfPoints() == 4);
  PGI_CHECK(mesh->GetPointData()->GetScalars() != nullptr);
  if (mesh->GetPointData()->GetScalars())
  {
    PGI_NEAR(mesh->GetPointData()->GetScalars()->GetComponent(1, 1), 255, 0);
  }
  vtkDataArray* vertexColors = mesh->GetPointData()->GetScalars();
  PGI_CHECK(vertexColors && vertexColors->GetNumberOfTuples() == 5);
  if (vertexColors && vertexColors->GetNumberOfTuples() == 5)
  {
    // Every vertex colour as written; "1 1 1" is integers, so 0..255 units.
    const double expect[5][3] = { { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 }, { 1, 1, 1 },
      { 10, 20, 30 } };
    for (int i = 0; i < 5; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        PGI_NEAR(vertexColors->GetComponent(i, c), expect[i][c], 0);
      }
    }
  }
  PGI_CHECK(mesh->GetCellData()->GetScalars() != nullptr);
  vtkDataArray* faceColors = mesh->GetCellData()->GetScalars();
  PGI_CHECK(faceColors && faceColors->GetNumberOfTuples() == 2);
  if (faceColors && faceColors->GetNumberOfTuples() == 2)
  {
    // The quad has no colour (white); the triangle's is 200 100 50.
    const double expect[2][3] = { { 255, 255, 255 }, { 200, 100, 50 } };
    for (int f = 0; f < 2; ++f)
    {
      for (int c = 0; c < 3; ++c)
      {
        PGI_NEAR(faceColors->GetComponent(f, c), expect[f][c], 0);
      }
    }
  }
  double p[3];
  mesh->GetPoint(4, p);
  PGI_NEAR(p[2], 1.0, 0.0);

  const std::string bunny = std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
  reader->SetFileName(bunny.c_str());
  reader->Update();
  std::printf("bunny: %lld points, %lld triangles\n",
    static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()),
    static_cast<long long>(reader->GetOutput()->GetNumberOfPolys()));
  PGI_CHECK(reader->GetOutput()->GetNumberOfPoints() == 37706);
  PGI_CHECK(reader->GetOutput()->GetNumberOfPolys() == 75408);

  // Bad files: an error each, empty output, no crash.
  const char* bad[] = { "OFF\n3 1 0\n0 0 0\n1 0 0\n", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
    "OFF\n3 1 0\n0 zero 0\n1 0 0\n0 1 0\n3 0 1 2\n", "",
    // Counts no file of this size can hold: refused before allocating
    // (1e11 vertices once aborted the program with std::bad_alloc).
    "OFF\n100000000000 1 0\n0 0 0\n", "OFF\n3 100000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n100000000000 0 1 2\n" };
  int index = 0;
  for (const char* text : bad)
  {
    vtkNew<vtkTest::ErrorObserver> observer;
    vtkNew<vtkPGIOFFReader> r;
    r->AddObserver(vtkCommand::ErrorEvent, observer);
    r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    r->SetFileName(WriteTemp(("bad" + std::to_string(index++)).c_str(), text).c_str());
    r->Update();
    PGI_CHECK(observer->GetError());
    PGI_CHECK(r->GetOutput()->GetNumberOfPoints() == 0);
  }
  {
    vtkNew<vtkTest::ErrorObserver> observer;
    vtkNew<vtkPGIOFFReader> r;
    r->AddObserver(vtkCommand::ErrorEvent, observer);
    r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    r->SetFileName("/nonexistent/mesh.off");
    r->Update();
    PGI_CHECK(observer->GetError());
  }
  return pgitest::Result();
}
