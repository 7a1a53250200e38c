#include "pgiReferenceTracer.h"

#include "pgiEnvironmentMap.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxygi
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

// splitmix64: tiny, good enough for Monte Carlo, seekable per stream.
struct Random
{
  std::uint64_t State;
  Random(std::uint64_t seed, std::uint64_t stream)
    : State(Mix(seed * 0x9E3779B97F4A7C15ull ^ Mix(stream + 0x632BE59BD9B4E019ull)))
  {
  }
  static std::uint64_t Mix(std::uint64_t z)
  {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Next()
  {
    this->State += 0x9E3779B97F4A7C15ull;
    return (Mix(this->State) >> 11) * (1.0 / 9007199254740992.0);
  }
};

// Orthonormal basis around n (Duff et al. 2017).
void Basis(const double n[3], double t[3], double b[3])
{
  const double sign = std::copysign(1.0, n[2]);
  const double a = -1.0 / (sign + n[2]);
  const double c = n[0] * n[1] * a;
  t[0] = 1.0 + sign * n[0] * n[0] * a;
  t[1] = sign * c;
  t[2] = -sign * n[0];
  b[0] = c;
  b[1] = sign + n[1] * n[1] * a;
  b[2] = -n[1];
}

void CosineSample(const double n[3], double u1, double u2, double w[3])
{
  double t[3], b[3];
  Basis(n, t, b);
  const double r = std::sqrt(u1), phi = 2 * Pi * u2;
  const double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0, 1 - u1));
  for (int k = 0; k < 3; ++k)
  {
    w[k] = x * t[k] + y * b[k] + z * n[k];
  }
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

struct Mesh
{
  std::vector<float> Points;
  std::vector<unsigned> Triangles;
  std::vector<float> Albedo; // per vertex, or empty
  float ObjectAlbedo[3];
};

struct SphereLight
{
  double Center[3], Radius;
  float Radiance[3];
};

struct PointLight
{
  double Position[3];
  float Intensity[3];
};
} // namespace

