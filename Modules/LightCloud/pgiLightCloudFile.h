/**
 * @file pgiLightCloudFile.h
 * @brief The light cloud on disk: a header (sizes, the cloud lights'
 * positions, the key of what it was computed from) and one record per cloud
 * light (its response), each with its own checksum.
 *
 * Records are appended as the precompute finishes lights, so a run that is
 * stopped (abort, crash, power) leaves a file that a later run resumes: the
 * reader keeps every whole record and reports a torn last one. Anything
 * else that does not add up (magic, version, header checksum, a record's
 * checksum or index, a non-finite position) is an error naming it. Native
 * byte order (little-endian on the machines we build for).
 *
 * A compressed cloud (zones, cluster lights, CPCA codes) has a file of its
 * own kind (another magic): a header, the dense cloud's light positions,
 * then one block per zone, each with its checksum. WriteLightCloud picks
 * the kind from the cloud; ReadLightCloud reads either, and checks that
 * every index in a compressed cloud lies inside its arrays.
 */
#ifndef pgiLightCloudFile_h
#define pgiLightCloudFile_h

#include "ProxyGILightCloudModule.h"

#include "vtkType.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkPGILightCloud;

namespace proxygi
{
/// Starts a cloud file (truncating one there): the header only.
PROXYGILIGHTCLOUD_EXPORT bool WriteLightCloudHeader(
  const std::string& path, vtkPGILightCloud* cloud, std::uint64_t key, std::string& error);
/// Appends the responses of `lights` (indices into the cloud) as records.
PROXYGILIGHTCLOUD_EXPORT bool AppendLightCloudRecords(const std::string& path,
  vtkPGILightCloud* cloud, const std::vector<vtkIdType>& lights, std::string& error);
/// The whole cloud: header and every light's record (dense), or the
/// compressed file.
PROXYGILIGHTCLOUD_EXPORT bool WriteLightCloud(
  const std::string& path, vtkPGILightCloud* cloud, std::uint64_t key, std::string& error);

struct LightCloudFileInfo
{
  std::uint64_t Key = 0;
  /// Present[j]: light j's record was read.
  std::vector<char> Present;
  vtkIdType LightsRead = 0;
  /// The file ends inside a record (a run stopped while writing it).
  bool TornTail = false;
};

/**
 * Reads a cloud file into `cloud` (sized from the header; lights without a
 * record keep zero responses, info.Present says which). False with a
 * message for a missing, foreign or corrupted file.
 */
PROXYGILIGHTCLOUD_EXPORT bool ReadLightCloud(
  const std::string& path, vtkPGILightCloud* cloud, LightCloudFileInfo& info, std::string& error);
} // namespace proxygi

#endif
