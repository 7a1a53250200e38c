// vtkPGIGICompositePolyDataMapper runs vtkPGIGIPolyDataMapper's GI over
// every block of a multiblock (nested, three vertex-buffer helpers): each
// block's per-vertex results equal the plain mapper's on that block alone,
// the sphere block's proxy shadows the ground block, the two pictures agree,
// and a camera move reuses the GI while a change of proxies or of one block
// recomputes it.
#include "pgiHardScenes.h"
#include "pgiOffscreenWindow.h"
#include "vtkPGIGICompositePolyDataMapper.h"
#include "vtkPGIGIPolyDataMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
vtkSmartPointer<vtkPolyData> Patch(double x0, double y0, double size, bool withNormals)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(x0, y0, 0);
  plane->SetPoint1(x0 + size, y0, 0);
  plane->SetPoint2(x0, y0 + size, 0);
  plane->SetResolution(16, 16);
  plane->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(plane->GetOutput());
  if (!withNormals)
  {
    // A block with other arrays gets a helper of its own.
    out->GetPointData()->SetNormals(nullptr);
    out->GetPointData()->SetTCoords(nullptr);
  }
  return out;
}

vtkSmartPointer<vtkImageData> Snapshot(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

int LargestPixelDifference(vtkImageData* a, vtkImageData* b)
{
  auto* pa = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* pb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  int worst = 0;
  for (vtkIdType i = 0; i < pa->GetNumberOfValues() && i < pb->GetNumberOfValues(); ++i)
  {
    worst = std::max(worst, std::abs(int(pa->GetValue(i)) - int(pb->GetValue(i))));
  }
  return worst;
}
} // namespace

