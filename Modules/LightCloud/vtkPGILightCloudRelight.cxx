#include "vtkPGILightCloudRelight.h"

#include "pgiLightCloudGlossy.h"
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
#include "vtkStringArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkPGILightCloudRelight);
vtkCxxSetObjectMacro(vtkPGILightCloudRelight, Occluder, vtkPGIOccluder);

namespace
{
// Receivers per task of the per-receiver sums, fewer the more values each
// has: enough work per task that a small mesh (a Cornell box) is not slowed
// by the threads' fork and join (diffuse, measured: 0.15 ms serial, 0.3-1.7
// ms split per zone on two threads).
vtkIdType RelightGrain(int stride)
{
  return std::max<vtkIdType>(64, 3 * 4096 / std::max(3, stride));
}

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

void vtkPGILightCloudRelight::SetLights(const std::vector<vtkPGILighting::PointLight>& lights)
{
  if (this->GetNumberOfLights() != static_cast<int>(lights.size()))
  {
    this->Lights.clear();
    for (const auto& l : lights)
    {
      UserLight u;
      std::copy_n(l.Position, 3, u.Position);
      std::copy_n(l.Intensity, 3, u.Intensity);
      this->Lights.push_back(u);
    }
    this->Modified();
    return;
  }
  for (std::size_t k = 0; k < lights.size(); ++k)
  {
    const double* p = lights[k].Position;
    const double* v = lights[k].Intensity;
    this->SetLightPosition(static_cast<int>(k), p[0], p[1], p[2]);
    this->SetLightIntensity(static_cast<int>(k), v[0], v[1], v[2]);
  }
}

void vtkPGILightCloudRelight::SetViewPoint(double x, double y, double z)
{
  if (!this->ViewPointSet || this->ViewPoint[0] != x || this->ViewPoint[1] != y ||
    this->ViewPoint[2] != z)
  {
    this->ViewPoint[0] = x;
    this->ViewPoint[1] = y;
    this->ViewPoint[2] = z;
    this->ViewPointSet = true;
    this->Modified();
  }
}

void vtkPGILightCloudRelight::RemoveViewPoint()
{
  if (this->ViewPointSet)
  {
    this->ViewPointSet = false;
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

bool vtkPGILightCloudRelight::PrepareFrame(
  vtkPolyData* receivers, vtkPGILightCloud* cloud, Frame& frame)
{
  frame = Frame();
  this->LightsOutside = this->CloudLightsUsed = 0;
  if (!receivers || !cloud)
  {
    vtkErrorMacro(<< "Needs the receivers (input 0) and a light cloud (input 1).");
    return false;
  }
  const vtkIdType lightCount = cloud->GetNumberOfLights(), n = receivers->GetNumberOfPoints();
  if (lightCount == 0 || cloud->GetNumberOfReceivers() == 0)
  {
    vtkErrorMacro(<< "The light cloud is empty (no cloud lights or no receivers).");
    return false;
  }
  if (cloud->GetNumberOfReceivers() != n ||
    cloud->GetReceiverKey() != vtkPGILightCloud::ReceiverKeyOf(receivers))
  {
    vtkErrorMacro(<< "The receivers are not the ones the cloud was computed for (" << n
                  << " points here, " << cloud->GetNumberOfReceivers()
                  << " in the cloud, or the same count at other positions).");
    return false;
  }
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    if (!Finite3(this->Lights[k].Position) || !Finite3(this->Lights[k].Intensity))
    {
      vtkErrorMacro(<< "User light " << k << " has a NaN or Inf position or intensity.");
      return false;
    }
  }
  if (this->ViewPointSet && !Finite3(this->ViewPoint))
  {
    vtkErrorMacro(<< "The view point is NaN or Inf.");
    return false;
  }
  std::string error;
  if (this->Occluder && !this->Occluder->Prepare(error))
  {
    vtkErrorMacro(<< "The occluder cannot trace: " << error);
    return false;
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

  const double spacing = cloud->GetSpacing();
  double box[6];
  cloud->GetLightBounds(box);
  // Float slack too: positions often come through float vtkPoints.
  double extent = 1.0;
  for (double b : box)
  {
    extent = std::max(extent, std::fabs(b));
  }
  const double margin = 0.5 * spacing + 1e-6 * extent;
  std::vector<char> inside(this->Lights.size(), 1);
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    const double* l = this->Lights[k].Position;
    for (int a = 0; a < 3; ++a)
    {
      inside[k] = inside[k] && l[a] >= box[2 * a] - margin && l[a] <= box[2 * a + 1] + margin;
    }
    if (!inside[k])
    {
      ++this->LightsOutside;
      vtkWarningMacro(<< "User light " << k << " at (" << l[0] << ", " << l[1] << ", " << l[2]
                      << ") lies outside the light cloud: it adds no cloud light (direct light "
                         "only, from the soft-shadow route).");
    }
  }

  // The cloud lights' sets: the dense cloud's, or each zone's own.
  if (this->LocatorCloud != cloud || this->LocatorTime < cloud->GetMTime())
  {
    this->Locators.clear();
    auto build = [this](vtkPoints* points)
    {
      vtkNew<vtkPolyData> set;
      set->SetPoints(points);
      auto locator = vtkSmartPointer<vtkStaticPointLocator>::New();
      locator->SetDataSet(set);
      locator->BuildLocator();
      this->Locators.push_back(locator);
    };
    if (!cloud->IsCompressed())
    {
      build(cloud->GetLightPositions());
    }
    for (const auto& zone : cloud->GetZones())
    {
      vtkNew<vtkPoints> points;
      points->SetDataTypeToDouble();
      for (std::size_t q = 0; q < zone.Lights.size() / 3; ++q)
      {
        points->InsertNextPoint(&zone.Lights[3 * q]);
      }
      build(points);
    }
    this->LocatorCloud = cloud;
    this->LocatorTime = cloud->GetMTime();
  }

  // What each receiver gets: RGB, or RGB per SH coefficient (glossy).
  const int stride = cloud->GetValuesPerReceiver();
  frame.Stride = stride;
  frame.Compressed = cloud->IsCompressed();
  if (frame.Compressed)
  {
    frame.ZoneVectors.resize(this->Locators.size());
  }
  std::vector<char> visibleAny(this->Lights.size(), 0);
  this->NextFade.assign(this->Lights.size(), {});
  for (std::size_t set = 0; set < this->Locators.size(); ++set)
  {
    // The weight vector w_t of this set: per light, per colour.
    std::map<vtkIdType, std::array<double, 3>> weights;
    for (std::size_t k = 0; k < this->Lights.size(); ++k)
    {
      if (!inside[k])
      {
        continue;
      }
      std::vector<std::pair<vtkIdType, double>> w;
      if (this->WeighLights(static_cast<int>(k), this->Locators[set], spacing, fadeStep,
            static_cast<vtkIdType>(set) << 32, w))
      {
        visibleAny[k] = 1;
      }
      for (const auto& [j, weight] : w)
      {
        for (int c = 0; c < 3; ++c)
        {
          weights[j][c] += weight * this->Lights[k].Intensity[c];
        }
      }
    }
    this->CloudLightsUsed += static_cast<int>(weights.size());
    if (weights.empty())
    {
      continue;
    }
    if (!frame.Compressed)
    {
      for (const auto& [j, w] : weights)
      {
        frame.DenseLights.push_back(j);
        frame.DenseWeights.insert(frame.DenseWeights.end(), w.begin(), w.end());
      }
      continue;
    }
    // Compressed: per PCA cluster x_m = Xbar w_t and b_i = B_i w_t.
    const vtkPGILightCloud::Zone& zone = cloud->GetZones()[set];
    const int clusters = static_cast<int>(zone.BasisCount.size());
    const int dim = zone.Dimension;
    const std::size_t vectors = zone.Basis.size() / std::max(1, dim);
    std::vector<double>& out = frame.ZoneVectors[set];
    out.assign((clusters + vectors) * stride, 0.0);
    auto project = [&](const float* v, double* result)
    {
      for (const auto& [j, w] : weights)
      {
        for (int c = 0; c < stride; ++c)
        {
          result[c] += w[c % 3] * v[stride * j + c];
        }
      }
    };
    for (int q = 0; q < clusters; ++q)
    {
      project(&zone.Means[static_cast<std::size_t>(q) * dim], &out[stride * q]);
    }
    for (std::size_t v = 0; v < vectors; ++v)
    {
      project(&zone.Basis[v * dim], &out[stride * (clusters + v)]);
    }
  }
  // Lights that left every kernel are forgotten.
  this->Fade.swap(this->NextFade);
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    if (inside[k] && !visibleAny[k])
    {
      vtkWarningMacro(<< "User light " << k << ": no cloud light near it is visible from it.");
    }
  }
  // The plan: what ran and why.
  std::vector<std::string>& plan = frame.Plan;
  {
    std::ostringstream line;
    line << "light cloud: " << lightCount << " cloud lights, "
         << (cloud->GetContents() == vtkPGILightCloud::IndirectOnly ? "indirect light only"
                                                                    : "direct and indirect light")
         << ", ";
    if (stride > 3)
    {
      line << "glossy receivers (" << stride / 3 << " SH coefficients per colour, seen "
           << (this->ViewPointSet ? "from the view point" : "along the normals") << "), ";
    }
    if (cloud->IsCompressed())
    {
      line << "compressed (" << cloud->GetNumberOfZones() << " zones, "
           << cloud->GetCoefficientsPerReceiver() << " coefficients per receiver)";
    }
    else
    {
      line << "dense (" << cloud->GetCoefficientsPerReceiver() << " coefficients per receiver)";
    }
    plan.push_back(line.str());
  }
  if (this->Lights.empty())
  {
    plan.push_back("user lights: none: no cloud light to add (radiance 0)");
  }
  else
  {
    std::ostringstream line;
    line << "user lights: " << this->Lights.size() << ", " << this->CloudLightsUsed
         << " cloud lights weighed" << (this->Occluder ? ", visibility by rays" : ", no occluder")
         << (this->Fading ? ", fading" : "");
    plan.push_back(line.str());
  }
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    if (!inside[k])
    {
      plan.push_back("user light " + std::to_string(k) +
        ": outside the cloud: skipped (direct light only, from the soft-shadow route)");
    }
    else if (!visibleAny[k])
    {
      plan.push_back("user light " + std::to_string(k) + ": no cloud light near it visible");
    }
  }
  return true;
}

