#include "pgiSphericalLights.h"

#include "pgiSHBatch.h"

#include "pgiEnvironmentShading.h"
#include "pgiMaterial.h"
#include "pgiSHBasis.h"
#include "pgiSHLightTables.h"
#include "pgiSHSphericalLight.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkPGILighting.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace proxygi
{

namespace
{
// Below this angular radius a light's cap is evaluated at this size with its
// radiance scaled to the same power: a vanishing cap is not resolved by the
// difference of two exps in float.
constexpr float MinLightTheta = 0.02f;
} // namespace

void SphericalLights::Add(float x, float y, float z, float r, int object)
{
  this->X.push_back(x);
  this->Y.push_back(y);
  this->Z.push_back(z);
  this->R.push_back(r);
  this->Object.push_back(object);
}

void SphericalLights::Finish()
{
  const std::size_t count = this->Count();
  this->Intersects.assign(count * count, 0);
  for (std::size_t i = 0; i < count; ++i)
  {
    for (std::size_t j = i + 1; j < count; ++j)
    {
      const float dx = this->X[i] - this->X[j], dy = this->Y[i] - this->Y[j],
                  dz = this->Z[i] - this->Z[j], rr = this->R[i] + this->R[j];
      const bool sameLevel = this->Level.empty() || this->Level[i] == this->Level[j];
      if (this->Object[i] == this->Object[j] && sameLevel && dx * dx + dy * dy + dz * dz < rr * rr)
      {
        this->Intersects[i * count + j] = this->Intersects[j * count + i] = 1;
      }
    }
  }
}

void LocalLightsRadiance(const LocalEmitters& lights, const sh::AnalyticLightTables& tables,
  const double p[3], const float n[3], const float* g, float lit[3])
{
  const int n2 = tables.GetOrder() * tables.GetOrder();
  float open[sh::MaxCoefficients];
  if (!g)
  {
    sh::SetConstant(tables.GetOrder(), 1.0f, open);
    g = open;
  }
  const double theta1 = sh::AnalyticLightTables::MaxTheta / (tables.GetThetaResolution() - 1);
  lit[0] = lit[1] = lit[2] = 0.0f;
  for (std::size_t k = 0; k < lights.Count(); ++k)
  {
    const bool point = lights.Point[k] != 0;
    const double radius = lights.R[k];
    double dir[3] = { lights.X[k] - p[0], lights.Y[k] - p[1], lights.Z[k] - p[2] };
    const double dist = vtkMath::Normalize(dir);
    if (!(dist > radius))
    {
      continue; // inside an emitter
    }
    const double theta = point ? 0.0 : std::asin(radius / dist);
    const double thetaEval = std::max(theta, theta1);
    const double s1 = std::sin(thetaEval);
    const double scale =
      point ? 1.0 / (vtkMath::Pi() * dist * dist * s1 * s1) : std::pow(std::sin(theta) / s1, 2);
    const float df[3] = { float(dir[0]), float(dir[1]), float(dir[2]) };
    float lh[sh::MaxCoefficients];
    tables.Evaluate(n, df, static_cast<float>(thetaEval), lh);
    const float weight = std::max(0.0f, sh::Dot(n2, lh, g));
    for (int c = 0; c < 3; ++c)
    {
      lit[c] += static_cast<float>(scale * lights.Radiance[3 * k + c]) * weight;
    }
  }
}

void LocalEmitters::AddLights(const vtkPGILighting& lighting)
{
  for (const auto& l : lighting.GetSphereLights())
  {
    this->Add(l.Center, l.Radius, l.Radiance, false);
  }
  for (const auto& l : lighting.GetPointLights())
  {
    this->Add(l.Position, 0.0, l.Intensity, true);
  }
}

void LocalEmitters::Add(const double c[3], double r, const double rgb[3], bool point)
{
  this->X.push_back(float(c[0]));
  this->Y.push_back(float(c[1]));
  this->Z.push_back(float(c[2]));
  this->R.push_back(point ? 0.0f : float(r));
  this->Radiance.insert(this->Radiance.end(), { float(rgb[0]), float(rgb[1]), float(rgb[2]) });
  this->Point.push_back(point ? 1 : 0);
}

ShadowedIndirect::ShadowedIndirect(
  const SoftShadowSettings& settings, SphericalLightBlocking blocking)
  : Settings(settings)
  , Blocking(blocking)
{
  // The tables are built on first use (thread-safe), so a kernel made for
  // an effect that does not run costs nothing.
}

bool ShadowedIndirect::ExitRadiance(const SphericalLights& lights, bool emitLights,
  const LocalEmitters* locals, const Blockers* planes, const float p[3], const float n[3],
  float rgb[3], SphericalLightScratch& s, float* contributions, int ownObject) const
{
  const bool skipOwn = ownObject >= 0 && lights.Object.size() == lights.Count();
  rgb[0] = rgb[1] = rgb[2] = 0.0f;
  if (contributions)
  {
    std::fill(contributions, contributions + lights.Count(), 0.0f);
  }
  const int order = this->Settings.Order, n2 = sh::NumCoefficients(order);
  const sh::CapTables& caps = sh::CapTables::Get(order);
  const sh::IndirectTables& tables = sh::IndirectTables::Get(order);
  const float sinMin = std::sin(this->Settings.MinAngle);
  const std::size_t count = lights.Count();
  s.List.clear();
  for (std::size_t i = 0; i < count; ++i)
  {
    float c[3] = { lights.X[i], lights.Y[i], lights.Z[i] };
    float r = lights.R[i];
    if (!(r > 0.0f) || (skipOwn && lights.Object[i] == ownObject) ||
      (this->Settings.SelfShadowRules && !ReplaceBlocker(p, n, c, r)))
    {
      continue;
    }
    const float d[3] = { c[0] - p[0], c[1] - p[1], c[2] - p[2] };
    const float dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dist > r) || r < sinMin * dist)
    {
      continue; // inside (rules off) or too small to resolve
    }
    s.List.push_back({ static_cast<int>(i), dist, std::asin(r / dist),
      { d[0] / dist, d[1] / dist, d[2] / dist } });
  }
  const std::size_t lightEntries = s.List.size();
  for (std::size_t k = 0; locals && k < locals->Count(); ++k)
  {
    const float d[3] = { locals->X[k] - p[0], locals->Y[k] - p[1], locals->Z[k] - p[2] };
    const float dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const float r = locals->R[k];
    if (!(dist > r) || (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) < -r)
    {
      continue; // inside the emitter, or wholly below the horizon
    }
    const float theta = std::max(MinLightTheta, std::asin(r / dist));
    s.List.push_back(
      { -1 - static_cast<int>(k), dist, theta, { d[0] / dist, d[1] / dist, d[2] / dist } });
  }
  if (s.List.empty())
  {
    return true;
  }
  // Sort keys: distance, or (per object) the object's nearest SL first.
  using Seen = SphericalLightScratch::Seen;
  std::vector<float>& objectKey = s.ObjectKey;
  objectKey.resize(s.List.size());
  std::vector<std::size_t>& rank = s.Rank;
  rank.resize(s.List.size());
  for (std::size_t a = 0; a < s.List.size(); ++a)
  {
    objectKey[a] = s.List[a].Key;
    rank[a] = a;
  }
  if (this->Blocking == SphericalLightBlocking::PerObject && lightEntries > 1)
  {
    // Each object's nearest light: group the entries by object (n log n,
    // where a pairwise scan made 1000 lights cost a million tests each).
    const auto objectOf = [&](std::size_t a) { return lights.Object[s.List[a].Index]; };
    std::sort(rank.begin(), rank.begin() + lightEntries,
      [&](std::size_t a, std::size_t b) { return objectOf(a) < objectOf(b); });
    for (std::size_t first = 0; first < lightEntries;)
    {
      std::size_t last = first;
      float nearest = objectKey[rank[first]];
      while (last < lightEntries && objectOf(rank[last]) == objectOf(rank[first]))
      {
        nearest = std::min(nearest, objectKey[rank[last]]);
        ++last;
      }
      for (std::size_t q = first; q < last; ++q)
      {
        objectKey[rank[q]] = nearest;
      }
      first = last;
    }
  }
  std::sort(rank.begin(), rank.end(),
    [&](std::size_t a, std::size_t b)
    {
      if (objectKey[a] != objectKey[b])
      {
        return objectKey[a] < objectKey[b];
      }
      if (s.List[a].Key != s.List[b].Key)
      {
        return s.List[a].Key < s.List[b].Key;
      }
      return s.List[a].Index < s.List[b].Index;
    });
  s.Sorted.resize(s.List.size());
  for (std::size_t a = 0; a < rank.size(); ++a)
  {
    s.Sorted[a] = s.List[rank[a]];
  }
  s.List.swap(s.Sorted);

  const std::size_t entries = s.List.size();
  s.Logs.resize(entries * n2);
  s.Basis.resize(entries * n2);
  float zh[sh::MaxOrder];
  for (std::size_t a = 0; a < entries; ++a)
  {
    // The basis serves the log and the light's radiance below.
    float* basis = &s.Basis[a * n2];
    sh::EvaluateBasis(order, s.List[a].Dir[0], s.List[a].Dir[1], s.List[a].Dir[2], basis);
    caps.CapLog(s.List[a].Theta, zh);
    for (int l = 0; l < order; ++l)
    {
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      {
        s.Logs[a * n2 + i] = basis[i] * zh[l];
      }
    }
  }
  // Planes block every SL as 90-degree caps when they are in log space (else
  // the light of the first pass carries them, and SLs sit above them).
  float running[sh::MaxCoefficients];
  sh::Fill(running, n2, 0.0f);
  const bool planeLogs = planes && this->Settings.PlanesInLogSpace;
  for (std::size_t k = 0; planeLogs && k < planes->Planes(); ++k)
  {
    const float* o = &planes->PlaneOrigin[3 * k];
    const float* pn = &planes->PlaneNormal[3 * k];
    const float height = (p[0] - o[0]) * pn[0] + (p[1] - o[1]) * pn[1] + (p[2] - o[2]) * pn[2];
    if (height > 0.0f)
    {
      float v[sh::MaxCoefficients];
      caps.CapLog(static_cast<float>(sh::CapTables::MaxAngle), zh);
      sh::RotateScaledZonal(order, zh, -pn[0], -pn[1], -pn[2], v);
      for (int t = 0; t < n2; ++t)
      {
        running[t] += v[t];
      }
    }
  }
  float h[sh::MaxCoefficients];
  sh::DiffuseTransfer(order, n[0], n[1], n[2], h);
  float before[sh::MaxCoefficients], after[sh::MaxCoefficients];
  bool ok = true;
  // exp per blocker set (a bit per sorted entry; the planes are in every
  // set): a set met again, such as the previous light's F + G, or F of a light
  // whose intersecting partner came just before it, costs no second exp.
  // First every light's sets, then their exps in batches, then the sums.
  const bool cache = entries <= 64;
  s.Sets.clear();
  s.SetKey.clear();
  s.SetCacheable.clear();
  s.Jobs.clear();
  std::uint64_t runningMask = 0;
  auto setOf = [&](const float* f, std::uint64_t key, bool cacheable)
  {
    if (key == 0 && !planeLogs)
    {
      return -1; // nothing blocks: exactly 1
    }
    for (std::size_t c = 0; cacheable && c < s.SetKey.size(); ++c)
    {
      if (s.SetCacheable[c] && s.SetKey[c] == key)
      {
        return static_cast<int>(c);
      }
    }
    s.Sets.insert(s.Sets.end(), f, f + n2);
    s.SetKey.push_back(key);
    s.SetCacheable.push_back(cacheable ? 1 : 0);
    return static_cast<int>(s.SetKey.size()) - 1;
  };
  for (std::size_t k = 0; k < entries; ++k)
  {
    const Seen& e = s.List[k];
    const bool blocks = e.Index >= 0;
    // Intersecting SLs of the same object do not block (eq. 23, section 6.2).
    s.Excluded.clear();
    if (blocks)
    {
      const char* row = &lights.Intersects[static_cast<std::size_t>(e.Index) * count];
      for (std::size_t q = 0; q < k; ++q)
      {
        if (s.List[q].Index >= 0 && row[s.List[q].Index])
        {
          s.Excluded.push_back(static_cast<int>(q));
        }
      }
    }
    SphericalLightScratch::Job job{ -1, -1, static_cast<int>(k), { 0, 0, 0 } };
    float* lbar = job.Lbar;
    if (blocks && emitLights)
    {
      const float* radiance = &lights.Radiance[static_cast<std::size_t>(e.Index) * 3 * n2];
      const float ratio = lights.ReflectionRatio.empty() ? 1.0f : lights.ReflectionRatio[e.Index];
      for (int c = 0; c < 3; ++c)
      {
        lbar[c] = ratio *
          tables.SphericalLightRadianceFromBasis(e.Theta, &s.Basis[k * n2], radiance + c * n2);
      }
    }
    else if (!blocks)
    {
      const int l = -1 - e.Index;
      // Same power as the true light: radiance times its solid angle.
      const float omega = static_cast<float>(sh::CapSolidAngle(e.Theta));
      const float scale = locals->Point[l]
        ? 1.0f / (e.Key * e.Key * omega)
        : static_cast<float>(sh::CapSolidAngle(std::asin(locals->R[l] / e.Key))) / omega;
      for (int c = 0; c < 3; ++c)
      {
        lbar[c] = scale * locals->Radiance[3 * l + c];
      }
    }
    const bool emits = lbar[0] > 0.0f || lbar[1] > 0.0f || lbar[2] > 0.0f;
    if (emits)
    {
      for (int t = 0; t < n2; ++t)
      {
        before[t] = running[t];
      }
      std::uint64_t beforeMask = runningMask;
      for (int q : s.Excluded)
      {
        for (int t = 0; t < n2; ++t)
        {
          before[t] -= s.Logs[q * n2 + t];
        }
        beforeMask &= cache ? ~(std::uint64_t(1) << q) : 0;
      }
      for (int t = 0; t < n2; ++t)
      {
        after[t] = before[t] + s.Logs[k * n2 + t];
      }
      const std::uint64_t afterMask =
        blocks && cache ? beforeMask | (std::uint64_t(1) << k) : ~std::uint64_t(0);
      job.Before = setOf(before, cache ? beforeMask : ~std::uint64_t(0), cache);
      // A light that does not block has no set of its own: no caching.
      job.After = setOf(after, afterMask, blocks && cache);
      s.Jobs.push_back(job);
    }
    if (blocks)
    {
      runningMask |= cache ? std::uint64_t(1) << k : 0;
      for (int t = 0; t < n2; ++t)
      {
        running[t] += s.Logs[k * n2 + t];
      }
    }
  }
  // The exps, sh::BatchWidth sets at a time.
  constexpr int W = sh::BatchWidth;
  const int sets = static_cast<int>(s.SetKey.size());
  s.SetExp.resize(static_cast<std::size_t>(sets) * n2);
  s.SetStatus.resize(sets);
  alignas(64) float lanes[sh::MaxCoefficients * W], exps[sh::MaxCoefficients * W];
  sh::Status status[W];
  for (int first = 0; first < sets; first += W)
  {
    const int m = std::min(W, sets - first);
    for (int q = 0; q < W; ++q)
    {
      const float* f = &s.Sets[static_cast<std::size_t>(first + std::min(q, m - 1)) * n2];
      for (int t = 0; t < n2; ++t)
      {
        lanes[t * W + q] = f[t];
      }
    }
    sh::BatchExp(order, lanes, exps, this->Settings.Exp, status);
    for (int q = 0; q < m; ++q)
    {
      for (int t = 0; t < n2; ++t)
      {
        s.SetExp[static_cast<std::size_t>(first + q) * n2 + t] = exps[t * W + q];
      }
      s.SetStatus[first + q] = static_cast<int>(status[q]);
    }
  }
  float one[sh::MaxCoefficients];
  sh::SetConstant(order, 1.0f, one);
  const auto expAt = [&](int set) { return set < 0 ? one : &s.SetExp[std::size_t(set) * n2]; };
  const auto okAt = [&](int set)
  { return set < 0 || s.SetStatus[set] == static_cast<int>(sh::Status::Ok); };
  for (const SphericalLightScratch::Job& job : s.Jobs)
  {
    if (!okAt(job.Before) || !okAt(job.After))
    {
      ok = false;
      continue;
    }
    const float* expBefore = expAt(job.Before);
    const float* expAfter = expAt(job.After);
    float v[sh::MaxCoefficients];
    for (int t = 0; t < n2; ++t)
    {
      v[t] = expBefore[t] - expAfter[t];
    }
    const float vbar = std::max(0.0f, sh::Dot(n2, h, v));
    const Seen& e = s.List[job.Entry];
    for (int c = 0; c < 3; ++c)
    {
      const float share = std::max(0.0f, job.Lbar[c]) * vbar;
      rgb[c] += share;
      if (contributions && e.Index >= 0)
      {
        contributions[e.Index] += share;
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!std::isfinite(rgb[c]))
    {
      rgb[c] = 0.0f;
      ok = false;
    }
  }
  return ok;
}

