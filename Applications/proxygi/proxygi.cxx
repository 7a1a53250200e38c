// proxygi: the command-line front of ProxyGI. One program, one subcommand
// per job; each prints what it did, how long it took and how far from the
// reference it landed.
#include "proxygiCommands.h"
#include "proxygiProgress.h"

#include "pgiOffscreenWindow.h"
#include "pgiSHTableCache.h"

#include "vtkLogger.h"

#include <vtkSMPTools.h>
#include <vtkVersionMacros.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

namespace proxygi
{
namespace cli
{

std::string Option(const Args& args, const std::string& name, const std::string& fallback)
{
  // The last occurrence wins, as in most command lines (a script's defaults
  // first, the user's choice after them).
  for (std::size_t i = args.size(); i-- > 1;)
  {
    if (args[i - 1] == name)
    {
      return args[i];
    }
  }
  return fallback;
}

double NumberOption(const Args& args, const std::string& name, double fallback, bool& ok)
{
  const std::string text = Option(args, name, "");
  if (text.empty())
  {
    return fallback;
  }
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (errno != 0 || end == text.c_str() || *end != '\0')
  {
    vtkLogF(ERROR, "proxygi: %s expects a number, got '%s'", name.c_str(), text.c_str());
    ok = false;
  }
  return v;
}

bool Flag(const Args& args, const std::string& name)
{
  for (const std::string& a : args)
  {
    if (a == name)
    {
      return true;
    }
  }
  return false;
}

std::string Positional(const Args& args, const std::vector<std::string>& flags)
{
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    if (args[i].size() > 1 && args[i][0] == '-')
    {
      bool valueless = false;
      for (const std::string& f : flags)
      {
        valueless = valueless || args[i] == f;
      }
      i += valueless ? 0 : 1;
      continue;
    }
    return args[i];
  }
  return std::string();
}

bool KnownOptions(const Args& args, const char* command, const std::vector<std::string>& valued,
  const std::vector<std::string>& flags)
{
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    if (a.size() < 2 || a[0] != '-' || std::find(flags.begin(), flags.end(), a) != flags.end())
    {
      continue;
    }
    if (std::find(valued.begin(), valued.end(), a) == valued.end())
    {
      vtkLogF(ERROR, "proxygi %s: unknown option '%s' (proxygi %s --help lists them)", command,
        a.c_str(), command);
      return false;
    }
    ++i; // its value
  }
  return true;
}

} // namespace cli
} // namespace proxygi

namespace
{
const char* Usage = R"(usage: proxygi <command> [options]

Commands:
  render     Render a scene (JSON file, default: the bunny over a plane under
             the forest map) with SH soft shadows, indirect and local lights;
             write the image, print the plan, time and error against a cached
             Embree reference. --analytic: the sphere-over-plane scene against
             its closed form. Run 'proxygi render --help'.
  sh         Spherical-harmonics tools: cap visibility and log-visibility,
             exp round trips per method, projection of test functions.
             Run 'proxygi sh --help'.
  bench      Run the Google Benchmark programs (accuracy counters included);
             arguments go to the benchmark program.
  proxies    Bounding sphere proxies of a mesh (variational, octree or
             k-means): write them (.vtp), print E and the build time.
             Run 'proxygi proxies --help'.
  shade      The CPU GI filter on a receiver mesh (.off/.vtp) and a proxies
             .vtp with the classes' defaults: the arrays and the plan.
             Run 'proxygi shade --help'.
  view       An interactive window on a scene with GI live: keys switch the
             effects, the backend, the SH order and the sphere count; a handle
             drags a light; an overlay shows the plan, times and error.
             Run 'proxygi view --help'.
  cloud      A scene's light cloud (Kristensen 2005; default: the Cornell
             box): precompute on Embree, then a point light moving along a
             path, relit per step; frames, time per frame, per-step change,
             error against Embree. Run 'proxygi cloud --help'.
  calibrate  Measure the accuracy budget's candidates on scenes against
             Embree and write the cost and error model that 'render
             --error/--time' chooses with. Run 'proxygi calibrate --help'.
  reference  Embree path-traced ground truth of a scene (or the default
             scene), per pixel (EXR/PNG) or per vertex (.vtp), with its noise.
             Run 'proxygi reference --help'.

  proxygi --help | --version

Every command takes --offscreen egl|glx|osmesa (the offscreen OpenGL path;
PROXYGI_OFFSCREEN does the same; osmesa restarts the program with libOSMesa
preloaded), --quiet (errors only, no progress) and --verbose (VTK's
log down to trace level, in vtkLogger's own format); by default errors,
warnings and notices are shown, one line each ("warning: ", "info: ").
Exit codes: 0 done, 1 failed (input, data, rendering or writing), 2 bad
arguments or unknown command, 130 interrupted (Ctrl-C).
)";

