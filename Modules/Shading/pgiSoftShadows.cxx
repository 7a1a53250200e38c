#include "pgiSoftShadows.h"

#include "pgiBrightLights.h"
#include "pgiSHBatch.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"
#include "pgiSHZonal.h"
#include "pgiSoftShadowsBatch.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

namespace proxygi
{

bool Blockers::AboveEveryPlane(const float p[3]) const
{
  for (std::size_t k = 0; k < this->Planes(); ++k)
  {
    const float* o = &this->PlaneOrigin[3 * k];
    const float* m = &this->PlaneNormal[3 * k];
    if (!((p[0] - o[0]) * m[0] + (p[1] - o[1]) * m[1] + (p[2] - o[2]) * m[2] > 0.0f))
    {
      return false;
    }
  }
  return true;
}

void Blockers::AddSphere(float x, float y, float z, float r, const float* albedo, int object)
{
  this->Object.push_back(object);
  this->X.push_back(x);
  this->Y.push_back(y);
  this->Z.push_back(z);
  this->R.push_back(r);
  const float black[3] = { 0, 0, 0 };
  const float* a = albedo ? albedo : black;
  this->Albedo.insert(this->Albedo.end(), a, a + 3);
}

void Blockers::AddPlane(
  const float origin[3], const float normal[3], const float* albedo, const float* halfEdges)
{
  const float black[3] = { 0, 0, 0 };
  const float* a = albedo ? albedo : black;
  this->PlaneAlbedo.insert(this->PlaneAlbedo.end(), a, a + 3);
  const float unbounded[6] = { 0, 0, 0, 0, 0, 0 };
  const float* e = halfEdges ? halfEdges : unbounded;
  this->PlaneExtent.insert(this->PlaneExtent.end(), e, e + 6);
  const float len =
    std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  this->PlaneOrigin.insert(this->PlaneOrigin.end(), origin, origin + 3);
  for (int k = 0; k < 3; ++k)
  {
    this->PlaneNormal.push_back(len > 0.0f ? normal[k] / len : (k == 2 ? 1.0f : 0.0f));
  }
}

bool ReplaceBlocker(const float p[3], const float n[3], float c[3], float& r)
{
  const float v[3] = { c[0] - p[0], c[1] - p[1], c[2] - p[2] };
  const float h = v[0] * n[0] + v[1] * n[1] + v[2] * n[2]; // centre height over T_p
  if (h <= -r)
  {
    return false; // entirely behind
  }
  if (h >= r)
  {
    return true; // entirely in front: unchanged
  }
  const float d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const float rho = std::sqrt(std::max(0.0f, d2 - h * h));      // along T_p to the foot F
  const float delta = std::sqrt(std::max(0.0f, r * r - h * h)); // T_p cuts a circle of this radius
  // F: the foot of the centre on T_p.
  const float f[3] = { c[0] - h * n[0], c[1] - h * n[1], c[2] - h * n[2] };
  if (d2 < r * r)
  {
    if (h <= 0.0f)
    {
      return false;
    }
    const float ramp = delta > 0.0f ? std::min(1.0f, 2.0f * (delta - rho) / delta) : 0.0f;
    r = h * std::max(0.0f, ramp);
    return r > 0.0f;
  }
  // Outside and cut by T_p: diameter from q0 = c + r n down to q1 = F + (r + h) n - (r + h) n.
  // rho - delta as (d^2 - r^2) / (rho + delta): no cancellation at the rim.
  const float ramp = delta > 0.0f ? std::min(1.0f, (d2 - r * r) / (rho + delta) / delta) : 1.0f;
  const float half = 0.5f * (h + r);
  for (int k = 0; k < 3; ++k)
  {
    c[k] = f[k] + half * n[k];
  }
  r = half * std::max(0.0f, ramp);
  return r > 0.0f;
}

SoftShadows::SoftShadows(const SoftShadowSettings& settings)
  : Settings(settings)
{
  this->AccOrder =
    settings.AccumulationOrder > settings.Order ? settings.AccumulationOrder : settings.Order;
  this->AccOrder = std::min(this->AccOrder, sh::MaxOrder);
  sh::CapTables::Get(this->AccOrder); // build before the parallel loops
}

namespace
{
// The self-shadow rules run only where the receiver's own proxies may be
// among the spheres (its object unknown); see the file comment.
bool RulesApply(const SoftShadowSettings& settings, const SelfVisibility& self)
{
  return settings.SelfShadowRules && self.Object < 0 && !self.OwnsNoSpheres;
}

// Calls visit(index, theta, dx, dy, dz, ratio) for every blocker receiver
// (p, n) accumulates, in accumulation order: spheres after the rules, then
// planes (index -1 - k; in log space only when inLog, else reported only
// with ratio null and theta MaxAngle). The batched twin is BlockerLanesImpl.
template <typename Visit>
void VisitBlockers(const SoftShadowSettings& settings, bool rules, bool ratios, const float p[3],
  const float n[3], const Blockers& b, Visit&& visit)
{
  const float sinMin = std::sin(settings.MinAngle);
  for (std::size_t s = 0; s < b.X.size(); ++s)
  {
    float c[3] = { b.X[s], b.Y[s], b.Z[s] };
    float r = b.R[s];
    if (!(r > 0.0f))
    {
      continue; // zero-radius (or NaN) spheres block nothing
    }
    if (rules && !ReplaceBlocker(p, n, c, r))
    {
      continue;
    }
    const float dx = c[0] - p[0], dy = c[1] - p[1], dz = c[2] - p[2];
    const float d = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(d > 0.0f) || r < sinMin * d)
    {
      continue;
    }
    const float inverse = 1.0f / d; // one division, as the batched twin
    const float theta = detail::BlockerAsin(std::min(1.0f, r * inverse));
    visit(static_cast<int>(s), theta, dx * inverse, dy * inverse, dz * inverse,
      ratios ? &b.Ratio[s * settings.Order] : nullptr, true);
  }
  for (std::size_t k = 0; k < b.Planes(); ++k)
  {
    const float* o = &b.PlaneOrigin[3 * k];
    const float* pn = &b.PlaneNormal[3 * k];
    const float height = (p[0] - o[0]) * pn[0] + (p[1] - o[1]) * pn[1] + (p[2] - o[2]) * pn[2];
    // Seen from above, the plane hides the half-space below: a 90-degree cap,
    // whatever the receiver's normal (no rule, so no jump as normals turn).
    // Receivers on or under the plane do not see it.
    if (!(height > 0.0f))
    {
      continue;
    }
    visit(-1 - static_cast<int>(k), static_cast<float>(sh::CapTables::MaxAngle), -pn[0], -pn[1],
      -pn[2], nullptr, settings.PlanesInLogSpace);
  }
}
} // namespace

