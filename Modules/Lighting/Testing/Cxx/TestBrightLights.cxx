// Bright lights out of environment maps: a synthetic sun (direction,
// size, power, rotation), two suns in order of power, a map without a peak,
// energy conservation, the cone's directions, and the project's sun maps.
#include "pgiBrightLights.h"
#include "vtkPGIEXRReader.h"

#include "pgiTesting.h"
#include "vtkImageData.h"
#include "vtkNew.h"

#include <cmath>
#include <string>
#include <vector>

using namespace proxygi;

namespace
{
constexpr double Pi = 3.14159265358979323846;

struct Sun
{
  double Dir[3]; // map space
  double HalfAngle, Radiance[3];
};
struct Sky
{
  std::vector<Sun> Suns;
  double Level = 0.5;
};

void SkyRadiance(const double d[3], float rgb[3], void* data)
{
  const Sky& sky = *static_cast<const Sky*>(data);
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = static_cast<float>(sky.Level * (c == 2 ? 1.5 : 1.0));
  }
  for (const Sun& s : sky.Suns)
  {
    const double cosine = d[0] * s.Dir[0] + d[1] * s.Dir[1] + d[2] * s.Dir[2];
    if (cosine >= std::cos(s.HalfAngle))
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] += static_cast<float>(s.Radiance[c]);
      }
    }
  }
}

void Power(const EnvironmentMap& map, double out[3])
{
  map.Mean(out);
  for (int c = 0; c < 3; ++c)
  {
    out[c] *= 4 * Pi;
  }
}

