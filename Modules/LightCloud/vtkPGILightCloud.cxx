#include "vtkPGILightCloud.h"

#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <cmath>
#include <cstring>

vtkStandardNewMacro(vtkPGILightCloud);

vtkPGILightCloud::vtkPGILightCloud()
  : Positions(vtkSmartPointer<vtkPoints>::New())
  , Response(std::make_shared<std::vector<float>>())
  , Zones(std::make_shared<std::vector<Zone>>())
{
  this->Positions->SetDataTypeToDouble();
}

vtkPGILightCloud::~vtkPGILightCloud() = default;

void vtkPGILightCloud::Allocate(vtkIdType lights, vtkIdType receivers, int coefficients)
{
  this->Coefficients = std::max(1, coefficients);
  lights = std::max<vtkIdType>(0, lights);
  receivers = std::max<vtkIdType>(0, receivers);
  this->Positions = vtkSmartPointer<vtkPoints>::New();
  this->Positions->SetDataTypeToDouble();
  this->Positions->SetNumberOfPoints(lights);
  for (vtkIdType j = 0; j < lights; ++j)
  {
    this->Positions->SetPoint(j, 0.0, 0.0, 0.0);
  }
  this->Receivers = receivers;
  this->Response = std::make_shared<std::vector<float>>(
    static_cast<std::size_t>(this->GetValuesPerReceiver() * lights * receivers), 0.0f);
  this->Zones = std::make_shared<std::vector<Zone>>();
  this->Spacing = -1.0;
  this->Modified();
}

void vtkPGILightCloud::SetZones(std::vector<Zone> zones)
{
  this->Zones = std::make_shared<std::vector<Zone>>(std::move(zones));
  this->Response = std::make_shared<std::vector<float>>();
  this->Modified();
}

double vtkPGILightCloud::GetCoefficientsPerReceiver() const
{
  if (!this->IsCompressed())
  {
    return static_cast<double>(this->GetValuesPerReceiver()) * this->GetNumberOfLights();
  }
  double weights = 0.0;
  for (const Zone& zone : *this->Zones)
  {
    weights += static_cast<double>(zone.Weights.size());
  }
  return this->Receivers > 0 ? weights / this->Receivers + 1.0 : 0.0;
}

vtkIdType vtkPGILightCloud::GetNumberOfLights() const
{
  return this->Positions->GetNumberOfPoints();
}

float* vtkPGILightCloud::GetResponse(vtkIdType light)
{
  return this->Response->empty()
    ? nullptr
    : this->Response->data() + this->GetValuesPerReceiver() * light * this->Receivers;
}

const float* vtkPGILightCloud::GetResponse(vtkIdType light) const
{
  return this->Response->empty()
    ? nullptr
    : this->Response->data() + this->GetValuesPerReceiver() * light * this->Receivers;
}

std::uint64_t vtkPGILightCloud::ReceiverKeyOf(vtkPolyData* receivers)
{
  // FNV-1a over the point count and the coordinates as floats.
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t bytes)
  {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
    {
      h = (h ^ b[i]) * 1099511628211ull;
    }
  };
  const vtkIdType n = receivers ? receivers->GetNumberOfPoints() : 0;
  const long long count = n;
  mix(&count, sizeof(count));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    receivers->GetPoint(i, p);
    const float f[3] = { static_cast<float>(p[0]), static_cast<float>(p[1]),
      static_cast<float>(p[2]) };
    mix(f, sizeof(f));
  }
  return h;
}

double vtkPGILightCloud::GetSpacing()
{
  if (this->Spacing >= 0.0)
  {
    return this->Spacing;
  }
  const vtkIdType n = this->GetNumberOfLights();
  this->Spacing = 0.0;
  if (n < 2)
  {
    return this->Spacing;
  }
  vtkNew<vtkPolyData> points;
  points->SetPoints(this->Positions);
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(points);
  locator->BuildLocator();
  vtkNew<vtkIdList> ids;
  std::vector<double> nearest;
  nearest.reserve(static_cast<std::size_t>(n));
  for (vtkIdType j = 0; j < n; ++j)
  {
    double p[3], q[3];
    this->Positions->GetPoint(j, p);
    locator->FindClosestNPoints(2, p, ids);
    double best = 0.0;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      if (ids->GetId(k) != j)
      {
        this->Positions->GetPoint(ids->GetId(k), q);
        best = std::sqrt(vtkMath::Distance2BetweenPoints(p, q));
        break;
      }
    }
    nearest.push_back(best);
  }
  std::nth_element(nearest.begin(), nearest.begin() + n / 2, nearest.end());
  this->Spacing = nearest[static_cast<std::size_t>(n / 2)];
  return this->Spacing;
}