namespace
{
// Whether a precomputed log row adds anything (an all-zero row is V = 1).
bool AnyNonZero(const float* v, int count)
{
  for (int i = 0; i < count; ++i)
  {
    if (v[i] != 0.0f)
    {
      return true;
    }
  }
  return false;
}
} // namespace

int SoftShadows::Visibility(const float p[3], const float n[3], const Blockers& b, float* g,
  sh::Status& status, std::vector<SeenBlocker>* seen, const SelfVisibility& self) const
{
  if (seen)
  {
    seen->clear();
  }
  const int order = this->Settings.Order, acc = this->AccOrder;
  const int n2 = sh::NumCoefficients(order), a2 = sh::NumCoefficients(acc);
  const sh::CapTables& tables = sh::CapTables::Get(acc);
  float f[sh::MaxCoefficients], zh[sh::MaxOrder], v[sh::MaxCoefficients];
  sh::Fill(f, a2, 0.0f);
  status = sh::Status::Ok;
  int used = 0;
  if (self.Log && AnyNonZero(self.Log, a2))
  {
    std::copy(self.Log, self.Log + a2, f);
    ++used;
  }
  const bool skipOwn = self.Object >= 0 && b.Object.size() == b.X.size();
  VisitBlockers(this->Settings, RulesApply(this->Settings, self), !b.Ratio.empty() && acc == order,
    p, n, b,
    [&](int index, float theta, float dx, float dy, float dz, const float* ratio, bool inLog)
    {
      if (inLog && !(skipOwn && index >= 0 && b.Object[index] == self.Object))
      {
        tables.CapLog(theta, zh);
        if (ratio)
        {
          for (int l = 0; l < order; ++l)
          {
            zh[l] *= ratio[l];
          }
        }
        sh::RotateScaledZonal(acc, zh, dx, dy, dz, v);
        for (int i = 0; i < a2; ++i)
        {
          f[i] += v[i];
        }
        ++used;
      }
      if (seen)
      {
        seen->push_back({ index, theta, { dx, dy, dz } });
      }
    });
  if (used == 0)
  {
    sh::SetConstant(order, 1.0f, g);
    return 0;
  }
  float full[sh::MaxCoefficients];
  status = sh::Exp(acc, f, full, this->Settings.Exp);
  std::copy(full, full + n2, g); // truncation to the output order
  this->Finish(g);
  return used;
}

