// One vtkPGIGISettings drives the CPU filter, the GI mapper and the
// image-space pass; what a GPU consumer cannot honour is replaced, warned
// once and said in its status (order 8 on the mapper runs 6, OL runs HYB,
// order 6 in image space runs 4, the shadowed bounce there runs unshadowed);
// proxies through a pipeline port re-execute upstream on change and the GI
// follows, while an unchanged frame reuses the bake and the GI pass.
#include "pgiHardScenes.h"
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGIImageSpaceGIPass.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkFloatArray.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkTransformFilter.h"

#include <cstdio>
#include <string>

namespace
{
int Warnings = 0;
void CountWarning(vtkObject*, unsigned long, void*, void*)
{
  ++Warnings;
}

bool Says(const std::string& status, const std::string& text)
{
  if (status.find(text) != std::string::npos)
  {
    return true;
  }
  std::printf("status lacks \"%s\": %s\n", text.c_str(), status.c_str());
  return false;
}

double LargestDifference(vtkFloatArray* a, vtkFloatArray* b)
{
  double worst = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues() && i < b->GetNumberOfValues(); ++i)
  {
    worst = std::max(worst, std::fabs(double(a->GetValue(i)) - double(b->GetValue(i))));
  }
  return worst;
}
} // namespace

int TestRenderingSettings(int, char*[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  if (!window)
  {
    std::printf("no offscreen window: %s\n", description.c_str());
    return EXIT_FAILURE;
  }
  window->SetSize(96, 96);
  vtkNew<vtkCallbackCommand> warnings;
  warnings->SetCallback(CountWarning);

  // Receivers: a ground patch; proxies: a sphere above it, moved upstream.
  vtkNew<vtkPlaneSource> ground;
  ground->SetOrigin(-2, -2, 0);
  ground->SetPoint1(2, -2, 0);
  ground->SetPoint2(-2, 2, 0);
  ground->SetResolution(24, 24);
  vtkNew<vtkTransform> move;
  vtkNew<vtkTransformFilter> moved;
  moved->SetInputData(pgitest::HardProxies({ { 0, 0, 1.0, 0.6, 0 } }));
  moved->SetTransform(move);

  vtkNew<vtkPGIGISettings> settings;
  settings->SetOrder(8);
  settings->SetExpMethod(vtkPGIGISettings::EXP_OL);
  vtkNew<vtkPGIGIPolyDataMapper> mapper;
  mapper->SetInputConnection(ground->GetOutputPort());
  mapper->SetProxiesConnection(moved->GetOutputPort());
  mapper->SetSettings(settings);
  mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  window->Render();
  const std::string status = mapper->GetGIStatus();
  std::printf("mapper: %s\n", status.c_str());
  PGI_CHECK(Says(status, "order 6"));
  PGI_CHECK(Says(status, "not honoured: Order: order 8 is outside 2..6; order 6 runs"));
  PGI_CHECK(Says(status, "not honoured: ExpMethod: OL is not available; HYB runs"));
  PGI_CHECK(Warnings == 2);
  vtkNew<vtkFloatArray> before, after, again;
  PGI_CHECK(mapper->GetPerVertexResults(before));
  PGI_CHECK(before->GetNumberOfComponents() == 3);

  // Nothing changed: the GI pass and the bake are reused, no new warning.
  window->Render();
  PGI_CHECK(mapper->GetNumberOfGIUpdates() == 1);
  PGI_CHECK(mapper->GetBake()->GetNumberOfBuilds() == 1);
  PGI_CHECK(Says(mapper->GetGIStatus(), "reused (nothing changed)"));
  PGI_CHECK(Warnings == 2);

  // A change upstream of the proxies port re-executes it and the GI follows.
  move->Translate(0.8, 0, 0);
  window->Render();
  PGI_CHECK(mapper->GetNumberOfGIUpdates() == 2);
  PGI_CHECK(mapper->GetBake()->GetNumberOfBuilds() == 2);
  PGI_CHECK(mapper->GetPerVertexResults(after));
  PGI_CHECK(LargestDifference(before, after) > 1e-3);
  PGI_NEAR(mapper->GetProxies()->GetPoint(0)[0], 0.8, 1e-6);

  // Settings the mapper honours: the warnings go away and the status with them.
  settings->SetOrder(4);
  settings->SetExpMethod(vtkPGIGISettings::EXP_HYB);
  window->Render();
  PGI_CHECK(mapper->GetGIStatus().find("not honoured") == std::string::npos);
  PGI_CHECK(Warnings == 2);
  PGI_CHECK(mapper->GetPerVertexResults(again));

  // The CPU filter on the same settings and proxies agrees with the mapper.
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputConnection(ground->GetOutputPort());
  gi->SetProxiesConnection(moved->GetOutputPort());
  gi->SetSettings(settings);
  settings->SetShadingPath(vtkPGIGISettings::SHADING_PRODUCT_MATRIX);
  gi->Update();
  window->Render();
  again->Initialize();
  PGI_CHECK(mapper->GetPerVertexResults(again));
  vtkDataArray* cpu = gi->GetOutput()->GetPointData()->GetArray("Radiance");
  pgitest::ErrorSum errors;
  for (vtkIdType i = 0; i < cpu->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      errors.Add(again->GetComponent(i, c), cpu->GetComponent(i, c));
    }
  }
  const double rms = errors.RelativeRMSE();
  std::printf("CPU filter against the mapper on one settings object: relative RMS %.2e\n", rms);
  PGI_BELOW(rms, 1e-3);
  window->RemoveRenderer(renderer);

  // The image-space pass on the same settings: order 6 runs 4, shadowed
  // runs unshadowed, each said; proxies through its connection.
  settings->SetOrder(6);
  settings->SetIndirectModeToShadowed();
  vtkNew<vtkPolyDataMapper> plain;
  plain->SetInputConnection(ground->GetOutputPort());
  vtkNew<vtkActor> plainActor;
  plainActor->SetMapper(plain);
  vtkNew<vtkRenderer> passRenderer;
  passRenderer->AddActor(plainActor);
  vtkNew<vtkPGIImageSpaceGIPass> pass;
  pass->SetSettings(settings);
  pass->SetProxiesConnection(moved->GetOutputPort());
  pass->AddObserver(vtkCommand::WarningEvent, warnings);
  passRenderer->SetPass(pass);
  window->AddRenderer(passRenderer);
  passRenderer->ResetCamera();
  Warnings = 0;
  window->Render();
  std::printf("pass: %s\n", pass->GetStatus().c_str());
  PGI_CHECK(Says(pass->GetStatus(), "order 4"));
  PGI_CHECK(Says(pass->GetStatus(), "Order: order 6 is outside 2..4; order 4 runs"));
  PGI_CHECK(Says(pass->GetStatus(), "IndirectMode: shadowed indirect light is not available"));
  PGI_CHECK(Warnings == 2);
  vtkNew<vtkFloatArray> visBefore, visAfter;
  PGI_CHECK(pass->GetVisibilityBuffer(visBefore));
  PGI_CHECK(visBefore->GetNumberOfComponents() == 16);
  window->Render();
  PGI_CHECK(pass->GetBake()->GetNumberOfBuilds() == 1);
  move->Translate(-1.6, 0, 0);
  window->Render();
  PGI_CHECK(pass->GetBake()->GetNumberOfBuilds() == 2);
  PGI_CHECK(pass->GetVisibilityBuffer(visAfter));
  PGI_CHECK(LargestDifference(visBefore, visAfter) > 1e-3);
  PGI_NEAR(pass->GetProxies()->GetPoint(0)[0], -0.8, 1e-6);
  window->RemoveRenderer(passRenderer);
  return pgitest::Result();
}
