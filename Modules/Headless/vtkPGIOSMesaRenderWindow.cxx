#include "vtkPGIOSMesaRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtk_glew.h"

// glew.h undefines these; osmesa.h, included after it, needs them.
#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

#include <dlfcn.h>

#include <cstring>
#include <vector>

vtkStandardNewMacro(vtkPGIOSMesaRenderWindow);

struct vtkPGIOSMesaRenderWindow::Internals
{
  using CreateContextAttribs = OSMesaContext (*)(const int*, OSMesaContext);
  using MakeCurrentFunction = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
  using DestroyContextFunction = void (*)(OSMesaContext);
  using GetCurrentContextFunction = OSMesaContext (*)();
  CreateContextAttribs Create = nullptr;
  MakeCurrentFunction Bind = nullptr;
  DestroyContextFunction Destroy = nullptr;
  GetCurrentContextFunction Current = nullptr;
  OSMesaContext Context = nullptr;
  std::vector<unsigned char> Buffer;
  int BufferSize[2] = { 0, 0 };
};

vtkPGIOSMesaRenderWindow::vtkPGIOSMesaRenderWindow()
  : OSMesa(new Internals)
{
}

vtkPGIOSMesaRenderWindow::~vtkPGIOSMesaRenderWindow()
{
  this->Finalize();
}

void vtkPGIOSMesaRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OSMesaLibrary: " << GetOSMesaLibrary() << "\n";
}

const char* vtkPGIOSMesaRenderWindow::GetOSMesaLibrary()
{
#ifdef PROXYGI_OSMESA_LIBRARY
  return PROXYGI_OSMESA_LIBRARY;
#else
  return "";
#endif
}

bool vtkPGIOSMesaRenderWindow::OSMesaEntryPointsBound()
{
  // glGetString as every library of this process calls it: libOSMesa's only
  // when it was loaded ahead of libGL.
  void* glGetStringAddress = dlsym(RTLD_DEFAULT, "glGetString");
  void* marker = dlsym(RTLD_DEFAULT, "OSMesaCreateContextAttribs");
  Dl_info a, b;
  return glGetStringAddress && marker && dladdr(glGetStringAddress, &a) && dladdr(marker, &b) &&
    a.dli_fbase == b.dli_fbase;
}

bool vtkPGIOSMesaRenderWindow::HasContext() const
{
  return this->OSMesa->Context != nullptr;
}

bool vtkPGIOSMesaRenderWindow::MakeContext()
{
  Internals& o = *this->OSMesa;
  const std::string preload =
    std::string("LD_PRELOAD=") + (*GetOSMesaLibrary() ? GetOSMesaLibrary() : "libOSMesa.so.8");
  o.Create = reinterpret_cast<Internals::CreateContextAttribs>(
    dlsym(RTLD_DEFAULT, "OSMesaCreateContextAttribs"));
  o.Bind =
    reinterpret_cast<Internals::MakeCurrentFunction>(dlsym(RTLD_DEFAULT, "OSMesaMakeCurrent"));
  o.Destroy = reinterpret_cast<Internals::DestroyContextFunction>(
    dlsym(RTLD_DEFAULT, "OSMesaDestroyContext"));
  o.Current = reinterpret_cast<Internals::GetCurrentContextFunction>(
    dlsym(RTLD_DEFAULT, "OSMesaGetCurrentContext"));
  if (!o.Create || !o.Bind || !o.Destroy || !o.Current)
  {
    this->ContextError = "libOSMesa is not loaded in this process: run it with " + preload;
    return false;
  }
  if (!OSMesaEntryPointsBound())
  {
    this->ContextError = "GL's entry points bind to libGL, not to libOSMesa: libOSMesa must be "
                         "loaded first, " +
      preload;
    return false;
  }
  const int attributes[] = { OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS,
    8, OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
    OSMESA_CONTEXT_MINOR_VERSION, 2, 0 };
  o.Context = o.Create(attributes, nullptr);
  if (!o.Context)
  {
    this->ContextError = "OSMesaCreateContextAttribs (OpenGL 3.2 core, RGBA8, depth 24) failed";
    return false;
  }
  if (!this->EnsureBuffer())
  {
    this->ContextError = "could not make the OSMesa context current";
    this->DestroyContext();
    return false;
  }
  return true;
}

// The buffer follows the window's size; binding it makes the context current.
bool vtkPGIOSMesaRenderWindow::EnsureBuffer()
{
  Internals& o = *this->OSMesa;
  const int w = this->Size[0] > 0 ? this->Size[0] : 300;
  const int h = this->Size[1] > 0 ? this->Size[1] : 300;
  if (o.BufferSize[0] != w || o.BufferSize[1] != h)
  {
    o.Buffer.assign(static_cast<std::size_t>(w) * h * 4, 0);
    o.BufferSize[0] = w;
    o.BufferSize[1] = h;
  }
  else if (o.Current() == o.Context)
  {
    return true;
  }
  return o.Bind(o.Context, o.Buffer.data(), GL_UNSIGNED_BYTE, w, h) == GL_TRUE;
}

void vtkPGIOSMesaRenderWindow::DestroyContext()
{
  Internals& o = *this->OSMesa;
  if (o.Context)
  {
    o.Destroy(o.Context);
  }
  o.Context = nullptr;
  o.Buffer.clear();
  o.BufferSize[0] = o.BufferSize[1] = 0;
}

void vtkPGIOSMesaRenderWindow::MakeCurrent()
{
  if (this->OSMesa->Context && !this->EnsureBuffer())
  {
    vtkErrorMacro("OSMesaMakeCurrent failed for " << this->Size[0] << "x" << this->Size[1]);
  }
}

void vtkPGIOSMesaRenderWindow::ReleaseCurrent()
{
  // OSMesa has no "no context" call that keeps the context; the next
  // MakeCurrent rebinds it.
}

bool vtkPGIOSMesaRenderWindow::IsCurrent()
{
  return this->OSMesa->Context && this->OSMesa->Current() == this->OSMesa->Context;
}

void* vtkPGIOSMesaRenderWindow::GetGenericContext()
{
  return this->OSMesa->Context;
}
