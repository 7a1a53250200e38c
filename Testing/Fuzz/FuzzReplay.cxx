// Replays inputs through a fuzz harness without libFuzzer: every file named,
// or every file in a folder named, once. The regression test of a harness's
// corpus (seeds and the crashers found so far) in any build.
#include "vtksys/Directory.hxx"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace
{
bool Replay(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    std::fprintf(stderr, "cannot read %s\n", path.c_str());
    return false;
  }
  const std::vector<char> bytes(
    (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // A harness that crashes ends the process: the test fails with its name.
  std::fprintf(stderr, "replay %s (%zu bytes)\n", path.c_str(), bytes.size());
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  int replayed = 0;
  for (int a = 1; a < argc; ++a)
  {
    const std::string path = argv[a];
    if (vtksys::SystemTools::FileIsDirectory(path))
    {
      vtksys::Directory folder;
      folder.Load(path);
      std::vector<std::string> names;
      for (unsigned long i = 0; i < folder.GetNumberOfFiles(); ++i)
      {
        const std::string name = folder.GetFile(i);
        if (name != "." && name != ".." && name != "README.md")
        {
          names.push_back(name);
        }
      }
      std::sort(names.begin(), names.end());
      for (const std::string& name : names)
      {
        std::string file = path;
        file.append("/").append(name);
        replayed += Replay(file) ? 1 : 0;
      }
    }
    else
    {
      if (!Replay(path))
      {
        return 1;
      }
      ++replayed;
    }
  }
  std::printf("replayed %d inputs, none crashed\n", replayed);
  return replayed > 0 ? 0 : 1;
}
