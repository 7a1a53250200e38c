/*
 * pgiGlewShim: a glewInit that tolerates a context GLX does not know.
 *
 * Debian's VTK uses the system GLEW, built for GLX. On an EGL context its
 * glewInit() loads every GL entry point (through libGLdispatch, which serves
 * EGL contexts too) and then fails in the GLX part with
 * GLEW_ERROR_NO_GLX_DISPLAY, so VTK stops its context set-up half way. This
 * library defines glewInit, forwards to the real one and maps that one error
 * to GLEW_OK. It must come before VTK's libraries in the program's lookup
 * order: link it first with -Wl,--no-as-needed (ProxyGI::Headless does so
 * through its interface link options). With GLX contexts it changes nothing.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>

/* From GL/glew.h, without pulling the whole header in. */
#define PGI_GLEW_OK 0
#define PGI_GLEW_ERROR_NO_GLX_DISPLAY 4

#if defined(__GNUC__)
#define PGI_SHIM_EXPORT __attribute__((visibility("default")))
#else
#define PGI_SHIM_EXPORT
#endif

typedef unsigned int (*pgiGlewInitFunction)(void);

static int pgiShimCalls = 0;
static int pgiShimMapped = 0;

PGI_SHIM_EXPORT unsigned int glewInit(void)
{
  static pgiGlewInitFunction real = NULL;
  unsigned int result;
  if (!real)
  {
    real = (pgiGlewInitFunction)dlsym(RTLD_NEXT, "glewInit");
  }
  ++pgiShimCalls;
  if (!real)
  {
    return 1; /* GLEW_ERROR_NO_GL_VERSION: no GLEW behind us */
  }
  result = real();
  if (result == PGI_GLEW_ERROR_NO_GLX_DISPLAY)
  {
    ++pgiShimMapped;
    return PGI_GLEW_OK;
  }
  return result;
}

/* Lets programs check that this definition, not GLEW's, is the one in use. */
PGI_SHIM_EXPORT int pgiGlewShimCalls(void)
{
  return pgiShimCalls;
}

PGI_SHIM_EXPORT int pgiGlewShimMappedErrors(void)
{
  return pgiShimMapped;
}
