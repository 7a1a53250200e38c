// The headless window factory: it reports the path it took, renders a
// sphere with VTK's own mapper, and the EGL path needs no X at all (run
// with DISPLAY unset, it must be the path taken; PROXYGI_EXPECT_OFFSCREEN
// names the path a run expects).
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <string>

int TestHeadlessOffscreenWindow(int, char*[])
{
  std::printf("offscreen paths in this build: %s\n", proxygi::AvailableOffscreenPaths().c_str());
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("offscreen window: %s\n", description.c_str());
  if (!PGI_CHECK(window != nullptr))
  {
    return pgitest::Result();
  }
  const char* display = std::getenv("DISPLAY");
  const char* forced = std::getenv("PROXYGI_OFFSCREEN");
  if ((!display || !*display) && !forced)
  {
    // No X: the EGL path, which must not have touched X.
    PGI_CHECK(description.rfind("EGL", 0) == 0);
  }
  // The path the run was set up for (the GLX test under Xvfb): a fallback to
  // another path is a failure there.
  if (const char* expected = std::getenv("PROXYGI_EXPECT_OFFSCREEN"))
  {
    PGI_CHECK(description.rfind(expected, 0) == 0);
  }

  window->Render(); // the context, and GLEW's entry points
  // Under OSMesa the shim must have answered GLEW from OSMesaGetProcAddress.
  using Count = int (*)();
  auto lookups = reinterpret_cast<Count>(dlsym(RTLD_DEFAULT, "pgiGlewShimOSMesaLookups"));
  if (description.rfind("OSMesa (ProxyGI", 0) == 0)
  {
    const int n = lookups ? lookups() : 0;
    std::printf("entry points from OSMesa: %d\n", n);
    PGI_CHECK(n > 100);
  }

  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1.0, 0.5, 0.25);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.0, 0.0, 0.0);
  window->AddRenderer(renderer);
  window->SetSize(64, 48);
  window->Render();

  // The centre is lit orange, the corner is background.
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, 63, 47, 0, pixels);
  const unsigned char* centre = pixels->GetPointer(3 * (24 * 64 + 32));
  const unsigned char* corner = pixels->GetPointer(0);
  std::printf("centre pixel %d %d %d, corner %d %d %d\n", centre[0], centre[1], centre[2],
    corner[0], corner[1], corner[2]);
  PGI_CHECK(centre[0] > 100 && centre[0] > centre[1] && centre[1] > centre[2]);
  PGI_CHECK(corner[0] == 0 && corner[1] == 0 && corner[2] == 0);

  // Resizing follows (a new pbuffer on EGL).
  window->SetSize(32, 32);
  window->Render();
  window->GetPixelData(0, 0, 31, 31, 0, pixels);
  PGI_CHECK(pixels->GetNumberOfTuples() == 32 * 32);
  PGI_CHECK(pixels->GetPointer(3 * (16 * 32 + 16))[0] > 100);

  // A second window at the same time, then both torn down.
  vtkSmartPointer<vtkRenderWindow> second = proxygi::NewOffscreenRenderWindow();
  PGI_CHECK(second != nullptr);
  if (second)
  {
    vtkNew<vtkRenderer> r2;
    r2->SetBackground(0.0, 1.0, 0.0);
    second->AddRenderer(r2);
    second->SetSize(8, 8);
    second->Render();
    vtkNew<vtkUnsignedCharArray> p2;
    second->GetPixelData(0, 0, 7, 7, 0, p2);
    PGI_CHECK(p2->GetPointer(0)[1] == 255 && p2->GetPointer(0)[0] == 0);
  }
  window->Render();
  window->GetPixelData(0, 0, 31, 31, 0, pixels);
  PGI_CHECK(pixels->GetPointer(3 * (16 * 32 + 16))[0] > 100);

  return pgitest::Result();
}