void SoftShadows::VisibilityBatch(int count, const float* p, const float* n, const Blockers& b,
  float* g, sh::Status* status, int* used, std::vector<SeenBlocker>* seen,
  const SelfVisibility& self) const
{
  const int order = this->Settings.Order, acc = this->AccOrder;
  const int n2 = sh::NumCoefficients(order), a2 = sh::NumCoefficients(acc);
  if (!sh::BatchKernelsEnabled())
  {
    for (int i = 0; i < count; ++i)
    {
      SelfVisibility mine = self;
      mine.Log = self.Log ? &self.Log[i * a2] : nullptr;
      used[i] = this->Visibility(
        &p[3 * i], &n[3 * i], b, &g[i * n2], status[i], seen ? &seen[i] : nullptr, mine);
    }
    return;
  }
  constexpr int W = sh::BatchWidth;
  constexpr int Rows = 32; // blockers per pass: the rows stay on the stack
  const sh::CapTables& tables = sh::CapTables::Get(acc);
  const bool ratios = !b.Ratio.empty() && acc == order;
  const float sinMin = std::sin(this->Settings.MinAngle);
  const int spheres = static_cast<int>(b.Spheres()), planes = static_cast<int>(b.Planes());
  const bool skipOwn = self.Object >= 0 && b.Object.size() == b.X.size();
  const bool rules = RulesApply(this->Settings, self);
  alignas(64) float lanes[6 * W], theta[Rows * W], dx[Rows * W], dy[Rows * W], dz[Rows * W];
  alignas(64) float f[sh::MaxCoefficients * W], e[sh::MaxCoefficients * W];
  int laneUsed[W];
  sh::Status laneStatus[W];
  // Rows [0, rows) of theta and the directions: counted for the lanes that
  // accumulate them, listed for the receivers that want them (row r is
  // blocker first + r, or plane k for index -1 - k).
  auto countUsed = [&](int rows)
  {
    for (int r = 0; r < rows; ++r)
    {
      for (int k = 0; k < W; ++k)
      {
        laneUsed[k] += theta[r * W + k] >= 0.0f ? 1 : 0;
      }
    }
  };
  auto list = [&](int start, int m, int rows, int firstIndex, int step)
  {
    for (int k = 0; seen && k < m; ++k)
    {
      for (int r = 0; r < rows; ++r)
      {
        const int q = r * W + k;
        if (theta[q] >= 0.0f)
        {
          seen[start + k].push_back({ firstIndex + step * r, theta[q], { dx[q], dy[q], dz[q] } });
        }
      }
    }
  };
  for (int first = 0; first < count; first += W)
  {
    const int m = std::min(W, count - first);
    for (int k = 0; k < W; ++k)
    {
      const int i = first + std::min(k, m - 1); // spare lanes repeat the last receiver
      for (int c = 0; c < 3; ++c)
      {
        lanes[c * W + k] = p[3 * i + c];
        lanes[(3 + c) * W + k] = n[3 * i + c];
      }
      laneUsed[k] = 0;
    }
    for (int k = 0; seen && k < m; ++k)
    {
      seen[first + k].clear();
    }
    std::fill(f, f + a2 * W, 0.0f);
    for (int k = 0; self.Log && k < m; ++k)
    {
      const float* row = &self.Log[(first + k) * a2];
      if (AnyNonZero(row, a2))
      {
        for (int j = 0; j < a2; ++j)
        {
          f[j * W + k] = row[j];
        }
        laneUsed[k] = 1;
      }
    }
    for (int s0 = 0; s0 < spheres; s0 += Rows)
    {
      const int rows = std::min(Rows, spheres - s0);
      detail::BlockerLanes(
        lanes, &b.X[s0], &b.Y[s0], &b.Z[s0], &b.R[s0], rows, sinMin, rules, theta, dx, dy, dz);
      list(first, m, rows, s0, 1);
      // The own object's spheres: listed, not accumulated.
      for (int r = 0; skipOwn && r < rows; ++r)
      {
        if (b.Object[s0 + r] == self.Object)
        {
          std::fill(&theta[r * W], &theta[r * W] + W, -1.0f);
        }
      }
      countUsed(rows);
      sh::BatchAddCaps(
        tables, acc, rows, theta, dx, dy, dz, ratios ? &b.Ratio[s0 * order] : nullptr, f);
    }
    // Planes are listed whether or not they are in log space.
    const bool planeRows = this->Settings.PlanesInLogSpace || seen;
    for (int k0 = 0; planeRows && k0 < planes; k0 += Rows)
    {
      const int rows = std::min(Rows, planes - k0);
      for (int r = 0; r < rows; ++r)
      {
        const float* o = &b.PlaneOrigin[3 * (k0 + r)];
        const float* pn = &b.PlaneNormal[3 * (k0 + r)];
        for (int k = 0; k < W; ++k)
        {
          const float height = (lanes[k] - o[0]) * pn[0] + (lanes[W + k] - o[1]) * pn[1] +
            (lanes[2 * W + k] - o[2]) * pn[2];
          theta[r * W + k] = height > 0.0f ? static_cast<float>(sh::CapTables::MaxAngle) : -1.0f;
          dx[r * W + k] = -pn[0];
          dy[r * W + k] = -pn[1];
          dz[r * W + k] = -pn[2];
        }
      }
      list(first, m, rows, -1 - k0, -1);
      if (this->Settings.PlanesInLogSpace)
      {
        countUsed(rows);
        sh::BatchAddCaps(tables, acc, rows, theta, dx, dy, dz, nullptr, f);
      }
    }
    if (std::any_of(laneUsed, laneUsed + W, [](int u) { return u > 0; }))
    {
      sh::BatchExp(acc, f, e, this->Settings.Exp, laneStatus);
    }
    for (int k = 0; k < m; ++k)
    {
      const int i = first + k;
      float* out = &g[i * n2];
      used[i] = laneUsed[k];
      status[i] = sh::Status::Ok;
      if (laneUsed[k] == 0)
      {
        sh::SetConstant(order, 1.0f, out);
        continue;
      }
      for (int j = 0; j < n2; ++j)
      {
        out[j] = e[j * W + k];
      }
      status[i] = laneStatus[k];
      this->Finish(out);
    }
  }
}

