// Long runs of an animation through the CPU filter (its output drawn by a
// plain mapper) and through the GI mapper: a proxy circles the ball, a
// spherical light circles the scene and the camera orbits, one period over
// frames 1..N, so frame N has frame 1's state. Checked per route:
// - frame N equals frame 1 (per-vertex radiance and the picture, exactly);
// - resident memory is flat after the first tenth (printed every tenth);
// - no GL object leaks: the live buffers, textures, framebuffers, vertex
//   arrays, programs and shaders (glIs* over every name given out) are the
//   same at the end as after the first tenth.
//
//   TestRenderingLongRun [--frames N]   (default 100; the soak target 1000)
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
#include <vector>

namespace
{
double ResidentMiB()
{
  long pages = 0, resident = 0;
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f)
  {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2)
    {
      resident = 0;
    }
    std::fclose(f);
  }
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// Live GL objects of each kind: every name up to the next one the driver
// would give out, asked with glIs*.
struct LiveObjects
{
  int Buffers = 0, Textures = 0, Framebuffers = 0, VertexArrays = 0, Programs = 0, Shaders = 0;
  bool operator==(const LiveObjects& o) const
  {
    return Buffers == o.Buffers && Textures == o.Textures && Framebuffers == o.Framebuffers &&
      VertexArrays == o.VertexArrays && Programs == o.Programs && Shaders == o.Shaders;
  }
};

template <typename Gen, typename Del, typename Is>
int CountLive(Gen gen, Del del, Is is)
{
  GLuint next = 0;
  gen(1, &next);
  del(1, &next);
  int live = 0;
  for (GLuint name = 1; name < next + 64; ++name)
  {
    live += is(name) ? 1 : 0;
  }
  return live;
}

LiveObjects CountLiveObjects(vtkRenderWindow* window)
{
  window->MakeCurrent();
  LiveObjects live;
  live.Buffers = CountLive([](GLsizei n, GLuint* p) { glGenBuffers(n, p); },
    [](GLsizei n, GLuint* p) { glDeleteBuffers(n, p); },
    [](GLuint x) { return glIsBuffer(x) == GL_TRUE; });
  live.Textures = CountLive([](GLsizei n, GLuint* p) { glGenTextures(n, p); },
    [](GLsizei n, GLuint* p) { glDeleteTextures(n, p); },
    [](GLuint x) { return glIsTexture(x) == GL_TRUE; });
  live.Framebuffers = CountLive([](GLsizei n, GLuint* p) { glGenFramebuffers(n, p); },
    [](GLsizei n, GLuint* p) { glDeleteFramebuffers(n, p); },
    [](GLuint x) { return glIsFramebuffer(x) == GL_TRUE; });
  live.VertexArrays = CountLive([](GLsizei n, GLuint* p) { glGenVertexArrays(n, p); },
    [](GLsizei n, GLuint* p) { glDeleteVertexArrays(n, p); },
    [](GLuint x) { return glIsVertexArray(x) == GL_TRUE; });
  // Programs and shaders share one name space.
  live.Programs = CountLive([](GLsizei, GLuint* p) { *p = glCreateProgram(); },
    [](GLsizei, GLuint* p) { glDeleteProgram(*p); },
    [](GLuint x) { return glIsProgram(x) == GL_TRUE; });
  live.Shaders = CountLive([](GLsizei, GLuint* p) { *p = glCreateProgram(); },
    [](GLsizei, GLuint* p) { glDeleteProgram(*p); },
    [](GLuint x) { return glIsShader(x) == GL_TRUE; });
  return live;
}

struct Animation
{
  vtkNew<vtkPolyData> Proxies;
  vtkNew<vtkPGILighting> Lighting;
  int Period = 1;

