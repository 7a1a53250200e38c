/**
 * @class   vtkPGIOSMesaRenderWindow
 * @brief   An offscreen render window on an OSMesa context this class makes
 *          itself, for VTK builds without OSMesa (Debian's are X-only).
 *
 * A vtkGenericOpenGLRenderWindow that owns an OSMesa context (desktop
 * OpenGL 3.2+ core, RGBA8, 24-bit depth, 8-bit stencil) rendering into a
 * buffer of the window's size; VTK renders into its own framebuffers on top
 * of it as with any offscreen window.
 *
 * Two things make OSMesa work under a VTK linked against GLVND's libGL:
 * - GL entry points. VTK calls the GL 1.1 functions directly and GLEW looks
 *   the rest up through glXGetProcAddress. The program must run with
 *   libOSMesa preloaded (LD_PRELOAD=libOSMesa.so.8; `proxygi` re-executes
 *   itself so when PROXYGI_OFFSCREEN=osmesa), so the direct calls bind to
 *   OSMesa; the ProxyGIGlewShim library answers glXGetProcAddress from
 *   OSMesaGetProcAddress while an OSMesa context is current, and maps GLEW's
 *   missing-GLX error to success, as for EGL.
 * - OSMesa's functions are looked up at run time (dlsym), so linking this
 *   module never pulls libOSMesa into programs that do not ask for it.
 *
 * CreateContext() (vtkPGIContextRenderWindow) checks both and says what is
 * missing (GetContextError) instead of rendering half-initialised.
 */
#ifndef vtkPGIOSMesaRenderWindow_h
#define vtkPGIOSMesaRenderWindow_h

#include "ProxyGIHeadlessModule.h"
#include "vtkPGIContextRenderWindow.h"

#include <memory>
#include <string>

class PROXYGIHEADLESS_EXPORT vtkPGIOSMesaRenderWindow : public vtkPGIContextRenderWindow
{
public:
  static vtkPGIOSMesaRenderWindow* New();
  vtkTypeMacro(vtkPGIOSMesaRenderWindow, vtkPGIContextRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Whether GL's entry points bind to libOSMesa in this process (LD_PRELOAD).
  static bool OSMesaEntryPointsBound();
  /// The libOSMesa this build found (what LD_PRELOAD must name), or "".
  static const char* GetOSMesaLibrary();

  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  void* GetGenericContext() override;

protected:
  vtkPGIOSMesaRenderWindow();
  ~vtkPGIOSMesaRenderWindow() override;

  /// False when libOSMesa is not preloaded or OSMesa refuses the context.
  bool MakeContext() override;
  void DestroyContext() override;
  bool HasContext() const override;
  const char* GetContextKind() const override { return "OSMesa"; }
  bool EnsureBuffer();

private:
  struct Internals;
  std::unique_ptr<Internals> OSMesa;

  vtkPGIOSMesaRenderWindow(const vtkPGIOSMesaRenderWindow&) = delete;
  void operator=(const vtkPGIOSMesaRenderWindow&) = delete;
};

#endif
