// Image-space indirect light (vtkPGIImageSpaceGIPass, Indirect on): a red
// unit-sphere proxy 1.5 above a grey ground plane that bounces light too,
// coloured sky with a sun, 256^2 pixels. At ReceiverScale 1 the image must
// match the CPU filter's per-vertex DirectShadowed + IndirectProxy (averaged
// operator, xi normalisation) on the same finely tessellated scene, drawn as
// vertex colours; the indirect light must brighten the image and redden
// the ground under the ball; 1/4 bilateral stays close to 1/1.
#include "pgiOffscreenWindow.h"
#include "pgiRenderingTestScenes.h"
#include "pgiSRGB.h"
#include "pgiTesting.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
constexpr int Size = 256;
constexpr double Exposure = 0.3;

std::vector<unsigned char> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, Size - 1, Size - 1, 0, pixels);
  const unsigned char* p = pixels->GetPointer(0);
  return std::vector<unsigned char>(p, p + 3 * Size * Size);
}

using proxygi::FromSRGB8;
using proxygi::ToSRGB8;

// Relative RMSE (linear) and largest difference (levels) over pixels where
// `reference` is not the background.
void Compare(const std::vector<unsigned char>& a, const std::vector<unsigned char>& reference,
  const unsigned char background[3], double& rmse, int& worst, int& over8, int rows = Size)
{
  pgitest::ErrorSum errors;
  worst = 0;
  over8 = 0;
  for (int i = 0; i < rows * Size; ++i)
  {
    const unsigned char* r = &reference[3 * i];
    if (r[0] == background[0] && r[1] == background[1] && r[2] == background[2])
    {
      continue;
    }
    int level = 0;
    for (int c = 0; c < 3; ++c)
    {
      errors.Add(FromSRGB8(a[3 * i + c]), FromSRGB8(r[c]));
      level = std::max(level, std::abs(int(a[3 * i + c]) - int(r[c])));
    }
    worst = std::max(worst, level);
    over8 += level > 8 ? 1 : 0;
  }
  rmse = errors.Reference > 0.0 ? errors.RelativeRMSE() : 0.0;
}
} // namespace

