/**
 * @file pgiBunnyScene.h
 * @brief The default scene's pieces the Rendering tests share: the data
 * files (bunny mesh, forest map), the bunny placed as the default scene
 * places it, the forest light, its committed 32 proxies, and the scene of
 * the bunny with a red and a green ball on a ground (image-space and
 * per-vertex colour-bleeding tests). Needs PROXYGI_DATA_DIR and
 * PGI_RENDERING_TEST_DATA defined.
 */
#ifndef pgiBunnyScene_h
#define pgiBunnyScene_h

#include "vtkPGIEXRReader.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSmartPointer.h"
#include "vtkTesting.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace pgitest
{
inline std::string BunnyPath()
{
  return std::string(PROXYGI_DATA_DIR) + "/meshes/bunny00.off";
}

inline std::string ForestPath()
{
  return std::string(PROXYGI_DATA_DIR) + "/environments/forest.exr";
}

/// Whether the set-up fetched the bunny and the forest map (else says so).
inline bool BunnyDataPresent()
{
  if (vtksys::SystemTools::FileExists(BunnyPath()) && vtksys::SystemTools::FileExists(ForestPath()))
  {
    return true;
  }
  std::printf("%s: %s or %s missing (run Utilities/setup.sh --data)\n",
    PROXYGI_DATA_CONFIGURED ? "FAILED" : "skipped", BunnyPath().c_str(), ForestPath().c_str());
  return false;
}

/// What a test returns without the data: a skip, unless the data was there
/// when the build was configured (PROXYGI_DATA_CONFIGURED), where a missing
/// file is a failure.
inline int MissingDataResult()
{
  return PROXYGI_DATA_CONFIGURED ? EXIT_FAILURE : VTK_SKIP_RETURN_CODE;
}

/// The bunny as the default scene places it (z up, feet on z = 0), with
/// unsplit point normals.
inline vtkSmartPointer<vtkPolyData> PlacedBunny()
{
  vtkNew<vtkPGIOFFReader> reader;
  reader->SetFileName(BunnyPath().c_str());
  vtkNew<vtkTransform> place;
  place->PostMultiply();
  place->RotateX(90);
  place->Translate(0, 0, 0.494);
  vtkNew<vtkTransformPolyDataFilter> moved;
  moved->SetInputConnection(reader->GetOutputPort());
  moved->SetTransform(place);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(moved->GetOutputPort());
  normals->SplittingOff();
  normals->Update();
  return normals->GetOutput();
}

inline vtkSmartPointer<vtkPGILighting> ForestLighting()
{
  vtkNew<vtkPGIEXRReader> forest;
  forest->SetFileName(ForestPath().c_str());
  forest->Update();
  auto lighting = vtkSmartPointer<vtkPGILighting>::New();
  lighting->SetEnvironmentImage(forest->GetOutput());
  return lighting;
}

/// The bunny's proxies, built once by vtkPGISphereSetApproximation and
/// committed, so images do not move when that algorithm changes.
inline vtkSmartPointer<vtkPolyData> BunnyProxies()
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((std::string(PGI_RENDERING_TEST_DATA) + "/bunny-proxies-32.vtp").c_str());
  reader->Update();
  return reader->GetOutput();
}

/// The bunny with a red and a green ball on a ground under the forest map.
struct BallScene
{
  struct Ball
  {
    double Centre[3], Radius, Albedo[3];
  };
  Ball Balls[2] = { { { -0.95, 0.35, 0.35 }, 0.35, { 0.9, 0.1, 0.1 } },
    { { 0.85, 0.45, 0.35 }, 0.35, { 0.1, 0.8, 0.15 } } };
  /// Ground points next to each ball, on the camera side.
  double NearRed[3] = { -0.95, -0.05, 0.0 }, NearGreen[3] = { 0.85, 0.05, 0.0 };

  /// Proxies: the bunny's 32 (grey) and the balls exactly (coloured);
  /// with objectIds, an "ObjectId" array (bunny 0, balls 1 and 2).
  vtkSmartPointer<vtkPolyData> Proxies(bool objectIds) const
  {
    vtkSmartPointer<vtkPolyData> bunny = BunnyProxies();
    vtkNew<vtkPoints> centres;
    vtkNew<vtkFloatArray> radii, albedos, objects;
    radii->SetName("Radius");
    albedos->SetName("Albedo");
    albedos->SetNumberOfComponents(3);
    objects->SetName("ObjectId");
    vtkDataArray* bunnyRadii = bunny->GetPointData()->GetArray("Radius");
    for (vtkIdType i = 0; i < bunny->GetNumberOfPoints(); ++i)
    {
      centres->InsertNextPoint(bunny->GetPoint(i));
      radii->InsertNextValue(static_cast<float>(bunnyRadii->GetTuple1(i)));
      albedos->InsertNextTuple3(0.8, 0.8, 0.8);
      objects->InsertNextValue(0);
    }
    for (int k = 0; k < 2; ++k)
    {
      const Ball& b = this->Balls[k];
      centres->InsertNextPoint(b.Centre);
      radii->InsertNextValue(static_cast<float>(b.Radius));
      albedos->InsertNextTuple3(b.Albedo[0], b.Albedo[1], b.Albedo[2]);
      objects->InsertNextValue(static_cast<float>(k + 1));
    }
    auto proxies = vtkSmartPointer<vtkPolyData>::New();
    proxies->SetPoints(centres);
    proxies->GetPointData()->AddArray(radii);
    proxies->GetPointData()->AddArray(albedos);
    if (objectIds)
    {
      proxies->GetPointData()->AddArray(objects);
    }
    return proxies;
  }

  static void SetCamera(vtkCamera* camera)
  {
    camera->SetPosition(0.3, -3.4, 2.2);
    camera->SetFocalPoint(0, 0.2, 0.3);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(35);
  }
};
} // namespace pgitest

#endif
