#include "pgiBrightLightShadows.h"

#include "vtkPGIOccluder.h"

#include <algorithm>
#include <cmath>

namespace proxygi
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

double Clamp1(double x)
{
  return std::max(-1.0, std::min(1.0, x));
}

// Whether plane k blocks direction w at p (p above it, w going below).
bool PlaneBlocks(
  const Blockers& blockers, std::size_t k, const float p[3], const float* w, float slack)
{
  const float* o = &blockers.PlaneOrigin[3 * k];
  const float* m = &blockers.PlaneNormal[3 * k];
  const float s = (p[0] - o[0]) * m[0] + (p[1] - o[1]) * m[1] + (p[2] - o[2]) * m[2];
  return s > -slack && w[0] * m[0] + w[1] * m[1] + w[2] * m[2] < 0.0f;
}

// Sum over light l's directions of max(n.w, 0).
double CosineSum(const BrightLightSet& lights, std::size_t l, const float n[3])
{
  const float* dirs = &lights.Directions[3 * static_cast<std::size_t>(lights.Rays) * l];
  double sum = 0.0;
  for (int k = 0; k < lights.Rays; ++k)
  {
    const float* w = &dirs[3 * k];
    sum += std::max(0.0f, n[0] * w[0] + n[1] * w[1] + n[2] * w[2]);
  }
  return sum;
}
} // namespace

double CapOverlapArea(double a, double b, double g)
{
  if (g >= a + b)
  {
    return 0.0;
  }
  if (g <= std::abs(a - b))
  {
    return 2 * Pi * (1.0 - std::cos(std::min(a, b)));
  }
  // Tovchigrechko and Vakser (2001): the lune of two caps.
  const double ca = std::cos(a), cb = std::cos(b), cg = std::cos(g);
  const double sa = std::sin(a), sb = std::sin(b), sg = std::sin(g);
  const double x = std::acos(Clamp1((cg - ca * cb) / (sa * sb)));
  const double y = std::acos(Clamp1((cb - cg * ca) / (sg * sa)));
  const double z = std::acos(Clamp1((ca - cg * cb) / (sg * sb)));
  const double area = 2.0 * (Pi - x - y * ca - z * cb);
  return std::max(0.0, std::min(area, 2 * Pi * (1.0 - std::cos(std::min(a, b)))));
}

void BrightLightSet::Set(const std::vector<DistantLight>& lights, int rays)
{
  this->Lights = lights;
  this->Rays = std::max(1, rays);
  const std::size_t k = static_cast<std::size_t>(this->Rays);
  this->Directions.assign(3 * k * lights.size(), 0.0f);
  this->Scale.assign(3 * lights.size(), 0.0f);
  for (std::size_t l = 0; l < lights.size(); ++l)
  {
    DistantLightDirections(lights[l], this->Rays, 0.0, &this->Directions[3 * k * l]);
    for (int c = 0; c < 3; ++c)
    {
      this->Scale[3 * l + c] =
        static_cast<float>(lights[l].Radiance[c] * lights[l].SolidAngle() / (Pi * this->Rays));
    }
  }
}

double ConeVisibility(const BrightLightSet& lights, std::size_t l, const Blockers& blockers,
  const float q[3], const float n[3], float minAngle)
{
  const DistantLight& light = lights.Lights[l];
  const double omega = light.SolidAngle();
  const double* d = light.Direction;
  const double ca = std::cos(light.HalfAngle), sa = std::sin(light.HalfAngle);
  double visible = 1.0;
  for (std::size_t s = 0; s < blockers.Spheres() && visible > 0.0; ++s)
  {
    float c[3] = { blockers.X[s], blockers.Y[s], blockers.Z[s] };
    float r = blockers.R[s];
    {
      // The rules only shrink a sphere within itself: one apart from the
      // cone as it is stays apart (no rules run).
      const double v[3] = { c[0] - q[0], c[1] - q[1], c[2] - q[2] };
      const double dist2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      const double along = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
      if (dist2 > static_cast<double>(r) * r)
      {
        const double dist = std::sqrt(dist2);
        const double sb = r / dist, cb = std::sqrt(1.0 - sb * sb);
        if (along / dist <= ca * cb - sa * sb)
        {
          continue;
        }
      }
    }
    if (!ReplaceBlocker(q, n, c, r))
    {
      continue;
    }
    const double v[3] = { c[0] - q[0], c[1] - q[1], c[2] - q[2] };
    const double dist = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(dist > 0.0))
    {
      continue;
    }
    const double sb = std::min(1.0, r / dist), cb = std::sqrt(1.0 - sb * sb);
    const double cg = (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / dist;
    // Apart (gamma >= alpha + beta) costs no acos.
    if (cg <= ca * cb - sa * sb || std::asin(sb) < minAngle)
    {
      continue;
    }
    const double covered = CapOverlapArea(light.HalfAngle, std::asin(sb), std::acos(Clamp1(cg)));
    visible *= 1.0 - std::min(1.0, covered / omega);
  }
  for (std::size_t k = 0; k < blockers.Planes() && visible > 0.0; ++k)
  {
    const float* o = &blockers.PlaneOrigin[3 * k];
    const float* m = &blockers.PlaneNormal[3 * k];
    if ((q[0] - o[0]) * m[0] + (q[1] - o[1]) * m[1] + (q[2] - o[2]) * m[2] <= 0.0f)
    {
      continue; // on or below it: not blocked by it
    }
    // The half-space beneath: a cap of 90 degrees about -m.
    const double gamma = std::acos(Clamp1(-(m[0] * d[0] + m[1] * d[1] + m[2] * d[2])));
    visible *= 1.0 - std::min(1.0, CapOverlapArea(light.HalfAngle, Pi / 2, gamma) / omega);
  }
  return std::max(0.0, visible);
}

