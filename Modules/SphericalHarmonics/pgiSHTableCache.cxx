#include "pgiSHTableCache.h"

#include "vtkSMPTools.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <thread>

namespace proxygi
{
namespace sh
{
namespace
{
std::mutex& DirectoryLock()
{
  static std::mutex lock;
  return lock;
}

std::string& Directory()
{
  static std::string directory;
  return directory;
}

bool& DirectorySet()
{
  static bool set = false;
  return set;
}

constexpr char Magic[8] = { 'P', 'G', 'I', 'T', 'A', 'B', '1', '\n' };

// FNV-1a over the values' bytes.
std::uint64_t Checksum(const std::vector<double>& values)
{
  std::uint64_t h = 1469598103934665603ULL;
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  for (std::size_t i = 0; i < values.size() * sizeof(double); ++i)
  {
    h = (h ^ bytes[i]) * 1099511628211ULL;
  }
  return h;
}
} // namespace

void SetTableCacheDirectory(const std::string& directory)
{
  std::lock_guard<std::mutex> guard(DirectoryLock());
  Directory() = directory;
  DirectorySet() = true;
}

std::string GetTableCacheDirectory()
{
  std::lock_guard<std::mutex> guard(DirectoryLock());
  if (DirectorySet())
  {
    return Directory();
  }
  const char* environment = std::getenv("PROXYGI_TABLE_CACHE");
  return environment ? environment : "";
}

bool ReadCachedTable(const std::string& name, std::size_t count, std::vector<double>& values)
{
  const std::string directory = GetTableCacheDirectory();
  if (directory.empty())
  {
    return false;
  }
  std::ifstream in(directory + "/" + name, std::ios::binary);
  char magic[8];
  std::uint64_t stored = 0, sum = 0;
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, Magic, sizeof(Magic)) != 0 ||
    !in.read(reinterpret_cast<char*>(&stored), sizeof(stored)) || stored != count)
  {
    return false;
  }
  std::vector<double> read(count);
  if (!in.read(reinterpret_cast<char*>(read.data()),
        static_cast<std::streamsize>(count * sizeof(double))) ||
    !in.read(reinterpret_cast<char*>(&sum), sizeof(sum)) || sum != Checksum(read))
  {
    return false;
  }
  values.swap(read);
  return true;
}

bool WriteCachedTable(const std::string& name, const std::vector<double>& values)
{
  const std::string directory = GetTableCacheDirectory();
  if (directory.empty() || !vtksys::SystemTools::MakeDirectory(directory))
  {
    return false;
  }
  // A name of its own per writer: processes and threads may write at once.
  static std::atomic<unsigned> writes{ 0 };
  std::ostringstream temporary;
  temporary << directory << "/." << name << "."
            << std::hash<std::thread::id>()(std::this_thread::get_id()) << "." << writes++
            << ".tmp";
  {
    std::ofstream out(temporary.str(), std::ios::binary | std::ios::trunc);
    const std::uint64_t count = values.size(), sum = Checksum(values);
    out.write(Magic, sizeof(Magic));
    out.write(reinterpret_cast<const char*>(&count), sizeof(count));
    out.write(reinterpret_cast<const char*>(values.data()),
      static_cast<std::streamsize>(values.size() * sizeof(double)));
    out.write(reinterpret_cast<const char*>(&sum), sizeof(sum));
    if (!out)
    {
      out.close();
      vtksys::SystemTools::RemoveFile(temporary.str());
      return false;
    }
  }
  if (std::rename(temporary.str().c_str(), (directory + "/" + name).c_str()) != 0)
  {
    vtksys::SystemTools::RemoveFile(temporary.str());
    return false;
  }
  return true;
}

bool ReadCachedSamples(const std::string& name, int width, std::vector<double>& values,
  const std::function<void(int, double*)>& compute)
{
  const int samples = width > 0 ? static_cast<int>(values.size() / width) : 0;
  std::vector<double> read;
  if (samples < 2 || !ReadCachedTable(name, values.size(), read))
  {
    return false;
  }
  std::vector<double> fresh(width);
  for (int s : { 1, samples / 2, samples - 1 })
  {
    std::fill(fresh.begin(), fresh.end(), std::numeric_limits<double>::quiet_NaN());
    compute(s, fresh.data());
    if (std::memcmp(
          fresh.data(), &read[static_cast<std::size_t>(s) * width], width * sizeof(double)) != 0)
    {
      return false;
    }
  }
  values.swap(read);
  return true;
}

bool CachedSamples(const std::string& name, int width, std::vector<double>& values,
  const std::function<void(int, double*)>& compute)
{
  if (ReadCachedSamples(name, width, values, compute))
  {
    return true;
  }
  const int samples = width > 0 ? static_cast<int>(values.size() / width) : 0;
  vtkSMPTools::For(0, samples,
    [&](int first, int last)
    {
      for (int s = first; s < last; ++s)
      {
        compute(s, &values[static_cast<std::size_t>(s) * width]);
      }
    });
  WriteCachedTable(name, values);
  return false;
}

} // namespace sh
} // namespace proxygi