void SoftShadows::Finish(float* g) const
{
  if (this->Settings.WindowH != 0.0)
  {
    sh::Window(
      this->Settings.Order, g, this->Settings.WindowH < 0.0 ? 0.0 : this->Settings.WindowH);
  }
}

bool ProxyHierarchy::Finish()
{
  const int count = static_cast<int>(this->X.size());
  this->Children.assign(count, {});
  this->Roots.clear();
  for (int i = 0; i < count; ++i)
  {
    const int parent = this->Parent[i];
    if (parent < 0)
    {
      this->Roots.push_back(i);
    }
    else if (parent >= count || parent == i || this->Level[parent] <= this->Level[i])
    {
      return false;
    }
    else
    {
      this->Children[parent].push_back(i);
    }
  }
  // A parent reflects like its children on average (bottom-up, by level).
  if (this->Albedo.size() == 3 * static_cast<std::size_t>(count))
  {
    const int top = count ? *std::max_element(this->Level.begin(), this->Level.end()) : 0;
    for (int level = 1; level <= top; ++level)
    {
      for (int i = 0; i < count; ++i)
      {
        if (this->Level[i] != level || this->Children[i].empty())
        {
          continue;
        }
        float sum[3] = { 0, 0, 0 };
        for (int child : this->Children[i])
        {
          for (int c = 0; c < 3; ++c)
          {
            sum[c] += this->Albedo[3 * child + c];
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          this->Albedo[3 * i + c] = sum[c] / static_cast<float>(this->Children[i].size());
        }
      }
    }
  }
  return true;
}

namespace
{
// Scaled log-visibility ZH and direction of a (replaced) sphere from p.
bool SphereLog(const sh::CapTables& tables, const float p[3], const float n[3], float c[3], float r,
  bool rules, float* zh, float dir[3])
{
  if (rules && !ReplaceBlocker(p, n, c, r))
  {
    return false;
  }
  const float d[3] = { c[0] - p[0], c[1] - p[1], c[2] - p[2] };
  const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0.0f) || !(r > 0.0f))
  {
    return false;
  }
  tables.CapLog(std::asin(std::min(1.0f, r / len)), zh);
  for (int k = 0; k < 3; ++k)
  {
    dir[k] = d[k] / len;
  }
  return true;
}

