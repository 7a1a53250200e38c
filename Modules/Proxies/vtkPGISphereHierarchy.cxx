#include "vtkPGISphereHierarchy.h"

#include "pgiProxyMetrics.h"
#include "pgiSphereTree.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <limits>
#include <map>

vtkStandardNewMacro(vtkPGISphereHierarchy);

vtkPGISphereHierarchy::vtkPGISphereHierarchy() = default;
vtkPGISphereHierarchy::~vtkPGISphereHierarchy() = default;

void vtkPGISphereHierarchy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Branching: " << this->Branching << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}

bool vtkPGISphereHierarchy::Refit(vtkPolyData* proxies)
{
  std::vector<proxygi::Sphere> nodes;
  std::vector<int> level;
  std::vector<long long> parent;
  std::string error;
  if (!proxygi::GetSphereTree(proxies, nodes, level, parent, error))
  {
    return false;
  }
  proxygi::RefitSphereTree(nodes, level, parent);
  proxygi::SetSphereGeometry(proxies, nodes);
  return true;
}

double vtkPGISphereHierarchy::GetMaximumBoundingViolation(vtkPolyData* proxies)
{
  std::vector<proxygi::Sphere> nodes;
  std::vector<int> level;
  std::vector<long long> parent;
  std::string error;
  if (!proxygi::GetSphereTree(proxies, nodes, level, parent, error))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return proxygi::AnalyseSphereTree(nodes, level, parent).MaximumViolation;
}

int vtkPGISphereHierarchy::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  std::vector<proxygi::Sphere> leaves;
  std::vector<int> objects;
  std::vector<long long> ids;
  std::string error;
  if (!proxygi::GetLeafSpheres(input, leaves, error, &objects, &ids))
  {
    vtkErrorMacro("Cannot build a hierarchy: " << error << ".");
    return 0;
  }
  // Leaves of each object, in input order.
  std::map<int, std::vector<int>> byObject;
  for (std::size_t i = 0; i < leaves.size(); ++i)
  {
    byObject[objects[i]].push_back(static_cast<int>(i));
  }
  std::vector<proxygi::Sphere> nodes(leaves);
  std::vector<int> level(leaves.size(), 0), object(objects);
  std::vector<long long> parent(leaves.size(), -1);
  vtkNew<vtkIntArray> depthArray;
  depthArray->SetName("HierarchyDepth");
  vtkNew<vtkDoubleArray> branchingArray;
  branchingArray->SetName("MeanBranching");
  int done = 0;
  for (const auto& entry : byObject)
  {
    std::vector<proxygi::Sphere> tree;
    for (int i : entry.second)
    {
      tree.push_back(leaves[i]);
    }
    std::vector<int> treeLevel;
    std::vector<long long> treeParent;
    proxygi::BuildSphereTree(tree, treeLevel, treeParent, this->Branching, this->Seed);
    // Tree index -> output index: leaves map back, parents are appended.
    const std::size_t nl = entry.second.size();
    std::vector<long long> map(tree.size());
    for (std::size_t i = 0; i < nl; ++i)
    {
      map[i] = entry.second[i];
    }
    for (std::size_t i = nl; i < tree.size(); ++i)
    {
      map[i] = static_cast<long long>(nodes.size());
      nodes.push_back(tree[i]);
      level.push_back(treeLevel[i]);
      parent.push_back(-1);
      object.push_back(entry.first);
    }
    for (std::size_t i = 0; i < tree.size(); ++i)
    {
      parent[map[i]] = treeParent[i] < 0 ? -1 : map[treeParent[i]];
    }
    const proxygi::SphereTreeStats stats = proxygi::AnalyseSphereTree(tree, treeLevel, treeParent);
    depthArray->InsertNextValue(stats.Depth);
    branchingArray->InsertNextValue(stats.MeanBranching);
    this->UpdateProgress(static_cast<double>(++done) / byObject.size());
    if (this->GetAbortExecute())
    {
      output->Initialize();
      return 1;
    }
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(nodes.size()));
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  radius->SetNumberOfTuples(points->GetNumberOfPoints());
  vtkNew<vtkIntArray> objectId, levelArray;
  objectId->SetName("ObjectId");
  levelArray->SetName("Level");
  objectId->SetNumberOfTuples(points->GetNumberOfPoints());
  levelArray->SetNumberOfTuples(points->GetNumberOfPoints());
  vtkNew<vtkIdTypeArray> parentArray;
  parentArray->SetName("Parent");
  parentArray->SetNumberOfTuples(points->GetNumberOfPoints());
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    const vtkIdType id = static_cast<vtkIdType>(i);
    points->SetPoint(id, nodes[i].Center);
    radius->SetValue(id, nodes[i].Radius);
    objectId->SetValue(id, object[i]);
    levelArray->SetValue(id, level[i]);
    parentArray->SetValue(id, static_cast<vtkIdType>(parent[i]));
  }
  // Other leaf arrays pass on; parents get zeros there.
  vtkPointData* inPD = input->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  for (const char* name : { "Radius", "ObjectId", "Level", "Parent" })
  {
    outPD->CopyFieldOff(name);
  }
  outPD->CopyAllocate(inPD, points->GetNumberOfPoints());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    outPD->CopyData(inPD, static_cast<vtkIdType>(ids[i]), static_cast<vtkIdType>(i));
  }
  for (std::size_t i = ids.size(); i < nodes.size(); ++i)
  {
    outPD->NullData(static_cast<vtkIdType>(i));
  }
  output->SetPoints(points);
  outPD->AddArray(radius);
  outPD->SetActiveScalars("Radius");
  outPD->AddArray(objectId);
  outPD->AddArray(levelArray);
  outPD->AddArray(parentArray);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  output->SetVerts(verts);
  output->GetFieldData()->PassData(input->GetFieldData());
  output->GetFieldData()->AddArray(depthArray);
  output->GetFieldData()->AddArray(branchingArray);
  return 1;
}
