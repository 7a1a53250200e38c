// Long work in the proxygi program: a progress display on standard error
// driven by a filter's ProgressEvent, Ctrl-C that aborts the filter cleanly,
// and output files that are never left half-written.
#ifndef proxygiProgress_h
#define proxygiProgress_h

#include "pgiSceneSetup.h" // SetupMonitor

#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;

namespace proxygi
{
namespace cli
{
/**
 * Shows `what`'s progress while `filter` updates: on a terminal a bar with
 * the percentage and the time left, redrawn in place; otherwise a line each
 * 10% (or 10 s). While it lives, Ctrl-C (SIGINT) sets the filter's abort
 * flag instead of killing the program; Interrupted() then says so.
 */
class Progress
{
public:
  Progress(vtkAlgorithm* filter, const std::string& what);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Whether Ctrl-C stopped the work (the command then writes nothing, exits 130).
  bool Interrupted() const;

private:
  struct Internals;
  Internals* Impl;
};

/// A Progress for each long filter of a scene's set-up (proxies, reference).
class SetupProgress : public SetupMonitor
{
public:
  explicit SetupProgress(const std::string& command)
    : Command(command)
  {
  }
  void Begin(vtkAlgorithm* filter, const std::string& what) override;
  bool End(vtkAlgorithm* filter) override;
  /// Whether Ctrl-C stopped one of them.
  bool Interrupted() const { return this->Stopped; }

private:
  std::string Command;
  std::unique_ptr<Progress> Current;
  bool Stopped = false;
};

/// Whether Progress draws anything (off with --quiet); Ctrl-C works either way.
void SetProgressShown(bool shown);

/// Exit code of a command stopped by Ctrl-C (128 + SIGINT, as shells report it).
constexpr int InterruptedExitCode = 130;

/**
 * Whether `path` ends with one of `extensions` (".exr", ...; case-insensitive);
 * if not, prints "proxygi <command>: <option> FILE must end in ..." and
 * returns false.
 */
bool HasExtension(const std::string& command, const std::string& option, const std::string& path,
  const std::vector<std::string>& extensions);

/**
 * Runs `write` on a temporary name next to `path`, then renames it to
 * `path`: readers never see a half-written file. False (and no file) if
 * `write` fails or the rename does.
 */
bool WriteThenRename(const std::string& path, const std::function<bool(const std::string&)>& write);
} // namespace cli
} // namespace proxygi

#endif
