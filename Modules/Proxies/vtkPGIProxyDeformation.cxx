#include "vtkPGIProxyDeformation.h"

#include "pgiMeshQueries.h"
#include "pgiProxyMesh.h"
#include "pgiProxyMetrics.h"
#include "pgiSphereTree.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkPGIProxyDeformation);

struct vtkPGIProxyDeformation::Internal
{
  vtkMTimeType ProxiesTime = 0, RestTime = 0;
  vtkPolyData* Proxies = nullptr;
  vtkPolyData* Rest = nullptr;
  std::vector<std::vector<vtkIdType>> Bound; // rest-mesh point ids per proxy point
};

vtkPGIProxyDeformation::vtkPGIProxyDeformation()
  : Impl(new Internal)
{
  this->SetNumberOfInputPorts(3);
}

vtkPGIProxyDeformation::~vtkPGIProxyDeformation()
{
  delete this->Impl;
}

void vtkPGIProxyDeformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MeasureBoundingLoss: " << this->MeasureBoundingLoss << "\n";
  os << indent << "SurfaceSubdivisions: " << this->SurfaceSubdivisions << "\n";
}

int vtkPGIProxyDeformation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkPGIProxyDeformation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* proxies = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* rest = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* deformed = vtkPolyData::GetData(inputVector[2], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!proxies || !rest || !deformed)
  {
    vtkErrorMacro("Needs the proxies (port 0), the rest mesh (port 1) and the deformed mesh "
                  "(port 2).");
    return 0;
  }
  if (rest->GetNumberOfPoints() != deformed->GetNumberOfPoints())
  {
    vtkErrorMacro("The deformed mesh has " << deformed->GetNumberOfPoints()
                                           << " points, the rest mesh " << rest->GetNumberOfPoints()
                                           << ": they must match.");
    return 0;
  }
  std::vector<proxygi::Sphere> nodes;
  std::vector<int> level;
  std::vector<long long> parent;
  std::string error;
  if (!proxygi::GetSphereTree(proxies, nodes, level, parent, error))
  {
    vtkErrorMacro("Bad proxies: " << error << ".");
    return 0;
  }
  vtkDataArray* sphereObject = proxies->GetPointData()->GetArray("ObjectId");
  vtkDataArray* pointObject = rest->GetPointData()->GetArray("ObjectId");

  // Binding: which rest vertices each leaf follows (cached).
  Internal& s = *this->Impl;
  if (s.Proxies != proxies || s.Rest != rest || s.ProxiesTime != proxies->GetMTime() ||
    s.RestTime != rest->GetMTime() || s.Bound.size() != nodes.size())
  {
    proxygi::ProxyMesh mesh;
    proxygi::ProxyMeshReport report;
    std::vector<vtkIdType> inputIds;
    if (!proxygi::ExtractProxyMesh(rest, mesh, report, error, &inputIds))
    {
      vtkErrorMacro("Bad rest mesh: " << error << ".");
      return 0;
    }
    proxygi::MeshQueries queries(mesh);
    if (!queries.Ok())
    {
      vtkErrorMacro(<< queries.Error() << ".");
      return 0;
    }
    // Plain copies: vtkDataArray::GetTuple1 is not thread-safe.
    std::vector<double> pointObjects, sphereObjects;
    if (pointObject && sphereObject)
    {
      for (vtkIdType v = 0; v < rest->GetNumberOfPoints(); ++v)
      {
        pointObjects.push_back(pointObject->GetTuple1(v));
      }
      for (vtkIdType i = 0; i < proxies->GetNumberOfPoints(); ++i)
      {
        sphereObjects.push_back(sphereObject->GetTuple1(i));
      }
    }
    s.Bound.assign(nodes.size(), std::vector<vtkIdType>());
    vtkSMPTools::For(0, static_cast<vtkIdType>(nodes.size()),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          if (level[i] != 0)
          {
            continue;
          }
          const proxygi::Sphere& sphere = nodes[i];
          auto ownObject = [&](vtkIdType v)
          { return pointObjects.empty() || pointObjects[v] == sphereObjects[i]; };
          const double r2 = sphere.Radius * sphere.Radius * (1.0 + 1e-9);
          for (int v = 0; v < mesh.NumberOfPoints(); ++v)
          {
            const double* p = mesh.Point(v);
            const double dx = p[0] - sphere.Center[0], dy = p[1] - sphere.Center[1],
                         dz = p[2] - sphere.Center[2];
            if (dx * dx + dy * dy + dz * dz <= r2 && ownObject(inputIds[v]))
            {
              s.Bound[i].push_back(inputIds[v]);
            }
          }
          if (s.Bound[i].size() < 3)
          {
            double q[3];
            int triangle = -1;
            queries.ClosestPoint(sphere.Center, q, triangle);
            if (triangle >= 0)
            {
              for (int k = 0; k < 3; ++k)
              {
                const vtkIdType v = inputIds[mesh.Triangles[3 * triangle + k]];
                if (std::find(s.Bound[i].begin(), s.Bound[i].end(), v) == s.Bound[i].end())
                {
                  s.Bound[i].push_back(v);
                }
              }
            }
          }
        }
      });
    s.Proxies = proxies;
    s.Rest = rest;
    s.ProxiesTime = proxies->GetMTime();
    s.RestTime = rest->GetMTime();
  }
  this->UpdateProgress(0.5);

  // Move each leaf with the rigid best fit of its vertices.
  vtkSMPTools::For(0, static_cast<vtkIdType>(nodes.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> a, b;
      for (vtkIdType i = begin; i < end; ++i)
      {
        const std::vector<vtkIdType>& bound = s.Bound[i];
        if (level[i] != 0 || bound.empty())
        {
          continue;
        }
        a.resize(3 * bound.size());
        b.resize(3 * bound.size());
        for (std::size_t j = 0; j < bound.size(); ++j)
        {
          rest->GetPoint(bound[j], a.data() + 3 * j);
          deformed->GetPoint(bound[j], b.data() + 3 * j);
        }
        double r[3][3], ma[3], mb[3];
        proxygi::BestRigidMotion(a.data(), b.data(), bound.size(), r, ma, mb);
        const double d[3] = { nodes[i].Center[0] - ma[0], nodes[i].Center[1] - ma[1],
          nodes[i].Center[2] - ma[2] };
        for (int k = 0; k < 3; ++k)
        {
          nodes[i].Center[k] = mb[k] + r[k][0] * d[0] + r[k][1] * d[1] + r[k][2] * d[2];
        }
      }
    });
  proxygi::RefitSphereTree(nodes, level, parent);

  output->DeepCopy(proxies);
  vtkNew<vtkPoints> points; // double: centres move by fractions of a float ulp
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(nodes.size()));
  output->SetPoints(points);
  proxygi::SetSphereGeometry(output, nodes);
  if (this->MeasureBoundingLoss)
  {
    proxygi::CoverageMeasure coverage;
    if (!proxygi::MeasureSurfaceCoverage(
          deformed, output, this->SurfaceSubdivisions, coverage, error))
    {
      vtkErrorMacro("Cannot measure the bounding loss: " << error << ".");
      return 0;
    }
    auto add = [output](const char* name, double value)
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(name);
      a->InsertNextValue(value);
      output->GetFieldData()->AddArray(a);
    };
    add("SurfaceOutsideFraction",
      coverage.Samples ? static_cast<double>(coverage.Outside) / coverage.Samples : 0.0);
    add("SurfaceGapMaximum", coverage.MaximumGap);
    add("SurfaceGapMean", coverage.MeanGap);
  }
  this->UpdateProgress(1.0);
  return 1;
}
