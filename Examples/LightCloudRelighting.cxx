// LightCloudRelighting: indirect light that follows a moving lamp, from a
// light cloud (Kristensen et al. 2005) precomputed once.
//
//   room -> vtkPGILightCloudPrecompute (Embree; cached in room.pgilc)
//        -> vtkPGILightCloudRelight    (a user light, moved per frame)
//        -> the array LightCloudRadiance per vertex
//
// A floor, a red and a white wall and a block. The cloud is a 4 x 4 x 4
// grid of point lights; a second run reads room.pgilc instead of tracing.
// The lamp moves in five steps; each prints the mean indirect radiance on
// the floor and the relighting time. The last frame goes to room.vtp.
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPrecompute.h"
#include "vtkPGILightCloudRelight.h"
#include "vtkPGIMeshOccluder.h"

#include <vtkAppendPolyData.h>
#include <vtkCubeSource.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataWriter.h>

#include <chrono>
#include <cstdio>

namespace
{
// A wall split res x res, facing (p1 - o) x (p2 - o), with an albedo array.
vtkSmartPointer<vtkPolyData> Wall(
  const double o[3], const double p1[3], const double p2[3], double r, double g, double b)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(o[0], o[1], o[2]);
  plane->SetPoint1(p1[0], p1[1], p1[2]);
  plane->SetPoint2(p2[0], p2[1], p2[2]);
  plane->SetResolution(12, 12);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  auto wall = vtkSmartPointer<vtkPolyData>::New();
  wall->ShallowCopy(triangles->GetOutput());
  wall->GetPointData()->SetNormals(nullptr); // the relighting computes them
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < wall->GetNumberOfPoints(); ++i)
  {
    albedo->InsertNextTuple3(r, g, b);
  }
  wall->GetPointData()->AddArray(albedo);
  return wall;
}
} // namespace

int main()
{
  vtkSMPTools::SetBackend("STDThread"); // all cores (Debian's VTK defaults to one)

  const double o[3] = { -1, -1, 0 }, x[3] = { 1, -1, 0 }, y[3] = { -1, 1, 0 };
  const double top[3] = { -1, -1, 2 }, backTop[3] = { -1, 1, 2 }, backRight[3] = { 1, 1, 0 };
  vtkNew<vtkAppendPolyData> room;
  room->AddInputData(Wall(o, x, y, 0.7, 0.7, 0.7));               // floor, facing +z
  room->AddInputData(Wall(o, y, top, 0.7, 0.1, 0.1));             // red wall, facing +x
  room->AddInputData(Wall(y, backRight, backTop, 0.7, 0.7, 0.7)); // back wall, facing -y
  room->Update();
  vtkPolyData* receivers = room->GetOutput();

  // The block blocks and reflects but receives nothing here (input 1).
  vtkNew<vtkCubeSource> block;
  block->SetCenter(0.3, 0.2, 0.4);
  block->SetXLength(0.5);
  block->SetYLength(0.5);
  block->SetZLength(0.8);
  vtkNew<vtkTriangleFilter> blockTriangles;
  blockTriangles->SetInputConnection(block->GetOutputPort());

  vtkNew<vtkPGILightCloudPrecompute> precompute;
  precompute->SetInputData(receivers);
  precompute->AddInputConnection(1, blockTriangles->GetOutputPort());
  precompute->SetRegionOfInterest(-1, 1, -1, 1, 0, 2);
  precompute->SetGridResolution(4, 4, 4);
  precompute->SetSamples(64);
  precompute->SetCacheFileName("room.pgilc");
  precompute->Update();
  vtkPGILightCloud* cloud = precompute->GetOutput();
  std::printf("cloud: %lld lights (%lld traced, %lld from room.pgilc; %lld moved off "
              "surfaces), %.2f s\n",
    static_cast<long long>(cloud->GetNumberOfLights()),
    static_cast<long long>(precompute->GetLightsTraced()),
    static_cast<long long>(precompute->GetLightsFromCache()),
    static_cast<long long>(precompute->GetLightsMoved()), precompute->GetSeconds());

  // Only cloud lights the lamp sees count: the occluder holds the meshes.
  vtkNew<vtkPGIMeshOccluder> occluder;
  occluder->AddMesh(receivers);
  blockTriangles->Update();
  occluder->AddMesh(blockTriangles->GetOutput());

  vtkNew<vtkPGILightCloudRelight> relight;
  relight->SetInputData(receivers);
  relight->SetCloudConnection(precompute->GetOutputPort());
  relight->SetOccluder(occluder);
  relight->AddLight(-0.6, -0.5, 1.5, 2.0, 2.0, 2.0); // W/sr
  const vtkIdType floorPoints = 13 * 13;
  for (int step = 0; step < 5; ++step)
  {
    relight->SetLightPosition(0, -0.6 + 0.3 * step, -0.5 + 0.2 * step, 1.5 - 0.1 * step);
    relight->SetTime(step / 30.0); // the fade's clock: 30 frames a second
    const auto t0 = std::chrono::steady_clock::now();
    relight->Update();
    const double ms =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    vtkDataArray* radiance = relight->GetOutput()->GetPointData()->GetArray("LightCloudRadiance");
    double mean[3] = { 0, 0, 0 };
    for (vtkIdType i = 0; i < floorPoints; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        mean[c] += radiance->GetComponent(i, c) / floorPoints;
      }
    }
    std::printf("step %d: floor indirect radiance %.4f %.4f %.4f (red from the wall), %d cloud "
                "lights, %.2f ms\n",
      step, mean[0], mean[1], mean[2], relight->GetCloudLightsUsed(), ms);
  }

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(relight->GetOutputPort());
  writer->SetFileName("room.vtp");
  writer->Write();
  std::printf("wrote room.vtp (colour by LightCloudRadiance)\n");
  return 0;
}
