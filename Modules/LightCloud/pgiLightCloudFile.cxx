#include "pgiLightCloudFile.h"

#include "vtkPGILightCloud.h"
#include "vtkPoints.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

namespace proxygi
{
namespace
{
const char Magic[8] = { 'P', 'G', 'I', 'C', 'L', 'O', 'U', 'D' };
const char CompressedMagic[8] = { 'P', 'G', 'I', 'C', 'L', 'C', 'M', 'P' };
const std::uint32_t Version = 1;

struct Hash
{
  std::uint64_t Value = 1469598103934665603ull; // FNV-1a
  void Add(const void* data, std::size_t bytes)
  {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
    {
      this->Value = (this->Value ^ b[i]) * 1099511628211ull;
    }
  }
};

#pragma pack(push, 1)
struct Header
{
  char Magic[8];
  std::uint32_t Version;
  std::uint32_t Contents;
  std::int32_t Samples;
  std::uint32_t Coefficients; // 0 in files from before glossy clouds: 1
  std::uint64_t Key;
  std::uint64_t ReceiverKey;
  std::uint64_t Receivers;
  std::uint64_t Lights;
};
#pragma pack(pop)

bool WriteRecord(std::ofstream& out, vtkPGILightCloud* cloud, vtkIdType light)
{
  const std::uint64_t index = static_cast<std::uint64_t>(light);
  const std::size_t bytes =
    static_cast<std::size_t>(cloud->GetValuesPerReceiver() * cloud->GetNumberOfReceivers()) * 4;
  Hash h;
  h.Add(&index, sizeof(index));
  h.Add(cloud->GetResponse(light), bytes);
  out.write(reinterpret_cast<const char*>(&index), sizeof(index));
  out.write(
    reinterpret_cast<const char*>(cloud->GetResponse(light)), static_cast<std::streamsize>(bytes));
  out.write(reinterpret_cast<const char*>(&h.Value), sizeof(h.Value));
  return static_cast<bool>(out);
}

// Both kinds' header and the cloud lights' positions (the dense cloud's).
Header HeaderOf(
  const char magic[8], vtkPGILightCloud* cloud, std::uint64_t key, std::vector<double>& positions)
{
  Header header;
  std::memcpy(header.Magic, magic, sizeof(header.Magic));
  header.Version = Version;
  header.Contents = static_cast<std::uint32_t>(cloud->GetContents());
  header.Samples = cloud->GetSamples();
  header.Coefficients = static_cast<std::uint32_t>(cloud->GetCoefficients());
  header.Key = key;
  header.ReceiverKey = cloud->GetReceiverKey();
  header.Receivers = static_cast<std::uint64_t>(cloud->GetNumberOfReceivers());
  header.Lights = static_cast<std::uint64_t>(cloud->GetNumberOfLights());
  positions.resize(3 * header.Lights);
  for (vtkIdType j = 0; j < cloud->GetNumberOfLights(); ++j)
  {
    cloud->GetLightPositions()->GetPoint(j, &positions[3 * j]);
  }
  return header;
}
} // namespace

bool WriteLightCloudHeader(
  const std::string& path, vtkPGILightCloud* cloud, std::uint64_t key, std::string& error)
{
  if (cloud->IsCompressed())
  {
    error = "a compressed light cloud is not written as a dense cloud file ('" + path + "')";
    return false;
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
  {
    error = "cannot write the light cloud file '" + path + "'";
    return false;
  }
  std::vector<double> positions;
  const Header header = HeaderOf(Magic, cloud, key, positions);
  Hash h;
  h.Add(&header, sizeof(header));
  h.Add(positions.data(), positions.size() * sizeof(double));
  out.write(reinterpret_cast<const char*>(&header), sizeof(header));
  out.write(reinterpret_cast<const char*>(positions.data()),
    static_cast<std::streamsize>(positions.size() * sizeof(double)));
  out.write(reinterpret_cast<const char*>(&h.Value), sizeof(h.Value));
  if (!out)
  {
    error = "writing the light cloud file '" + path + "' failed";
    return false;
  }
  return true;
}

bool AppendLightCloudRecords(const std::string& path, vtkPGILightCloud* cloud,
  const std::vector<vtkIdType>& lights, std::string& error)
{
  std::ofstream out(path, std::ios::binary | std::ios::app);
  bool ok = static_cast<bool>(out);
  for (std::size_t k = 0; ok && k < lights.size(); ++k)
  {
    ok = WriteRecord(out, cloud, lights[k]);
  }
  out.flush();
  if (!ok || !out)
  {
    error = "appending to the light cloud file '" + path + "' failed";
    return false;
  }
  return true;
}

namespace
{
// The compressed file's arrays: a count, then the values.
template <typename T>
void PutArray(std::string& bytes, const std::vector<T>& v)
{
  const std::uint64_t count = v.size();
  bytes.append(reinterpret_cast<const char*>(&count), sizeof(count));
  bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

struct BlockReader
{
  const std::string& Bytes;
  std::size_t At = 0;
  bool Ok = true;
  template <typename T>
  void Get(std::vector<T>& v)
  {
    std::uint64_t count = 0;
    if (!this->Ok || this->Bytes.size() - this->At < sizeof(count))
    {
      this->Ok = false;
      return;
    }
    std::memcpy(&count, this->Bytes.data() + this->At, sizeof(count));
    this->At += sizeof(count);
    if (count > (this->Bytes.size() - this->At) / sizeof(T))
    {
      this->Ok = false;
      return;
    }
    v.resize(static_cast<std::size_t>(count));
    if (!v.empty())
    {
      std::memcpy(v.data(), this->Bytes.data() + this->At, v.size() * sizeof(T));
    }
    this->At += v.size() * sizeof(T);
  }
};

std::string ZoneBytes(const vtkPGILightCloud::Zone& z)
{
  std::string bytes;
  const std::vector<std::int64_t> receivers(z.Receivers.begin(), z.Receivers.end());
  PutArray(bytes, receivers);
  PutArray(bytes, z.Lights);
  PutArray(bytes, z.LightMembers);
  PutArray(bytes, std::vector<std::int32_t>{ z.Dimension });
  PutArray(bytes, z.Cluster);
  PutArray(bytes, z.Means);
  PutArray(bytes, z.BasisStart);
  PutArray(bytes, z.BasisCount);
  PutArray(bytes, z.Basis);
  PutArray(bytes, z.WeightStart);
  PutArray(bytes, z.Weights);
  return bytes;
}

// Every index of a zone inside its arrays (a file can pass its checksums
// and still not add up).
bool ZoneConsistent(const vtkPGILightCloud::Zone& z, vtkIdType receivers, int values)
{
  const std::size_t r = z.Receivers.size(), clusters = z.BasisCount.size();
  const std::size_t lights = z.Lights.size() / 3;
  if (z.Lights.size() % 3 || z.Dimension != static_cast<int>(values * lights) ||
    z.Cluster.size() != r || z.WeightStart.size() != r || z.BasisStart.size() != clusters ||
    z.Means.size() != clusters * static_cast<std::size_t>(z.Dimension) ||
    (z.Dimension > 0 && z.Basis.size() % static_cast<std::size_t>(z.Dimension)))
  {
    return false;
  }
  const std::size_t vectors = z.Dimension > 0 ? z.Basis.size() / z.Dimension : 0;
  for (std::size_t q = 0; q < clusters; ++q)
  {
    if (z.BasisStart[q] < 0 || z.BasisCount[q] < 0 ||
      static_cast<std::size_t>(z.BasisStart[q]) + z.BasisCount[q] > vectors)
    {
      return false;
    }
  }
  for (std::size_t k = 0; k < r; ++k)
  {
    if (z.Receivers[k] < 0 || z.Receivers[k] >= receivers || z.Cluster[k] < 0 ||
      static_cast<std::size_t>(z.Cluster[k]) >= clusters || z.WeightStart[k] < 0 ||
      static_cast<std::size_t>(z.WeightStart[k]) + z.BasisCount[z.Cluster[k]] > z.Weights.size())
    {
      return false;
    }
  }
  for (double p : z.Lights)
  {
    if (!std::isfinite(p))
    {
      return false;
    }
  }
  return true;
}

bool WriteCompressedLightCloud(
  const std::string& path, vtkPGILightCloud* cloud, std::uint64_t key, std::string& error)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
  {
    error = "cannot write the light cloud file '" + path + "'";
    return false;
  }
  std::vector<double> positions;
  const Header header = HeaderOf(CompressedMagic, cloud, key, positions);
  const std::uint64_t zones = cloud->GetZones().size();
  Hash h;
  h.Add(&header, sizeof(header));
  h.Add(positions.data(), positions.size() * sizeof(double));
  h.Add(&zones, sizeof(zones));
  out.write(reinterpret_cast<const char*>(&header), sizeof(header));
  out.write(reinterpret_cast<const char*>(positions.data()),
    static_cast<std::streamsize>(positions.size() * sizeof(double)));
  out.write(reinterpret_cast<const char*>(&zones), sizeof(zones));
  out.write(reinterpret_cast<const char*>(&h.Value), sizeof(h.Value));
  for (const vtkPGILightCloud::Zone& zone : cloud->GetZones())
  {
    const std::string bytes = ZoneBytes(zone);
    const std::uint64_t size = bytes.size();
    Hash z;
    z.Add(&size, sizeof(size));
    z.Add(bytes.data(), bytes.size());
    out.write(reinterpret_cast<const char*>(&size), sizeof(size));
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.write(reinterpret_cast<const char*>(&z.Value), sizeof(z.Value));
  }
  out.flush();
  if (!out)
  {
    error = "writing the light cloud file '" + path + "' failed";
    return false;
  }
  return true;
}

// After the header: the positions (and, compressed, the zone count), the
// header's checksum, the sizes both kinds share, finite positions.
bool ReadHeaderRest(std::ifstream& in, std::uint64_t fileSize, const Header& header,
  const std::string& where, std::uint64_t* zones, std::vector<double>& positions,
  std::string& error)
{
  // The sizes are trusted only once the header's checksum holds, and the
  // positions must fit in the file before they are read.
  const std::uint64_t rest = fileSize - sizeof(Header);
  if (header.Lights > rest / 24)
  {
    error = where + "corrupted header (more lights than the file holds)";
    return false;
  }
  positions.resize(3 * header.Lights);
  std::uint64_t stored = 0;
  in.read(reinterpret_cast<char*>(positions.data()),
    static_cast<std::streamsize>(positions.size() * sizeof(double)));
  if (zones)
  {
    in.read(reinterpret_cast<char*>(zones), sizeof(*zones));
  }
  in.read(reinterpret_cast<char*>(&stored), sizeof(stored));
  Hash h;
  h.Add(&header, sizeof(header));
  h.Add(positions.data(), positions.size() * sizeof(double));
  if (zones)
  {
    h.Add(zones, sizeof(*zones));
  }
  if (!in || stored != h.Value)
  {
    error = where + "corrupted header (checksum mismatch)";
    return false;
  }
  const std::uint64_t coefficients = std::max<std::uint32_t>(1, header.Coefficients);
  const std::uint64_t order = static_cast<std::uint64_t>(std::lround(std::sqrt(coefficients)));
  if (header.Contents > 1 || header.Receivers > (1ull << 32) || order * order != coefficients ||
    order > 8)
  {
    error = where + "header sizes out of range";
    return false;
  }
  for (double p : positions)
  {
    if (!std::isfinite(p))
    {
      error = where + "a cloud light position is NaN or infinite";
      return false;
    }
  }
  return true;
}

bool ReadCompressedLightCloud(std::ifstream& in, std::uint64_t fileSize, const Header& header,
  const std::string& where, vtkPGILightCloud* cloud, LightCloudFileInfo& info, std::string& error)
{
  std::vector<double> positions;
  std::uint64_t zones = 0;
  if (!ReadHeaderRest(in, fileSize, header, where, &zones, positions, error))
  {
    return false;
  }
  const std::uint64_t coefficients = std::max<std::uint32_t>(1, header.Coefficients);
  if (zones > header.Receivers || zones > (1ull << 20))
  {
    error = where + "header sizes out of range";
    return false;
  }
  std::vector<vtkPGILightCloud::Zone> read(static_cast<std::size_t>(zones));
  const int values = static_cast<int>(3 * coefficients);
  for (std::uint64_t z = 0; z < zones; ++z)
  {
    const std::uint64_t offset = static_cast<std::uint64_t>(in.tellg());
    std::uint64_t size = 0, check = 0;
    if (!in.read(reinterpret_cast<char*>(&size), sizeof(size)) ||
      size > fileSize - std::min(fileSize, offset + 16))
    {
      error =
        where + "zone " + std::to_string(z) + " is cut short (byte " + std::to_string(offset) + ")";
      return false;
    }
    std::string bytes(static_cast<std::size_t>(size), '\0');
    in.read(&bytes[0], static_cast<std::streamsize>(size));
    in.read(reinterpret_cast<char*>(&check), sizeof(check));
    Hash r;
    r.Add(&size, sizeof(size));
    r.Add(bytes.data(), bytes.size());
    if (!in || check != r.Value)
    {
      error = where + "corrupted zone " + std::to_string(z) + " at byte " + std::to_string(offset);
      return false;
    }
    BlockReader b{ bytes };
    vtkPGILightCloud::Zone& zone = read[z];
    std::vector<std::int64_t> receivers;
    std::vector<std::int32_t> dimension;
    b.Get(receivers);
    b.Get(zone.Lights);
    b.Get(zone.LightMembers);
    b.Get(dimension);
    b.Get(zone.Cluster);
    b.Get(zone.Means);
    b.Get(zone.BasisStart);
    b.Get(zone.BasisCount);
    b.Get(zone.Basis);
    b.Get(zone.WeightStart);
    b.Get(zone.Weights);
    zone.Receivers.assign(receivers.begin(), receivers.end());
    zone.Dimension = dimension.size() == 1 ? dimension[0] : -1;
    if (!b.Ok || b.At != bytes.size() ||
      !ZoneConsistent(zone, static_cast<vtkIdType>(header.Receivers), values))
    {
      error = where + "zone " + std::to_string(z) + " does not add up (indices out of range)";
      return false;
    }
  }
  const vtkIdType lights = static_cast<vtkIdType>(header.Lights);
  cloud->Allocate(0, static_cast<vtkIdType>(header.Receivers), static_cast<int>(coefficients));
  cloud->GetLightPositions()->SetNumberOfPoints(lights);
  for (vtkIdType j = 0; j < lights; ++j)
  {
    cloud->GetLightPositions()->SetPoint(j, &positions[3 * j]);
  }
  cloud->SetContents(static_cast<int>(header.Contents));
  cloud->SetSamples(header.Samples);
  cloud->SetReceiverKey(header.ReceiverKey);
  cloud->SetZones(std::move(read));
  info.Key = header.Key;
  info.Present.assign(static_cast<std::size_t>(lights), 1);
  info.LightsRead = lights;
  return true;
}
} // namespace

bool WriteLightCloud(
  const std::string& path, vtkPGILightCloud* cloud, std::uint64_t key, std::string& error)
{
  if (cloud->IsCompressed())
  {
    return WriteCompressedLightCloud(path, cloud, key, error);
  }
  std::vector<vtkIdType> all(static_cast<std::size_t>(cloud->GetNumberOfLights()));
  for (std::size_t j = 0; j < all.size(); ++j)
  {
    all[j] = static_cast<vtkIdType>(j);
  }
  return WriteLightCloudHeader(path, cloud, key, error) &&
    AppendLightCloudRecords(path, cloud, all, error);
}

bool ReadLightCloud(
  const std::string& path, vtkPGILightCloud* cloud, LightCloudFileInfo& info, std::string& error)
{
  info = LightCloudFileInfo();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
  {
    error = "cannot open the light cloud file '" + path + "'";
    return false;
  }
  const std::uint64_t fileSize = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  const std::string where = "light cloud file '" + path + "': ";
  Header header;
  if (fileSize < sizeof(Header) || !in.read(reinterpret_cast<char*>(&header), sizeof(header)))
  {
    error = where + "too short for a header";
    return false;
  }
  const bool compressed = std::memcmp(header.Magic, CompressedMagic, sizeof(Magic)) == 0;
  if (!compressed && std::memcmp(header.Magic, Magic, sizeof(Magic)) != 0)
  {
    error = where + "not a ProxyGI light cloud (bad magic)";
    return false;
  }
  if (header.Version != Version)
  {
    error = where + "version " + std::to_string(header.Version) + ", this build reads " +
      std::to_string(Version);
    return false;
  }
  if (compressed)
  {
    return ReadCompressedLightCloud(in, fileSize, header, where, cloud, info, error);
  }
  std::vector<double> positions;
  if (!ReadHeaderRest(in, fileSize, header, where, nullptr, positions, error))
  {
    return false;
  }
  const std::uint64_t coefficients = std::max<std::uint32_t>(1, header.Coefficients);
  if (header.Lights * header.Receivers * coefficients > (1ull << 32))
  {
    error = where + "header sizes out of range";
    return false;
  }
  const vtkIdType lights = static_cast<vtkIdType>(header.Lights);
  cloud->Allocate(lights, static_cast<vtkIdType>(header.Receivers), static_cast<int>(coefficients));
  for (vtkIdType j = 0; j < lights; ++j)
  {
    cloud->GetLightPositions()->SetPoint(j, &positions[3 * j]);
  }
  cloud->SetContents(static_cast<int>(header.Contents));
  cloud->SetSamples(header.Samples);
  cloud->SetReceiverKey(header.ReceiverKey);
  info.Key = header.Key;
  info.Present.assign(static_cast<std::size_t>(lights), 0);

  const std::uint64_t dataBytes = 12 * coefficients * header.Receivers;
  const std::uint64_t recordBytes = 16 + dataBytes;
  std::uint64_t offset = sizeof(Header) + positions.size() * sizeof(double) + 8;
  std::vector<float> data(static_cast<std::size_t>(3 * coefficients * header.Receivers));
  while (offset < fileSize)
  {
    if (fileSize - offset < recordBytes)
    {
      info.TornTail = true;
      break;
    }
    std::uint64_t index = 0, check = 0;
    in.read(reinterpret_cast<char*>(&index), sizeof(index));
    in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(dataBytes));
    in.read(reinterpret_cast<char*>(&check), sizeof(check));
    Hash r;
    r.Add(&index, sizeof(index));
    r.Add(data.data(), dataBytes);
    if (!in || check != r.Value || index >= header.Lights)
    {
      error = where + "corrupted record at byte " + std::to_string(offset);
      return false;
    }
    std::memcpy(cloud->GetResponse(static_cast<vtkIdType>(index)), data.data(), dataBytes);
    if (!info.Present[index])
    {
      info.Present[index] = 1;
      ++info.LightsRead;
    }
    offset += recordBytes;
  }
  return true;
}
} // namespace proxygi
