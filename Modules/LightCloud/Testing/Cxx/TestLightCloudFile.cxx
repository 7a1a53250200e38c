// The light cloud file: a round trip is exact; a torn last record (a
// stopped run) keeps the whole records before it; a flipped byte in the
// header or in a record, a foreign file and an unfinished cloud are errors
// naming the problem.
#include "pgiLightCloudFile.h"
#include "pgiTesting.h"
#include "pgiTestingErrors.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudReader.h"

#include "vtkNew.h"
#include "vtkPoints.h"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace
{
std::vector<char> ReadBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}
void WriteBytes(const std::string& path, const std::vector<char>& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
bool ReadFails(const std::string& path, const std::string& text)
{
  vtkNew<vtkPGILightCloud> cloud;
  proxygi::LightCloudFileInfo info;
  std::string error;
  const bool ok = proxygi::ReadLightCloud(path, cloud, info, error);
  if (ok || error.find(text) == std::string::npos)
  {
    std::printf(
      "expected an error with \"%s\", got ok=%d \"%s\"\n", text.c_str(), ok, error.c_str());
    return false;
  }
  return true;
}
} // namespace

int TestLightCloudFile(int argc, char* argv[])
{
  const std::string dir = pgitest::TempDirectory(argc, argv);
  const std::string path = dir + "/TestLightCloudFile.cloud";
  const vtkIdType lights = 5, receivers = 7;
  vtkNew<vtkPGILightCloud> cloud;
  cloud->Allocate(lights, receivers);
  for (vtkIdType j = 0; j < lights; ++j)
  {
    cloud->GetLightPositions()->SetPoint(j, 0.5 * j, -0.25 * j, 1.0 + j);
    for (vtkIdType k = 0; k < 3 * receivers; ++k)
    {
      cloud->GetResponse(j)[k] = 0.001f * static_cast<float>((j + 1) * (k + 3));
    }
  }
  cloud->SetContents(vtkPGILightCloud::DirectAndIndirect);
  cloud->SetSamples(17);
  cloud->SetReceiverKey(0x1234567890abcdefull);
  std::string error;
  PGI_CHECK(proxygi::WriteLightCloud(path, cloud, 42, error));

  // Round trip.
  vtkNew<vtkPGILightCloud> back;
  proxygi::LightCloudFileInfo info;
  PGI_CHECK(proxygi::ReadLightCloud(path, back, info, error));
  PGI_CHECK(info.Key == 42 && info.LightsRead == lights && !info.TornTail);
  PGI_CHECK(back->GetNumberOfLights() == lights && back->GetNumberOfReceivers() == receivers);
  PGI_CHECK(back->GetContents() == vtkPGILightCloud::DirectAndIndirect);
  PGI_CHECK(back->GetSamples() == 17 && back->GetReceiverKey() == 0x1234567890abcdefull);
  double worst = 0.0;
  for (vtkIdType j = 0; j < lights; ++j)
  {
    double p[3], q[3];
    cloud->GetLightPositions()->GetPoint(j, p);
    back->GetLightPositions()->GetPoint(j, q);
    for (int a = 0; a < 3; ++a)
    {
      worst = std::max(worst, std::fabs(p[a] - q[a]));
    }
    for (vtkIdType k = 0; k < 3 * receivers; ++k)
    {
      worst = std::max(
        worst, static_cast<double>(std::fabs(cloud->GetResponse(j)[k] - back->GetResponse(j)[k])));
    }
  }
  PGI_NEAR(worst, 0.0, 0.0);
  PGI_CHECK(back->GetCoefficientsPerReceiver() == 3 * lights);
  PGI_NEAR(back->GetSpacing(), std::sqrt(0.25 + 0.0625 + 1.0), 1e-12);

  // The reader in a pipeline.
  vtkNew<vtkPGILightCloudReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  PGI_CHECK(reader->GetOutput()->GetNumberOfLights() == lights);

  const std::vector<char> bytes = ReadBytes(path);
  const std::size_t record = 16 + 12 * receivers;
  const std::size_t header = bytes.size() - lights * record;

  // Torn: three whole records and part of the fourth.
  std::vector<char> torn(bytes.begin(), bytes.begin() + header + 3 * record + record / 2);
  WriteBytes(path, torn);
  PGI_CHECK(proxygi::ReadLightCloud(path, back, info, error));
  PGI_CHECK(info.TornTail && info.LightsRead == 3 && info.Present[2] && !info.Present[3]);
  PGI_CHECK(pgitest::FailsSaying(reader, "unfinished: 3 of 5 lights"));

  // A flipped byte in the header (a position), in a record, in the magic.
  std::vector<char> bad = bytes;
  bad[header - 20] ^= 0x10;
  WriteBytes(path, bad);
  PGI_CHECK(ReadFails(path, "corrupted header"));
  bad = bytes;
  bad[header + 2 * record + 20] ^= 0x01;
  WriteBytes(path, bad);
  PGI_CHECK(ReadFails(path, "corrupted record at byte"));
  PGI_CHECK(pgitest::FailsSaying(reader, "corrupted record"));
  bad = bytes;
  bad[0] = 'X';
  WriteBytes(path, bad);
  PGI_CHECK(ReadFails(path, "bad magic"));
  WriteBytes(path, std::vector<char>(bytes.begin(), bytes.begin() + 10));
  PGI_CHECK(ReadFails(path, "too short"));
  PGI_CHECK(ReadFails(dir + "/no-such-file.cloud", "cannot open"));
  reader->SetFileName(nullptr);
  PGI_CHECK(pgitest::FailsSaying(reader, "No FileName"));
  std::remove(path.c_str());
  return pgitest::Result();
}
