#include "vtkPGISurfaceRepresentation.h"

#include "pgiParallel.h"
#include "vtkAppendPolyData.h"
#include "vtkCompositeDataSet.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPGIGICompositePolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGILighting.h"
#include "vtkPGISphereSetApproximation.h"
#include "vtkPVRenderView.h"
#include "vtkPVView.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkPGISurfaceRepresentation);

namespace
{
vtkPGIGICompositePolyDataMapper* GIMapper(vtkMapper* mapper)
{
  return static_cast<vtkPGIGICompositePolyDataMapper*>(mapper);
}
} // namespace

vtkPGISurfaceRepresentation::vtkPGISurfaceRepresentation()
{
  this->SetNumberOfInputPorts(2);
  // Replace the superclass's mappers, then redo its pipeline set-up.
  this->Mapper->Delete();
  this->LODMapper->Delete();
  auto* mapper = vtkPGIGICompositePolyDataMapper::New();
  auto* lod = vtkPGIGICompositePolyDataMapper::New();
  lod->SetSettings(mapper->GetSettings());
  this->Mapper = mapper;
  this->LODMapper = lod;
  this->SetupDefaults();
  this->Proxies = vtkSmartPointer<vtkPolyData>::New();
}

vtkPGISurfaceRepresentation::~vtkPGISurfaceRepresentation() = default;

int vtkPGISurfaceRepresentation::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

void vtkPGISurfaceRepresentation::SetSettings(vtkPGIGISettings* settings)
{
  GIMapper(this->Mapper)->SetSettings(settings);
  GIMapper(this->LODMapper)->SetSettings(settings);
}

void vtkPGISurfaceRepresentation::SetLighting(vtkPGILighting* lighting)
{
  GIMapper(this->Mapper)->SetLighting(lighting);
  GIMapper(this->LODMapper)->SetLighting(lighting);
}

void vtkPGISurfaceRepresentation::SetNumberOfAutomaticProxies(int spheres)
{
  spheres = std::max(0, spheres);
  if (spheres != this->NumberOfAutomaticProxies)
  {
    this->NumberOfAutomaticProxies = spheres;
    this->MarkModified();
  }
}

void vtkPGISurfaceRepresentation::SetExposure(double exposure)
{
  GIMapper(this->Mapper)->SetExposure(exposure);
  GIMapper(this->LODMapper)->SetExposure(exposure);
}

void vtkPGISurfaceRepresentation::SetCombineWithVTKLighting(bool on)
{
  GIMapper(this->Mapper)->SetCombineWithVTKLighting(on);
  GIMapper(this->LODMapper)->SetCombineWithVTKLighting(on);
}

void vtkPGISurfaceRepresentation::SetAlwaysRecompute(bool on)
{
  GIMapper(this->Mapper)->SetAlwaysRecompute(on);
  GIMapper(this->LODMapper)->SetAlwaysRecompute(on);
}

void vtkPGISurfaceRepresentation::SetErrorBudget(double fraction)
{
  GIMapper(this->Mapper)->SetErrorBudget(fraction);
  GIMapper(this->LODMapper)->SetErrorBudget(fraction);
}

void vtkPGISurfaceRepresentation::SetTimeBudget(double seconds)
{
  GIMapper(this->Mapper)->SetTimeBudget(seconds);
  GIMapper(this->LODMapper)->SetTimeBudget(seconds);
}

void vtkPGISurfaceRepresentation::SetBudgetModelFileName(const char* fileName)
{
  GIMapper(this->Mapper)->SetBudgetModelFileName(fileName);
  GIMapper(this->LODMapper)->SetBudgetModelFileName(fileName);
}

void vtkPGISurfaceRepresentation::AddBlockerPlane(
  double ox, double oy, double oz, double nx, double ny, double nz, double ar, double ag, double ab)
{
  const double origin[3] = { ox, oy, oz }, normal[3] = { nx, ny, nz }, albedo[3] = { ar, ag, ab };
  GIMapper(this->Mapper)->AddBlockerPlane(origin, normal, albedo);
  GIMapper(this->LODMapper)->AddBlockerPlane(origin, normal, albedo);
}

void vtkPGISurfaceRepresentation::RemoveAllBlockerPlanes()
{
  GIMapper(this->Mapper)->RemoveAllBlockerPlanes();
  GIMapper(this->LODMapper)->RemoveAllBlockerPlanes();
}

vtkPolyData* vtkPGISurfaceRepresentation::GetProxies()
{
  return this->Proxies;
}

const char* vtkPGISurfaceRepresentation::GetGIStatus()
{
  this->GIStatus = GIMapper(this->Mapper)->GetGIStatus();
  return this->GIStatus.c_str();
}

int vtkPGISurfaceRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkPolyData* connected = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkPolyData::GetData(inputVector[1], 0)
    : nullptr;
  // Under MPI (pvbatch, pvserver) every data-server rank runs this with its
  // own piece; the proxies are made global here, so each rank's mapper
  // shades its piece against all of them.
  vtkMultiProcessController* controller =
    proxygi::parallel::Active(vtkMultiProcessController::GetGlobalController());
  if (connected)
  {
    this->Proxies = vtkSmartPointer<vtkPolyData>::New();
    this->Proxies->ShallowCopy(connected);
  }
  else
  {
    // ParaView marks a representation modified on any property change:
    // fit again only when the data or the sphere count changed (on any rank).
    vtkDataObject* input = inputVector[0]->GetNumberOfInformationObjects() > 0
      ? vtkDataObject::GetData(inputVector[0], 0)
      : nullptr;
    const vtkMTimeType inputTime = input ? input->GetMTime() : 0;
    if (proxygi::parallel::AnyTrue(controller,
          input != this->FittedInput || inputTime != this->FittedTime ||
            this->NumberOfAutomaticProxies != this->FittedCount || this->FittedConnected))
    {
      this->FitAutomaticProxies(controller);
      this->FittedInput = input;
      this->FittedTime = inputTime;
      this->FittedCount = this->NumberOfAutomaticProxies;
    }
  }
  this->FittedConnected = connected != nullptr;
  std::string error;
  vtkSmartPointer<vtkPolyData> global =
    proxygi::parallel::GatherProxies(controller, this->Proxies, error);
  if (!global)
  {
    vtkErrorMacro(<< "GI proxies: " << error << ".");
    this->Proxies = vtkSmartPointer<vtkPolyData>::New();
    return 1;
  }
  this->Proxies = global;
  return 1;
}

void vtkPGISurfaceRepresentation::FitAutomaticProxies(vtkMultiProcessController* controller)
{
  vtkDataObject* surface = this->MultiBlockMaker->GetOutputDataObject(0);
  std::vector<vtkPolyData*> blocks, pieces;
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(surface))
  {
    for (vtkDataSet* block : vtkCompositeDataSet::GetDataSets(composite))
    {
      if (auto* polydata = vtkPolyData::SafeDownCast(block))
      {
        blocks.push_back(polydata);
      }
    }
  }
  else if (auto* polydata = vtkPolyData::SafeDownCast(surface))
  {
    blocks.push_back(polydata);
  }
  for (vtkPolyData* block : blocks)
  {
    // A flat block (a ground, a slice) bounds no volume: spheres fitted to
    // it would be blobs of shadow on it. It receives light but casts none.
    double b[6];
    block->GetBounds(b);
    const double extent[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
    const double largest = std::max({ extent[0], extent[1], extent[2] });
    const double thinnest = std::min({ extent[0], extent[1], extent[2] });
    if (block->GetNumberOfPolys() > 0 && largest > 0.0 && thinnest > 0.01 * largest)
    {
      pieces.push_back(block);
    }
  }
  this->Proxies = vtkSmartPointer<vtkPolyData>::New();
  // Under MPI the count is shared by the ranks' triangles (every rank
  // takes part in the count, even with nothing to fit).
  long long triangles = 0;
  for (vtkPolyData* piece : pieces)
  {
    triangles += piece->GetNumberOfPolys();
  }
  const std::vector<long long> all = proxygi::parallel::AllGatherCounts(controller, triangles);
  long long total = 0;
  for (long long t : all)
  {
    total += t;
  }
  int count = this->NumberOfAutomaticProxies;
  if (controller && total > 0 && triangles > 0)
  {
    count = std::max(1,
      static_cast<int>(std::lround(
        static_cast<double>(count) * static_cast<double>(triangles) / static_cast<double>(total))));
  }
  if (this->NumberOfAutomaticProxies == 0 || pieces.empty())
  {
    return;
  }
  vtkNew<vtkAppendPolyData> append;
  for (vtkPolyData* piece : pieces)
  {
    // Positions and cells only: the blocks' arrays need not match.
    auto bare = vtkSmartPointer<vtkPolyData>::New();
    bare->SetPoints(piece->GetPoints());
    bare->SetPolys(piece->GetPolys());
    append->AddInputData(bare);
  }
  vtkNew<vtkPGISphereSetApproximation> fit;
  fit->SetController(nullptr); // this rank's share; gathered by RequestData
  fit->SetInputConnection(append->GetOutputPort());
  fit->SetMethodToKMeans();
  fit->SetNumberOfSpheres(count);
  fit->SetSeed(1);
  fit->Update();
  this->Proxies->ShallowCopy(fit->GetOutput());
}

int vtkPGISurfaceRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    // The proxies travel to the rendering processes as a second piece.
    // Under MPI every rank holds the global set already: only rank 0's
    // travels, so that a client rendering locally gets it once.
    vtkMultiProcessController* controller =
      proxygi::parallel::Active(vtkMultiProcessController::GetGlobalController());
    vtkNew<vtkPolyData> none;
    vtkPVView::SetPiece(inInfo, this,
      !controller || controller->GetLocalProcessId() == 0 ? this->Proxies.Get() : none.Get(), 0, 1);
    // The light (an environment file the server reads) lives where the
    // data does: a client would draw the delivered geometry without it, so
    // with a server the frame is drawn there (ignored without one).
    vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    // Server ranks under MPI shade with their own (global) copy.
    auto* proxies = proxygi::parallel::Active(vtkMultiProcessController::GetGlobalController())
      ? this->Proxies.Get()
      : vtkPolyData::SafeDownCast(vtkPVView::GetDeliveredPiece(inInfo, this, 1));
    GIMapper(this->Mapper)->SetProxies(proxies);
    GIMapper(this->LODMapper)->SetProxies(proxies);
  }
  return 1;
}

void vtkPGISurfaceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfAutomaticProxies: " << this->NumberOfAutomaticProxies << "\n";
  os << indent << "Proxies: " << this->Proxies->GetNumberOfPoints() << " spheres\n";
  os << indent << "GIStatus: " << this->GetGIStatus() << "\n";
}
