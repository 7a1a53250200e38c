// Relighting time per frame in the Cornell box (Testing/Data/cornell-box.json):
// the CPU filter (vtkPGILightCloudRelight, then its colours drawn) against
// the GPU mapper (vtkPGILightCloudPolyDataMapper), a user light moving
// along a path so that every frame recomputes, for dense and compressed,
// diffuse and glossy clouds. Times are medians of one run, as ratios; the
// plain draw of the same mesh is the floor. Writes a Markdown table to
// stdout (and to --out FILE).
//
//   ProxyGIBenchLightCloudMapper [--frames N] [--size PIXELS] [--out FILE]
#include "pgiCornellBox.h"
#include "pgiOffscreenWindow.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPolyDataMapper.h"
#include "vtkPGILightCloudRelight.h"
#include "vtkPGIMeshOccluder.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// The path: a loop through the box's inside.
void PathPoint(int frame, int frames, double p[3])
{
  const double t = 6.283185307179586 * frame / frames;
  p[0] = 0.55 * std::cos(t);
  p[1] = 0.45 * std::sin(t);
  p[2] = 1.0 + 0.4 * std::sin(2.0 * t);
}
} // namespace

int main(int argc, char* argv[])
{
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkSMPTools::SetBackend("STDThread");
  }
  int frames = 60, size = 512;
  std::string out;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(4, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--size") && i + 1 < argc)
    {
      size = std::max(64, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
    {
      out = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "usage: %s [--frames N] [--size PIXELS] [--out FILE]\n", argv[0]);
      return EXIT_FAILURE;
    }
  }
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  if (!window)
  {
    std::fprintf(stderr, "no offscreen window: %s\n", description.c_str());
    return EXIT_FAILURE;
  }
  window->SetSize(size, size);
  vtkNew<vtkPGIMeshOccluder> occluder;
  vtkSmartPointer<vtkPolyData> box =
    pgitest::LoadCornellBox(PROXYGI_TEST_DATA_DIR "/cornell-box.json", occluder);
  if (!box)
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkActor> actor;
  renderer->AddActor(actor);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, -4.6, 1);
  camera->SetFocalPoint(0, 0, 1);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange(-1, 1, -1, 1, 0, 2);
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  actor->GetProperty()->LightingOff();

  std::ostringstream table;
  table << "Renderer: " << proxygi::DescribeRenderWindowContext(window) << "; " << size << "x"
        << size << " pixels, " << box->GetNumberOfPoints() << " receivers, " << frames
        << " frames of a moving light (medians, ms)\n\n"
        << "| cloud | coefficients per receiver | CPU relight | CPU frame (relight + draw) | "
           "GPU mapper frame | plain draw | CPU frame / GPU frame |\n"
        << "|---|---:|---:|---:|---:|---:|---:|\n";
  struct Case
  {
    const char* Name;
    bool Compress;
    double Specular;
  };
  const Case cases[] = { { "diffuse, dense", false, 0.0 }, { "diffuse, compressed", true, 0.0 },
    { "glossy order 4, dense", false, 0.5 }, { "glossy order 4, compressed", true, 0.5 } };
  for (const Case& c : cases)
  {
    vtkSmartPointer<vtkPGILightCloud> cloud = pgitest::CornellCloud(box, 5, c.Compress, c.Specular);

    // CPU: the filter, then its radiance drawn as vertex colours.
    vtkNew<vtkPGILightCloudRelight> relight;
    relight->SetInputData(box);
    relight->SetCloudData(cloud);
    relight->SetOccluder(occluder);
    relight->SetViewPoint(camera->GetPosition());
    relight->AddLight(0, 0, 1, 1, 1, 1);
    vtkNew<vtkPolyData> coloured;
    vtkNew<vtkPolyDataMapper> plain;
    plain->SetInputData(coloured);
    plain->SetColorModeToDirectScalars();
    actor->SetMapper(plain);
    std::vector<double> cpuRelight, cpuFrame, plainDraw;
    for (int f = 0; f < frames; ++f)
    {
      double p[3];
      PathPoint(f, frames, p);
      const double t0 = Now();
      relight->SetLightPosition(0, p[0], p[1], p[2]);
      relight->Update();
      const double t1 = Now();
      auto* radiance = vtkFloatArray::SafeDownCast(
        relight->GetOutput()->GetPointData()->GetArray("LightCloudRadiance"));
      vtkNew<vtkUnsignedCharArray> colours;
      colours->SetNumberOfComponents(3);
      colours->SetNumberOfTuples(box->GetNumberOfPoints());
      for (vtkIdType k = 0; k < colours->GetNumberOfValues(); ++k)
      {
        const double v = std::min(1.0, std::max(0.0, 4.0 * radiance->GetValue(k)));
        colours->SetValue(k, static_cast<unsigned char>(255.0 * v));
      }
      coloured->ShallowCopy(box);
      coloured->GetPointData()->SetScalars(colours);
      window->Render();
      const double t2 = Now();
      window->Render(); // nothing changed: the draw alone
      const double t3 = Now();
      if (f > 0)
      {
        cpuRelight.push_back(t1 - t0);
        cpuFrame.push_back(t2 - t0);
        plainDraw.push_back(t3 - t2);
      }
    }

    // GPU: the mapper (weights on the CPU, sums on the GPU).
    vtkNew<vtkPGILightCloudPolyDataMapper> mapper;
    mapper->SetInputData(box);
    mapper->SetCloud(cloud);
    mapper->SetCombineWithVTKLighting(false);
    mapper->GetRelight()->SetOccluder(occluder);
    mapper->GetRelight()->AddLight(0, 0, 1, 1, 1, 1);
    mapper->SetExposure(4.0);
    actor->SetMapper(mapper);
    window->Render(); // compiles the shader
    std::vector<double> gpuFrame;
    for (int f = 0; f < frames; ++f)
    {
      double p[3];
      PathPoint(f, frames, p);
      const double t0 = Now();
      mapper->GetRelight()->SetLightPosition(0, p[0], p[1], p[2]);
      window->Render();
      const double t1 = Now();
      if (f > 0)
      {
        gpuFrame.push_back(t1 - t0);
      }
    }
    std::fprintf(stderr, "%s: %s\n", c.Name, mapper->GetStatus().c_str());
    const double cr = 1e3 * Median(cpuRelight), cf = 1e3 * Median(cpuFrame),
                 gf = 1e3 * Median(gpuFrame), pd = 1e3 * Median(plainDraw);
    char line[512];
    std::snprintf(line, sizeof(line), "| %s | %.0f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", c.Name,
      cloud->GetCoefficientsPerReceiver(), cr, cf, gf, pd, gf > 0.0 ? cf / gf : 0.0);
    table << line;
  }
  std::printf("%s", table.str().c_str());
  if (!out.empty())
  {
    std::ofstream file(out);
    file << table.str();
  }
  return EXIT_SUCCESS;
}
