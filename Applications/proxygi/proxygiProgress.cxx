#include "proxygiProgress.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkNew.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <unistd.h>

namespace proxygi
{
namespace cli
{
namespace
{
std::atomic<bool> InterruptRequested(false);
bool ProgressShown = true;

extern "C" void OnInterrupt(int)
{
  InterruptRequested = true;
}
} // namespace

struct Progress::Internals
{
  vtkAlgorithm* Filter = nullptr;
  std::string What;
  vtkNew<vtkCallbackCommand> Observer;
  unsigned long Tag = 0;
  bool Terminal = false;
  bool Drawn = false;
  int LastDecile = -1;
  double LastLine = 0.0;
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
  void (*PreviousHandler)(int) = nullptr;
  bool Interrupted = false;

  double Elapsed() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }

  void Show(double fraction)
  {
    fraction = std::min(1.0, std::max(0.0, fraction));
    const double elapsed = this->Elapsed();
    const double left = fraction > 0.01 ? elapsed * (1.0 - fraction) / fraction : -1.0;
    char eta[32] = "";
    if (left >= 0.0)
    {
      std::snprintf(eta, sizeof(eta), ", %.0f s left", left);
    }
    if (this->Terminal)
    {
      constexpr int width = 30;
      const int filled = static_cast<int>(std::lround(fraction * width));
      std::fprintf(stderr, "\r%s [%.*s%*s] %3.0f%%%s   ", this->What.c_str(), filled,
        "##############################", width - filled, "", 100.0 * fraction, eta);
      std::fflush(stderr);
      this->Drawn = true;
      return;
    }
    const int decile = static_cast<int>(fraction * 10.0);
    if (decile > this->LastDecile || elapsed - this->LastLine >= 10.0)
    {
      std::fprintf(
        stderr, "%s: %.0f%% (%.1f s%s)\n", this->What.c_str(), 100.0 * fraction, elapsed, eta);
      this->LastDecile = decile;
      this->LastLine = elapsed;
    }
  }

  static void OnProgress(vtkObject*, unsigned long, void* self, void* data)
  {
    auto* impl = static_cast<Internals*>(self);
    if (InterruptRequested && !impl->Interrupted)
    {
      impl->Interrupted = true;
      impl->Filter->SetAbortExecute(1);
    }
    if (!impl->Interrupted && ProgressShown) // the executive still reports 100% at the end
    {
      impl->Show(data ? *static_cast<double*>(data) : 0.0);
    }
  }
};

Progress::Progress(vtkAlgorithm* filter, const std::string& what)
  : Impl(new Internals)
{
  this->Impl->Filter = filter;
  this->Impl->What = what;
  this->Impl->Terminal = isatty(STDERR_FILENO) != 0;
  this->Impl->Observer->SetCallback(&Internals::OnProgress);
  this->Impl->Observer->SetClientData(this->Impl);
  this->Impl->Tag = filter->AddObserver(vtkCommand::ProgressEvent, this->Impl->Observer);
  InterruptRequested = false;
  this->Impl->PreviousHandler = std::signal(SIGINT, OnInterrupt);
}

Progress::~Progress()
{
  this->Impl->Filter->RemoveObserver(this->Impl->Tag);
  std::signal(SIGINT, this->Impl->PreviousHandler ? this->Impl->PreviousHandler : SIG_DFL);
  if (this->Impl->Drawn)
  {
    std::fputc('\n', stderr);
  }
  if (this->Interrupted())
  {
    std::fprintf(stderr, "%s: interrupted after %.1f s; nothing written\n",
      this->Impl->What.c_str(), this->Impl->Elapsed());
  }
  delete this->Impl;
}

void SetProgressShown(bool shown)
{
  ProgressShown = shown;
}

bool Progress::Interrupted() const
{
  return this->Impl->Interrupted || InterruptRequested;
}

bool HasExtension(const std::string& command, const std::string& option, const std::string& path,
  const std::vector<std::string>& extensions)
{
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const std::string& extension : extensions)
  {
    if (lower.size() > extension.size() &&
      lower.compare(lower.size() - extension.size(), extension.size(), extension) == 0)
    {
      return true;
    }
  }
  std::string list;
  for (std::size_t k = 0; k < extensions.size(); ++k)
  {
    list += (k == 0 ? "" : (k + 1 == extensions.size() ? " or " : ", ")) + extensions[k];
  }
  vtkLogF(ERROR, "proxygi %s: %s '%s' must end in %s", command.c_str(), option.c_str(),
    path.c_str(), list.c_str());
  return false;
}

bool WriteThenRename(const std::string& path, const std::function<bool(const std::string&)>& write)
{
  // The same extension, so writers that look at it pick the same format.
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  const bool hasDot = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string temporary = hasDot
    ? path.substr(0, dot) + ".partial-" + std::to_string(getpid()) + path.substr(dot)
    : path + ".partial-" + std::to_string(getpid());
  if (!write(temporary))
  {
    std::remove(temporary.c_str());
    return false;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    vtkLogF(ERROR, "proxygi: cannot rename '%s' to '%s'", temporary.c_str(), path.c_str());
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}
void SetupProgress::Begin(vtkAlgorithm* filter, const std::string& what)
{
  this->Current.reset(new Progress(filter, this->Command + ": " + what));
}

bool SetupProgress::End(vtkAlgorithm*)
{
  const bool stopped = this->Current && this->Current->Interrupted();
  this->Current.reset();
  this->Stopped = this->Stopped || stopped;
  return !stopped;
}

} // namespace cli
} // namespace proxygi