int vtkPGILightCloudRelight::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPGILightCloud* cloud = vtkPGILightCloud::GetData(in[1]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  Frame frame;
  if (!this->PrepareFrame(receivers, cloud, frame))
  {
    return 0;
  }
  const vtkIdType n = receivers->GetNumberOfPoints();
  const int stride = frame.Stride;
  std::string error;
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName(stride > 3 ? "LightCloudRadianceSH" : "LightCloudRadiance");
  radiance->SetNumberOfComponents(stride);
  radiance->SetNumberOfTuples(n);
  radiance->Fill(0.0);
  float* values = radiance->GetPointer(0);
  if (!frame.Compressed && !frame.DenseLights.empty())
  {
    // Dense: a = sum_j w_j X_j, per receiver.
    vtkSMPTools::For(0, n, RelightGrain(stride),
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType i = first; i < last; ++i)
        {
          float* o = values + static_cast<std::ptrdiff_t>(stride) * i;
          for (std::size_t q = 0; q < frame.DenseLights.size(); ++q)
          {
            const double* w = &frame.DenseWeights[3 * q];
            const float* x =
              cloud->GetResponse(frame.DenseLights[q]) + static_cast<std::ptrdiff_t>(stride) * i;
            for (int c = 0; c < stride; ++c)
            {
              o[c] += static_cast<float>(w[c % 3] * x[c]);
            }
          }
        }
      });
  }
  for (std::size_t set = 0; set < frame.ZoneVectors.size(); ++set)
  {
    // Per receiver a = x_m + sum_i z_i b_i (the GPU mapper's twin).
    const std::vector<double>& vectors = frame.ZoneVectors[set];
    if (vectors.empty())
    {
      continue;
    }
    const vtkPGILightCloud::Zone& zone = cloud->GetZones()[set];
    const std::size_t clusters = zone.BasisCount.size();
    const vtkIdType zoneReceivers = static_cast<vtkIdType>(zone.Receivers.size());
    vtkSMPTools::For(0, zoneReceivers, RelightGrain(stride),
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType r = first; r < last; ++r)
        {
          const int q = zone.Cluster[r];
          const float* z = &zone.Weights[zone.WeightStart[r]];
          const double* xm = &vectors[static_cast<std::size_t>(stride) * q];
          const double* bi = &vectors[stride * (clusters + zone.BasisStart[q])];
          float* o = values + static_cast<std::ptrdiff_t>(stride) * zone.Receivers[r];
          for (int c = 0; c < stride; ++c)
          {
            double a = xm[c];
            for (int v = 0; v < zone.BasisCount[q]; ++v)
            {
              a += z[v] * bi[static_cast<std::size_t>(stride) * v + c];
            }
            o[c] = static_cast<float>(a);
          }
        }
      });
  }
  vtkNew<vtkStringArray> planArray;
  planArray->SetName("Plan");
  for (const std::string& line : frame.Plan)
  {
    planArray->InsertNextValue(line);
  }
  output->ShallowCopy(receivers);
  output->GetPointData()->AddArray(radiance);
  if (stride > 3)
  {
    // Glossy: the SH evaluated toward the viewer (or along the normal).
    std::vector<double> normals;
    if (!this->ViewPointSet && !proxygi::ReceiverNormals(receivers, normals, error))
    {
      vtkErrorMacro(<< "Glossy receivers without a view point: " << error << ".");
      return 0;
    }
    const int order = static_cast<int>(std::lround(std::sqrt(stride / 3)));
    vtkNew<vtkFloatArray> seen;
    seen->SetName("LightCloudRadiance");
    seen->SetNumberOfComponents(3);
    seen->SetNumberOfTuples(n);
    float* s = seen->GetPointer(0);
    vtkSMPTools::For(0, n, RelightGrain(stride),
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType i = first; i < last; ++i)
        {
          double wo[3] = { 0.0, 0.0, 1.0 };
          if (this->ViewPointSet)
          {
            double x[3];
            receivers->GetPoint(i, x);
            vtkMath::Subtract(this->ViewPoint, x, wo);
            if (!(vtkMath::Normalize(wo) > 0.0))
            {
              wo[0] = wo[1] = 0.0;
              wo[2] = 1.0;
            }
          }
          else
          {
            std::copy_n(&normals[3 * i], 3, wo);
          }
          for (int c = 0; c < 3; ++c)
          {
            s[3 * i + c] = static_cast<float>(proxygi::GlossyProjection::Evaluate(
              order, values + static_cast<std::ptrdiff_t>(stride) * i + c, 3, wo));
          }
        }
      });
    output->GetPointData()->AddArray(seen);
  }
  output->GetFieldData()->AddArray(planArray);
  vtkNew<vtkIntArray> usedField;
  usedField->SetName("LightCloudLightsUsed");
  usedField->InsertNextValue(this->CloudLightsUsed);
  output->GetFieldData()->AddArray(usedField);
  return 1;
}

