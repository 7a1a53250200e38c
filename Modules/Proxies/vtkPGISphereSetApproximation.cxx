#include "vtkPGISphereSetApproximation.h"

#include "pgiMeshQueries.h"
#include "pgiParallel.h"
#include "pgiProxyMesh.h"
#include "pgiSphereSetBuilder.h"

#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkPGISphereSetApproximation);

struct vtkPGISphereSetApproximation::Internal
{
  std::vector<double> Ratio, RatioSum, Time;
  proxygi::parallel::Traffic Gather;
};

vtkCxxSetObjectMacro(vtkPGISphereSetApproximation, Controller, vtkMultiProcessController);

vtkPGISphereSetApproximation::vtkPGISphereSetApproximation()
  : Impl(new Internal)
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPGISphereSetApproximation::~vtkPGISphereSetApproximation()
{
  this->SetController(nullptr);
  delete this->Impl;
}

double vtkPGISphereSetApproximation::GetGatherTime() const
{
  return this->Impl->Gather.Seconds;
}

double vtkPGISphereSetApproximation::GetGatheredBytes() const
{
  return static_cast<double>(this->Impl->Gather.BytesReceived);
}

const char* vtkPGISphereSetApproximation::GetMethodName(int method)
{
  switch (method)
  {
    case OCTREE:
      return "octree";
    case KMEANS:
      return "k-means";
    default:
      return "variational";
  }
}

void vtkPGISphereSetApproximation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << GetMethodName(this->Method) << "\n";
  os << indent << "NumberOfSpheres: " << this->NumberOfSpheres << "\n";
  os << indent << "TargetOutsideVolumeRatio: " << this->TargetOutsideVolumeRatio << "\n";
  os << indent << "MaximumNumberOfSpheres: " << this->MaximumNumberOfSpheres << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "SplitConnectedComponents: " << this->SplitConnectedComponents << "\n";
  os << indent << "VolumeResolution: " << this->VolumeResolution << "\n";
  os << indent << "InteriorResolution: " << this->InteriorResolution << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "MaximumTeleportFailures: " << this->MaximumTeleportFailures << "\n";
  os << indent << "ComputeOutsideVolume: " << this->ComputeOutsideVolume << "\n";
  os << indent << "MetricResolution: " << this->MetricResolution << "\n";
  os << indent << "CapDistributedPieces: " << this->CapDistributedPieces << "\n";
  os << indent << "Controller: " << this->Controller << " ("
     << proxygi::parallel::Ranks(this->Controller) << " ranks)\n";
}

int vtkPGISphereSetApproximation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

int vtkPGISphereSetApproximation::GetNumberOfObjects() const
{
  return static_cast<int>(this->Impl->Ratio.size());
}

double vtkPGISphereSetApproximation::GetOutsideVolumeRatio(int object) const
{
  return object >= 0 && object < this->GetNumberOfObjects()
    ? this->Impl->Ratio[object]
    : std::numeric_limits<double>::quiet_NaN();
}

double vtkPGISphereSetApproximation::GetOutsideVolumeRatioSum(int object) const
{
  return object >= 0 && object < this->GetNumberOfObjects()
    ? this->Impl->RatioSum[object]
    : std::numeric_limits<double>::quiet_NaN();
}

double vtkPGISphereSetApproximation::GetBuildTime(int object) const
{
  return object >= 0 && object < this->GetNumberOfObjects() ? this->Impl->Time[object] : 0.0;
}

double vtkPGISphereSetApproximation::GetTotalBuildTime() const
{
  double t = 0.0;
  for (double v : this->Impl->Time)
  {
    t += v;
  }
  return t;
}