long ShadowedIndirect::UpdateRadiance(SphericalLights& lights, const SphericalLightSamples& samples,
  const Blockers& blockers, const EnvironmentShading& environment,
  const LocalEmitters* locals) const
{
  const int order = this->Settings.Order, n2 = sh::NumCoefficients(order);
  const int m = samples.Directions;
  const std::size_t count = lights.Count();
  lights.Radiance.assign(count * 3 * n2, 0.0f);
  const SoftShadows shadows(this->Settings);
  const sh::TripleProduct& product = sh::TripleProduct::Get(order);
  std::atomic<long> failures(0);
  const bool anyLocal = locals && locals->Count() > 0;
  vtkSMPTools::For(0, static_cast<vtkIdType>(count),
    [&](vtkIdType first, vtkIdType last)
    {
      SphericalLightScratch scratch;
      float g[sh::MaxCoefficients], light[3][sh::MaxCoefficients];
      long localFailures = 0;
      for (vtkIdType i = first; i < last; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          sh::Fill(light[c], n2, 0.0f);
        }
        for (int j = 0; j < m; ++j)
        {
          const std::size_t at = (static_cast<std::size_t>(i) * m + j) * 3;
          const float* pn = &samples.Normal[at];
          if (pn[0] == 0.0f && pn[1] == 0.0f && pn[2] == 0.0f)
          {
            continue; // no sample: the SL emits nothing in this direction
          }
          const float* pp = &samples.Position[at];
          sh::Status status;
          shadows.Visibility(pp, pn, blockers, g, status);
          if (status != sh::Status::Ok)
          {
            ++localFailures;
            continue;
          }
          float rgb[3];
          environment.Shade(pn, g, rgb);
          if (anyLocal)
          {
            float lit[3];
            if (!this->ExitRadiance(lights, false, locals, &blockers, pp, pn, lit, scratch))
            {
              ++localFailures;
            }
            for (int c = 0; c < 3; ++c)
            {
              rgb[c] += lit[c];
            }
          }
          const float* y = &samples.Voronoi[static_cast<std::size_t>(j) * n2];
          for (int c = 0; c < 3; ++c)
          {
            for (int t = 0; t < n2; ++t)
            {
              light[c][t] += rgb[c] * y[t];
            }
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          const std::size_t at = (static_cast<std::size_t>(i) * 3 + c) * n2;
          product.Product(light[c], &samples.AlbedoSH[at], &lights.Radiance[at]);
        }
      }
      failures += localFailures;
    });
  return failures.load();
}