void BrightLightsFromProxies(const BrightLightSet& lights, const Blockers& blockers,
  const float p[3], const float n[3], float minAngle, bool shadows, float rgb[3])
{
  for (std::size_t l = 0; l < lights.Lights.size(); ++l)
  {
    const double cosines = CosineSum(lights, l, n);
    if (cosines <= 0.0)
    {
      continue;
    }
    const double visible = shadows ? ConeVisibility(lights, l, blockers, p, n, minAngle) : 1.0;
    const double weight = cosines * std::max(0.0, visible);
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] += static_cast<float>(lights.Scale[3 * l + c] * weight);
    }
  }
}

void BrightLightsFromRays(const BrightLightSet& lights, const Blockers& blockers,
  const vtkPGIOccluder& occluder, const float p[3], const float n[3], float offset,
  BrightLightScratch& scratch, float rgb[3])
{
  BrightLightsFromRays(lights, blockers, occluder, 1, p, n, offset, scratch, rgb);
}

void BrightLightsFromRays(const BrightLightSet& lights, const Blockers& blockers,
  const vtkPGIOccluder& occluder, int points, const float* p, const float* n, float offset,
  BrightLightScratch& scratch, float* rgb)
{
  const int rays = lights.Rays;
  // Room for every ray that may be cast, the first `count` of them used
  // (no growth per ray).
  const std::size_t most = static_cast<std::size_t>(points) * lights.Lights.size() * rays;
  scratch.Origins.resize(3 * most);
  scratch.Directions.resize(3 * most);
  scratch.Weights.resize(most);
  scratch.Light.resize(most);
  scratch.Point.resize(most);
  int count = 0;
  for (int j = 0; j < points; ++j)
  {
    const float* pj = &p[3 * j];
    const float* nj = &n[3 * j];
    const float o[3] = { pj[0] + offset * nj[0], pj[1] + offset * nj[1], pj[2] + offset * nj[2] };
    for (std::size_t l = 0; l < lights.Lights.size(); ++l)
    {
      const float* dirs = &lights.Directions[3 * rays * l];
      for (int k = 0; k < rays; ++k)
      {
        const float* w = &dirs[3 * k];
        const float cosine = nj[0] * w[0] + nj[1] * w[1] + nj[2] * w[2];
        if (cosine <= 0.0f)
        {
          continue;
        }
        bool blocked = false;
        for (std::size_t q = 0; q < blockers.Planes() && !blocked; ++q)
        {
          blocked = PlaneBlocks(blockers, q, pj, w, offset);
        }
        if (blocked)
        {
          continue;
        }
        std::copy_n(o, 3, &scratch.Origins[3 * static_cast<std::size_t>(count)]);
        std::copy_n(w, 3, &scratch.Directions[3 * static_cast<std::size_t>(count)]);
        scratch.Weights[count] = cosine;
        scratch.Light[count] = static_cast<int>(l);
        scratch.Point[count] = j;
        ++count;
      }
    }
  }
  if (count == 0)
  {
    return;
  }
  scratch.Blocked.resize(count);
  occluder.Occluded(
    count, scratch.Origins.data(), scratch.Directions.data(), offset, scratch.Blocked.data());
  for (int i = 0; i < count; ++i)
  {
    if (!scratch.Blocked[i])
    {
      const float* scale = &lights.Scale[3 * scratch.Light[i]];
      float* out = &rgb[3 * scratch.Point[i]];
      for (int c = 0; c < 3; ++c)
      {
        out[c] += scale[c] * scratch.Weights[i];
      }
    }
  }
}