bool vtkPGILightCloudRelight::WeighLights(int k, vtkStaticPointLocator* locator, double spacing,
  double fadeStep, vtkIdType fadeKey, std::vector<std::pair<vtkIdType, double>>& weights)
{
  weights.clear();
  const UserLight& light = this->Lights[k];
  const double* l = light.Position;
  vtkDataSet* set = locator->GetDataSet();
  const vtkIdType count = set->GetNumberOfPoints();
  if (count == 0)
  {
    return false;
  }
  vtkNew<vtkIdList> nearest, within;
  locator->FindClosestNPoints(
    static_cast<int>(std::min<vtkIdType>(this->NeighborCount, count)), l, nearest);
  double farthest = 0.0, closest = VTK_DOUBLE_MAX;
  vtkIdType closestId = -1;
  for (vtkIdType q = 0; q < nearest->GetNumberOfIds(); ++q)
  {
    double p[3];
    set->GetPoint(nearest->GetId(q), p);
    const double d = std::sqrt(vtkMath::Distance2BetweenPoints(l, p));
    farthest = std::max(farthest, d);
    if (d < closest)
    {
      closest = d;
      closestId = nearest->GetId(q);
    }
  }
  // On a cloud light (to float precision): that light alone.
  const double onLight =
    1e-6 * (spacing > 0.0 ? spacing : 1.0 + std::fabs(l[0]) + std::fabs(l[1]) + std::fabs(l[2]));
  double r = this->RadiusScale * farthest;
  if (closestId >= 0 && closest <= onLight)
  {
    r = 0.0;
    within->InsertNextId(closestId);
  }
  else if (r > 0.0)
  {
    locator->FindPointsWithinRadius(r, l, within);
  }
  else
  {
    within->DeepCopy(nearest);
  }
  const int rays = this->VisibilityRays;
  std::vector<float> origins(3 * rays), directions(3 * rays), lengths(rays);
  std::vector<unsigned char> blocked(rays);
  const std::map<vtkIdType, double>& fade = this->Fade[k];
  std::map<vtkIdType, double>& next = this->NextFade[k];
  double kernelSum = 0.0, weightedSum = 0.0;
  for (vtkIdType q = 0; q < within->GetNumberOfIds(); ++q)
  {
    const vtkIdType j = within->GetId(q);
    double p[3];
    set->GetPoint(j, p);
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
      for (int ray = 0; ray < rays; ++ray)
      {
        double t[3] = { p[0], p[1], p[2] };
        if (ray > 0)
        {
          double dir[3];
          SpreadDirection(ray - 1, rays - 1, dir);
          for (int a = 0; a < 3; ++a)
          {
            t[a] += 0.25 * spacing * dir[a];
          }
        }
        double v[3] = { t[0] - l[0], t[1] - l[1], t[2] - l[2] };
        const double len = std::sqrt(vtkMath::Dot(v, v));
        for (int a = 0; a < 3; ++a)
        {
          origins[3 * ray + a] = static_cast<float>(l[a]);
          directions[3 * ray + a] = static_cast<float>(len > 0.0 ? v[a] / len : 0.0);
        }
        lengths[ray] = static_cast<float>(len);
        if (!(len > 0.0))
        {
          directions[3 * ray + 2] = 1.0f;
        }
      }
      this->Occluder->OccludedSegments(
        rays, origins.data(), directions.data(), lengths.data(), 0.0f, blocked.data());
      int open = 0;
      for (int ray = 0; ray < rays; ++ray)
      {
        open += blocked[ray] ? 0 : 1;
      }
      target = static_cast<double>(open) / rays;
    }
    // The fade: a light already weighted moves toward its target; one that
    // just entered the kernel (weight ~0 there) starts at it.
    double f = target;
    auto previous = fade.find(fadeKey + j);
    if (previous != fade.end())
    {
      const double delta = target - previous->second;
      f = previous->second + std::max(-fadeStep, std::min(fadeStep, delta));
    }
    if (std::fabs(f - target) > 1e-12)
    {
      this->Fading = true;
    }
    next[fadeKey + j] = f;
    kernelSum += w;
    weightedSum += w * f;
    weights.emplace_back(j, w * f);
  }
  // At least 5% of the unweighted sum: the last visible lights fade out too.
  const double norm = std::max(weightedSum, 0.05 * kernelSum);
  if (!(norm > 0.0) || !(weightedSum > 0.0))
  {
    weights.clear();
    return false;
  }
  for (auto& entry : weights)
  {
    entry.second /= norm;
  }
  return true;
}

void vtkPGILightCloudRelight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ViewPoint: ";
  if (this->ViewPointSet)
  {
    os << this->ViewPoint[0] << " " << this->ViewPoint[1] << " " << this->ViewPoint[2] << "\n";
  }
  else
  {
    os << "(none: glossy receivers seen along their normals)\n";
  }
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