  Animation()
  {
    vtkNew<vtkPoints> centres;
    centres->InsertNextPoint(0, 0, 1.5);
    centres->InsertNextPoint(2, 0, 0.5);
    vtkNew<vtkDoubleArray> radius;
    radius->SetName("Radius");
    radius->InsertNextValue(1.0);
    radius->InsertNextValue(0.5);
    this->Proxies->SetPoints(centres);
    this->Proxies->GetPointData()->AddArray(radius);
    this->Lighting->SetUniformRadiance(0.6, 0.7, 0.9);
  }

  // The state of frame f (1-based): frame Period + 1 is frame 1 again.
  void Set(int f, vtkCamera* camera)
  {
    const double a = 2.0 * M_PI * ((f - 1) % this->Period) / this->Period;
    this->Proxies->GetPoints()->SetPoint(1, 2.0 * std::cos(a), 2.0 * std::sin(a), 0.5);
    this->Proxies->GetPoints()->Modified();
    this->Proxies->Modified();
    this->Lighting->RemoveAllSphereLights();
    this->Lighting->AddSphereLight(3.0 * std::cos(-a), 3.0 * std::sin(-a), 3.0, 0.4, 8.0, 7.0, 6.0);
    camera->SetPosition(7.0 * std::cos(a + 0.3), 7.0 * std::sin(a + 0.3), 4.0);
    camera->SetFocalPoint(0, 0, 0.7);
    camera->SetViewUp(0, 0, 1);
  }
};

struct Frame
{
  std::vector<float> Radiance;
  std::vector<unsigned char> Pixels;
};

Frame Grab(vtkDataArray* radiance, vtkRenderWindow* window)
{
  Frame frame;
  for (vtkIdType i = 0; radiance && i < radiance->GetNumberOfValues(); ++i)
  {
    frame.Radiance.push_back(static_cast<float>(radiance->GetVariantValue(i).ToDouble()));
  }
  const int* size = window->GetSize();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetRGBACharPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
  frame.Pixels.assign(pixels->GetPointer(0), pixels->GetPointer(0) + pixels->GetNumberOfValues());
  return frame;
}

// One route over frames 1..frames: `step` sets frame f up and renders it,
// returning the per-vertex radiance it drew.
template <typename Step>
void LongRun(const char* route, int frames, vtkRenderWindow* window, Step step)
{
  Frame first, last;
  LiveObjects warm;
  double warmMiB = 0.0, peakMiB = 0.0;
  const int tenth = std::max(1, frames / 10);
  std::printf("%s: resident MiB by frame:", route);
  for (int f = 1; f <= frames; ++f)
  {
    vtkDataArray* radiance = step(f);
    if (f == 1 || f == frames)
    {
      (f == 1 ? first : last) = Grab(radiance, window);
    }
    if (f % tenth == 0)
    {
      const double mib = ResidentMiB();
      std::printf(" %d:%.1f", f, mib);
      std::fflush(stdout);
      if (f == tenth)
      {
        warmMiB = mib;
        warm = CountLiveObjects(window);
      }
      peakMiB = std::max(peakMiB, mib);
    }
  }
  const LiveObjects end = CountLiveObjects(window);
  std::printf("\n%s: resident %.1f MiB at frame %d, %.1f at the end, peak %.1f\n", route, warmMiB,
    tenth, ResidentMiB(), peakMiB);
  std::printf("%s: live GL objects at frame %d / at the end: buffers %d/%d, textures %d/%d, "
              "framebuffers %d/%d, vertex arrays %d/%d, programs %d/%d, shaders %d/%d\n",
    route, tenth, warm.Buffers, end.Buffers, warm.Textures, end.Textures, warm.Framebuffers,
    end.Framebuffers, warm.VertexArrays, end.VertexArrays, warm.Programs, end.Programs,
    warm.Shaders, end.Shaders);
  long differentValues = 0, differentPixels = 0;
  for (std::size_t i = 0; i < std::min(first.Radiance.size(), last.Radiance.size()); ++i)
  {
    differentValues += first.Radiance[i] != last.Radiance[i] ? 1 : 0;
  }
  for (std::size_t i = 0; i < std::min(first.Pixels.size(), last.Pixels.size()); ++i)
  {
    differentPixels += first.Pixels[i] != last.Pixels[i] ? 1 : 0;
  }
  std::printf("%s: frame %d against frame 1: %ld of %zu radiance values and %ld of %zu pixel "
              "bytes differ\n",
    route, frames, differentValues, first.Radiance.size(), differentPixels, first.Pixels.size());
  PGI_CHECK(!first.Radiance.empty() && first.Radiance.size() == last.Radiance.size());
  PGI_CHECK(differentValues == 0);
  PGI_CHECK(differentPixels == 0);
  PGI_CHECK(warm == end);
  // Flat: what the allocator keeps may move a little, a leak per frame
  // would grow with the frames.
  PGI_BELOW(peakMiB - warmMiB, 8.0);
}
} // namespace