namespace
{
struct NamedMesh
{
  proxygi::ProxyMesh Mesh;
  std::string Name;
};

// One object from a polydata; false (with error) on bad input, empty
// polydata (no points) skipped when `skipEmpty`.
bool AddPolyData(vtkPolyData* pd, const std::string& name, std::vector<NamedMesh>& objects,
  std::string& error, std::vector<std::string>& warnings, bool skipEmpty)
{
  if (skipEmpty && (!pd || pd->GetNumberOfPoints() == 0))
  {
    warnings.push_back(name + " is empty: skipped");
    return true;
  }
  NamedMesh object;
  object.Name = name;
  proxygi::ProxyMeshReport report;
  if (!proxygi::ExtractProxyMesh(pd, object.Mesh, report, error))
  {
    error = name + ": " + error;
    return false;
  }
  if (report.IgnoredCells > 0)
  {
    warnings.push_back(name + ": " + std::to_string(report.IgnoredCells) +
      " vertex/line cells ignored (only polygons and strips are bounded)");
  }
  objects.push_back(std::move(object));
  return true;
}

// Under MPI an object's pieces lie on several ranks: object o (by its place
// in each rank's list) gets `total` spheres over all ranks, shared by
// triangle count (largest remainder, ties to the lower rank), at least one
// per non-empty piece so that every piece stays bounded.
std::vector<int> ShareSpheres(
  vtkMultiProcessController* c, const std::vector<NamedMesh>& objects, int total)
{
  const long long most = proxygi::parallel::Max(c, static_cast<double>(objects.size()));
  const int rank = proxygi::parallel::Rank(c);
  std::vector<int> counts(objects.size(), total);
  for (long long o = 0; o < most; ++o)
  {
    const long long mine = o < static_cast<long long>(objects.size())
      ? objects[static_cast<std::size_t>(o)].Mesh.NumberOfTriangles()
      : 0;
    const std::vector<long long> triangles = proxygi::parallel::AllGatherCounts(c, mine);
    long long sum = 0;
    for (long long t : triangles)
    {
      sum += t;
    }
    if (mine == 0 || sum == 0)
    {
      continue;
    }
    const std::size_t ranks = triangles.size();
    std::vector<long long> share(ranks, 0);
    std::vector<double> remainder(ranks, -1.0);
    long long given = 0;
    for (std::size_t r = 0; r < ranks; ++r)
    {
      if (triangles[r] == 0)
      {
        continue;
      }
      const double exact =
        static_cast<double>(total) * static_cast<double>(triangles[r]) / static_cast<double>(sum);
      share[r] = std::max(1LL, static_cast<long long>(std::floor(exact)));
      remainder[r] = exact - std::floor(exact);
      given += share[r];
    }
    while (given < total)
    {
      const auto r = static_cast<std::size_t>(
        std::max_element(remainder.begin(), remainder.end()) - remainder.begin());
      if (remainder[r] < 0.0)
      {
        break;
      }
      ++share[r];
      remainder[r] = -1.0;
      ++given;
    }
    counts[static_cast<std::size_t>(o)] = static_cast<int>(share[static_cast<std::size_t>(rank)]);
  }
  return counts;
}
} // namespace