void vtkPGILightCloud::GetLightBounds(double bounds[6]) const
{
  if (this->GetNumberOfLights() == 0)
  {
    std::fill_n(bounds, 6, 0.0);
    return;
  }
  this->Positions->GetBounds(bounds);
}

unsigned long vtkPGILightCloud::GetActualMemorySize()
{
  std::size_t bytes = this->Response->size() * sizeof(float) +
    static_cast<std::size_t>(this->GetNumberOfLights()) * 3 * sizeof(double);
  for (const Zone& z : *this->Zones)
  {
    bytes += z.Receivers.size() * sizeof(vtkIdType) + z.Lights.size() * sizeof(double) +
      (z.LightMembers.size() + z.Cluster.size() + z.BasisStart.size() + z.BasisCount.size() +
        z.WeightStart.size()) *
        sizeof(int) +
      (z.Means.size() + z.Basis.size() + z.Weights.size()) * sizeof(float);
  }
  return static_cast<unsigned long>(bytes / 1024) + this->Superclass::GetActualMemorySize();
}

void vtkPGILightCloud::Initialize()
{
  this->Superclass::Initialize();
  this->Allocate(0, 0);
  this->Contents = IndirectOnly;
  this->Samples = 0;
  this->ReceiverKey = 0;
}

void vtkPGILightCloud::ShallowCopy(vtkDataObject* source)
{
  this->Superclass::ShallowCopy(source);
  if (auto* cloud = vtkPGILightCloud::SafeDownCast(source))
  {
    this->Positions = cloud->Positions;
    this->Response = cloud->Response;
    this->Zones = cloud->Zones;
    this->Receivers = cloud->Receivers;
    this->Coefficients = cloud->Coefficients;
    this->Contents = cloud->Contents;
    this->Samples = cloud->Samples;
    this->ReceiverKey = cloud->ReceiverKey;
    this->Spacing = cloud->Spacing;
  }
}

void vtkPGILightCloud::DeepCopy(vtkDataObject* source)
{
  this->Superclass::DeepCopy(source);
  if (auto* cloud = vtkPGILightCloud::SafeDownCast(source))
  {
    this->Positions = vtkSmartPointer<vtkPoints>::New();
    this->Positions->DeepCopy(cloud->Positions);
    this->Response = std::make_shared<std::vector<float>>(*cloud->Response);
    this->Zones = std::make_shared<std::vector<Zone>>(*cloud->Zones);
    this->Receivers = cloud->Receivers;
    this->Coefficients = cloud->Coefficients;
    this->Contents = cloud->Contents;
    this->Samples = cloud->Samples;
    this->ReceiverKey = cloud->ReceiverKey;
    this->Spacing = cloud->Spacing;
  }
}

void vtkPGILightCloud::EnsureOutput(vtkInformationVector* out)
{
  vtkInformation* info = out->GetInformationObject(0);
  if (!vtkPGILightCloud::GetData(info))
  {
    vtkNew<vtkPGILightCloud> cloud;
    info->Set(vtkDataObject::DATA_OBJECT(), cloud);
  }
}

vtkPGILightCloud* vtkPGILightCloud::GetData(vtkInformation* info)
{
  return info ? vtkPGILightCloud::SafeDownCast(info->Get(DATA_OBJECT())) : nullptr;
}

vtkPGILightCloud* vtkPGILightCloud::GetData(vtkInformationVector* v, int i)
{
  return vtkPGILightCloud::GetData(v->GetInformationObject(i));
}

void vtkPGILightCloud::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lights: " << this->GetNumberOfLights() << "\n";
  os << indent << "Receivers: " << this->Receivers << "\n";
  os << indent << "Coefficients: " << this->Coefficients
     << (this->Coefficients > 1 ? " (glossy receivers, SH)" : " (diffuse receivers)") << "\n";
  os << indent << "Contents: "
     << (this->Contents == DirectAndIndirect ? "direct and indirect" : "indirect only") << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Zones: " << this->Zones->size() << "\n";
  os << indent << "CoefficientsPerReceiver: " << this->GetCoefficientsPerReceiver() << "\n";
}
