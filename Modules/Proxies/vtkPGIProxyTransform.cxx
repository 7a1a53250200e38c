#include "vtkPGIProxyTransform.h"

#include "pgiSphereMath.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLinearTransform.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <map>

vtkStandardNewMacro(vtkPGIProxyTransform);
vtkCxxSetObjectMacro(vtkPGIProxyTransform, Transform, vtkLinearTransform);

struct vtkPGIProxyTransform::Internal
{
  std::map<int, vtkSmartPointer<vtkLinearTransform>> PerObject;
};

vtkPGIProxyTransform::vtkPGIProxyTransform()
  : Impl(new Internal)
{
}

vtkPGIProxyTransform::~vtkPGIProxyTransform()
{
  this->SetTransform(nullptr);
  delete this->Impl;
}

void vtkPGIProxyTransform::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Transform: " << this->Transform << "\n";
  os << indent << "ObjectTransforms: " << this->Impl->PerObject.size() << "\n";
}

void vtkPGIProxyTransform::SetObjectTransform(int objectId, vtkLinearTransform* transform)
{
  if (transform)
  {
    this->Impl->PerObject[objectId] = transform;
  }
  else
  {
    this->Impl->PerObject.erase(objectId);
  }
  this->Modified();
}

vtkLinearTransform* vtkPGIProxyTransform::GetObjectTransform(int objectId)
{
  auto it = this->Impl->PerObject.find(objectId);
  return it == this->Impl->PerObject.end() ? nullptr : it->second.Get();
}

void vtkPGIProxyTransform::RemoveAllObjectTransforms()
{
  this->Impl->PerObject.clear();
  this->Modified();
}

vtkMTimeType vtkPGIProxyTransform::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Transform)
  {
    t = std::max(t, this->Transform->GetMTime());
  }
  for (const auto& entry : this->Impl->PerObject)
  {
    t = std::max(t, entry.second->GetMTime());
  }
  return t;
}

int vtkPGIProxyTransform::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->ShallowCopy(input);
  const vtkIdType n = input->GetNumberOfPoints();
  if (n == 0)
  {
    return 1;
  }
  vtkDataArray* radius = input->GetPointData()->GetArray("Radius");
  if (!radius)
  {
    vtkErrorMacro("Proxies need a \"Radius\" point array.");
    output->Initialize();
    return 0;
  }
  vtkDataArray* objects = input->GetPointData()->GetArray("ObjectId");
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(n);
  bool nonUniform = false;
  // Stretch per transform, computed once.
  std::map<vtkLinearTransform*, double> stretch;
  auto stretchOf = [&](vtkLinearTransform* t)
  {
    auto it = stretch.find(t);
    if (it != stretch.end())
    {
      return it->second;
    }
    double m[3][3];
    vtkMatrix4x4* matrix = t->GetMatrix();
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        m[a][b] = matrix->GetElement(a, b);
      }
    }
    const double hi = proxygi::LargestStretch(m), lo = proxygi::SmallestStretch(m);
    nonUniform = nonUniform || hi - lo > 1e-9 * hi;
    return stretch[t] = hi;
  };
  for (vtkIdType i = 0; i < n; ++i)
  {
    vtkLinearTransform* t = this->Transform;
    if (objects && !this->Impl->PerObject.empty())
    {
      auto it = this->Impl->PerObject.find(static_cast<int>(objects->GetTuple1(i)));
      if (it != this->Impl->PerObject.end())
      {
        t = it->second;
      }
    }
    double c[3];
    input->GetPoint(i, c);
    double r = radius->GetTuple1(i);
    if (t)
    {
      double moved[3];
      t->TransformPoint(c, moved);
      std::copy(moved, moved + 3, c);
      r *= stretchOf(t);
    }
    points->SetPoint(i, c);
    radii->SetValue(i, r);
  }
  if (nonUniform)
  {
    vtkWarningMacro("The transform scales non-uniformly or shears: radii grow by its largest "
                    "stretch, so the spheres still bound but more loosely.");
  }
  output->SetPoints(points);
  const bool active = input->GetPointData()->GetScalars() == radius;
  output->GetPointData()->RemoveArray("Radius");
  output->GetPointData()->AddArray(radii);
  if (active)
  {
    output->GetPointData()->SetActiveScalars("Radius");
  }
  return 1;
}
