#include "vtkPGILightCloudRelight.h"

#include "vtkPGILightCloud.h"
#include "vtkPGIOccluder.h"

#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkPGILightCloudRelight);
vtkCxxSetObjectMacro(vtkPGILightCloudRelight, Occluder, vtkPGIOccluder);

namespace
{
bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// Unit directions spread over the sphere (Fibonacci), for the rays that
// land around a cloud light.
void SpreadDirection(int q, int count, double d[3])
{
  const double golden = 2.39996322972865332; // pi (3 - sqrt 5)
  const double z = 1.0 - (q + 0.5) * 2.0 / count;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  d[0] = r * std::cos(golden * q);
  d[1] = r * std::sin(golden * q);
  d[2] = z;
}
} // namespace

vtkPGILightCloudRelight::vtkPGILightCloudRelight()
{
  this->SetNumberOfInputPorts(2);
}

vtkPGILightCloudRelight::~vtkPGILightCloudRelight()
{
  this->SetOccluder(nullptr);
}

int vtkPGILightCloudRelight::AddLight(double x, double y, double z, double r, double g, double b)
{
  this->Lights.push_back({ { x, y, z }, { r, g, b } });
  this->Modified();
  return static_cast<int>(this->Lights.size()) - 1;
}

void vtkPGILightCloudRelight::SetLightPosition(int index, double x, double y, double z)
{
  if (index < 0 || index >= this->GetNumberOfLights())
  {
    vtkErrorMacro(<< "No user light " << index << " (there are " << this->GetNumberOfLights()
                  << ").");
    return;
  }
  double* p = this->Lights[index].Position;
  if (p[0] != x || p[1] != y || p[2] != z)
  {
    p[0] = x;
    p[1] = y;
    p[2] = z;
    this->Modified();
  }
}

void vtkPGILightCloudRelight::SetLightIntensity(int index, double r, double g, double b)
{
  if (index < 0 || index >= this->GetNumberOfLights())
  {
    vtkErrorMacro(<< "No user light " << index << " (there are " << this->GetNumberOfLights()
                  << ").");
    return;
  }
  double* v = this->Lights[index].Intensity;
  if (v[0] != r || v[1] != g || v[2] != b)
  {
    v[0] = r;
    v[1] = g;
    v[2] = b;
    this->Modified();
  }
}

void vtkPGILightCloudRelight::RemoveAllLights()
{
  if (!this->Lights.empty())
  {
    this->Lights.clear();
    this->Modified();
  }
}

void vtkPGILightCloudRelight::ResetFade()
{
  this->Fade.clear();
  this->FadeStarted = false;
  this->Fading = false;
  this->Modified();
}

vtkMTimeType vtkPGILightCloudRelight::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Occluder)
  {
    t = std::max(t, this->Occluder->GetMTime());
  }
  return t;
}

int vtkPGILightCloudRelight::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkPGILightCloud");
  return 1;
}