// Cosine-weighted spherical-Fibonacci directions about +z, per count: the
// same for every receiver, so their square roots and trigonometry once.
struct CosineFibonacci
{
  std::vector<double> Side, Up, Cos, Sin;

  static const CosineFibonacci& Get(int samples)
  {
    static std::mutex lock;
    static std::map<int, std::unique_ptr<CosineFibonacci>> made;
    const std::lock_guard<std::mutex> guard(lock);
    std::unique_ptr<CosineFibonacci>& entry = made[samples];
    if (!entry)
    {
      entry.reset(new CosineFibonacci);
      const double golden = sh::Pi * (3.0 - std::sqrt(5.0));
      for (int k = 0; k < samples; ++k)
      {
        const double u = (k + 0.5) / samples;
        entry->Side.push_back(std::sqrt(u));
        entry->Up.push_back(std::sqrt(1.0 - u));
        entry->Cos.push_back(std::cos(golden * k));
        entry->Sin.push_back(std::sin(golden * k));
      }
    }
    return *entry;
  }
};

// Whether a ray along the unit w meets the sphere at offset e from its
// origin (ee = |e|^2, rr = radius^2) ahead of it.
inline bool RayMeetsOffsetSphere(const double e[3], double ee, double rr, const double w[3])
{
  const double along = e[0] * w[0] + e[1] * w[1] + e[2] * w[2];
  return along > 0.0 && ee - along * along < rr;
}

// Whether the ray from p along the unit w meets the sphere (x, y, z, r)
// ahead of p.
bool RayMeetsSphere(const float p[3], const double w[3], float x, float y, float z, float r)
{
  const double e[3] = { x - p[0], y - p[1], z - p[2] };
  return RayMeetsOffsetSphere(
    e, e[0] * e[0] + e[1] * e[1] + e[2] * e[2], static_cast<double>(r) * r, w);
}

// The solid angles of `leaves` seen from p, summed.
double LeavesSolidAngle(const ProxyHierarchy& h, const std::vector<int>& leaves, const float p[3])
{
  double sum = 0.0;
  for (int j : leaves)
  {
    const double d[3] = { h.X[j] - p[0], h.Y[j] - p[1], h.Z[j] - p[2] };
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    sum += sh::CapSolidAngle(len > h.R[j] ? std::asin(h.R[j] / len) : sh::Pi / 2);
  }
  return sum;
}

// The solid angle the union of `leaves` covers seen from p: the share of
// 128 spherical-Fibonacci directions in the cap of `node` (which bounds
// them) that meet a leaf, times the cap's solid angle.
double UnionSolidAngle(
  const ProxyHierarchy& h, const std::vector<int>& leaves, int node, const float p[3])
{
  constexpr int Samples = 128;
  const double d[3] = { h.X[node] - p[0], h.Y[node] - p[1], h.Z[node] - p[2] };
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > h.R[node]))
  {
    return LeavesSolidAngle(h, leaves, p);
  }
  const double axis[3] = { d[0] / len, d[1] / len, d[2] / len };
  const double cosCap = std::sqrt(std::max(0.0, 1.0 - (h.R[node] / len) * (h.R[node] / len)));
  double t[3], b[3];
  FrameAbout(axis, t, b);
  const CosineFibonacci& fibonacci = CosineFibonacci::Get(Samples);
  int hits = 0;
  for (int k = 0; k < Samples; ++k)
  {
    const double z = 1.0 - (1.0 - cosCap) * (k + 0.5) / Samples;
    const double side = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double c = fibonacci.Cos[k], s = fibonacci.Sin[k];
    double w[3];
    for (int q = 0; q < 3; ++q)
    {
      w[q] = z * axis[q] + side * (c * t[q] + s * b[q]);
    }
    for (int j : leaves)
    {
      if (RayMeetsSphere(p, w, h.X[j], h.Y[j], h.Z[j], h.R[j]))
      {
        ++hits;
        break;
      }
    }
  }
  return 2.0 * sh::Pi * (1.0 - cosCap) * hits / Samples;
}
} // namespace