int TestRenderingImageSpaceIndirect(int, char*[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("window: %s\n", description.c_str());
  if (!PGI_CHECK(window != nullptr))
  {
    return EXIT_FAILURE;
  }
  window->SetSize(Size, Size);

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -4, 0);
  plane->SetPoint1(4, -4, 0);
  plane->SetPoint2(-4, 4, 0);
  plane->SetResolution(128, 128);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0, 1.5);
  ball->SetRadius(1.0);
  ball->SetThetaResolution(128);
  ball->SetPhiResolution(64);
  vtkNew<vtkAppendPolyData> scene;
  scene->AddInputConnection(plane->GetOutputPort());
  scene->AddInputConnection(ball->GetOutputPort());
  scene->Update();
  auto proxies = pgitest::Spheres({ { 0, 0, 1.5, 1.0 } });
  vtkNew<vtkDoubleArray> proxyAlbedo;
  proxyAlbedo->SetName("Albedo");
  proxyAlbedo->SetNumberOfComponents(3);
  proxyAlbedo->InsertNextTuple3(0.9, 0.2, 0.1);
  proxies->GetPointData()->AddArray(proxyAlbedo);
  vtkNew<vtkPGILighting> lighting;
  lighting->SetEnvironmentImage(pgitest::Sky());
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, ground[3] = { 0.5, 0.5, 0.5 };

  // CPU reference, per vertex.
  vtkNew<vtkPGIGlobalIllumination> cpu;
  cpu->SetInputConnection(scene->GetOutputPort());
  cpu->SetProxiesData(proxies);
  cpu->SetLighting(lighting);
  cpu->GetSettings()->SetOrder(4);
  cpu->GetSettings()->IndirectOn();
  cpu->GetSettings()->SetIndirectOperator(vtkPGIGISettings::INDIRECT_AVERAGED);
  cpu->GetSettings()->LocalLightsOff();
  cpu->AddBlockerPlane(origin, up, ground);
  // The GPU kernels accumulate planes in log space, as the filter did before.
  cpu->GetSettings()->SetPlaneBlocking(vtkPGIGISettings::PLANES_IN_LOG_SPACE);
  cpu->Update();
  vtkPolyData* result = cpu->GetOutput();
  vtkDataArray* direct = result->GetPointData()->GetArray("DirectShadowed");
  vtkDataArray* bounce = result->GetPointData()->GetArray("IndirectProxy");
  if (!PGI_CHECK(direct && bounce))
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colours");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(result->GetNumberOfPoints());
  for (vtkIdType i = 0; i < result->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      colours->SetValue(
        3 * i + c, ToSRGB8(Exposure * (direct->GetComponent(i, c) + bounce->GetComponent(i, c))));
    }
  }
  vtkNew<vtkPolyData> coloured;
  coloured->ShallowCopy(result);
  coloured->GetPointData()->SetScalars(colours);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.5, -7.0, 5.0);
  camera->SetFocalPoint(-0.3, 0.5, 0.5);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  const unsigned char background[3] = { 26, 26, 38 };

  vtkNew<vtkPolyDataMapper> referenceMapper;
  referenceMapper->SetInputData(coloured);
  referenceMapper->SetColorModeToDirectScalars();
  referenceMapper->SetScalarModeToUsePointData();
  vtkNew<vtkActor> referenceActor;
  referenceActor->SetMapper(referenceMapper);
  referenceActor->GetProperty()->LightingOff();
  renderer->AddActor(referenceActor);
  renderer->ResetCameraClippingRange();
  window->Render();
  const std::vector<unsigned char> perVertex = Grab(window);
  // The CPU filter's direct light alone (for the direct-only comparison).
  for (vtkIdType i = 0; i < result->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      colours->SetValue(3 * i + c, ToSRGB8(Exposure * direct->GetComponent(i, c)));
    }
  }
  colours->Modified();
  window->Render();
  const std::vector<unsigned char> perVertexDirect = Grab(window);
  renderer->RemoveAllViewProps();

  // Image space, the same mesh with a plain mapper (albedo 0.8).
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(scene->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  renderer->AddActor(actor);
  vtkNew<vtkPGIImageSpaceGIPass> pass;
  pass->GetSettings()->IndirectOff(); // the GPU default before the shared settings
  pass->SetProxies(proxies);
  pass->SetLighting(lighting);
  pass->AddBlockerPlane(origin, up, ground);
  pass->SetExposure(Exposure);
  pass->SetReceiverScale(1);
  renderer->SetPass(pass);
  window->Render();
  const std::vector<unsigned char> shadowsOnly = Grab(window);
  pass->GetSettings()->IndirectOn();
  window->Render();
  std::printf("%s\n", pass->GetStatus().c_str());
  const std::vector<unsigned char> full = Grab(window);

  double rmse = 0.0;
  int worst = 0, over8 = 0;
  // The bottom 96 rows show only the ground, around and under the ball:
  // direct light there matches the CPU filter, so the comparison checks the
  // bounce from the ball and xi.
  Compare(shadowsOnly, perVertexDirect, background, rmse, worst, over8, 96);
  std::printf("ground, direct only, 1/1 vs CPU per-vertex: relative RMSE %.3f%%, max %d levels\n",
    100 * rmse, worst);
  // Measured 0.45%, 1 level.
  PGI_BELOW(rmse, 0.01);
  PGI_BELOW(worst, 3);
  Compare(full, perVertex, background, rmse, worst, over8, 96);
  std::printf("ground, direct + indirect, 1/1 vs CPU per-vertex: relative RMSE %.3f%%, max %d "
              "levels, %d pixels off by more than 8\n",
    100 * rmse, worst, over8);
  PGI_BELOW(rmse, 0.01);
  PGI_BELOW(worst, 4);
  Compare(full, perVertex, background, rmse, worst, over8);
  std::printf("whole image (the ball too), 1/1 vs CPU per-vertex: relative RMSE %.3f%%, max %d "
              "levels\n",
    100 * rmse, worst);
  // Measured 1.0%, 16 levels: the ball's underside differs most, since the
  // CPU filter dims the ground's bounce by the proxies' shadow and the pass
  // does not (Documentation/Rendering.md).
  PGI_BELOW(rmse, 0.02);
  PGI_BELOW(worst, 24);

  // Indirect light adds light everywhere, and red light from the ball to
  // the ground around its shadow (rows 40-96, columns 90-166 of the image).
  double gain = 0.0, red = 0.0, blue = 0.0;
  int pixels = 0;
  for (int i = 0; i < Size * Size; ++i)
  {
    const unsigned char* r = &perVertex[3 * i];
    if (r[0] == background[0] && r[1] == background[1] && r[2] == background[2])
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      gain += FromSRGB8(full[3 * i + c]) - FromSRGB8(shadowsOnly[3 * i + c]);
    }
    ++pixels;
    const int x = i % Size, y = i / Size;
    if (y >= 40 && y < 96 && x >= 90 && x < 166)
    {
      red += FromSRGB8(full[3 * i]) - FromSRGB8(shadowsOnly[3 * i]);
      blue += FromSRGB8(full[3 * i + 2]) - FromSRGB8(shadowsOnly[3 * i + 2]);
    }
  }
  std::printf("indirect adds %.4f (linear, mean per pixel and channel); on the ground red "
              "%.2f, blue %.2f (summed)\n",
    gain / (3 * pixels), red, blue);
  PGI_CHECK(gain > 0.0);
  PGI_CHECK(red > 2.0 * blue);

  // Upsampled indirect stays close.
  pass->SetReceiverScale(4);
  window->Render();
  Compare(Grab(window), full, background, rmse, worst, over8);
  std::printf(
    "1/4 bilateral with indirect vs 1/1: relative RMSE %.3f%%, max %d levels\n", 100 * rmse, worst);
  PGI_BELOW(rmse, 0.01);

  // The exact fallback everywhere (threshold 1) recomputes shadows and
  // indirect light per pixel: the 1/1 image again.
  pass->SetFallbackThreshold(1.0);
  window->Render();
  Compare(Grab(window), full, background, rmse, worst, over8);
  std::printf(
    "1/4 with the exact fallback everywhere vs 1/1: relative RMSE %.3f%%, max %d levels\n",
    100 * rmse, worst);
  PGI_BELOW(worst, 1);
  return pgitest::Result();
}