struct ReferenceTracer::Internal
{
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
  std::vector<Mesh> Meshes;
  std::vector<float> Spheres; // x, y, z, r
  std::vector<float> SphereAlbedo;
  unsigned SphereGeometry = RTC_INVALID_GEOMETRY_ID;
  std::vector<unsigned> MeshOfGeometry;
  const EnvironmentMap* Environment = nullptr;
  std::vector<SphereLight> SphereLights;
  std::vector<PointLight> PointLights;
  double Bounds[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  double Epsilon = 1e-4;

  ~Internal()
  {
    if (this->Scene)
    {
      rtcReleaseScene(this->Scene);
    }
    if (this->Device)
    {
      rtcReleaseDevice(this->Device);
    }
  }

  void Grow(double x, double y, double z)
  {
    const double p[3] = { x, y, z };
    for (int k = 0; k < 3; ++k)
    {
      this->Bounds[2 * k] = std::min(this->Bounds[2 * k], p[k]);
      this->Bounds[2 * k + 1] = std::max(this->Bounds[2 * k + 1], p[k]);
    }
  }
};

ReferenceTracer::ReferenceTracer()
  : Impl(new Internal)
{
}

ReferenceTracer::~ReferenceTracer() = default;

bool ReferenceTracer::AddMesh(const std::vector<float>& points,
  const std::vector<unsigned>& triangles, const float* albedo, const float objectAlbedo[3],
  std::string& error)
{
  const std::size_t np = points.size() / 3;
  for (float v : points)
  {
    if (!std::isfinite(v))
    {
      error = "mesh has NaN or Inf point coordinates";
      return false;
    }
  }
  Mesh mesh;
  mesh.Points = points;
  std::copy(objectAlbedo, objectAlbedo + 3, mesh.ObjectAlbedo);
  if (albedo)
  {
    mesh.Albedo.assign(albedo, albedo + 3 * np);
  }
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    const unsigned a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    if (a >= np || b >= np || c >= np)
    {
      error = "mesh has a triangle index out of range";
      return false;
    }
    const float* pa = &points[3 * a];
    const float* pb = &points[3 * b];
    const float* pc = &points[3 * c];
    const double e1[3] = { pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
    const double e2[3] = { pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2] };
    const double cr[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    if (Dot(cr, cr) <= 0.0)
    {
      ++this->SkippedTriangles;
      continue;
    }
    mesh.Triangles.insert(mesh.Triangles.end(), { a, b, c });
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    this->Impl->Grow(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
  }
  if (!mesh.Triangles.empty())
  {
    this->Impl->Meshes.push_back(std::move(mesh));
  }
  return true;
}

bool ReferenceTracer::AddSphere(
  const double center[3], double radius, const float albedo[3], std::string& error)
{
  if (!std::isfinite(center[0]) || !std::isfinite(center[1]) || !std::isfinite(center[2]) ||
    !std::isfinite(radius) || radius < 0.0)
  {
    error = "sphere with NaN, Inf or negative values";
    return false;
  }
  if (radius == 0.0)
  {
    return true; // blocks nothing
  }
  for (int k = 0; k < 3; ++k)
  {
    this->Impl->Spheres.push_back(static_cast<float>(center[k]));
  }
  this->Impl->Spheres.push_back(static_cast<float>(radius));
  this->Impl->SphereAlbedo.insert(this->Impl->SphereAlbedo.end(), albedo, albedo + 3);
  this->Impl->Grow(center[0] - radius, center[1] - radius, center[2] - radius);
  this->Impl->Grow(center[0] + radius, center[1] + radius, center[2] + radius);
  return true;
}

void ReferenceTracer::SetEnvironment(const EnvironmentMap* environment)
{
  this->Impl->Environment = environment;
}

void ReferenceTracer::AddSphereLight(const double c[3], double r, const float radiance[3])
{
  SphereLight light = { { c[0], c[1], c[2] }, r, { radiance[0], radiance[1], radiance[2] } };
  this->Impl->SphereLights.push_back(light);
}

void ReferenceTracer::AddPointLight(const double p[3], const float intensity[3])
{
  PointLight light = { { p[0], p[1], p[2] }, { intensity[0], intensity[1], intensity[2] } };
  this->Impl->PointLights.push_back(light);
}

bool ReferenceTracer::Commit(std::string& error)
{
  Internal& s = *this->Impl;
  if (s.Meshes.empty() && s.Spheres.empty())
  {
    error = "the scene holds no geometry";
    return false;
  }
  if (!s.Device)
  {
    s.Device = rtcNewDevice(nullptr);
    if (!s.Device)
    {
      error = "Embree could not create a device";
      return false;
    }
  }
  if (s.Scene)
  {
    rtcReleaseScene(s.Scene);
  }
  s.Scene = rtcNewScene(s.Device);
  rtcSetSceneBuildQuality(s.Scene, RTC_BUILD_QUALITY_HIGH);
  s.MeshOfGeometry.clear();
  for (std::size_t m = 0; m < s.Meshes.size(); ++m)
  {
    const Mesh& mesh = s.Meshes[m];
    RTCGeometry geometry = rtcNewGeometry(s.Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t np = mesh.Points.size() / 3, nt = mesh.Triangles.size() / 3;
    // Embree reads vertex buffers 16 bytes at a time: pad by one float.
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), np + 1));
    std::copy(mesh.Points.begin(), mesh.Points.end(), v);
    v[3 * np] = v[3 * np + 1] = v[3 * np + 2] = 0.0f;
    unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    std::copy(mesh.Triangles.begin(), mesh.Triangles.end(), idx);
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(s.Scene, geometry);
    rtcReleaseGeometry(geometry);
    if (s.MeshOfGeometry.size() <= id)
    {
      s.MeshOfGeometry.resize(id + 1, RTC_INVALID_GEOMETRY_ID);
    }
    s.MeshOfGeometry[id] = static_cast<unsigned>(m);
  }
  if (!s.Spheres.empty())
  {
    RTCGeometry geometry = rtcNewGeometry(s.Device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    const std::size_t n = s.Spheres.size() / 4;
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n));
    std::copy(s.Spheres.begin(), s.Spheres.end(), v);
    rtcCommitGeometry(geometry);
    s.SphereGeometry = rtcAttachGeometry(s.Scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(s.Scene);
  const double dx = s.Bounds[1] - s.Bounds[0], dy = s.Bounds[3] - s.Bounds[2],
               dz = s.Bounds[5] - s.Bounds[4];
  this->SceneSize = std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-30);
  // Ray offset relative to the scene, so scaling the scene scales nothing else.
  s.Epsilon = 1e-5 * this->SceneSize;
  return true;
}

