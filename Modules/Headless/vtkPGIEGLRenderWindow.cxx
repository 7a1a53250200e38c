#include "vtkPGIEGLRenderWindow.h"

#include "pgiOffscreenWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtk_glew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkPGIEGLRenderWindow);

namespace
{
// eglTerminate must wait for the last window of a display: several windows
// get the same EGLDisplay handle for the same device.
std::mutex& DisplayMutex()
{
  static std::mutex m;
  return m;
}
std::map<EGLDisplay, int>& DisplayUsers()
{
  static std::map<EGLDisplay, int> users;
  return users;
}
bool AcquireDisplay(EGLDisplay display)
{
  std::lock_guard<std::mutex> lock(DisplayMutex());
  int& users = DisplayUsers()[display];
  if (users == 0)
  {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
    {
      DisplayUsers().erase(display);
      return false;
    }
  }
  ++users;
  return true;
}
void ReleaseDisplay(EGLDisplay display)
{
  std::lock_guard<std::mutex> lock(DisplayMutex());
  auto it = DisplayUsers().find(display);
  if (it != DisplayUsers().end() && --it->second == 0)
  {
    DisplayUsers().erase(it);
    eglTerminate(display);
  }
}

bool HasExtension(const char* list, const char* name)
{
  if (!list)
  {
    return false;
  }
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
  {
    const bool startOk = p == list || p[-1] == ' ';
    const bool endOk = p[n] == '\0' || p[n] == ' ';
    if (startOk && endOk)
    {
      return true;
    }
  }
  return false;
}

const char* ErrorName(EGLint error)
{
  switch (error)
  {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error";
  }
}
} // namespace

struct vtkPGIEGLRenderWindow::Internals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLConfig Config = nullptr;
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE;
  int SurfaceSize[2] = { 0, 0 };
};

vtkPGIEGLRenderWindow::vtkPGIEGLRenderWindow()
  : EGL(new Internals)
{
  this->DeviceIndex = -1;
  if (const char* env = std::getenv("PROXYGI_EGL_DEVICE"))
  {
    char* end = nullptr;
    const long index = std::strtol(env, &end, 10);
    if (end != env && index >= 0)
    {
      this->DeviceIndex = static_cast<int>(index);
    }
  }
}

vtkPGIEGLRenderWindow::~vtkPGIEGLRenderWindow()
{
  this->Finalize();
}

void vtkPGIEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DeviceIndex: " << this->DeviceIndex << "\n";
  os << indent << "Platform: " << this->PlatformDescription << "\n";
}

bool vtkPGIEGLRenderWindow::IsGlewShimActive()
{
  return proxygi::GlewShimActive();
}

bool vtkPGIEGLRenderWindow::HasContext() const
{
  return this->EGL->Context != EGL_NO_CONTEXT;
}

bool vtkPGIEGLRenderWindow::MakeContext()
{
  Internals& e = *this->EGL;

  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
    eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::ostringstream tried;

  // 1. A hardware EGL device (NVIDIA, or a Mesa DRM device): the GPU.
  const bool deviceExtensions = getPlatformDisplay &&
    (HasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
      HasExtension(clientExtensions, "EGL_EXT_device_base")) &&
    HasExtension(clientExtensions, "EGL_EXT_platform_device");
  if (!deviceExtensions)
  {
    tried << "no EGL_EXT_device_enumeration/EGL_EXT_platform_device; ";
  }
  else
  {
    auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLint count = 0;
    if (!queryDevices || !queryDevices(0, nullptr, &count) || count <= 0)
    {
      tried << "eglQueryDevicesEXT found no device; ";
    }
    else
    {
      std::vector<EGLDeviceEXT> devices(count);
      queryDevices(count, devices.data(), &count);
      for (EGLint i = 0; i < count && e.Display == EGL_NO_DISPLAY; ++i)
      {
        const char* deviceExtensions =
          queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
        const bool software = HasExtension(deviceExtensions, "EGL_MESA_device_software");
        const bool wanted = this->DeviceIndex >= 0 ? i == this->DeviceIndex : !software;
        if (!wanted)
        {
          tried << "device " << i << " skipped (" << (software ? "software" : "not asked for")
                << "); ";
          continue;
        }
        EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display != EGL_NO_DISPLAY && AcquireDisplay(display))
        {
          e.Display = display;
          std::ostringstream what;
          what << "EGL device " << i << " of " << count;
          if (HasExtension(deviceExtensions, "EGL_NV_device_cuda"))
          {
            what << " (NVIDIA)";
          }
          else if (software)
          {
            what << " (Mesa software)";
          }
          this->PlatformDescription = what.str();
        }
        else
        {
          tried << "device " << i << ": " << ErrorName(eglGetError()) << " ("
                << (deviceExtensions ? deviceExtensions : "no extensions") << "); ";
        }
      }
    }
  }
  // 2. Mesa's surfaceless platform: llvmpipe without any display.
  if (e.Display == EGL_NO_DISPLAY && this->DeviceIndex < 0 && getPlatformDisplay &&
    HasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
  {
    EGLDisplay display =
      getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && AcquireDisplay(display))
    {
      e.Display = display;
      std::string why = tried.str();
      this->PlatformDescription = "EGL surfaceless (Mesa platform)" +
        (why.empty() ? std::string() : " [" + why.substr(0, why.size() - 2) + "]");
    }
    else
    {
      tried << "surfaceless: " << ErrorName(eglGetError()) << "; ";
    }
  }
  if (e.Display == EGL_NO_DISPLAY)
  {
    this->ContextError = "no EGL display could be initialised (" + tried.str() + "client " +
      "extensions: " + (clientExtensions ? clientExtensions : "none") + ")";
    return false;
  }

  const EGLint configAttributes[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RED_SIZE, 8,
    EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_RENDERABLE_TYPE,
    EGL_OPENGL_BIT, EGL_NONE };
  EGLint configs = 0;
  if (!eglChooseConfig(e.Display, configAttributes, &e.Config, 1, &configs) || configs < 1)
  {
    this->ContextError = std::string("no EGL pbuffer config with desktop OpenGL on ") +
      this->PlatformDescription + " (" + ErrorName(eglGetError()) + ")";
    this->DestroyContext();
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API))
  {
    this->ContextError = "eglBindAPI(EGL_OPENGL_API) failed";
    this->DestroyContext();
    return false;
  }
  // VTK needs a 3.2 core context; drivers give the newest compatible one.
  const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
  e.Context = eglCreateContext(e.Display, e.Config, EGL_NO_CONTEXT, contextAttributes);
  if (e.Context == EGL_NO_CONTEXT)
  {
    this->ContextError = std::string("eglCreateContext (OpenGL 3.2 core) failed on ") +
      this->PlatformDescription + ": " + ErrorName(eglGetError());
    this->DestroyContext();
    return false;
  }
  if (!this->EnsureSurface() || !eglMakeCurrent(e.Display, e.Surface, e.Surface, e.Context))
  {
    this->ContextError =
      std::string("could not make the EGL context current: ") + ErrorName(eglGetError());
    this->DestroyContext();
    return false;
  }
  return true;
}

