// The EGL window used directly, whatever display the run has (CI runs the
// tests under Xvfb, where the factory takes GLX): the glewInit shim is in
// effect, a context is made without X, VTK renders into it and reads back,
// and resizing makes a new pbuffer. GLX and EGL contexts are not mixed in
// one thread (libglvnd refuses that), hence a test of its own.
#include "pgiTesting.h"
#include "vtkPGIEGLRenderWindow.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <cstdio>

int TestHeadlessEGLWindow(int, char*[])
{
  PGI_CHECK(vtkPGIEGLRenderWindow::IsGlewShimActive());
  vtkNew<vtkPGIEGLRenderWindow> window;
  const bool made = window->CreateContext();
  std::printf("EGL window: %s: %s%s\n", window->GetPlatformDescription().c_str(),
    window->GetRendererDescription().c_str(), window->GetContextError().c_str());
  if (!PGI_CHECK(made))
  {
    return pgitest::Result();
  }
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1.0, 0.5, 0.25);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.0, 0.0, 1.0);
  window->AddRenderer(renderer);
  for (int size : { 40, 64 })
  {
    window->SetSize(size, size - 10);
    window->Render();
    vtkNew<vtkUnsignedCharArray> pixels;
    vtkRenderWindow* base = window;
    base->GetPixelData(0, 0, size - 1, size - 11, 0, pixels);
    PGI_CHECK(pixels->GetNumberOfTuples() == size * (size - 10));
    const unsigned char* c = pixels->GetPointer(3 * ((size - 10) / 2 * size + size / 2));
    std::printf("%dx%d: centre %d %d %d, corner %d %d %d\n", size, size - 10, c[0], c[1], c[2],
      pixels->GetValue(0), pixels->GetValue(1), pixels->GetValue(2));
    PGI_CHECK(c[0] > 100 && c[0] > c[1] && c[1] > c[2]);
    PGI_CHECK(pixels->GetValue(2) == 255 && pixels->GetValue(0) == 0);
  }
  return pgitest::Result();
}