double UnionCoveredShare(
  const Blockers& leaves, const float p[3], const float n[3], int directions, bool everyPair)
{
  const int samples = std::max(16, directions);
  const CosineFibonacci& fibonacci = CosineFibonacci::Get(samples);
  const double axis[3] = { n[0], n[1], n[2] };
  double t[3], b[3];
  FrameAbout(axis, t, b);
  // The directions, once per receiver.
  thread_local std::vector<double> directionsAt;
  thread_local std::vector<char> hit;
  directionsAt.resize(3 * static_cast<std::size_t>(samples));
  hit.assign(samples, 0);
  for (int k = 0; k < samples; ++k)
  {
    const double side = fibonacci.Side[k], up = fibonacci.Up[k], c = fibonacci.Cos[k],
                 s = fibonacci.Sin[k];
    for (int q = 0; q < 3; ++q)
    {
      directionsAt[3 * k + q] = up * axis[q] + side * (c * t[q] + s * b[q]);
    }
  }
  // A leaf can only meet the directions whose polar angle lies within its
  // angular radius of its own: the samples run in polar angle (u = sin^2),
  // so each leaf tests one range of them, widened against rounding. The
  // count is the union's, whatever order the leaves mark it in.
  for (std::size_t j = 0; j < leaves.Spheres(); ++j)
  {
    const double e[3] = { leaves.X[j] - p[0], leaves.Y[j] - p[1], leaves.Z[j] - p[2] };
    const double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    const double rr = static_cast<double>(leaves.R[j]) * leaves.R[j];
    const double height = e[0] * axis[0] + e[1] * axis[1] + e[2] * axis[2];
    if (!everyPair && !(height > -1.001 * leaves.R[j] - 1e-30))
    {
      continue; // wholly below the receiver's plane (or not a number)
    }
    int first = 0, last = samples - 1;
    const double len = std::sqrt(ee);
    if (!everyPair && len > 0.0 && ee > rr && std::isfinite(len))
    {
      const double margin = 1e-4;
      const double polar = std::acos(std::max(-1.0, std::min(1.0, height / len)));
      const double radius = std::asin(std::min(1.0, leaves.R[j] / len));
      const double lo = std::max(0.0, polar - radius - margin);
      const double hi = std::min(0.5 * sh::Pi, polar + radius + margin);
      if (lo >= hi)
      {
        continue;
      }
      const double sinLo = std::sin(lo), sinHi = std::sin(hi);
      first = std::max(0, static_cast<int>(std::floor(sinLo * sinLo * samples - 0.5)) - 1);
      last = std::min(samples - 1, static_cast<int>(std::ceil(sinHi * sinHi * samples - 0.5)) + 1);
    }
    for (int k = first; k <= last; ++k)
    {
      if (hit[k])
      {
        continue;
      }
      hit[k] = RayMeetsOffsetSphere(e, ee, rr, &directionsAt[3 * k]) ? 1 : 0;
    }
  }
  int hits = 0;
  for (int k = 0; k < samples; ++k)
  {
    hits += hit[k];
  }
  return static_cast<double>(hits) / samples;
}

float ScaleCutToUnion(Blockers& cut, const Blockers& leaves, const SoftShadows& kernel,
  const float p[3], const float n[3], int directions)
{
  const int order = kernel.GetOrder(), n2 = order * order;
  if (cut.Spheres() == 0 || kernel.GetAccumulationOrder() != order)
  {
    return 1.0f;
  }
  // The union's cosine-weighted share of the hemisphere.
  const double covered = UnionCoveredShare(leaves, p, n, directions);
  if (cut.Ratio.size() != static_cast<std::size_t>(order) * cut.Spheres())
  {
    cut.Ratio.assign(static_cast<std::size_t>(order) * cut.Spheres(), 1.0f);
  }
  const std::vector<float> base = cut.Ratio;
  float h[sh::MaxCoefficients], g[sh::MaxCoefficients];
  sh::DiffuseTransfer(order, n[0], n[1], n[2], h);
  const double open = static_cast<double>(h[0]) * sh::SqrtFourPi;
  SelfVisibility ground;
  ground.OwnsNoSpheres = true;
  // The blocked share falls with the logs' scale: a few multiplicative steps.
  double scale = 1.0;
  for (int step = 0; step < 6 && open > 0.0; ++step)
  {
    for (std::size_t q = 0; q < base.size(); ++q)
    {
      cut.Ratio[q] = base[q] * static_cast<float>(scale);
    }
    sh::Status status;
    kernel.Visibility(p, n, cut, g, status, nullptr, ground);
    const double blocked = 1.0 - sh::Dot(n2, h, g) / open;
    if (status != sh::Status::Ok || !(blocked > covered * 1.01) || !(blocked > 0.0))
    {
      break;
    }
    scale = std::max(0.05, scale * covered / blocked);
  }
  for (std::size_t q = 0; q < base.size(); ++q)
  {
    cut.Ratio[q] = base[q] * static_cast<float>(scale);
  }
  return static_cast<float>(scale);
}

