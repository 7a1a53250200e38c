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
  Header header;
  std::memcpy(header.Magic, Magic, sizeof(Magic));
  header.Version = Version;
  header.Contents = static_cast<std::uint32_t>(cloud->GetContents());
  header.Samples = cloud->GetSamples();
  header.Coefficients = static_cast<std::uint32_t>(cloud->GetCoefficients());
  header.Key = key;
  header.ReceiverKey = cloud->GetReceiverKey();
  header.Receivers = static_cast<std::uint64_t>(cloud->GetNumberOfReceivers());
  header.Lights = static_cast<std::uint64_t>(cloud->GetNumberOfLights());
  std::vector<double> positions(3 * header.Lights);
  for (vtkIdType j = 0; j < cloud->GetNumberOfLights(); ++j)
  {
    cloud->GetLightPositions()->GetPoint(j, &positions[3 * j]);
  }
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

bool WriteLightCloud(
  const std::string& path, vtkPGILightCloud* cloud, std::uint64_t key, std::string& error)
{
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
  if (std::memcmp(header.Magic, Magic, sizeof(Magic)) != 0)
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
  // The sizes are trusted only once the header's checksum holds, and the
  // positions must fit in the file before they are read.
  const std::uint64_t rest = fileSize - sizeof(Header);
  if (header.Lights > rest / 24)
  {
    error = where + "corrupted header (more lights than the file holds)";
    return false;
  }
  std::vector<double> positions(3 * header.Lights);
  std::uint64_t stored = 0;
  in.read(reinterpret_cast<char*>(positions.data()),
    static_cast<std::streamsize>(positions.size() * sizeof(double)));
  in.read(reinterpret_cast<char*>(&stored), sizeof(stored));
  Hash h;
  h.Add(&header, sizeof(header));
  h.Add(positions.data(), positions.size() * sizeof(double));
  if (!in || stored != h.Value)
  {
    error = where + "corrupted header (checksum mismatch)";
    return false;
  }
  const std::uint64_t coefficients = std::max<std::uint32_t>(1, header.Coefficients);
  const std::uint64_t order = static_cast<std::uint64_t>(std::lround(std::sqrt(coefficients)));
  if (header.Contents > 1 || header.Receivers > (1ull << 32) || order * order != coefficients ||
    order > 8 || header.Lights * header.Receivers * coefficients > (1ull << 32))
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