int TestRenderingLongRun(int argc, char* argv[])
{
  int frames = 100;
  for (int a = 1; a + 1 < argc; ++a)
  {
    if (!std::strcmp(argv[a], "--frames"))
    {
      frames = std::max(2, std::atoi(argv[++a]));
    }
  }
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("window: %s, %d frames\n", description.c_str(), frames);
  if (!PGI_CHECK(window != nullptr))
  {
    return EXIT_FAILURE;
  }
  window->SetSize(160, 120);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -4, 0);
  plane->SetPoint1(4, -4, 0);
  plane->SetPoint2(-4, 4, 0);
  plane->SetResolution(24, 24);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0, 1.5);
  ball->SetThetaResolution(24);
  ball->SetPhiResolution(12);
  vtkNew<vtkAppendPolyData> scene;
  scene->AddInputConnection(plane->GetOutputPort());
  scene->AddInputConnection(ball->GetOutputPort());
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(35);

  Animation animation;
  animation.Period = frames - 1;

  // The probe sees a leak: one buffer and one texture made and bound.
  window->Render();
  const LiveObjects before = CountLiveObjects(window);
  GLuint buffer = 0, texture = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glBindTexture(GL_TEXTURE_2D, 0);
  const LiveObjects leaked = CountLiveObjects(window);
  glDeleteBuffers(1, &buffer);
  glDeleteTextures(1, &texture);
  PGI_CHECK(leaked.Buffers == before.Buffers + 1 && leaked.Textures == before.Textures + 1);
  PGI_CHECK(CountLiveObjects(window) == before);

  // The CPU filter, its radiance drawn as colours.
  {
    vtkNew<vtkPGIGlobalIllumination> gi;
    gi->SetInputConnection(scene->GetOutputPort());
    gi->SetProxiesData(animation.Proxies);
    gi->SetLighting(animation.Lighting);
    gi->GetSettings()->SetIndirectMode(vtkPGIGISettings::INDIRECT_MODE_SHADOWED);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(gi->GetOutputPort());
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("RadianceSRGB");
    mapper->SetColorModeToDirectScalars();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    LongRun("filter", frames, window,
      [&](int f) -> vtkDataArray*
      {
        animation.Set(f, camera);
        renderer->ResetCameraClippingRange();
        window->Render();
        return gi->GetOutput()->GetPointData()->GetArray("Radiance");
      });
    renderer->RemoveActor(actor);
  }

  // The GI mapper.
  {
    vtkNew<vtkPGIGIPolyDataMapper> mapper;
    mapper->SetInputConnection(scene->GetOutputPort());
    mapper->SetProxies(animation.Proxies);
    mapper->SetLighting(animation.Lighting);
    const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
    mapper->AddBlockerPlane(origin, up);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    vtkNew<vtkFloatArray> radiance;
    LongRun("mapper", frames, window,
      [&](int f) -> vtkDataArray*
      {
        animation.Set(f, camera);
        renderer->ResetCameraClippingRange();
        window->Render();
        if (f == 1 || f == frames)
        {
          mapper->GetPerVertexResults(radiance);
        }
        return radiance;
      });
    renderer->RemoveActor(actor);
  }
  return pgitest::Result();
}