namespace
{
struct Hit
{
  double T;
  double Normal[3]; // unit, facing the incoming ray
  float Albedo[3];
};

bool Occluded(const ReferenceTracer::Settings&, RTCScene scene, const double o[3],
  const double d[3], double tfar, std::atomic<std::uint64_t>& rays)
{
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = static_cast<float>(o[0]);
  ray.org_y = static_cast<float>(o[1]);
  ray.org_z = static_cast<float>(o[2]);
  ray.dir_x = static_cast<float>(d[0]);
  ray.dir_y = static_cast<float>(d[1]);
  ray.dir_z = static_cast<float>(d[2]);
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(std::min(tfar, 3.0e38));
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  ray.time = 0.0f;
  ray.id = 0;
  rtcOccluded1(scene, &context, &ray);
  rays.fetch_add(1, std::memory_order_relaxed);
  return ray.tfar < 0.0f;
}
} // namespace

// Internal tracing helpers live in a struct to reach private state.
struct TracerAccess
{
  // The first hit along o + t d, t > 0 (geomID invalid: none).
  static void Cast(const ReferenceTracer::Internal& s, const double o[3], const double d[3],
    RTCRayHit& rh, std::atomic<std::uint64_t>& rays)
  {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rh.ray.org_x = static_cast<float>(o[0]);
    rh.ray.org_y = static_cast<float>(o[1]);
    rh.ray.org_z = static_cast<float>(o[2]);
    rh.ray.dir_x = static_cast<float>(d[0]);
    rh.ray.dir_y = static_cast<float>(d[1]);
    rh.ray.dir_z = static_cast<float>(d[2]);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0.0f;
    rh.ray.id = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s.Scene, &context, &rh);
    rays.fetch_add(1, std::memory_order_relaxed);
  }

  static bool Intersect(const ReferenceTracer::Internal& s, const double o[3], const double d[3],
    Hit& hit, std::atomic<std::uint64_t>& rays)
  {
    RTCRayHit rh;
    Cast(s, o, d, rh, rays);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
    {
      return false;
    }
    hit.T = rh.ray.tfar;
    double ng[3] = { rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z };
    const double len = std::sqrt(Dot(ng, ng));
    if (!(len > 0.0))
    {
      return false;
    }
    const double flip = Dot(ng, d) > 0.0 ? -1.0 / len : 1.0 / len;
    for (int k = 0; k < 3; ++k)
    {
      hit.Normal[k] = ng[k] * flip;
    }
    if (rh.hit.geomID == s.SphereGeometry)
    {
      std::copy(
        &s.SphereAlbedo[3 * rh.hit.primID], &s.SphereAlbedo[3 * rh.hit.primID] + 3, hit.Albedo);
      return true;
    }
    const Mesh& mesh = s.Meshes[s.MeshOfGeometry[rh.hit.geomID]];
    if (mesh.Albedo.empty())
    {
      std::copy(mesh.ObjectAlbedo, mesh.ObjectAlbedo + 3, hit.Albedo);
    }
    else
    {
      const unsigned* t = &mesh.Triangles[3 * rh.hit.primID];
      const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
      for (int k = 0; k < 3; ++k)
      {
        hit.Albedo[k] = w * mesh.Albedo[3 * t[0] + k] + u * mesh.Albedo[3 * t[1] + k] +
          v * mesh.Albedo[3 * t[2] + k];
      }
    }
    return true;
  }

  // One-sample estimate of direct irradiance at x (normal n), all lights.
  static void Direct(const ReferenceTracer::Internal& s, const ReferenceTracer::Settings& settings,
    const double x[3], const double n[3], Random& rng, double e[3],
    std::atomic<std::uint64_t>& rays)
  {
    e[0] = e[1] = e[2] = 0.0;
    double o[3];
    for (int k = 0; k < 3; ++k)
    {
      o[k] = x[k] + s.Epsilon * n[k];
    }
    const double inf = std::numeric_limits<double>::infinity();
    if (s.Environment)
    {
      // Cosine sample, weighted against the environment's own sampling.
      double w[3];
      float rgb[3];
      CosineSample(n, rng.Next(), rng.Next(), w);
      const double cosB = Dot(n, w);
      if (cosB > 0.0 && !Occluded(settings, s.Scene, o, w, inf, rays))
      {
        s.Environment->Lookup(w, rgb);
        const double pb = cosB / Pi, pl = s.Environment->Pdf(w);
        const double weight = pb / (pb + pl) * Pi; // L cos / pb = L pi
        for (int k = 0; k < 3; ++k)
        {
          e[k] += weight * rgb[k];
        }
      }
      const double pl = s.Environment->Sample(rng.Next(), rng.Next(), w, rgb);
      const double cosL = Dot(n, w);
      if (cosL > 0.0 && pl > 0.0 && !Occluded(settings, s.Scene, o, w, inf, rays))
      {
        const double pb = cosL / Pi;
        const double weight = pl / (pl + pb) * cosL / pl;
        for (int k = 0; k < 3; ++k)
        {
          e[k] += weight * rgb[k];
        }
      }
    }
    for (const SphereLight& light : s.SphereLights)
    {
      double axis[3] = { light.Center[0] - x[0], light.Center[1] - x[1], light.Center[2] - x[2] };
      const double d2 = Dot(axis, axis), d = std::sqrt(d2);
      if (!(d > light.Radius))
      {
        continue; // inside an emitter: not a receiver of it
      }
      for (double& c : axis)
      {
        c /= d;
      }
      const double sinMax = light.Radius / d;
      const double cosMax = std::sqrt(std::max(0.0, 1 - sinMax * sinMax));
      // Uniform in the cone the light subtends.
      const double cosT = 1 - rng.Next() * (1 - cosMax);
      const double sinT = std::sqrt(std::max(0.0, 1 - cosT * cosT));
      const double phi = 2 * Pi * rng.Next();
      double t[3], b[3], w[3];
      Basis(axis, t, b);
      for (int k = 0; k < 3; ++k)
      {
        w[k] = sinT * std::cos(phi) * t[k] + sinT * std::sin(phi) * b[k] + cosT * axis[k];
      }
      const double cosN = Dot(n, w);
      if (cosN <= 0.0)
      {
        continue;
      }
      // Distance to the light's near surface along w.
      const double proj = d * cosT;
      const double tHit =
        proj - std::sqrt(std::max(0.0, light.Radius * light.Radius - d2 + proj * proj));
      if (Occluded(settings, s.Scene, o, w, tHit * (1 - 1e-6), rays))
      {
        continue;
      }
      const double invPdf = 2 * Pi * (1 - cosMax);
      for (int k = 0; k < 3; ++k)
      {
        e[k] += light.Radiance[k] * cosN * invPdf;
      }
    }
    for (const PointLight& light : s.PointLights)
    {
      double w[3] = { light.Position[0] - x[0], light.Position[1] - x[1],
        light.Position[2] - x[2] };
      const double d2 = Dot(w, w), d = std::sqrt(d2);
      if (!(d > 0.0))
      {
        continue;
      }
      for (double& c : w)
      {
        c /= d;
      }
      const double cosN = Dot(n, w);
      if (cosN > 0.0 && !Occluded(settings, s.Scene, o, w, d * (1 - 1e-6), rays))
      {
        for (int k = 0; k < 3; ++k)
        {
          e[k] += light.Intensity[k] * cosN / d2;
        }
      }
    }
  }

  // One-sample estimate of indirect irradiance (bounce `depth` onwards).
  static void Indirect(const ReferenceTracer::Internal& s,
    const ReferenceTracer::Settings& settings, const double x[3], const double n[3], int depth,
    Random& rng, double e[3], std::atomic<std::uint64_t>& rays)
  {
    e[0] = e[1] = e[2] = 0.0;
    if (depth > settings.MaxBounces)
    {
      return;
    }
    double o[3], w[3];
    for (int k = 0; k < 3; ++k)
    {
      o[k] = x[k] + s.Epsilon * n[k];
    }
    CosineSample(n, rng.Next(), rng.Next(), w);
    Hit hit;
    if (!Intersect(s, o, w, hit, rays))
    {
      return; // the environment is direct light
    }
    if (hit.Albedo[0] <= 0.0f && hit.Albedo[1] <= 0.0f && hit.Albedo[2] <= 0.0f)
    {
      return;
    }
    double y[3], direct[3], further[3];
    for (int k = 0; k < 3; ++k)
    {
      y[k] = o[k] + hit.T * w[k];
    }
    Direct(s, settings, y, hit.Normal, rng, direct, rays);
    Indirect(s, settings, y, hit.Normal, depth + 1, rng, further, rays);
    // Cosine sampling: E = pi L(y), L(y) = albedo/pi (E_d + E_i): albedo (E_d + E_i).
    for (int k = 0; k < 3; ++k)
    {
      e[k] = hit.Albedo[k] * (direct[k] + further[k]);
    }
  }
};