// The program's messages (its own and VTK's, all through vtkLogger) as plain
// lines: errors as they are ("proxygi render: ..."), the rest tagged.
void PrintMessage(void*, const vtkLogger::Message& message)
{
  const char* tag = message.verbosity <= vtkLogger::VERBOSITY_ERROR ? ""
    : message.verbosity == vtkLogger::VERBOSITY_WARNING             ? "warning: "
                                                                    : "info: ";
  std::fprintf(stderr, "%s%s%s\n", tag, message.prefix, message.message);
}

int RunBench(const char* self, const proxygi::cli::Args& args)
{
  // The benchmark program sits next to this one in the build's bin folder.
  std::string path = self;
  const std::size_t slash = path.rfind('/');
  path =
    (slash == std::string::npos ? std::string(".") : path.substr(0, slash)) + "/ProxyGIBenchSH";
  if (access(path.c_str(), X_OK) != 0)
  {
    vtkLogF(ERROR, "proxygi bench: %s not found (configure with PROXYGI_BUILD_BENCHMARKS=ON)",
      path.c_str());
    return 1;
  }
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(path.c_str()));
  for (const std::string& a : args)
  {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  execv(path.c_str(), argv.data());
  vtkLogF(ERROR, "proxygi bench: cannot run %s: %s", path.c_str(), std::strerror(errno));
  return 1;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
    !std::strcmp(argv[1], "help"))
  {
    std::fputs(Usage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 1, 0)
  // Debian's VTK defaults to the sequential SMP backend; use the threads
  // unless the user chose one (VTK_SMP_BACKEND_IN_USE).
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkSMPTools::SetBackend("STDThread");
  }
#endif
  const std::string command = argv[1];
  // --quiet and --verbose apply to every command: they set how much of
  // vtkLogger's output (VTK's warnings and errors included) reaches stderr.
  proxygi::cli::Args args;
  vtkLogger::Verbosity shown = vtkLogger::VERBOSITY_INFO;
  for (int k = 2; k < argc; ++k)
  {
    if (!std::strcmp(argv[k], "--quiet"))
    {
      shown = vtkLogger::VERBOSITY_ERROR;
      proxygi::cli::SetProgressShown(false);
    }
    else if (!std::strcmp(argv[k], "--verbose"))
    {
      shown = vtkLogger::VERBOSITY_TRACE;
    }
    else if (!std::strcmp(argv[k], "--offscreen") && k + 1 < argc)
    {
      setenv("PROXYGI_OFFSCREEN", argv[++k], 1);
    }
    else
    {
      args.emplace_back(argv[k]);
    }
  }
  if (shown == vtkLogger::VERBOSITY_TRACE)
  {
    vtkLogger::SetStderrVerbosity(shown); // vtkLogger's own lines: time, thread, file:line
  }
  else
  {
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    vtkLogger::AddCallback("proxygi-stderr", PrintMessage, nullptr, shown);
  }
  // OSMesa under Debian's X-only VTK needs libOSMesa ahead of libGL: the
  // program starts again with it preloaded (see vtkPGIOSMesaRenderWindow).
  std::string preloadError;
  proxygi::PreloadOSMesaIfAsked(argv, &preloadError);
  if (!preloadError.empty())
  {
    vtkLogF(ERROR, "proxygi: OSMesa: %s", preloadError.c_str());
    return 1;
  }
  if (command == "--version")
  {
    std::printf("proxygi %s\n", PROXYGI_VERSION);
    return 0;
  }
  // The commands that keep their scenes' data in --cache keep the SH tables
  // there too (unless PROXYGI_TABLE_CACHE names a place): a process's first
  // update then reads the tables instead of computing them.
  if ((command == "render" || command == "view" || command == "calibrate" || command == "cloud") &&
    !std::getenv("PROXYGI_TABLE_CACHE"))
  {
    proxygi::sh::SetTableCacheDirectory(
      proxygi::cli::Option(args, "--cache", "proxygi-cache") + "/tables");
  }
  if (command == "render")
  {
    return proxygi::cli::RunRender(args);
  }
  if (command == "sh")
  {
    return proxygi::cli::RunSH(args);
  }
  if (command == "bench")
  {
    return RunBench(argv[0], args);
  }
  if (command == "reference")
  {
    return proxygi::cli::RunReference(args);
  }
  if (command == "proxies")
  {
    return proxygi::cli::RunProxies(args);
  }
  if (command == "shade")
  {
    return proxygi::cli::RunShade(args);
  }
  if (command == "view")
  {
    return proxygi::cli::RunView(args);
  }
  if (command == "calibrate")
  {
    return proxygi::cli::RunCalibrate(args);
  }
  if (command == "cloud")
  {
    return proxygi::cli::RunCloud(args);
  }
  vtkLogF(ERROR, "proxygi: unknown command '%s'", command.c_str());
  std::fputs(Usage, stderr);
  return 2;
}