std::string PrepareSphericalLights(vtkPolyData* proxies, const std::vector<vtkIdType>& leafIds,
  vtkDataArray* levels, int order, const char* albedoArray, const double defaultAlbedo[3],
  const proxygi::EnvironmentShading& shading, bool dark, const proxygi::Blockers& blockers,
  const proxygi::LocalEmitters* emitters, const proxygi::ShadowedIndirect& kernel,
  proxygi::SphericalLights& lights, std::string& summary, std::string& error)
{
  if (leafIds.empty())
  {
    return "no proxies to act as spherical lights";
  }
  if (dark && !emitters)
  {
    return "the environment is black and there are no local lights";
  }
  const int n2 = order * order;
  vtkPointData* pd = proxies->GetPointData();
  vtkDataArray* radius = pd->GetArray("Radius");
  vtkDataArray* objectIds = pd->GetArray("ObjectId");
  vtkDataArray* offsets = pd->GetArray("SampleOffset");
  vtkDataArray* normals = pd->GetArray("SampleNormal");
  vtkDataArray* albedoSH = pd->GetArray("AlbedoSH");
  lights.Order = order;
  proxygi::SphericalLightSamples samples;
  std::vector<double> directions;
  const bool fromMesh = offsets && normals &&
    offsets->GetNumberOfComponents() == normals->GetNumberOfComponents() &&
    offsets->GetNumberOfComponents() % 3 == 0;
  if (fromMesh)
  {
    const int m = offsets->GetNumberOfComponents() / 3;
    vtkDataArray* given = proxies->GetFieldData()->GetArray("SampleDirections");
    if (given && given->GetNumberOfTuples() == m && given->GetNumberOfComponents() == 3)
    {
      directions.resize(3 * m);
      for (int j = 0; j < m; ++j)
      {
        given->GetTuple(j, &directions[3 * j]);
      }
    }
    else
    {
      directions = proxygi::sh::GeodesicDirections(3);
      if (static_cast<int>(directions.size()) != 3 * m)
      {
        error = "SampleOffset has " + std::to_string(m) +
          " samples per proxy but no SampleDirections field array matches them";
        return "bad samples";
      }
    }
  }
  else
  {
    directions = proxygi::sh::GeodesicDirections(3);
  }
  const int m = static_cast<int>(directions.size() / 3);
  samples.Directions = m;
  const std::size_t count = leafIds.size();
  samples.Position.assign(count * m * 3, 0.0f);
  samples.Normal.assign(count * m * 3, 0.0f);
  samples.AlbedoSH.assign(count * 3 * n2, 0.0f);
  std::vector<double> row;
  long found = 0;
  bool anyAlbedo = false;
  for (std::size_t i = 0; i < count; ++i)
  {
    const vtkIdType id = leafIds[i];
    double c[3];
    proxies->GetPoint(id, c);
    const double r = radius->GetTuple1(id);
    lights.Add(float(c[0]), float(c[1]), float(c[2]), float(r),
      objectIds ? static_cast<int>(objectIds->GetTuple1(id)) : 0);
    if (levels)
    {
      lights.Level.push_back(static_cast<int>(levels->GetTuple1(id)));
    }
    for (int j = 0; j < m; ++j)
    {
      double o[3], nn[3];
      if (fromMesh)
      {
        o[0] = offsets->GetComponent(id, 3 * j);
        o[1] = offsets->GetComponent(id, 3 * j + 1);
        o[2] = offsets->GetComponent(id, 3 * j + 2);
        nn[0] = normals->GetComponent(id, 3 * j);
        nn[1] = normals->GetComponent(id, 3 * j + 1);
        nn[2] = normals->GetComponent(id, 3 * j + 2);
      }
      else
      {
        // The sphere itself is the surface: the sample in w_j is c + r w_j.
        for (int k = 0; k < 3; ++k)
        {
          o[k] = nn[k] = directions[3 * j + k];
        }
      }
      const double len = vtkMath::Norm(nn);
      if (!(len > 0.0) || !std::isfinite(len) || !std::isfinite(vtkMath::Norm(o)))
      {
        continue;
      }
      float* pos = &samples.Position[(i * m + j) * 3];
      float* nor = &samples.Normal[(i * m + j) * 3];
      for (int k = 0; k < 3; ++k)
      {
        pos[k] = static_cast<float>(c[k] + r * o[k]);
        nor[k] = static_cast<float>(nn[k] / len);
      }
      ++found;
    }
    float* albedo = &samples.AlbedoSH[i * 3 * n2];
    const int k2 = albedoSH ? albedoSH->GetNumberOfComponents() / 3 : 0;
    const int k = static_cast<int>(std::lround(std::sqrt(double(k2))));
    if (albedoSH && k > 0 && k * k == k2 && 3 * k2 == albedoSH->GetNumberOfComponents())
    {
      // Per-vertex colour, sampled by vtkPGISphereLightSampler: truncate or pad.
      for (int ch = 0; ch < 3; ++ch)
      {
        for (int t = 0; t < std::min(k2, n2); ++t)
        {
          const double v = albedoSH->GetComponent(id, ch * k2 + t);
          albedo[ch * n2 + t] = std::isfinite(v) ? static_cast<float>(v) : 0.0f;
        }
      }
    }
    else
    {
      double a[3];
      proxygi::AlbedoOf(proxies, albedoArray, id, defaultAlbedo, a);
      for (int ch = 0; ch < 3; ++ch)
      {
        albedo[ch * n2] = static_cast<float>(a[ch] * proxygi::sh::SqrtFourPi);
      }
    }
    for (int ch = 0; ch < 3; ++ch)
    {
      anyAlbedo = anyAlbedo || albedo[ch * n2] > 0.0f;
    }
  }
  if (!fromMesh)
  {
    // Rule 2 on the spheres: a point inside another sphere of the object is hidden.
    lights.Finish();
    for (std::size_t i = 0; i < count; ++i)
    {
      for (int j = 0; j < m; ++j)
      {
        float* pos = &samples.Position[(i * m + j) * 3];
        for (std::size_t q = 0; q < count; ++q)
        {
          if (!lights.Intersects[i * count + q])
          {
            continue;
          }
          const float dx = pos[0] - lights.X[q], dy = pos[1] - lights.Y[q],
                      dz = pos[2] - lights.Z[q];
          if (dx * dx + dy * dy + dz * dz < lights.R[q] * lights.R[q])
          {
            std::fill(pos, pos + 3, 0.0f);
            std::fill(&samples.Normal[(i * m + j) * 3], &samples.Normal[(i * m + j) * 3] + 3, 0.0f);
            --found;
            break;
          }
        }
      }
    }
  }
  if (!anyAlbedo)
  {
    return "every spherical light has albedo 0";
  }
  if (found <= 0)
  {
    return "no surface samples";
  }
  lights.Finish();
  const std::vector<double> voronoi = proxygi::sh::VoronoiBasisSums(order, directions);
  samples.Voronoi.assign(voronoi.begin(), voronoi.end());
  const auto start = std::chrono::steady_clock::now();
  const long failed = kernel.UpdateRadiance(lights, samples, blockers, shading, emitters);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream line;
  line << count << " spherical lights, " << found << " surface samples of " << count * m << " ("
       << (fromMesh ? "SampleOffset/SampleNormal arrays" : "on the spheres themselves") << "), "
       << (albedoSH ? "AlbedoSH" : "per-object albedo") << ", first pass " << seconds << " s"
       << (emitters ? " (with local lights)" : "");
  if (failed > 0)
  {
    line << ", " << failed << " samples left unlit (non-finite SH)";
  }
  summary = line.str();
  return "";
}

} // namespace proxygi