void ReferenceTracer::EstimateIrradiance(const double x[3], const double n[3], std::uint64_t stream,
  const Settings& settings, Estimate& out) const
{
  out = Estimate();
  const int count = std::max(1, settings.Samples);
  Random rng(settings.Seed, stream);
  double sum[3][3] = {}, sq[3][3] = {}; // [direct, indirect, total][rgb]
  for (int i = 0; i < count; ++i)
  {
    double d[3], ind[3] = { 0, 0, 0 };
    TracerAccess::Direct(*this->Impl, settings, x, n, rng, d, this->RayCounter());
    if (settings.MaxBounces > 0)
    {
      TracerAccess::Indirect(*this->Impl, settings, x, n, 1, rng, ind, this->RayCounter());
    }
    for (int k = 0; k < 3; ++k)
    {
      const double v[3] = { d[k], ind[k], d[k] + ind[k] };
      for (int e = 0; e < 3; ++e)
      {
        sum[e][k] += v[e];
        sq[e][k] += v[e] * v[e];
      }
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    double err[3];
    for (int e = 0; e < 3; ++e)
    {
      const double mean = sum[e][k] / count;
      const double var =
        count > 1 ? std::max(0.0, (sq[e][k] / count - mean * mean)) / (count - 1) : 0.0;
      err[e] = std::sqrt(var);
    }
    out.Direct[k] = sum[0][k] / count;
    out.Indirect[k] = sum[1][k] / count;
    out.DirectStdErr[k] = err[0];
    out.IndirectStdErr[k] = err[1];
    out.TotalStdErr[k] = err[2];
  }
}

void ReferenceTracer::EstimateRadianceAlongRay(const double origin[3], const double direction[3],
  std::uint64_t stream, const Settings& settings, RadianceEstimate& out) const
{
  out = RadianceEstimate();
  Hit hit;
  if (!TracerAccess::Intersect(*this->Impl, origin, direction, hit, this->RayCounter()))
  {
    float rgb[3] = { 0, 0, 0 };
    if (this->Impl->Environment)
    {
      this->Impl->Environment->Lookup(direction, rgb);
    }
    for (int k = 0; k < 3; ++k)
    {
      out.Direct[k] = out.Total[k] = rgb[k];
    }
    return;
  }
  out.Hit = true;
  double x[3];
  for (int k = 0; k < 3; ++k)
  {
    x[k] = origin[k] + hit.T * direction[k];
  }
  Estimate e;
  this->EstimateIrradiance(x, hit.Normal, stream, settings, e);
  for (int k = 0; k < 3; ++k)
  {
    const double s = hit.Albedo[k] / Pi;
    out.Direct[k] = s * e.Direct[k];
    out.Indirect[k] = s * e.Indirect[k];
    out.Total[k] = out.Direct[k] + out.Indirect[k];
    out.TotalStdErr[k] = s * e.TotalStdErr[k];
  }
}

void ReferenceTracer::OccludedRays(int count, const float* origins, const float* directions,
  float tnear, const float* lengths, unsigned char* blocked) const
{
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  // A call's rays leave one point or its neighbours towards one light or
  // one hemisphere: packets of 16 share their traversal.
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  constexpr int Width = 16;
  for (int first = 0; first < count; first += Width)
  {
    const int lanes = std::min(Width, count - first);
    RTCRay16 packet;
    alignas(64) int valid[Width]; // Embree reads the mask as one aligned vector
    for (int k = 0; k < Width; ++k)
    {
      // Idle lanes repeat the first ray (finite values) and stay invalid.
      const int i = first + (k < lanes ? k : 0);
      valid[k] = k < lanes ? -1 : 0;
      packet.org_x[k] = origins[3 * i];
      packet.org_y[k] = origins[3 * i + 1];
      packet.org_z[k] = origins[3 * i + 2];
      packet.dir_x[k] = directions[3 * i];
      packet.dir_y[k] = directions[3 * i + 1];
      packet.dir_z[k] = directions[3 * i + 2];
      packet.tnear[k] = tnear;
      packet.tfar[k] = lengths ? lengths[i] : std::numeric_limits<float>::infinity();
      packet.mask[k] = 0xFFFFFFFFu;
      packet.flags[k] = 0;
      packet.time[k] = 0.0f;
      packet.id[k] = 0;
    }
    rtcOccluded16(valid, this->Impl->Scene, &context, &packet);
    for (int k = 0; k < lanes; ++k)
    {
      blocked[first + k] = packet.tfar[k] < 0.0f ? 1 : 0;
    }
  }
  this->RayCounter().fetch_add(static_cast<std::uint64_t>(count), std::memory_order_relaxed);
}

double ReferenceTracer::GetRayOffset() const
{
  return this->Impl->Epsilon;
}

std::atomic<std::uint64_t>& ReferenceTracer::RayCounter() const
{
  static std::atomic<unsigned> nextSlot{ 0 };
  thread_local const unsigned slot = nextSlot.fetch_add(1, std::memory_order_relaxed);
  return this->Rays[slot % RayShards].Count;
}

std::uint64_t ReferenceTracer::GetRayCount() const
{
  std::uint64_t sum = 0;
  for (const RayShard& shard : this->Rays)
  {
    sum += shard.Count.load(std::memory_order_relaxed);
  }
  return sum;
}

bool ReferenceTracer::SegmentBlocked(const double a[3], const double b[3]) const
{
  double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double length = std::sqrt(Dot(d, d));
  if (!(length > this->Impl->Epsilon))
  {
    return false;
  }
  for (double& c : d)
  {
    c /= length;
  }
  return Occluded(
    Settings(), this->Impl->Scene, a, d, length - this->Impl->Epsilon, this->RayCounter());
}

void ReferenceTracer::GatherHits(const double x[3], const double n[3], std::uint64_t seed,
  std::uint64_t stream, int count, std::vector<GatherHit>& hits) const
{
  hits.clear();
  const Internal& s = *this->Impl;
  Random rng(seed, stream);
  const double o[3] = { x[0] + s.Epsilon * n[0], x[1] + s.Epsilon * n[1], x[2] + s.Epsilon * n[2] };
  // A Fibonacci lattice on the unit square, randomly shifted per receiver:
  // stratified, so smooth indirect light converges much faster than with
  // independent samples, and still unbiased.
  const double shift[2] = { rng.Next(), rng.Next() };
  const double golden = 0.61803398874989484820;
  for (int i = 0; i < count; ++i)
  {
    double w[3], u1 = (i + 0.5) / count + shift[0], u2 = i * golden + shift[1];
    u1 -= std::floor(u1);
    u2 -= std::floor(u2);
    CosineSample(n, u1, u2, w);
    Hit hit;
    if (!TracerAccess::Intersect(s, o, w, hit, this->RayCounter()))
    {
      continue;
    }
    GatherHit g;
    for (int k = 0; k < 3; ++k)
    {
      g.Position[k] = static_cast<float>(o[k] + hit.T * w[k] + s.Epsilon * hit.Normal[k]);
      g.Normal[k] = static_cast<float>(hit.Normal[k]);
      g.Albedo[k] = hit.Albedo[k];
    }
    hits.push_back(g);
  }
}

bool ReferenceTracer::HitVertices(
  const double x[3], const double n[3], const double d[3], unsigned ids[3], double weights[3]) const
{
  const Internal& s = *this->Impl;
  const double o[3] = { x[0] + s.Epsilon * n[0], x[1] + s.Epsilon * n[1], x[2] + s.Epsilon * n[2] };
  RTCRayHit rh;
  TracerAccess::Cast(s, o, d, rh, this->RayCounter());
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || rh.hit.geomID == s.SphereGeometry)
  {
    return false;
  }
  const Mesh& mesh = s.Meshes[s.MeshOfGeometry[rh.hit.geomID]];
  std::copy_n(&mesh.Triangles[3 * rh.hit.primID], 3, ids);
  weights[0] = 1.0 - rh.hit.u - rh.hit.v;
  weights[1] = rh.hit.u;
  weights[2] = rh.hit.v;
  return true;
}