bool vtkPGIEGLRenderWindow::EnsureSurface()
{
  Internals& e = *this->EGL;
  const int w = this->Size[0] > 0 ? this->Size[0] : 300;
  const int h = this->Size[1] > 0 ? this->Size[1] : 300;
  if (e.Surface != EGL_NO_SURFACE && e.SurfaceSize[0] == w && e.SurfaceSize[1] == h)
  {
    return true;
  }
  if (e.Surface != EGL_NO_SURFACE)
  {
    if (eglGetCurrentSurface(EGL_DRAW) == e.Surface)
    {
      eglMakeCurrent(e.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroySurface(e.Display, e.Surface);
    e.Surface = EGL_NO_SURFACE;
  }
  const EGLint attributes[] = { EGL_WIDTH, w, EGL_HEIGHT, h, EGL_NONE };
  e.Surface = eglCreatePbufferSurface(e.Display, e.Config, attributes);
  if (e.Surface == EGL_NO_SURFACE)
  {
    return false;
  }
  e.SurfaceSize[0] = w;
  e.SurfaceSize[1] = h;
  return true;
}

void vtkPGIEGLRenderWindow::DestroyContext()
{
  Internals& e = *this->EGL;
  if (e.Display == EGL_NO_DISPLAY)
  {
    return;
  }
  if (eglGetCurrentContext() == e.Context)
  {
    eglMakeCurrent(e.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (e.Surface != EGL_NO_SURFACE)
  {
    eglDestroySurface(e.Display, e.Surface);
  }
  if (e.Context != EGL_NO_CONTEXT)
  {
    eglDestroyContext(e.Display, e.Context);
  }
  ReleaseDisplay(e.Display);
  e = Internals();
}

void vtkPGIEGLRenderWindow::MakeCurrent()
{
  Internals& e = *this->EGL;
  if (e.Context == EGL_NO_CONTEXT)
  {
    return;
  }
  if (!this->EnsureSurface())
  {
    vtkErrorMacro("Could not create an EGL pbuffer of " << this->Size[0] << "x" << this->Size[1]);
    return;
  }
  if (eglGetCurrentContext() != e.Context || eglGetCurrentSurface(EGL_DRAW) != e.Surface)
  {
    if (!eglMakeCurrent(e.Display, e.Surface, e.Surface, e.Context))
    {
      vtkErrorMacro("eglMakeCurrent failed: " << ErrorName(eglGetError()));
    }
  }
}

void vtkPGIEGLRenderWindow::ReleaseCurrent()
{
  if (this->EGL->Display != EGL_NO_DISPLAY && this->IsCurrent())
  {
    eglMakeCurrent(this->EGL->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

bool vtkPGIEGLRenderWindow::IsCurrent()
{
  return this->EGL->Context != EGL_NO_CONTEXT && eglGetCurrentContext() == this->EGL->Context;
}

void vtkPGIEGLRenderWindow::SetSize(int width, int height)
{
  // The surface follows at the next MakeCurrent; VTK's framebuffers at Start.
  this->Superclass::SetSize(width, height);
}

void* vtkPGIEGLRenderWindow::GetGenericContext()
{
  return this->EGL->Context;
}

void* vtkPGIEGLRenderWindow::GetGenericDisplayId()
{
  return this->EGL->Display;
}
