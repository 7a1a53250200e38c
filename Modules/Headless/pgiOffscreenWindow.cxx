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
#define PROXYGI_HEADLESS_VTK_OSMESA 1
#include "vtkOSOpenGLRenderWindow.h"
#endif
#ifdef PROXYGI_HEADLESS_HAS_OSMESA
#include "vtkPGIOSMesaRenderWindow.h"
#endif

#include <dlfcn.h>
#include <unistd.h>

#include <cerrno>
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
// (no X headers or link needed for the EGL-only case). The connection stays
// open: an X server without -noreset (Xvfb as xvfb-run starts it) resets
// when its last client leaves, and VTK's window, opened during that reset,
// fails with "bad X server connection".
bool XServerAnswers()
{
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    return false;
  }
  static void* kept = nullptr;
  static std::string keptFor;
  if (kept && keptFor == display)
  {
    return true;
  }
  void* x11 = dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  if (!x11)
  {
    return false;
  }
  using OpenDisplay = void* (*)(const char*);
  auto open = reinterpret_cast<OpenDisplay>(dlsym(x11, "XOpenDisplay"));
  void* connection = open ? open(nullptr) : nullptr;
  if (!connection)
  {
    dlclose(x11);
    return false;
  }
  kept = connection; // libX11 stays loaded with it
  keptFor = display;
  return true;
}

vtkSmartPointer<vtkRenderWindow> Configure(vtkSmartPointer<vtkRenderWindow> window)
{
  window->SetOffScreenRendering(1);
  window->SetSize(300, 300);
  window->SetMultiSamples(0); // the same image on every driver
  return window;
}
} // namespace

bool GlewShimActive()
{
  // The shim exports pgiGlewShimCalls; the glewInit the process resolves must
  // live in the same object as that marker.
  void* marker = dlsym(RTLD_DEFAULT, "pgiGlewShimCalls");
  void* glewInitAddress = dlsym(RTLD_DEFAULT, "glewInit");
  if (!marker || !glewInitAddress)
  {
    return false;
  }
  Dl_info a, b;
  if (!dladdr(marker, &a) || !dladdr(glewInitAddress, &b))
  {
    return false;
  }
  return a.dli_fbase == b.dli_fbase;
}

void PreloadOSMesaIfAsked(char* argv[], std::string* error)
{
  const char* asked = std::getenv("PROXYGI_OFFSCREEN");
  if (!asked || std::strcmp(asked, "osmesa") != 0)
  {
    return;
  }
#if defined(PROXYGI_HEADLESS_HAS_OSMESA) && !defined(PROXYGI_HEADLESS_VTK_OSMESA)
  if (vtkPGIOSMesaRenderWindow::OSMesaEntryPointsBound())
  {
    return;
  }
  if (std::getenv("PROXYGI_OSMESA_PRELOADED"))
  {
    if (error)
    {
      *error = "libOSMesa was preloaded but GL's entry points still bind elsewhere";
    }
    return;
  }
  std::string preload = vtkPGIOSMesaRenderWindow::GetOSMesaLibrary();
  if (const char* previous = std::getenv("LD_PRELOAD"))
  {
    preload += std::string(":") + previous;
  }
  setenv("LD_PRELOAD", preload.c_str(), 1);
  setenv("PROXYGI_OSMESA_PRELOADED", "1", 1);
  execv("/proc/self/exe", argv);
  if (error)
  {
    *error = std::string("could not re-execute with LD_PRELOAD: ") + std::strerror(errno);
  }
#else
  (void)argv;
  (void)error;
#endif
}

std::string AvailableOffscreenPaths()
{
  std::string paths;
#ifdef PROXYGI_HEADLESS_HAS_EGL
  paths += "EGL ";
#endif
#ifdef VTK_USE_X
  paths += "GLX ";
#endif
#if defined(PROXYGI_HEADLESS_VTK_OSMESA) || defined(PROXYGI_HEADLESS_HAS_OSMESA)
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
#ifdef PROXYGI_HEADLESS_HAS_OSMESA
  if (auto* osmesa = vtkPGIOSMesaRenderWindow::SafeDownCast(window))
  {
    if (!osmesa->CreateContext())
    {
      return "no context: " + osmesa->GetContextError();
    }
    return osmesa->GetRendererDescription();
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

#if defined(PROXYGI_HEADLESS_VTK_OSMESA)
  if (forced.empty() || forced == "osmesa")
  {
    vtkSmartPointer<vtkRenderWindow> osmesa = vtkSmartPointer<vtkOSOpenGLRenderWindow>::New();
    Configure(osmesa);
    report("OSMesa (VTK's window): " + DescribeRenderWindowContext(osmesa));
    return osmesa;
  }
#elif defined(PROXYGI_HEADLESS_HAS_OSMESA)
  // Unasked, only where libOSMesa was preloaded (else it cannot work).
  if (forced == "osmesa" || (forced.empty() && vtkPGIOSMesaRenderWindow::OSMesaEntryPointsBound()))
  {
    vtkSmartPointer<vtkPGIOSMesaRenderWindow> osmesa =
      vtkSmartPointer<vtkPGIOSMesaRenderWindow>::New();
    if (osmesa->CreateContext())
    {
      Configure(osmesa);
      report("OSMesa (ProxyGI's window, libOSMesa preloaded): " + osmesa->GetRendererDescription());
      return osmesa;
    }
    notes << "OSMesa: " << osmesa->GetContextError() << "; ";
  }
#else
  if (forced == "osmesa")
  {
    notes << "OSMesa: neither VTK nor this build has it (no GL/osmesa.h or libOSMesa at "
             "configure time); ";
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