int TestRenderingComposite(int, char*[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  if (!window)
  {
    std::printf("no offscreen window: %s\n", description.c_str());
    return EXIT_FAILURE;
  }
  window->SetSize(128, 128);
  int failures = 0;

  // Blocks: a ground in two patches (one without normals, in a nested
  // multiblock) and a sphere above the first patch; the sphere's proxy.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 0, 1.0);
  sphere->SetRadius(0.5);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  sphere->Update();
  std::vector<vtkSmartPointer<vtkPolyData>> blocks = { Patch(-2, -2, 4, true),
    Patch(2, -2, 4, false), vtkSmartPointer<vtkPolyData>(sphere->GetOutput()) };
  vtkNew<vtkMultiBlockDataSet> data, nested;
  data->SetBlock(0, blocks[0]);
  nested->SetBlock(0, blocks[1]);
  data->SetBlock(1, nested);
  data->SetBlock(2, blocks[2]);
  vtkSmartPointer<vtkPolyData> proxies = pgitest::HardProxies({ { 0, 0, 1.0, 0.5, 0 } });

  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkPGIGICompositePolyDataMapper> composite;
  composite->SetInputDataObject(data);
  composite->SetProxies(proxies);
  composite->GetSettings()->IndirectOff();
  vtkNew<vtkActor> compositeActor;
  compositeActor->SetMapper(composite);
  renderer->AddActor(compositeActor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(-50);
  renderer->ResetCameraClippingRange();
  window->Render();
  std::printf("composite: %s\n", composite->GetGIStatus().c_str());
  vtkSmartPointer<vtkImageData> compositeImage = Snapshot(window);

  std::vector<vtkSmartPointer<vtkFloatArray>> compositeRadiance;
  for (vtkPolyData* block : blocks)
  {
    auto radiance = vtkSmartPointer<vtkFloatArray>::New();
    if (!composite->GetPerVertexResults(block, radiance) ||
      radiance->GetNumberOfTuples() != block->GetNumberOfPoints())
    {
      std::printf("no composite results for a block of %lld points\n",
        static_cast<long long>(block->GetNumberOfPoints()));
      return EXIT_FAILURE;
    }
    compositeRadiance.push_back(radiance);
  }
  // Three vertex-buffer helpers: the blocks' arrays differ.
  const int helpers = composite->GetNumberOfGIUpdates();
  if (helpers != 3)
  {
    std::printf("expected three helpers' GI passes, got %d\n", helpers);
    ++failures;
  }

  // Every block lit; the ground's point under the sphere in its shadow.
  for (std::size_t b = 0; b < blocks.size(); ++b)
  {
    double sum = 0.0;
    for (vtkIdType i = 0; i < compositeRadiance[b]->GetNumberOfTuples(); ++i)
    {
      sum += compositeRadiance[b]->GetComponent(i, 0);
    }
    const double mean = sum / compositeRadiance[b]->GetNumberOfTuples();
    std::printf("block %zu: mean red %.4f\n", b, mean);
    if (!(mean > 0.05) || !std::isfinite(mean))
    {
      ++failures;
    }
  }
  {
    const vtkIdType under = blocks[0]->FindPoint(0, 0, 0);
    const vtkIdType far = blocks[0]->FindPoint(-2, -2, 0);
    const double shadowed = compositeRadiance[0]->GetComponent(under, 0);
    const double open = compositeRadiance[0]->GetComponent(far, 0);
    std::printf("ground under the sphere %.4f, at the corner %.4f\n", shadowed, open);
    if (!(shadowed < 0.8 * open))
    {
      ++failures;
    }
  }

  // Camera moves reuse the GI.
  renderer->GetActiveCamera()->Azimuth(30);
  window->Render();
  if (composite->GetNumberOfGIUpdates() != helpers)
  {
    std::printf("a camera move recomputed the GI: %d passes\n", composite->GetNumberOfGIUpdates());
    ++failures;
  }
  renderer->GetActiveCamera()->Azimuth(-30);

  // New proxies: every helper recomputes; one block changed: its helper only.
  composite->SetProxies(pgitest::HardProxies({ { 0.5, 0, 1.0, 0.5, 0 } }));
  window->Render();
  const int afterProxies = composite->GetNumberOfGIUpdates();
  blocks[1]->GetPoints()->Modified();
  blocks[1]->Modified();
  window->Render();
  const int afterBlock = composite->GetNumberOfGIUpdates();
  composite->SetProxies(proxies);
  window->Render();
  const int afterRestore = composite->GetNumberOfGIUpdates();
  std::printf("passes: %d, after new proxies %d, after one block changed %d, after the first "
              "proxies again %d\n",
    helpers, afterProxies, afterBlock, afterRestore);
  if (afterProxies != 2 * helpers || afterBlock != afterProxies + 1 ||
    afterRestore != afterBlock + helpers)
  {
    ++failures;
  }

  // The plain mapper, one actor per block, on the same view.
  renderer->RemoveActor(compositeActor);
  std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> plain;
  for (vtkPolyData* block : blocks)
  {
    auto mapper = vtkSmartPointer<vtkPGIGIPolyDataMapper>::New();
    mapper->SetInputData(block);
    mapper->SetProxies(proxies);
    mapper->GetSettings()->IndirectOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    plain.push_back(mapper);
  }
  window->Render();
  vtkSmartPointer<vtkImageData> plainImage = Snapshot(window);
  double worst = 0.0;
  for (std::size_t b = 0; b < blocks.size(); ++b)
  {
    vtkNew<vtkFloatArray> radiance;
    plain[b]->GetPerVertexResults(radiance);
    for (vtkIdType i = 0; i < radiance->GetNumberOfValues(); ++i)
    {
      worst = std::max(worst,
        std::fabs(double(radiance->GetValue(i)) - double(compositeRadiance[b]->GetValue(i))));
    }
  }
  const int pixels = LargestPixelDifference(compositeImage, plainImage);
  std::printf("composite vs plain mapper: radiance %.3g, pixels %d of 255\n", worst, pixels);
  if (!(worst <= 1e-6) || pixels > 2)
  {
    ++failures;
  }

  std::printf("%s\n", composite->GetGIStatus().c_str());
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
