// The tables' disk cache: CapTables and IndirectTables read from the cache
// equal those computed, bit for bit; a damaged file, a file of another
// length and a file whose samples a changed formula no longer gives are
// each recomputed and written again; with no directory nothing is written.
#include "pgiSHLightTables.h"
#include "pgiSHTableCache.h"
#include "pgiSHTables.h"
#include "pgiTesting.h"

#include "vtksys/Directory.hxx"
#include "vtksys/SystemTools.hxx"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using namespace proxygi;
using namespace proxygi::sh;

namespace
{
bool SameCaps(const CapTables& a, const CapTables& b)
{
  return a.GetLogTable() == b.GetLogTable() && a.GetVisibilityTable() == b.GetVisibilityTable() &&
    a.GetOptimalLinearA() == b.GetOptimalLinearA() &&
    a.GetOptimalLinearB() == b.GetOptimalLinearB() &&
    a.GetLogTableFloat() == b.GetLogTableFloat() && a.GetLogBandTable() == b.GetLogBandTable() &&
    a.GetOptimalLinearMaxNorm() == b.GetOptimalLinearMaxNorm() &&
    a.GetOptimalLinearScale() == b.GetOptimalLinearScale();
}

bool SameIndirect(const IndirectTables& a, const IndirectTables& b)
{
  return a.GetAveragedIndirectTable() == b.GetAveragedIndirectTable() &&
    a.GetSphericalLightWeightTable() == b.GetSphericalLightWeightTable() &&
    a.GetExactIndirectTable() == b.GetExactIndirectTable() &&
    a.GetFitCoefficients() == b.GetFitCoefficients() &&
    a.GetAveragedTableFloat() == b.GetAveragedTableFloat();
}

double Milliseconds(std::chrono::steady_clock::time_point from)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - from).count();
}

// The cache's files whose names start with `prefix`.
std::vector<std::string> CachedFiles(const std::string& directory, const std::string& prefix)
{
  std::vector<std::string> files;
  vtksys::Directory listing;
  if (listing.Load(directory))
  {
    for (unsigned long i = 0; i < listing.GetNumberOfFiles(); ++i)
    {
      const std::string name = listing.GetFile(i);
      if (name.rfind(prefix, 0) == 0)
      {
        std::string path = directory;
        path.append("/").append(name);
        files.push_back(path);
      }
    }
  }
  return files;
}

std::vector<char> ReadBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteBytes(const std::string& path, const std::vector<char>& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
} // namespace

int TestSHTableCache(int, char*[])
{
  const std::string directory =
    vtksys::SystemTools::GetCurrentWorkingDirectory() + "/TestSHTableCache-tables";
  vtksys::SystemTools::RemoveADirectory(directory);

  // No directory: computed, nothing written.
  SetTableCacheDirectory("");
  const CapTables computedCaps(5);
  const IndirectTables computedIndirect(5);
  PGI_CHECK(!vtksys::SystemTools::FileExists(directory));

  SetTableCacheDirectory(directory);
  auto start = std::chrono::steady_clock::now();
  const CapTables firstCaps(5); // computes and writes
  const double computeMs = Milliseconds(start);
  start = std::chrono::steady_clock::now();
  const CapTables readCaps(5); // reads
  const double readMs = Milliseconds(start);
  PGI_CHECK(SameCaps(computedCaps, firstCaps));
  PGI_CHECK(SameCaps(computedCaps, readCaps));
  start = std::chrono::steady_clock::now();
  const IndirectTables firstIndirect(5);
  const double indirectComputeMs = Milliseconds(start);
  start = std::chrono::steady_clock::now();
  const IndirectTables readIndirect(5);
  const double indirectReadMs = Milliseconds(start);
  PGI_CHECK(SameIndirect(computedIndirect, firstIndirect));
  PGI_CHECK(SameIndirect(computedIndirect, readIndirect));
  std::printf("order 5: cap tables computed %.2f ms, read %.2f ms; indirect tables computed "
              "%.2f ms, read %.2f ms\n",
    computeMs, readMs, indirectComputeMs, indirectReadMs);

  const std::vector<std::string> caps = CachedFiles(directory, "cap-logs-order5-");
  const std::vector<std::string> indirect = CachedFiles(directory, "indirect-order5-");
  PGI_CHECK(caps.size() == 1 && indirect.size() == 1);
  if (caps.size() != 1 || indirect.size() != 1)
  {
    return pgitest::Result();
  }
  const std::vector<char> good = ReadBytes(caps[0]);
  PGI_CHECK(good.size() > 1000);

  // A damaged file (one byte of a sample flipped): its checksum fails.
  std::vector<char> damaged = good;
  damaged[good.size() / 2] ^= 0x5a;
  WriteBytes(caps[0], damaged);
  PGI_CHECK(SameCaps(computedCaps, CapTables(5)));
  PGI_CHECK(ReadBytes(caps[0]) == good); // written again

  // Another length (a cut file).
  WriteBytes(caps[0], std::vector<char>(good.begin(), good.begin() + good.size() / 3));
  PGI_CHECK(SameCaps(computedCaps, CapTables(5)));
  PGI_CHECK(ReadBytes(caps[0]) == good);

  // A whole, well-formed file whose samples another formula gave: the
  // samples computed afresh disagree.
  {
    const std::string name = caps[0].substr(directory.size() + 1);
    std::vector<double> values((256 + 4 * 256) * 5);
    PGI_CHECK(ReadCachedTable(name, values.size(), values));
    for (double& v : values)
    {
      v *= 1.0 + 1e-12;
    }
    PGI_CHECK(WriteCachedTable(name, values));
    PGI_CHECK(ReadBytes(caps[0]) != good);
    PGI_CHECK(SameCaps(computedCaps, CapTables(5)));
    PGI_CHECK(ReadBytes(caps[0]) == good);
  }
  // The same for the bounce's tables.
  {
    const std::vector<char> goodIndirect = ReadBytes(indirect[0]);
    std::vector<char> damagedIndirect = goodIndirect;
    damagedIndirect[goodIndirect.size() - 20] ^= 0x01;
    WriteBytes(indirect[0], damagedIndirect);
    PGI_CHECK(SameIndirect(computedIndirect, IndirectTables(5)));
    PGI_CHECK(ReadBytes(indirect[0]) == goodIndirect);
  }
  // Off again: nothing read, nothing written.
  SetTableCacheDirectory("");
  vtksys::SystemTools::RemoveADirectory(directory);
  PGI_CHECK(SameCaps(computedCaps, CapTables(5)));
  PGI_CHECK(!vtksys::SystemTools::FileExists(directory));
  return pgitest::Result();
}
