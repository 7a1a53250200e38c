/**
 * @class   vtkPGIEGLRenderWindow
 * @brief   An offscreen render window on an EGL context this class makes
 *          itself: no X server, and no VTK built with EGL needed.
 *
 * Debian's VTK is an X build (VTK_OPENGL_HAS_EGL off), so its own EGL window
 * is not there. This window is a vtkGenericOpenGLRenderWindow that owns its
 * context: an EGL display (the first hardware EGL device, e.g. an NVIDIA GPU,
 * through EGL_EXT_device_enumeration; else Mesa's surfaceless platform, i.e.
 * llvmpipe; else the default display), a pbuffer config, a desktop OpenGL
 * 3.2+ core context, and a pbuffer surface of the window's size. It answers
 * MakeCurrent/IsCurrent/SupportsOpenGL/IsDirect itself and initialises VTK's
 * OpenGL state from that context.
 *
 * Programs using it must link the ProxyGIGlewShim library before VTK's
 * (ProxyGI::Headless adds it to its users' link lines): the system GLEW is
 * the GLX flavour and fails on EGL contexts without it. CreateContext()
 * reports a missing shim as an error instead of rendering half-initialised.
 *
 * | property | default | meaning |
 * |---|---|---|
 * | DeviceIndex | -1 | EGL device to use; -1: the first hardware device, else surfaceless.
 * The environment variable PROXYGI_EGL_DEVICE sets it too. |
 */
#ifndef vtkPGIEGLRenderWindow_h
#define vtkPGIEGLRenderWindow_h

#include "ProxyGIHeadlessModule.h"
#include "vtkPGIContextRenderWindow.h"

#include <memory>
#include <string>

class PROXYGIHEADLESS_EXPORT vtkPGIEGLRenderWindow : public vtkPGIContextRenderWindow
{
public:
  static vtkPGIEGLRenderWindow* New();
  vtkTypeMacro(vtkPGIEGLRenderWindow, vtkPGIContextRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // DeviceIndex is vtkRenderWindow's (Set/GetDeviceIndex): here -1, the
  // default, means automatic. It takes effect before the context exists.

  // CreateContext() (vtkPGIContextRenderWindow) makes the EGL display,
  // context and surface.
  /// How the context was made, e.g. "EGL device 0 (EGL_NV_device_cuda ...)".
  const std::string& GetPlatformDescription() const { return this->PlatformDescription; }

  /// True when the glewInit shim of ProxyGI is the glewInit this process uses.
  static bool IsGlewShimActive();

  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  void SetSize(int width, int height) override;
  void SetSize(int a[2]) override { this->SetSize(a[0], a[1]); }
  void* GetGenericContext() override;
  void* GetGenericDisplayId() override;

protected:
  vtkPGIEGLRenderWindow();
  ~vtkPGIEGLRenderWindow() override;

  bool MakeContext() override;
  void DestroyContext() override;
  bool HasContext() const override;
  const char* GetContextKind() const override { return "EGL"; }
  bool EnsureSurface();

  std::string PlatformDescription;

private:
  struct Internals;
  std::unique_ptr<Internals> EGL;

  vtkPGIEGLRenderWindow(const vtkPGIEGLRenderWindow&) = delete;
  void operator=(const vtkPGIEGLRenderWindow&) = delete;
};

#endif