int vtkPGILightCloudRelight::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPGILightCloud* cloud = vtkPGILightCloud::GetData(in[1]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  this->LightsOutside = this->CloudLightsUsed = 0;
  if (!receivers || !cloud)
  {
    vtkErrorMacro(<< "Needs the receivers (input 0) and a light cloud (input 1).");
    return 0;
  }
  const vtkIdType lightCount = cloud->GetNumberOfLights(), n = receivers->GetNumberOfPoints();
  if (lightCount == 0 || cloud->GetNumberOfReceivers() == 0)
  {
    vtkErrorMacro(<< "The light cloud is empty (no cloud lights or no receivers).");
    return 0;
  }
  if (cloud->GetNumberOfReceivers() != n ||
    cloud->GetReceiverKey() != vtkPGILightCloud::ReceiverKeyOf(receivers))
  {
    vtkErrorMacro(<< "The receivers are not the ones the cloud was computed for (" << n
                  << " points here, " << cloud->GetNumberOfReceivers()
                  << " in the cloud, or the same count at other positions).");
    return 0;
  }
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    if (!Finite3(this->Lights[k].Position) || !Finite3(this->Lights[k].Intensity))
    {
      vtkErrorMacro(<< "User light " << k << " has a NaN or Inf position or intensity.");
      return 0;
    }
  }
  std::string error;
  if (this->Occluder && !this->Occluder->Prepare(error))
  {
    vtkErrorMacro(<< "The occluder cannot trace: " << error);
    return 0;
  }

  // A new cloud or another number of lights: the fade starts afresh.
  if (this->FadeCloud != cloud || this->Fade.size() != this->Lights.size())
  {
    this->Fade.assign(this->Lights.size(), {});
    this->FadeCloud = cloud;
    this->FadeStarted = false;
  }
  const double dt = this->FadeStarted ? std::max(0.0, this->Time - this->FadeClock) : 0.0;
  const double fadeStep =
    !this->FadeStarted || this->FadeTime <= 0.0 ? 1.0 : std::min(1.0, dt / this->FadeTime);
  this->FadeClock = this->Time;
  this->FadeStarted = true;
  this->Fading = false;

  vtkNew<vtkPolyData> lightPoints;
  lightPoints->SetPoints(cloud->GetLightPositions());
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(lightPoints);
  locator->BuildLocator();
  const double spacing = cloud->GetSpacing();
  double box[6];
  cloud->GetLightBounds(box);
  const double margin = 0.5 * spacing + 1e-9 * (1.0 + std::fabs(box[1]) + std::fabs(box[3]));

  // The total weight vector, per colour.
  std::vector<double> weights(static_cast<std::size_t>(3 * lightCount), 0.0);
  std::vector<char> used(static_cast<std::size_t>(lightCount), 0);
  vtkNew<vtkIdList> nearest, within;
  const int rays = this->VisibilityRays;
  std::vector<float> origins(3 * rays), directions(3 * rays), lengths(rays);
  std::vector<unsigned char> blocked(rays);
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    const UserLight& light = this->Lights[k];
    const double* l = light.Position;
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      inside = inside && l[a] >= box[2 * a] - margin && l[a] <= box[2 * a + 1] + margin;
    }
    if (!inside)
    {
      ++this->LightsOutside;
      this->Fade[k].clear();
      vtkWarningMacro(<< "User light " << k << " at (" << l[0] << ", " << l[1] << ", " << l[2]
                      << ") lies outside the light cloud: it adds no cloud light (direct light "
                         "only, from the soft-shadow route).");
      continue;
    }
    locator->FindClosestNPoints(
      static_cast<int>(std::min<vtkIdType>(this->NeighborCount, lightCount)), l, nearest);
    double farthest = 0.0;
    for (vtkIdType q = 0; q < nearest->GetNumberOfIds(); ++q)
    {
      double p[3];
      cloud->GetLightPositions()->GetPoint(nearest->GetId(q), p);
      farthest = std::max(farthest, std::sqrt(vtkMath::Distance2BetweenPoints(l, p)));
    }
    const double r = this->RadiusScale * farthest;
    if (r > 0.0)
    {
      locator->FindPointsWithinRadius(r, l, within);
    }
    else
    {
      within->DeepCopy(nearest);
    }

    std::map<vtkIdType, double> next;
    double kernelSum = 0.0, weightedSum = 0.0;
    std::vector<std::pair<vtkIdType, double>> kernel;
    for (vtkIdType q = 0; q < within->GetNumberOfIds(); ++q)
    {
      const vtkIdType j = within->GetId(q);
      double p[3];
      cloud->GetLightPositions()->GetPoint(j, p);
      const double d = std::sqrt(vtkMath::Distance2BetweenPoints(l, p));
      const double u = r > 0.0 ? std::max(0.0, 1.0 - d / r) : 1.0;
      const double w = u * u * u * u;
      if (!(w > 0.0))
      {
        continue;
      }
      // Visibility: the fraction of rays from l that reach around p.
      double target = 1.0;
      if (this->Occluder)
      {
        for (int q2 = 0; q2 < rays; ++q2)
        {
          double t[3] = { p[0], p[1], p[2] };
          if (q2 > 0)
          {
            double dir[3];
            SpreadDirection(q2 - 1, rays - 1, dir);
            for (int a = 0; a < 3; ++a)
            {
              t[a] += 0.25 * spacing * dir[a];
            }
          }
          double v[3] = { t[0] - l[0], t[1] - l[1], t[2] - l[2] };
          const double len = std::sqrt(vtkMath::Dot(v, v));
          for (int a = 0; a < 3; ++a)
          {
            origins[3 * q2 + a] = static_cast<float>(l[a]);
            directions[3 * q2 + a] = static_cast<float>(len > 0.0 ? v[a] / len : 0.0);
          }
          lengths[q2] = static_cast<float>(len);
          if (!(len > 0.0))
          {
            directions[3 * q2 + 2] = 1.0f;
          }
        }
        this->Occluder->OccludedSegments(
          rays, origins.data(), directions.data(), lengths.data(), 0.0f, blocked.data());
        int open = 0;
        for (int q2 = 0; q2 < rays; ++q2)
        {
          open += blocked[q2] ? 0 : 1;
        }
        target = static_cast<double>(open) / rays;
      }
      // The fade: a light already weighted moves toward its target; one
      // that just entered the kernel (weight ~0 there) starts at it.
      double f = target;
      auto previous = this->Fade[k].find(j);
      if (previous != this->Fade[k].end())
      {
        const double delta = target - previous->second;
        f = previous->second + std::max(-fadeStep, std::min(fadeStep, delta));
      }
      if (std::fabs(f - target) > 1e-12)
      {
        this->Fading = true;
      }
      next[j] = f;
      kernelSum += w;
      weightedSum += w * f;
      kernel.emplace_back(j, w * f);
    }
    this->Fade[k] = std::move(next);
    const double norm = std::max(weightedSum, 0.05 * kernelSum);
    if (!(norm > 0.0))
    {
      vtkWarningMacro(<< "User light " << k << ": no cloud light near it is visible from it.");
      continue;
    }
    for (const auto& [j, w] : kernel)
    {
      if (w > 0.0)
      {
        used[j] = 1;
        for (int c = 0; c < 3; ++c)
        {
          weights[3 * j + c] += w / norm * light.Intensity[c];
        }
      }
    }
  }

  std::vector<vtkIdType> active;
  for (vtkIdType j = 0; j < lightCount; ++j)
  {
    if (used[j])
    {
      active.push_back(j);
    }
  }
  this->CloudLightsUsed = static_cast<int>(active.size());
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("LightCloudRadiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(n);
  float* a = radiance->GetPointer(0);
  vtkSMPTools::For(0, n,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        double sum[3] = { 0, 0, 0 };
        for (vtkIdType j : active)
        {
          const float* x = cloud->GetResponse(j) + 3 * i;
          for (int c = 0; c < 3; ++c)
          {
            sum[c] += weights[3 * j + c] * x[c];
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          a[3 * i + c] = static_cast<float>(sum[c]);
        }
      }
    });
  output->ShallowCopy(receivers);
  output->GetPointData()->AddArray(radiance);
  vtkNew<vtkIntArray> usedField;
  usedField->SetName("LightCloudLightsUsed");
  usedField->InsertNextValue(this->CloudLightsUsed);
  output->GetFieldData()->AddArray(usedField);
  return 1;
}

void vtkPGILightCloudRelight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lights: " << this->Lights.size() << "\n";
  for (const UserLight& l : this->Lights)
  {
    os << indent.GetNextIndent() << "at (" << l.Position[0] << ", " << l.Position[1] << ", "
       << l.Position[2] << "), intensity (" << l.Intensity[0] << ", " << l.Intensity[1] << ", "
       << l.Intensity[2] << ")\n";
  }
  os << indent << "NeighborCount: " << this->NeighborCount << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "Occluder: " << (this->Occluder ? this->Occluder->Describe() : "(none)") << "\n";
  os << indent << "VisibilityRays: " << this->VisibilityRays << "\n";
  os << indent << "FadeTime: " << this->FadeTime << ", Time: " << this->Time
     << ", Fading: " << this->Fading << "\n";
}
