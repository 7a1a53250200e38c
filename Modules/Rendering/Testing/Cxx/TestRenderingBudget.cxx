// The GPU mapper's accuracy budget: SetErrorBudget / SetTimeBudget choose
// among the model's GPU-mapper candidates only (a model with a faster and
// more accurate filter candidate beside them), on a copy of the settings
// (the user's are left as set); the status says the choice; an unchanged
// frame re-bakes nothing; an unreachable, a bad and a missing model are
// said; the model that ships has mapper candidates the mapper takes.
#include "pgiAccuracyBudget.h"
#include "pgiHardScenes.h"
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkFloatArray.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
using namespace proxygi::budget;

int Warnings = 0, Errors = 0;
void CountWarning(vtkObject*, unsigned long, void*, void*)
{
  ++Warnings;
}
void CountError(vtkObject*, unsigned long, void*, void*)
{
  ++Errors;
}

bool Says(const std::string& status, const std::string& text)
{
  return pgitest::Says({ status }, text, true);
}

// Mapper candidates of order 3 (20% in 10 ms) and 4 (10% in 50 ms) at 16
// spheres, and a filter candidate better in both that the mapper must not take.
Model SmallModel()
{
  Model m;
  m.Machine = "test";
  m.MapperRenderer = "test renderer";
  m.Scenes = 2;
  const auto add = [&](Route route, int order, double error, double seconds)
  {
    Model::Candidate c;
    c.Settings.Backend = route;
    c.Settings.Order = order;
    c.Settings.Spheres = 16;
    c.Settings.SelfVisibility = 0;
    c.Settings.IndirectOrder = 0;
    c.Settings.HierarchyAngle = route == Route::Mapper ? 0.0 : 25.0;
    c.Time[0] = seconds;
    c.ErrorIntercept = std::log(error);
    m.Candidates.push_back(c);
  };
  add(Route::Mapper, 3, 0.20, 0.010);
  add(Route::Mapper, 4, 0.10, 0.050);
  add(Route::Filter, 6, 0.01, 0.001);
  return m;
}
} // namespace

int TestRenderingBudget(int argc, char* argv[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  if (!window)
  {
    std::printf("no offscreen window: %s\n", description.c_str());
    return EXIT_FAILURE;
  }
  window->SetSize(64, 64);
  const std::string temp = pgitest::TempDirectory(argc, argv);
  const std::string modelFile = temp + "/TestRenderingBudget-model.txt";
  std::string error;
  PGI_CHECK(SmallModel().Save(modelFile, error));

  vtkNew<vtkPGIGIPolyDataMapper> mapper;
  mapper->SetInputData(pgitest::HardPlane(2.0, 0.0, 16));
  mapper->SetProxies(pgitest::HardProxies({ { 0, 0, 1.0, 0.6, 0 } }));
  mapper->GetSettings()->SetOrder(6);
  mapper->GetSettings()->SetIndirect(false); // the budget's knobs only: fast on llvmpipe
  vtkNew<vtkCallbackCommand> warnings, errors;
  warnings->SetCallback(CountWarning);
  errors->SetCallback(CountError);
  mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  window->AddRenderer(renderer);
  renderer->ResetCamera();

  // 15%: order 4 is the only mapper candidate within it.
  mapper->SetBudgetModelFileName(modelFile.c_str());
  mapper->SetErrorBudget(0.15);
  window->Render();
  std::string status = mapper->GetGIStatus();
  std::printf("15%%: %s\n", status.c_str());
  PGI_CHECK(Says(status, "budget: GPU mapper: order 4, 16 spheres"));
  PGI_CHECK(Says(status, "predicted error 10%"));
  PGI_CHECK(Says(status, "order 4"));
  PGI_CHECK(mapper->GetSettings()->GetOrder() == 6);
  PGI_CHECK(mapper->GetBake()->GetSettings()->GetOrder() == 4);
  // The model's renderer is neither software nor this one's kind when
  // this one is llvmpipe; on a hardware GL it is the same kind.
  const bool software = SoftwareRenderer(proxygi::DescribeRenderWindowContext(window));
  PGI_CHECK(!software || Says(status, "its times do not hold here"));

  // Nothing changed: no new bake, no new GI pass.
  const int builds = mapper->GetBake()->GetNumberOfBuilds();
  const int updates = mapper->GetNumberOfGIUpdates();
  window->Render();
  PGI_CHECK(mapper->GetBake()->GetNumberOfBuilds() == builds);
  PGI_CHECK(mapper->GetNumberOfGIUpdates() == updates);

  // 25%: the faster order 3.
  mapper->SetErrorBudget(0.25);
  window->Render();
  status = mapper->GetGIStatus();
  PGI_CHECK(Says(status, "budget: GPU mapper: order 3"));
  PGI_CHECK(mapper->GetBake()->GetSettings()->GetOrder() == 3);
  vtkNew<vtkFloatArray> radiance;
  PGI_CHECK(mapper->GetPerVertexResults(radiance));
  PGI_CHECK(pgitest::NonFiniteValues(radiance.GetPointer()) == 0);

  // 30 ms a frame: the most accurate that fits, order 3; 1 ns: nothing fits.
  mapper->SetErrorBudget(0.0);
  mapper->SetTimeBudget(0.03);
  window->Render();
  PGI_CHECK(Says(mapper->GetGIStatus(), "budget: GPU mapper: order 3"));
  mapper->SetTimeBudget(1e-9);
  window->Render();
  PGI_CHECK(Says(mapper->GetGIStatus(), "NOT MET"));
  PGI_CHECK(Says(mapper->GetGIStatus(), "the fastest instead"));

  // A bad budget: one warning, and it still shades.
  PGI_CHECK(Warnings == 0);
  mapper->SetTimeBudget(-1.0);
  window->Render();
  window->Render();
  PGI_CHECK(Warnings == 1);
  PGI_CHECK(Says(mapper->GetGIStatus(), "a time budget must be positive"));

  // A model that cannot be read: one error, the settings as set (order 6).
  mapper->SetTimeBudget(0.0);
  mapper->SetErrorBudget(0.1);
  mapper->SetBudgetModelFileName((temp + "/no-such-model.txt").c_str());
  window->Render();
  window->Render();
  PGI_CHECK(Errors == 1);
  PGI_CHECK(Says(mapper->GetGIStatus(), "the settings as set instead"));
  PGI_CHECK(mapper->GetBake()->GetSettings()->GetOrder() == 6);

  // The model that ships: it has the mapper's candidates and the mapper
  // takes one of them.
  PGI_CHECK(Model::Default().HasRoute(Route::Mapper));
  mapper->SetBudgetModelFileName(nullptr);
  mapper->SetErrorBudget(0.5);
  window->Render();
  PGI_CHECK(Says(mapper->GetGIStatus(), "budget: GPU mapper: order "));

  // No budget: no budget line, the user's order again.
  mapper->SetErrorBudget(0.0);
  window->Render();
  PGI_CHECK(mapper->GetGIStatus().find("budget:") == std::string::npos);
  PGI_CHECK(mapper->GetBake()->GetSettings()->GetOrder() == 6);
  return pgitest::Result();
}