double AngleBetween(const double a[3], const double b[3])
{
  return std::acos(std::min(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
}

void FromAngles(double elevation, double azimuth, double d[3])
{
  d[0] = std::cos(elevation) * std::cos(azimuth);
  d[1] = std::cos(elevation) * std::sin(azimuth);
  d[2] = std::sin(elevation);
}
} // namespace

int TestBrightLights(int, char*[])
{
  const double degree = Pi / 180.0;
  // One sun, the map turned: found where world space has it, its size and
  // power kept, and the residual plus the light is the map.
  for (double rotation : { 0.0, 0.7 })
  {
    double world[3];
    FromAngles(30 * degree, 40 * degree, world);
    EnvironmentMap probe;
    probe.SetRotation(rotation);
    Sky sky;
    Sun sun{ {}, 2.0 * degree, { 3000, 2800, 2500 } };
    probe.ToMap(world, sun.Dir);
    sky.Suns.push_back(sun);
    EnvironmentMap map;
    map.SetFromFunction(1024, 512, SkyRadiance, &sky);
    map.SetRotation(rotation);
    BrightLightResult result;
    ExtractBrightLights(map, BrightLightOptions(), result);
    PGI_CHECK(result.Lights.size() == 1);
    if (result.Lights.size() != 1)
    {
      continue;
    }
    const DistantLight& light = result.Lights[0];
    PGI_BELOW(AngleBetween(light.Direction, world) / degree, 0.1);
    PGI_NEAR(light.HalfAngle / degree, 2.0, 0.2);
    const double omega = 2 * Pi * (1 - std::cos(sun.HalfAngle));
    double before[3], after[3];
    Power(map, before);
    Power(result.Residual, after);
    for (int c = 0; c < 3; ++c)
    {
      // The disk's texels against the exact disk.
      PGI_NEAR(light.Radiance[c] * light.SolidAngle() / (sun.Radiance[c] * omega), 1.0, 0.02);
      // Nothing made or lost.
      PGI_NEAR((after[c] + light.Radiance[c] * light.SolidAngle()) / before[c], 1.0, 1e-5);
    }
    PGI_NEAR(result.ExtractedFraction, light.Fraction, 1e-12);
    PGI_NEAR(
      light.Fraction, 10.797 / (10.797 + 0.5 * 4 * Pi * (0.2126 + 0.7152 + 0.0722 * 1.5)), 0.01);
    // The residual is the sky.
    float rgb[3];
    result.Residual.Lookup(world, rgb);
    PGI_NEAR(rgb[0], 0.5, 1e-3);
    PGI_NEAR(rgb[2], 0.75, 1e-3);
  }

  // Two suns: the stronger first; a weak third one under MinFraction stays.
  {
    Sky sky;
    Sun a{ {}, 1.0 * degree, { 4000, 4000, 4000 } }, b{ {}, 3.0 * degree, { 200, 150, 100 } },
      weak{ {}, 0.5 * degree, { 100, 100, 100 } };
    FromAngles(10 * degree, -100 * degree, a.Dir);
    FromAngles(60 * degree, 20 * degree, b.Dir);
    FromAngles(45 * degree, 150 * degree, weak.Dir);
    sky.Suns = { b, a, weak };
    EnvironmentMap map;
    map.SetFromFunction(1024, 512, SkyRadiance, &sky);
    BrightLightResult result;
    ExtractBrightLights(map, BrightLightOptions(), result);
    PGI_CHECK(result.Lights.size() == 2);
    if (result.Lights.size() == 2)
    {
      PGI_BELOW(AngleBetween(result.Lights[0].Direction, a.Dir) / degree, 0.1);
      PGI_BELOW(AngleBetween(result.Lights[1].Direction, b.Dir) / degree, 0.1);
      PGI_CHECK(result.Lights[0].Fraction > result.Lights[1].Fraction);
      PGI_NEAR(result.Lights[1].HalfAngle / degree, 3.0, 0.3);
    }
  }

  // No peak: nothing taken, the residual is the map.
  {
    Sky sky;
    EnvironmentMap map;
    map.SetFromFunction(256, 128, SkyRadiance, &sky);
    BrightLightResult result;
    ExtractBrightLights(map, BrightLightOptions(), result);
    PGI_CHECK(result.Lights.empty());
    PGI_NEAR(result.BrightestFraction, 0.0, 0.0);
    PGI_CHECK(result.Residual.GetRGB() == map.GetRGB());
    // A black map: nothing either, and no NaN.
    EnvironmentMap black = EnvironmentMap::Uniform(0, 0, 0);
    ExtractBrightLights(black, BrightLightOptions(), result);
    PGI_CHECK(result.Lights.empty());
  }

  // The cone's directions: inside it, centred on it.
  {
    DistantLight light;
    FromAngles(20 * degree, 70 * degree, light.Direction);
    light.HalfAngle = 4 * degree;
    std::vector<float> dirs(3 * 32);
    DistantLightDirections(light, 32, 0.3, dirs.data());
    double mean[3] = { 0, 0, 0 }, widest = 0.0;
    for (int k = 0; k < 32; ++k)
    {
      const double d[3] = { dirs[3 * k], dirs[3 * k + 1], dirs[3 * k + 2] };
      PGI_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-6);
      widest = std::max(widest, AngleBetween(d, light.Direction));
      for (int c = 0; c < 3; ++c)
      {
        mean[c] += d[c] / 32;
      }
    }
    PGI_BELOW(widest, light.HalfAngle * 1.0001);
    const double m = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
    for (double& v : mean)
    {
      v /= m;
    }
    PGI_BELOW(AngleBetween(mean, light.Direction) / degree, 0.2);
  }

  // The project's maps with a sun or lamps give lights; finite throughout.
  for (const char* name : { "sunrise", "city", "interior" })
  {
    vtkNew<vtkPGIEXRReader> reader;
    reader->SetFileName((std::string(PROXYGI_DATA_DIR) + "/environments/" + name + ".exr").c_str());
    reader->Update();
    EnvironmentMap map;
    std::string error;
    PGI_CHECK(EnvironmentMap::FromImage(reader->GetOutput(), map, error));
    BrightLightResult result;
    ExtractBrightLights(map, BrightLightOptions(), result);
    std::printf("%s: %zu lights, %.1f%% of the power (brightest %.1f%%)", name,
      result.Lights.size(), 100 * result.ExtractedFraction, 100 * result.BrightestFraction);
    for (const DistantLight& l : result.Lights)
    {
      std::printf("; %.2f deg, %.1f%%", l.HalfAngle / degree, 100 * l.Fraction);
      for (int c = 0; c < 3; ++c)
      {
        PGI_CHECK(std::isfinite(l.Radiance[c]) && l.Radiance[c] >= 0.0);
      }
    }
    std::printf("\n");
    PGI_CHECK(!result.Lights.empty() && result.ExtractedFraction > 0.15);
  }
  return pgitest::Result();
}