Blockers CutHierarchy(const ProxyHierarchy& h, const float pR[3], float rR, const float p[3],
  const float n[3], float maxAngle, int order, bool rules, std::vector<int>* nodes)
{
  Blockers cut;
  if (nodes)
  {
    nodes->clear();
  }
  const sh::CapTables& tables = sh::CapTables::Get(order);
  const int n2 = sh::NumCoefficients(order);
  const float sinMax = std::sin(maxAngle);
  std::vector<int> stack(h.Roots.rbegin(), h.Roots.rend()), leaves;
  float zh[sh::MaxOrder], dir[3], fb[sh::MaxCoefficients], fd[sh::MaxCoefficients],
    v[sh::MaxCoefficients];
  while (!stack.empty())
  {
    const int i = stack.back();
    stack.pop_back();
    const float dx = h.X[i] - pR[0], dy = h.Y[i] - pR[1], dz = h.Z[i] - pR[2];
    const float dist = std::sqrt(dx * dx + dy * dy + dz * dz);
    const bool leaf = h.Children[i].empty();
    if (!leaf && !(h.R[i] < sinMax * (dist - rR)))
    {
      stack.insert(stack.end(), h.Children[i].rbegin(), h.Children[i].rend());
      continue;
    }
    cut.AddSphere(h.X[i], h.Y[i], h.Z[i], h.R[i], h.Albedo.empty() ? nullptr : &h.Albedo[3 * i],
      h.Object.empty() ? -1 : h.Object[i]);
    if (nodes)
    {
      nodes->push_back(i);
    }
    std::vector<float> ratio(order, 1.0f);
    float c[3] = { h.X[i], h.Y[i], h.Z[i] };
    if (!leaf && SphereLog(tables, p, n, c, h.R[i], rules, zh, dir))
    {
      // Bounding log at p, and the sum of its leaves' logs at p.
      sh::RotateScaledZonal(order, zh, dir[0], dir[1], dir[2], fb);
      sh::Fill(fd, n2, 0.0f);
      std::vector<int> below(h.Children[i]);
      leaves.clear();
      while (!below.empty())
      {
        const int j = below.back();
        below.pop_back();
        if (!h.Children[j].empty())
        {
          below.insert(below.end(), h.Children[j].begin(), h.Children[j].end());
          continue;
        }
        leaves.push_back(j);
        float cj[3] = { h.X[j], h.Y[j], h.Z[j] };
        if (SphereLog(tables, p, n, cj, h.R[j], rules, zh, dir))
        {
          sh::RotateScaledZonal(order, zh, dir[0], dir[1], dir[2], v);
          for (int q = 0; q < n2; ++q)
          {
            fd[q] += v[q];
          }
        }
      }
      // Least-squares per-band scale of the bounding log onto the detailed one.
      for (int l = 0; l < order; ++l)
      {
        float num = 0.0f, den = 0.0f;
        for (int q = l * l; q < (l + 1) * (l + 1); ++q)
        {
          num += fb[q] * fd[q];
          den += fb[q] * fb[q];
        }
        ratio[l] = den > 0.0f ? num / den : 1.0f;
      }
      // Below the SH's resolution the exp of summed logs adds overlapping
      // caps: the node blocks what its leaves' union blocks instead.
      const double sum = LeavesSolidAngle(h, leaves, p);
      const double covered = UnionSolidAngle(h, leaves, i, p);
      if (sum > covered && sum > 0.0)
      {
        for (float& x : ratio)
        {
          x *= static_cast<float>(covered / sum);
        }
      }
    }
    cut.Ratio.insert(cut.Ratio.end(), ratio.begin(), ratio.end());
  }
  return cut;
}

} // namespace proxygi