int vtkPGISphereSetApproximation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->Impl->Ratio.clear();
  this->Impl->RatioSum.clear();
  this->Impl->Time.clear();
  this->Impl->Gather = proxygi::parallel::Traffic();
  vtkMultiProcessController* controller = proxygi::parallel::Active(this->Controller);
  if (!input && !controller)
  {
    vtkErrorMacro("No input.");
    return 0;
  }

  // Gather the objects.
  std::vector<NamedMesh> objects;
  std::vector<std::string> warnings;
  std::string error;
  bool ok = true;
  if (!input)
  {
    error = "no input";
    ok = false;
  }
  else if (auto* pd = vtkPolyData::SafeDownCast(input))
  {
    // Under MPI a rank's piece may be empty (ParaView's readers fill rank 0
    // only): it bounds nothing, and is not worth a warning on every rank.
    if (!controller || pd->GetNumberOfPoints() > 0)
    {
      ok = AddPolyData(pd, "the input mesh", objects, error, warnings, controller != nullptr);
    }
  }
  else if (auto* pdc = vtkPartitionedDataSetCollection::SafeDownCast(input))
  {
    for (unsigned i = 0; ok && i < pdc->GetNumberOfPartitionedDataSets(); ++i)
    {
      vtkPartitionedDataSet* pds = pdc->GetPartitionedDataSet(i);
      std::vector<NamedMesh> parts;
      for (unsigned p = 0; ok && pds && p < pds->GetNumberOfPartitions(); ++p)
      {
        auto* part = vtkPolyData::SafeDownCast(pds->GetPartitionAsDataObject(p));
        if (!part && pds->GetPartitionAsDataObject(p))
        {
          warnings.push_back("partitioned dataset " + std::to_string(i) +
            ": a partition that is not a vtkPolyData is skipped");
        }
        if (part && part->GetNumberOfPoints() > 0)
        {
          ok = AddPolyData(
            part, "partitioned dataset " + std::to_string(i), parts, error, warnings, true);
        }
      }
      if (ok && !parts.empty())
      {
        NamedMesh merged = std::move(parts[0]);
        for (std::size_t p = 1; p < parts.size(); ++p)
        {
          proxygi::AppendMesh(merged.Mesh, parts[p].Mesh);
        }
        merged.Mesh.Analyse();
        objects.push_back(std::move(merged));
      }
    }
  }
  else if (auto* pds = vtkPartitionedDataSet::SafeDownCast(input))
  {
    std::vector<NamedMesh> parts;
    for (unsigned p = 0; ok && p < pds->GetNumberOfPartitions(); ++p)
    {
      auto* part = vtkPolyData::SafeDownCast(pds->GetPartitionAsDataObject(p));
      if (part && part->GetNumberOfPoints() > 0)
      {
        ok = AddPolyData(part, "partition " + std::to_string(p), parts, error, warnings, true);
      }
    }
    if (ok && !parts.empty())
    {
      NamedMesh merged = std::move(parts[0]);
      merged.Name = "the partitioned input";
      for (std::size_t p = 1; p < parts.size(); ++p)
      {
        proxygi::AppendMesh(merged.Mesh, parts[p].Mesh);
      }
      merged.Mesh.Analyse();
      objects.push_back(std::move(merged));
    }
  }
  else if (auto* cd = vtkDataObjectTree::SafeDownCast(input))
  {
    vtkSmartPointer<vtkDataObjectTreeIterator> it;
    it.TakeReference(cd->NewTreeIterator());
    it->VisitOnlyLeavesOn();
    it->SkipEmptyNodesOn();
    int leaf = 0;
    for (it->InitTraversal(); ok && !it->IsDoneWithTraversal(); it->GoToNextItem(), ++leaf)
    {
      auto* part = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
      const std::string name = "block " + std::to_string(it->GetCurrentFlatIndex());
      if (!part)
      {
        warnings.push_back(name + " is not a vtkPolyData: skipped");
        continue;
      }
      ok = AddPolyData(part, name, objects, error, warnings, true);
    }
  }
  else
  {
    error = std::string("unsupported input type ") + input->GetClassName();
    ok = false;
  }
  if (ok && objects.empty() && !controller)
  {
    error = "the input holds no mesh";
    ok = false;
  }
  std::string agreed;
  if (!proxygi::parallel::AllOk(
        controller, ok, "Cannot build sphere proxies: " + error, agreed, &this->Impl->Gather))
  {
    vtkErrorMacro(<< agreed << ".");
    output->Initialize();
    return 0;
  }
  if (this->SplitConnectedComponents)
  {
    std::vector<NamedMesh> split;
    for (NamedMesh& object : objects)
    {
      std::vector<proxygi::ProxyMesh> parts;
      proxygi::SplitComponents(object.Mesh, parts);
      for (std::size_t p = 0; p < parts.size(); ++p)
      {
        NamedMesh m;
        m.Mesh = std::move(parts[p]);
        m.Name = object.Name + (parts.size() > 1 ? ", component " + std::to_string(p) : "");
        split.push_back(std::move(m));
      }
    }
    objects.swap(split);
  }
  if (controller && this->CapDistributedPieces)
  {
    // A piece of a closed object is open along the partition's cut: capped,
    // its inside (and so its interior samples) is defined again.
    for (NamedMesh& object : objects)
    {
      if (object.Mesh.BoundaryEdges > 0)
      {
        proxygi::CapBoundaryLoops(object.Mesh);
      }
    }
  }
  for (const std::string& w : warnings)
  {
    vtkWarningMacro(<< w << ".");
  }

  vtkNew<vtkPoints> centers;
  centers->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> radius, outsideVolume;
  radius->SetName("Radius");
  outsideVolume->SetName("OutsideVolume");
  vtkNew<vtkIntArray> objectId, level;
  objectId->SetName("ObjectId");
  level->SetName("Level");
  vtkNew<vtkIdTypeArray> parent;
  parent->SetName("Parent");
  vtkNew<vtkDoubleArray> ratio, ratioSum, meshVolume;
  ratio->SetName("OutsideVolumeRatio");
  ratioSum->SetName("OutsideVolumeRatioSum");
  meshVolume->SetName("MeshVolume");
  vtkNew<vtkIntArray> sphereCount;
  sphereCount->SetName("SphereCount");

  const int n = static_cast<int>(objects.size());
  const std::vector<int> shares = controller
    ? ShareSpheres(controller, objects, this->NumberOfSpheres)
    : std::vector<int>(objects.size(), this->NumberOfSpheres);
  // Failures inside the loop stop this rank's build; under MPI the ranks
  // agree on them before the gather.
  bool aborted = false;
  for (int o = 0; o < n && ok; ++o)
  {
    const proxygi::ProxyMesh& mesh = objects[o].Mesh;
    const std::string& name = objects[o].Name;
    if (mesh.BoundaryEdges > 0 || mesh.NonManifoldEdges > 0)
    {
      vtkWarningMacro(<< name << " is not a closed manifold (" << mesh.BoundaryEdges
                      << " boundary edges, " << mesh.NonManifoldEdges
                      << " non-manifold edges): its inside is taken by a ray-parity vote; the "
                         "spheres still bound its whole surface.");
    }
    if (mesh.ZeroAreaTriangles > 0)
    {
      vtkWarningMacro(<< name << " has " << mesh.ZeroAreaTriangles
                      << " zero-area triangles (bounded, never hit by rays).");
    }
    // Build time: Embree scene, rows, samples and the clustering itself.
    const auto start = std::chrono::steady_clock::now();
    proxygi::MeshQueries queries(mesh);
    if (!queries.Ok())
    {
      error = "Cannot build sphere proxies of " + name + ": " + queries.Error();
      ok = false;
      break;
    }
    proxygi::SphereSetOptions options;
    options.Method = static_cast<proxygi::SphereMethod>(this->Method);
    options.Seed = this->Seed;
    options.VolumeResolution = this->VolumeResolution;
    options.InteriorResolution = this->InteriorResolution;
    options.MaximumIterations = this->MaximumIterations;
    options.MaximumTeleportFailures = this->MaximumTeleportFailures;
    double span = 1.0, offset = 0.0;
    options.Progress = [this, o, n, &span, &offset](double f)
    {
      this->UpdateProgress((o + offset + span * std::min(1.0, std::max(0.0, f))) / n);
      return !this->GetAbortExecute();
    };
    proxygi::SphereSetBuilder builder(mesh, queries, options);
    const auto t0Setup = std::chrono::steady_clock::now() - start;
    if (!builder.Rows().Solid())
    {
      vtkWarningMacro(<< name << " does not enclose a volume consistently ("
                      << builder.Rows().ResolvedRows() << " of " << builder.Rows().TracedRows()
                      << " rays cross it an odd number of times): only its surface is bounded "
                         "and E is undefined.");
    }
    int count = shares[o];
    const int most = std::min(builder.NumberOfElements(), mesh.NumberOfPoints());
    if (count > most)
    {
      vtkWarningMacro(<< name << ": " << count << " spheres asked, more than its "
                      << mesh.NumberOfPoints() << " vertices (" << mesh.NumberOfTriangles()
                      << " triangles, " << builder.InteriorSamples().size() / 3
                      << " interior samples): building " << most << ".");
      count = most;
    }
    proxygi::SphereSetResult result;
    proxygi::OutsideVolumeMeasure measure;
    const bool target = this->TargetOutsideVolumeRatio > 0.0;
    const int maxCount = std::min(most, std::max(count, this->MaximumNumberOfSpheres));
    double buildTime = 0.0;
    for (int attempt = 0;; ++attempt)
    {
      // The target search cannot know its length: each attempt takes the
      // remaining half of the object's progress.
      span = target ? std::pow(0.5, attempt + 1) : 1.0;
      offset = target ? 1.0 - 2.0 * span : 0.0;
      const auto t0 = std::chrono::steady_clock::now();
      if (!builder.Run(count, result))
      {
        aborted = result.Aborted;
        error = aborted ? "aborted" : "Building sphere proxies of " + name + " failed";
        ok = false;
        break;
      }
      buildTime += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (this->ComputeOutsideVolume || target)
      {
        proxygi::MeasureOutsideVolume(
          mesh, queries, result.Spheres, this->MetricResolution, measure);
      }
      if (!target || !(measure.Ratio > this->TargetOutsideVolumeRatio) || count >= maxCount)
      {
        if (target && measure.Ratio > this->TargetOutsideVolumeRatio)
        {
          vtkWarningMacro(<< name << ": E = " << measure.Ratio << " with " << count
                          << " spheres, the most allowed; target " << this->TargetOutsideVolumeRatio
                          << " not met.");
        }
        break;
      }
      count = std::min(maxCount, std::max(count + 1, static_cast<int>(std::ceil(1.5 * count))));
    }
    if (!ok)
    {
      break;
    }
    buildTime += std::chrono::duration<double>(t0Setup).count();
    this->Impl->Time.push_back(buildTime);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    this->Impl->Ratio.push_back(this->ComputeOutsideVolume ? measure.Ratio : nan);
    this->Impl->RatioSum.push_back(this->ComputeOutsideVolume ? measure.SumRatio : nan);
    ratio->InsertNextValue(this->Impl->Ratio.back());
    ratioSum->InsertNextValue(this->Impl->RatioSum.back());
    meshVolume->InsertNextValue(result.MeshVolume);
    sphereCount->InsertNextValue(static_cast<int>(result.Spheres.size()));
    for (std::size_t i = 0; i < result.Spheres.size(); ++i)
    {
      const proxygi::Sphere& s = result.Spheres[i];
      centers->InsertNextPoint(s.Center);
      radius->InsertNextValue(s.Radius);
      objectId->InsertNextValue(o);
      level->InsertNextValue(0);
      parent->InsertNextValue(-1);
      outsideVolume->InsertNextValue(this->ComputeOutsideVolume && i < measure.SphereOutside.size()
          ? measure.SphereOutside[i]
          : nan);
    }
  }
  if (!proxygi::parallel::AllOk(controller, ok, error, agreed, &this->Impl->Gather))
  {
    output->Initialize();
    if (aborted && !controller)
    {
      return 1;
    }
    vtkErrorMacro(<< agreed << ".");
    return 0;
  }
  output->SetPoints(centers);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < centers->GetNumberOfPoints(); ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  output->SetVerts(verts);
  output->GetPointData()->AddArray(radius);
  output->GetPointData()->SetActiveScalars("Radius");
  output->GetPointData()->AddArray(objectId);
  output->GetPointData()->AddArray(level);
  output->GetPointData()->AddArray(parent);
  if (this->ComputeOutsideVolume)
  {
    output->GetPointData()->AddArray(outsideVolume);
  }
  output->GetFieldData()->AddArray(ratio);
  output->GetFieldData()->AddArray(ratioSum);
  output->GetFieldData()->AddArray(meshVolume);
  output->GetFieldData()->AddArray(sphereCount);
  if (controller)
  {
    // Every rank shades against every rank's spheres.
    std::string gatherError;
    vtkSmartPointer<vtkPolyData> global =
      proxygi::parallel::GatherProxies(controller, output, gatherError, &this->Impl->Gather);
    if (!global)
    {
      vtkErrorMacro(<< gatherError << ".");
      output->Initialize();
      return 0;
    }
    output->ShallowCopy(global);
  }
  this->UpdateProgress(1.0);
  return 1;
}
