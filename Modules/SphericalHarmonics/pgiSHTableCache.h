/**
 * @file pgiSHTableCache.h
 * @brief An optional disk cache of the per-process tables' expensive
 * samples (CapTables' cap logs, IndirectTables' bounce integrals), so that
 * a process's first update reads them instead of computing them.
 *
 * Off unless a directory is given (SetTableCacheDirectory, or the
 * environment variable PROXYGI_TABLE_CACHE). A table reads its samples
 * from the cache only where a few of them computed afresh equal the
 * cached ones bit for bit (a changed formula or a damaged file is
 * recomputed and written again), so cached and computed tables are the
 * same floats.
 */
#ifndef pgiSHTableCache_h
#define pgiSHTableCache_h

#include "ProxyGISphericalHarmonicsModule.h"

#include <functional>
#include <string>
#include <vector>

namespace proxygi
{
namespace sh
{
/// The directory the tables are cached in ("" switches the cache off; it
/// is made when first written). Thread-safe.
PROXYGISPHERICALHARMONICS_EXPORT void SetTableCacheDirectory(const std::string& directory);
/// The directory set, else PROXYGI_TABLE_CACHE, else "".
PROXYGISPHERICALHARMONICS_EXPORT std::string GetTableCacheDirectory();

/// Reads `count` doubles cached under `name` (a file name, no directory).
/// False (values untouched) when the cache is off, the file is missing,
/// of another size, or its checksum does not match.
PROXYGISPHERICALHARMONICS_EXPORT bool ReadCachedTable(
  const std::string& name, std::size_t count, std::vector<double>& values);
/// Writes `values` under `name` (a temporary file renamed into place, so a
/// concurrent reader sees a whole file or none). False when the cache is
/// off or the file cannot be written.
PROXYGISPHERICALHARMONICS_EXPORT bool WriteCachedTable(
  const std::string& name, const std::vector<double>& values);

/**
 * A table of samples, `width` doubles each (values.size() / width of
 * them), cached under `name`: read, then samples 1, the middle and the
 * last computed afresh by compute(sample, out) and compared with the read
 * ones bit for bit. True (values replaced) only when all agree.
 */
PROXYGISPHERICALHARMONICS_EXPORT bool ReadCachedSamples(const std::string& name, int width,
  std::vector<double>& values, const std::function<void(int, double*)>& compute);

/// A table's samples: read (ReadCachedSamples) where the cache holds them,
/// else computed by compute(sample, out) for every sample, in parallel,
/// and written to the cache. True when they were read.
PROXYGISPHERICALHARMONICS_EXPORT bool CachedSamples(const std::string& name, int width,
  std::vector<double>& values, const std::function<void(int, double*)>& compute);
} // namespace sh
} // namespace proxygi

#endif
