/**
 * @file pgiOffscreenWindow.h
 * @brief A render window for programs and tests without a screen, picked
 * from what this process can use:
 *
 * - EGL: no DISPLAY (or the X server does not answer), ProxyGI built with
 *   EGL: vtkPGIEGLRenderWindow, the first hardware EGL device (the NVIDIA
 *   GPU), else Mesa surfaceless (llvmpipe).
 * - GLX: DISPLAY set and reachable (a desktop, Xvfb): VTK's X window, offscreen.
 * - OSMesa: asked for (PROXYGI_OFFSCREEN=osmesa), or nothing else worked and
 *   libOSMesa is preloaded: VTK's OSMesa window where VTK has one
 *   (VTK_OPENGL_HAS_OSMESA), else vtkPGIOSMesaRenderWindow (which needs
 *   LD_PRELOAD of libOSMesa).
 *
 * The environment variable PROXYGI_OFFSCREEN=egl|glx|osmesa forces a path
 * (auto otherwise); PROXYGI_EGL_DEVICE picks an EGL device by index.
 * The description says which path was taken and why, and, once the context
 * exists, the GL renderer and version.
 */
#ifndef pgiOffscreenWindow_h
#define pgiOffscreenWindow_h

#include "ProxyGIHeadlessModule.h"
#include "vtkSmartPointer.h"

#include <string>

class vtkRenderWindow;

namespace proxygi
{

/**
 * A new offscreen render window (offscreen rendering on, size 300x300), or
 * null when no path works; `description` (optional) receives the path taken,
 * e.g. "EGL surfaceless (Mesa): llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5
 * (Core Profile) Mesa 22.3.6", or why none worked.
 */
PROXYGIHEADLESS_EXPORT vtkSmartPointer<vtkRenderWindow> NewOffscreenRenderWindow(
  std::string* description = nullptr);

/// The GL renderer and version of a window (initialises its context if needed).
PROXYGIHEADLESS_EXPORT std::string DescribeRenderWindowContext(vtkRenderWindow* window);

/// True when the glewInit shim of ProxyGI (libProxyGIGlewShim) is the
/// glewInit this process uses: the EGL and OSMesa windows need it.
PROXYGIHEADLESS_EXPORT bool GlewShimActive();

/**
 * For programs: when PROXYGI_OFFSCREEN=osmesa asks for ProxyGI's OSMesa
 * window and libOSMesa is not preloaded yet, re-executes the program
 * (/proc/self/exe with `argv`) with libOSMesa added to LD_PRELOAD. Returns
 * when nothing needed doing, or with a message in `error` when the re-exec
 * failed (or was already tried).
 */
PROXYGIHEADLESS_EXPORT void PreloadOSMesaIfAsked(char* argv[], std::string* error = nullptr);

/// Which paths this build has: "EGL GLX", "GLX OSMesa", ...
PROXYGIHEADLESS_EXPORT std::string AvailableOffscreenPaths();

} // namespace proxygi

#endif
