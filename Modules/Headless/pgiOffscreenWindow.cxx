#include "pgiOffscreenWindow.h"

#include "vtkAutoInit.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderingOpenGLConfigure.h"
#include "vtk_glew.h"

#ifdef PROXYGI_HEADLESS_HAS_EGL
#include "vtkPGIEGLRenderWindow.h"
#endif
#if defined(VTK_OPENGL_HAS_OSMESA) && __has_include("vtkOSOpenGLRenderWindow.h")
#define PROXYGI_HEADLESS_HAS_OSMESA 1
#include "vtkOSOpenGLRenderWindow.h"
#endif

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <sstream>

// vtkRenderWindow::New() must find the OpenGL2 windows whoever links us.
VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace proxygi
{

namespace
{
// Whether an X server answers on DISPLAY, asked through libX11 at run time
// (no X headers or link needed for the EGL-only case).
bool XServerAnswers()
{
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    return false;
  }
  void* x11 = dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  if (!x11)
  {
    return false;
  }
  using OpenDisplay = void* (*)(const char*);
  using CloseDisplay = int (*)(void*);
  auto open = reinterpret_cast<OpenDisplay>(dlsym(x11, "XOpenDisplay"));
  auto close = reinterpret_cast<CloseDisplay>(dlsym(x11, "XCloseDisplay"));
  bool ok = false;
  if (open && close)
  {
    if (void* d = open(nullptr))
    {
      close(d);
      ok = true;
    }
  }
  dlclose(x11);
  return ok;
}

vtkSmartPointer<vtkRenderWindow> Configure(vtkSmartPointer<vtkRenderWindow> window)
{
  window->SetOffScreenRendering(1);
  window->SetSize(300, 300);
  window->SetMultiSamples(0); // the same image on every driver
  return window;
}
} // namespace

std::string AvailableOffscreenPaths()
{
  std::string paths;
#ifdef PROXYGI_HEADLESS_HAS_EGL
  paths += "EGL ";
#endif
#ifdef VTK_USE_X
  paths += "GLX ";
#endif
#ifdef PROXYGI_HEADLESS_HAS_OSMESA
  paths += "OSMesa ";
#endif
  if (!paths.empty())
  {
    paths.pop_back();
  }
  return paths;
}

std::string DescribeRenderWindowContext(vtkRenderWindow* window)
{
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!gl)
  {
    return "not an OpenGL window";
  }
#ifdef PROXYGI_HEADLESS_HAS_EGL
  if (auto* egl = vtkPGIEGLRenderWindow::SafeDownCast(window))
  {
    if (!egl->CreateContext())
    {
      return "no context: " + egl->GetContextError();
    }
    return egl->GetRendererDescription();
  }
#endif
  gl->Initialize();
  gl->MakeCurrent();
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + ", OpenGL " + (version ? version : "?");
}

vtkSmartPointer<vtkRenderWindow> NewOffscreenRenderWindow(std::string* description)
{
  std::string forced;
  if (const char* env = std::getenv("PROXYGI_OFFSCREEN"))
  {
    forced = env;
    if (forced == "auto")
    {
      forced.clear();
    }
  }
  std::ostringstream notes;
  auto report = [&](const std::string& text)
  {
    if (description)
    {
      *description = text;
    }
  };

  const bool x = (forced.empty() || forced == "glx") && XServerAnswers();
#ifdef VTK_USE_X
  if (x)
  {
    auto window = Configure(vtkSmartPointer<vtkRenderWindow>::New());
    if (vtkOpenGLRenderWindow::SafeDownCast(window))
    {
      report(std::string("GLX offscreen on DISPLAY=") + std::getenv("DISPLAY") + ": " +
        DescribeRenderWindowContext(window));
      return window;
    }
    notes << "GLX: no OpenGL window from VTK's factory; ";
  }
#endif
  if (forced.empty() && !x)
  {
    notes << "no X display; ";
  }
  else if (forced == "glx")
  {
    notes << "GLX: the X server on DISPLAY does not answer; ";
  }

#ifdef PROXYGI_HEADLESS_HAS_EGL
  if (forced.empty() || forced == "egl")
  {
    vtkSmartPointer<vtkPGIEGLRenderWindow> egl = vtkSmartPointer<vtkPGIEGLRenderWindow>::New();
    if (egl->CreateContext())
    {
      Configure(egl);
      report(egl->GetPlatformDescription() + ": " + egl->GetRendererDescription());
      return egl;
    }
    notes << "EGL: " << egl->GetContextError() << "; ";
  }
#else
  if (forced == "egl")
  {
    notes << "EGL: this build has no EGL (no EGL headers or library at configure time); ";
  }
#endif

#ifdef PROXYGI_HEADLESS_HAS_OSMESA
  if (forced.empty() || forced == "osmesa")
  {
    vtkSmartPointer<vtkRenderWindow> osmesa = vtkSmartPointer<vtkOSOpenGLRenderWindow>::New();
    Configure(osmesa);
    report("OSMesa: " + DescribeRenderWindowContext(osmesa));
    return osmesa;
  }
#else
  if (forced == "osmesa")
  {
    notes << "OSMesa: VTK was not built with it; ";
  }
#endif
  std::string why = notes.str();
  if (why.size() > 2)
  {
    why.resize(why.size() - 2);
  }
  report("no offscreen window (" + why + ")");
  return nullptr;
}

} // namespace proxygi
