#include "pgiBrightLights.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>
#include <utility>

namespace proxygi
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

double Luminance(const float* rgb)
{
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

void TexelDirection(int i, int j, int w, int h, double d[3])
{
  const double phi = 2 * Pi * (i + 0.5) / w, theta = Pi * (j + 0.5) / h;
  d[0] = std::sin(theta) * std::cos(phi);
  d[1] = std::sin(theta) * std::sin(phi);
  d[2] = std::cos(theta);
}

// The up to 8 neighbours of texel (i, j): phi wraps, theta stops at the poles.
int Neighbours(int i, int j, int w, int h, int out[8])
{
  int count = 0;
  for (int dj = -1; dj <= 1; ++dj)
  {
    const int jj = j + dj;
    if (jj < 0 || jj >= h)
    {
      continue;
    }
    for (int di = -1; di <= 1; ++di)
    {
      if (di == 0 && dj == 0)
      {
        continue;
      }
      const int ii = (i + di + w) % w;
      out[count++] = jj * w + ii;
    }
  }
  return count;
}
} // namespace

double DistantLight::SolidAngle() const
{
  return 2 * Pi * (1.0 - std::cos(this->HalfAngle));
}

void ExtractBrightLights(
  const EnvironmentMap& map, const BrightLightOptions& options, BrightLightResult& result)
{
  result.Lights.clear();
  result.BrightestFraction = result.ExtractedFraction = 0.0;
  const int w = map.GetWidth(), h = map.GetHeight();
  std::vector<float> rgb = map.GetRGB();
  std::vector<double> rowSolid(h);
  for (int j = 0; j < h; ++j)
  {
    rowSolid[j] = (2 * Pi / w) * (std::cos(Pi * j / h) - std::cos(Pi * (j + 1) / h));
  }
  const std::size_t texels = static_cast<std::size_t>(w) * h;
  std::vector<double> lum(texels);
  double power = 0.0;
  for (std::size_t t = 0; t < texels; ++t)
  {
    lum[t] = Luminance(&rgb[3 * t]);
    power += lum[t] * rowSolid[t / w];
  }
  const double maxSolid = 2 * Pi * (1.0 - std::cos(options.MaxHalfAngle));
  const double threshold = options.PeakRatio * power / (4 * Pi);
  // 0: free, 1: in the region being grown, 2: queued, 3: taken out before.
  std::vector<char> state(texels, 0);
  std::vector<std::size_t> region, touched;
  for (int k = 0; power > 0.0 && k < options.MaxLights; ++k)
  {
    std::size_t seed = texels;
    for (std::size_t t = 0; t < texels; ++t)
    {
      if (state[t] != 3 && (seed == texels || lum[t] > lum[seed]))
      {
        seed = t;
      }
    }
    if (seed == texels || !(lum[seed] >= threshold))
    {
      break;
    }
    // Grow through the brightest neighbours.
    region.clear();
    touched.clear();
    std::priority_queue<std::pair<double, std::size_t>> frontier;
    frontier.emplace(lum[seed], seed);
    state[seed] = 2;
    touched.push_back(seed);
    double solid = 0.0;
    while (!frontier.empty())
    {
      const std::size_t t = frontier.top().second;
      frontier.pop();
      const double dw = rowSolid[t / w];
      if (lum[t] < threshold || solid + dw > maxSolid)
      {
        break;
      }
      state[t] = 1;
      region.push_back(t);
      solid += dw;
      int next[8];
      const int count = Neighbours(static_cast<int>(t % w), static_cast<int>(t / w), w, h, next);
      for (int q = 0; q < count; ++q)
      {
        if (state[next[q]] == 0)
        {
          state[next[q]] = 2;
          touched.push_back(next[q]);
          frontier.emplace(lum[next[q]], next[q]);
        }
      }
    }
    // The level around the region: its neighbours outside it.
    double fill[3] = { 0, 0, 0 }, ringSolid = 0.0;
    for (std::size_t t : region)
    {
      int next[8];
      const int count = Neighbours(static_cast<int>(t % w), static_cast<int>(t / w), w, h, next);
      for (int q = 0; q < count; ++q)
      {
        if (state[next[q]] == 2)
        {
          state[next[q]] = 4; // counted once
          const double dw = rowSolid[next[q] / w];
          for (int c = 0; c < 3; ++c)
          {
            fill[c] += dw * rgb[3 * next[q] + c];
          }
          ringSolid += dw;
        }
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      fill[c] = ringSolid > 0.0 ? fill[c] / ringSolid : 0.0;
    }
    double removed[3] = { 0, 0, 0 }, removedLum = 0.0, centroid[3] = { 0, 0, 0 };
    for (std::size_t t : region)
    {
      const double dw = rowSolid[t / w];
      float cut[3];
      for (int c = 0; c < 3; ++c)
      {
        cut[c] = static_cast<float>(std::max(0.0, rgb[3 * t + c] - fill[c]));
        removed[c] += dw * cut[c];
      }
      const double wl = dw * Luminance(cut);
      removedLum += wl;
      double d[3];
      TexelDirection(static_cast<int>(t % w), static_cast<int>(t / w), w, h, d);
      for (int c = 0; c < 3; ++c)
      {
        centroid[c] += wl * d[c];
      }
    }
    const double fraction = removedLum / power;
    if (k == 0)
    {
      result.BrightestFraction = fraction;
    }
    const double norm =
      std::sqrt(centroid[0] * centroid[0] + centroid[1] * centroid[1] + centroid[2] * centroid[2]);
    if (!(fraction >= options.MinFraction) || !(norm > 0.0))
    {
      break;
    }
    for (int c = 0; c < 3; ++c)
    {
      centroid[c] /= norm;
    }
    // Spread: the texel centres' second moment plus each texel's own
    // (a square of side s has s^2 / 6 about its centre).
    double moment = 0.0;
    for (std::size_t t : region)
    {
      const double dw = rowSolid[t / w];
      float cut[3];
      for (int c = 0; c < 3; ++c)
      {
        cut[c] = static_cast<float>(std::max(0.0, rgb[3 * t + c] - fill[c]));
        rgb[3 * t + c] -= cut[c];
      }
      double d[3];
      TexelDirection(static_cast<int>(t % w), static_cast<int>(t / w), w, h, d);
      const double cosine =
        std::min(1.0, d[0] * centroid[0] + d[1] * centroid[1] + d[2] * centroid[2]);
      const double theta = std::acos(cosine);
      moment += dw * Luminance(cut) * (theta * theta + dw / 6.0);
    }
    DistantLight light;
    light.HalfAngle = std::sqrt(2.0 * moment / removedLum);
    map.ToWorld(centroid, light.Direction);
    const double omega = light.SolidAngle();
    for (int c = 0; c < 3; ++c)
    {
      light.Radiance[c] = removed[c] / omega;
    }
    light.Fraction = fraction;
    result.Lights.push_back(light);
    result.ExtractedFraction += fraction;
    for (std::size_t t : touched)
    {
      state[t] = 0;
    }
    for (std::size_t t : region)
    {
      state[t] = 3;
      lum[t] = Luminance(&rgb[3 * t]);
    }
  }
  std::string error;
  result.Residual.Set(w, h, std::move(rgb), error);
  result.Residual.SetRotation(map.GetRotation());
}

void FrameAbout(const double z[3], double x[3], double y[3])
{
  x[0] = std::abs(z[0]) > 0.9 ? 0.0 : 1.0;
  x[1] = 1.0 - x[0];
  x[2] = 0.0;
  const double dot = x[0] * z[0] + x[1] * z[1];
  for (int c = 0; c < 3; ++c)
  {
    x[c] -= dot * z[c];
  }
  const double nx = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (int c = 0; c < 3; ++c)
  {
    x[c] /= nx;
  }
  y[0] = z[1] * x[2] - z[2] * x[1];
  y[1] = z[2] * x[0] - z[0] * x[2];
  y[2] = z[0] * x[1] - z[1] * x[0];
}

void DistantLightDirections(const DistantLight& light, int count, double turn, float* directions)
{
  const double* z = light.Direction;
  double x[3], y[3];
  FrameAbout(z, x, y);
  const double golden = (1.0 + std::sqrt(5.0)) / 2.0;
  const double span = 1.0 - std::cos(light.HalfAngle);
  for (int k = 0; k < count; ++k)
  {
    const double cz = 1.0 - span * (k + 0.5) / count;
    const double sz = std::sqrt(std::max(0.0, 1.0 - cz * cz));
    const double phi = 2 * Pi * k / golden + turn;
    const double a = sz * std::cos(phi), b = sz * std::sin(phi);
    for (int c = 0; c < 3; ++c)
    {
      directions[3 * k + c] = static_cast<float>(a * x[c] + b * y[c] + cz * z[c]);
    }
  }
}

} // namespace proxygi