ReferenceTracer::PointPlace ReferenceTracer::PlacePoint(const double p[3], int rays) const
{
  const Internal& s = *this->Impl;
  PointPlace place;
  place.NearestHit = std::numeric_limits<double>::infinity();
  int hits = 0, behind = 0;
  rays = std::max(1, rays);
  for (int q = 0; q < rays; ++q)
  {
    // Fibonacci directions.
    const double z = 1.0 - (q + 0.5) * 2.0 / rays;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.39996322972865332 * q;
    const double d[3] = { r * std::cos(phi), r * std::sin(phi), z };
    RTCRayHit rh;
    TracerAccess::Cast(s, p, d, rh, this->RayCounter());
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
    {
      continue;
    }
    ++hits;
    if (rh.ray.tfar < place.NearestHit)
    {
      place.NearestHit = rh.ray.tfar;
      std::copy(d, d + 3, place.NearestDirection);
    }
    if (rh.hit.geomID == s.SphereGeometry)
    {
      const float* sphere = &s.Spheres[4 * rh.hit.primID];
      double c[3];
      for (int k = 0; k < 3; ++k)
      {
        c[k] = sphere[k] - p[k];
      }
      behind += Dot(c, c) < static_cast<double>(sphere[3]) * sphere[3] ? 1 : 0;
      continue;
    }
    const Mesh& mesh = s.Meshes[s.MeshOfGeometry[rh.hit.geomID]];
    const unsigned* t = &mesh.Triangles[3 * rh.hit.primID];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k)
    {
      e1[k] = mesh.Points[3 * t[1] + k] - mesh.Points[3 * t[0] + k];
      e2[k] = mesh.Points[3 * t[2] + k] - mesh.Points[3 * t[0] + k];
    }
    const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    behind += Dot(n, d) > 0.0 ? 1 : 0;
  }
  place.Inside = hits == rays && 2 * behind > rays;
  return place;
}

bool ReferenceTracer::FirstHit(const double origin[3], const double direction[3], double& t,
  double normal[3], float albedo[3]) const
{
  Hit hit;
  if (!TracerAccess::Intersect(*this->Impl, origin, direction, hit, this->RayCounter()))
  {
    return false;
  }
  t = hit.T;
  std::copy(hit.Normal, hit.Normal + 3, normal);
  std::copy(hit.Albedo, hit.Albedo + 3, albedo);
  return true;
}

} // namespace proxygi