void CosineHemisphere(int count, float* directions)
{
  const double golden = (1.0 + std::sqrt(5.0)) / 2.0;
  for (int k = 0; k < count; ++k)
  {
    // Equal areas of the unit disk, lifted to the hemisphere.
    const double r = std::sqrt((k + 0.5) / count), phi = 2 * Pi * k / golden;
    directions[3 * k] = static_cast<float>(r * std::cos(phi));
    directions[3 * k + 1] = static_cast<float>(r * std::sin(phi));
    directions[3 * k + 2] = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - r * r)));
  }
}

bool BrightLightsOnPlane(const BrightLightSet& lights, const Blockers& blockers, int plane,
  const vtkPGIOccluder* occluder, float offset, float minAngle, const float p[3], const float n[3],
  const std::vector<float>& hemisphere, BrightLightScratch& scratch, float shadowed[3],
  float open[3])
{
  const float* o = &blockers.PlaneOrigin[3 * plane];
  const float* m = &blockers.PlaneNormal[3 * plane];
  const float height = (p[0] - o[0]) * m[0] + (p[1] - o[1]) * m[1] + (p[2] - o[2]) * m[2];
  shadowed[0] = shadowed[1] = shadowed[2] = open[0] = open[1] = open[2] = 0.0f;
  if (!(height > 0.0f))
  {
    return false;
  }
  const double nd[3] = { n[0], n[1], n[2] };
  double td[3], bd[3];
  FrameAbout(nd, td, bd);
  const float t[3] = { static_cast<float>(td[0]), static_cast<float>(td[1]),
    static_cast<float>(td[2]) };
  const float b[3] = { static_cast<float>(bd[0]), static_cast<float>(bd[1]),
    static_cast<float>(bd[2]) };
  // The points where the directions meet the plane.
  std::vector<float>& points = scratch.Points;
  points.clear();
  const int count = static_cast<int>(hemisphere.size() / 3);
  for (int k = 0; k < count; ++k)
  {
    const float* h = &hemisphere[3 * k];
    float w[3];
    for (int c = 0; c < 3; ++c)
    {
      w[c] = h[0] * t[c] + h[1] * b[c] + h[2] * n[c];
    }
    const float down = -(w[0] * m[0] + w[1] * m[1] + w[2] * m[2]);
    if (down > 1e-3f)
    {
      const float along = height / down;
      for (int c = 0; c < 3; ++c)
      {
        points.push_back(p[c] + along * w[c]);
      }
    }
  }
  const int hits = static_cast<int>(points.size() / 3);
  if (hits == 0)
  {
    return false;
  }
  const int rays = lights.Rays;
  for (std::size_t l = 0; l < lights.Lights.size(); ++l)
  {
    // The light's unshadowed exit radiance off the plane (the same everywhere on it).
    const float* dirs = &lights.Directions[3 * rays * l];
    const double cosines = CosineSum(lights, l, m);
    if (cosines <= 0.0)
    {
      continue;
    }
    double visible = 0.0;
    if (occluder)
    {
      scratch.Directions.resize(points.size());
      std::vector<float>& lifted = scratch.Origins;
      lifted.resize(points.size());
      for (int i = 0; i < hits; ++i)
      {
        // One ray per point, the light's directions in turn: the penumbra averages.
        const float* w = &dirs[3 * (i % rays)];
        for (int c = 0; c < 3; ++c)
        {
          scratch.Directions[3 * i + c] = w[c];
          lifted[3 * i + c] = points[3 * i + c] + offset * m[c];
        }
      }
      scratch.Blocked.resize(hits);
      occluder->Occluded(
        hits, lifted.data(), scratch.Directions.data(), offset, scratch.Blocked.data());
      for (int i = 0; i < hits; ++i)
      {
        bool blocked = scratch.Blocked[i] != 0;
        for (std::size_t q = 0; q < blockers.Planes() && !blocked; ++q)
        {
          blocked = static_cast<int>(q) != plane &&
            PlaneBlocks(blockers, q, &points[3 * i], &scratch.Directions[3 * i], offset);
        }
        visible += blocked ? 0.0 : 1.0;
      }
    }
    else
    {
      for (int i = 0; i < hits; ++i)
      {
        visible += ConeVisibility(lights, l, blockers, &points[3 * i], m, minAngle);
      }
    }
    visible /= hits;
    for (int c = 0; c < 3; ++c)
    {
      const float unshadowed = static_cast<float>(lights.Scale[3 * l + c] * cosines);
      open[c] += unshadowed;
      shadowed[c] += static_cast<float>(unshadowed * visible);
    }
  }
  return true;
}

} // namespace proxygi
