// ExampleGIMapper: per-vertex soft shadows on the GPU in a plain VTK
// pipeline, rendered offscreen (no display needed) and written to a PNG.
//
// 1. A window from proxygi::NewOffscreenRenderWindow(): EGL without X when
//    there is no display (the GPU on NVIDIA, llvmpipe elsewhere), GLX when
//    there is one. It says which path it took.
// 2. vtkPGIGIPolyDataMapper in place of vtkPolyDataMapper: give it the sphere
//    proxies (points + "Radius") and the light (vtkPGILighting); it computes
//    SH soft shadows per vertex on the GPU once, and again only when the
//    scene changes.
// 3. vtkWindowToImageFilter + vtkPNGWriter, as for any VTK window.
//
//   ExampleGIMapper [out.png]        (default: gi-mapper.png)
#include "pgiOffscreenWindow.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkWindowToImageFilter.h"

#include <cstdio>
#include <string>

int main(int argc, char* argv[])
{
  const std::string output = argc > 1 ? argv[1] : "gi-mapper.png";

  // The window, and how it was made.
  std::string path;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&path);
  if (!window)
  {
    std::fprintf(stderr, "%s\n", path.c_str());
    return 1;
  }
  std::printf("offscreen window: %s\n", path.c_str());

  // The scene: a unit sphere 1.5 above a ground plane.
  vtkNew<vtkPlaneSource> ground;
  ground->SetOrigin(-4, -4, 0);
  ground->SetPoint1(4, -4, 0);
  ground->SetPoint2(-4, 4, 0);
  ground->SetResolution(64, 64); // GI is per vertex: tessellate receivers
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0, 1.5);
  ball->SetRadius(1.0);
  ball->SetThetaResolution(64);
  ball->SetPhiResolution(32);

  // The blockers: one sphere proxy standing in for the ball.
  vtkNew<vtkPolyData> proxies;
  vtkNew<vtkPoints> centres;
  centres->InsertNextPoint(0, 0, 1.5);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  radius->InsertNextValue(1.0);
  proxies->SetPoints(centres);
  proxies->GetPointData()->AddArray(radius);

  // The light: a uniform white sky (SetEnvironmentImage takes a lat-long map,
  // e.g. from vtkPGIEXRReader).
  vtkNew<vtkPGILighting> lighting;

  vtkNew<vtkPGIGIPolyDataMapper> groundMapper, ballMapper;
  groundMapper->SetInputConnection(ground->GetOutputPort());
  ballMapper->SetInputConnection(ball->GetOutputPort());
  for (vtkPGIGIPolyDataMapper* mapper : { groundMapper.Get(), ballMapper.Get() })
  {
    mapper->SetProxies(proxies);
    mapper->SetLighting(lighting);
    mapper->GetSettings()->SetOrder(4);
  }
  // The ball is shadowed by the ground: an infinite blocker plane.
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
  ballMapper->AddBlockerPlane(origin, up);
  ballMapper->GetSettings()->SetDefaultAlbedo(0.9, 0.5, 0.3);

  vtkNew<vtkActor> groundActor, ballActor;
  groundActor->SetMapper(groundMapper);
  ballActor->SetMapper(ballMapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(groundActor);
  renderer->AddActor(ballActor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);
  window->SetSize(512, 512);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.5, -7.0, 5.0);
  camera->SetFocalPoint(-0.3, 0.5, 0.5);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCameraClippingRange();
  window->Render();
  std::printf("%s\n", groundMapper->GetGIStatus().c_str());

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(output.c_str());
  writer->Write();
  std::printf("wrote %s\n", output.c_str());
  return 0;
}
