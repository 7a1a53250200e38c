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
 *
 * It also answers glXGetProcAddress(ARB), where GLEW looks its entry points
 * up: while an OSMesa context is current (vtkPGIOSMesaRenderWindow) the
 * addresses come from OSMesaGetProcAddress, since GLX's would dispatch to no
 * context at all; otherwise GLX answers as before.
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

typedef void (*pgiProc)(void);
typedef pgiProc (*pgiGetProcFunction)(const unsigned char*);
typedef void* (*pgiCurrentFunction)(void);
typedef pgiProc (*pgiOSMesaGetProcFunction)(const char*);

static int pgiShimOSMesaLookups = 0;

/* OSMesa's entry point when libOSMesa is loaded and one of its contexts is current. */
static pgiProc pgiOSMesaProc(const unsigned char* name)
{
  pgiCurrentFunction current = (pgiCurrentFunction)dlsym(RTLD_DEFAULT, "OSMesaGetCurrentContext");
  pgiOSMesaGetProcFunction get =
    (pgiOSMesaGetProcFunction)dlsym(RTLD_DEFAULT, "OSMesaGetProcAddress");
  if (!current || !get || !current())
  {
    return NULL;
  }
  ++pgiShimOSMesaLookups;
  return get((const char*)name);
}

static pgiProc pgiGLXProc(const char* which, const unsigned char* name)
{
  pgiGetProcFunction real = (pgiGetProcFunction)dlsym(RTLD_NEXT, which);
  return real ? real(name) : NULL;
}

PGI_SHIM_EXPORT pgiProc glXGetProcAddressARB(const unsigned char* name)
{
  pgiProc proc = pgiOSMesaProc(name);
  return proc ? proc : pgiGLXProc("glXGetProcAddressARB", name);
}

PGI_SHIM_EXPORT pgiProc glXGetProcAddress(const unsigned char* name)
{
  pgiProc proc = pgiOSMesaProc(name);
  return proc ? proc : pgiGLXProc("glXGetProcAddress", name);
}

/* How many entry points came from OSMesa (tests check the route was taken). */
PGI_SHIM_EXPORT int pgiGlewShimOSMesaLookups(void)
{
  return pgiShimOSMesaLookups;
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
