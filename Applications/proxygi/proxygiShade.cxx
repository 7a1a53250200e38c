// proxygi shade: the CPU GI filter (vtkPGIGlobalIllumination) on a receiver
// mesh and a proxies file, with the classes' defaults unless told: the plain
// C++ answer the ParaView plugin's Global Illumination is compared with.
#include "proxygiCommands.h"
#include "proxygiImage.h"
#include "proxygiProgress.h"

#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIOFFReader.h"

#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>

namespace proxygi
{
namespace cli
{
namespace
{
const char* Usage = R"(usage: proxygi shade RECEIVERS PROXIES.vtp [options]

Shades every vertex of RECEIVERS (.off or .vtp) with the CPU GI filter and
the sphere proxies of PROXIES.vtp under a uniform sky (or an environment
file), with vtkPGIGlobalIllumination's defaults unless an option says
otherwise; writes the arrays and prints the plan.

  -o FILE            output .vtp (default proxygi-shade.vtp)
  --order N          SH order 2..8 (default 4)
  --indirect M       unshadowed (default), shadowed, off
  --environment FILE an OpenEXR lat-long environment (default: uniform sky 1)
)";

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
{
  const bool off = path.size() > 4 && path.compare(path.size() - 4, 4, ".off") == 0;
  if (off)
  {
    vtkNew<vtkPGIOFFReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return reader->GetOutput();
  }
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}
} // namespace

int RunShade(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  bool ok = true;
  const int order = static_cast<int>(NumberOption(args, "--order", 4, ok));
  const std::string indirect = Option(args, "--indirect", "unshadowed");
  const std::string output = Option(args, "-o", "proxygi-shade.vtp");
  const std::string environment = Option(args, "--environment", "");
  std::vector<std::string> files;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    if (!args[i].empty() && args[i][0] == '-')
    {
      ++i; // every option here takes a value
      continue;
    }
    files.push_back(args[i]);
  }
  if (!HasExtension("shade", "-o", output, { ".vtp" }))
  {
    return 2;
  }
  if (!ok || files.size() != 2 || order < 2 || order > 8 ||
    (indirect != "unshadowed" && indirect != "shadowed" && indirect != "off"))
  {
    std::fputs(Usage, stderr);
    return 2;
  }
  vtkSmartPointer<vtkPolyData> receivers = ReadMesh(files[0]);
  vtkSmartPointer<vtkPolyData> proxies = ReadMesh(files[1]);
  if (!receivers || receivers->GetNumberOfPoints() == 0 || !proxies)
  {
    std::fprintf(
      stderr, "proxygi shade: cannot read '%s' or '%s'\n", files[0].c_str(), files[1].c_str());
    return 1;
  }
  vtkNew<vtkPGILighting> lighting;
  if (!environment.empty())
  {
    lighting->SetEnvironmentFileName(environment.c_str());
  }
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputData(receivers);
  gi->SetProxiesData(proxies);
  gi->SetLighting(lighting);
  gi->GetSettings()->SetOrder(order);
  gi->GetSettings()->SetIndirect(indirect != "off");
  gi->GetSettings()->SetIndirectMode(indirect == "shadowed"
      ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
      : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  gi->Update();
  if (gi->GetOutput()->GetNumberOfPoints() == 0)
  {
    vtkLogF(ERROR, "proxygi shade: the GI filter failed (see the messages above)");
    return 1;
  }
  for (const std::string& line : gi->GetPlan())
  {
    std::printf("plan: %s\n", line.c_str());
  }
  if (!WritePolyData(gi->GetOutput(), output))
  {
    vtkLogF(ERROR, "proxygi shade: cannot write %s", output.c_str());
    return 1;
  }
  std::printf("wrote %s (%lld receivers)\n", output.c_str(),
    static_cast<long long>(receivers->GetNumberOfPoints()));
  return 0;
}

} // namespace cli
} // namespace proxygi
