// libFuzzer harness: bytes as an OpenEXR file through vtkPGIEXRReader and,
// when read, into an environment map projected to SH (what a scene's map
// goes through). OpenEXR reads files, so each input is written to a
// process-private file first. Findings: a crash, an uncaught exception, an
// allocation beyond MaximumNumberOfPixels, non-finite radiance or SH.
#include "pgiFuzz.h"

#include "pgiEnvironmentMap.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPGIEXRReader.h"
#include "vtkPointData.h"

#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const bool quiet = pgiFuzz::Quiet();
  (void)quiet;
  static const std::string path = "/tmp/pgi-fuzz-exr-" + std::to_string(getpid()) + ".exr";
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file)
  {
    return 0;
  }
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  vtkNew<vtkPGIEXRReader> reader;
  reader->SetFileName(path.c_str());
  // Maps are 2:1 in use; any shape here reaches the pixel code more often.
  reader->LatLongOff();
  reader->SetMaximumNumberOfPixels(1 << 20);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!pgiFuzz::Finite(image->GetPointData()))
  {
    pgiFuzz::Finding("non-finite radiance");
  }
  int dims[3];
  image->GetDimensions(dims);
  if (!image->GetPointData()->GetArray("Radiance") || dims[0] != 2 * dims[1])
  {
    return 0;
  }
  proxygi::EnvironmentMap map;
  std::string error;
  if (!proxygi::EnvironmentMap::FromImage(image, map, error))
  {
    return 0;
  }
  double sh[3][16];
  map.ProjectSH(4, sh[0], sh[1], sh[2]);
  for (const auto& channel : sh)
  {
    for (double c : channel)
    {
      if (!std::isfinite(c))
      {
        pgiFuzz::Finding("non-finite SH of a finite map");
      }
    }
  }
  return 0;
}
