/**
 * @class   vtkPGIContextRenderWindow
 * @brief   What ProxyGI's own offscreen windows share: a
 *          vtkGenericOpenGLRenderWindow that makes its GL context itself
 *          (EGL, OSMesa) and initialises VTK from it.
 *
 * CreateContext() checks the glewInit shim is in effect, calls the
 * subclass's MakeContext() once (a failure is not retried on every Render
 * until Finalize), reads GL_RENDERER/GL_VERSION, and leaves the reason of a
 * failure in GetContextError(). Initialize, Start, Finalize, SupportsOpenGL
 * and IsDirect are written once here; subclasses make, bind and destroy
 * their context.
 */
#ifndef vtkPGIContextRenderWindow_h
#define vtkPGIContextRenderWindow_h

#include "ProxyGIHeadlessModule.h"
#include "vtkGenericOpenGLRenderWindow.h"

#include <string>

class PROXYGIHEADLESS_EXPORT vtkPGIContextRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  vtkTypeMacro(vtkPGIContextRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Makes the context now (Render does it on demand). False, with the reason
   * in GetContextError(), when none can be had or the glewInit shim is not
   * in effect; nothing is logged as an error, so callers can fall back to
   * another window type.
   */
  bool CreateContext();
  /// Why CreateContext() failed ("" if it did not).
  const std::string& GetContextError() const { return this->ContextError; }
  /// GL_RENDERER and GL_VERSION of the context (after CreateContext()).
  const std::string& GetRendererDescription() const { return this->RendererDescription; }

  void Initialize() override;
  void Finalize() override;
  void Start() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;

protected:
  vtkPGIContextRenderWindow();
  /// Subclasses call Finalize() in their destructor (their context is gone here).
  ~vtkPGIContextRenderWindow() override;

  /// Makes the context and makes it current; false with ContextError set
  /// (and nothing left behind).
  virtual bool MakeContext() = 0;
  virtual void DestroyContext() = 0;
  virtual bool HasContext() const = 0;
  /// "EGL", "OSMesa": for messages.
  virtual const char* GetContextKind() const = 0;

  std::string ContextError;
  std::string RendererDescription;

private:
  bool VTKInitialized = false;
  bool Failed = false;

  vtkPGIContextRenderWindow(const vtkPGIContextRenderWindow&) = delete;
  void operator=(const vtkPGIContextRenderWindow&) = delete;
};

#endif
