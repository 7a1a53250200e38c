#include "pgiMeshQueries.h"

#include "pgiProxyMesh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace proxygi
{
namespace
{
struct RayHit
{
  double T;
  unsigned Triangle;
};

// Extends Embree's context so the filter can append every hit it sees.
struct CollectContext
{
  RTCIntersectContext Context;
  std::vector<RayHit>* Hits;
};

void CollectAllHits(const RTCFilterFunctionNArguments* args)
{
  auto* context = reinterpret_cast<CollectContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i)
  {
    if (args->valid[i] != -1)
    {
      continue;
    }
    context->Hits->push_back(
      { RTCRayN_tfar(args->ray, args->N, i), RTCHitN_primID(args->hit, args->N, i) });
    args->valid[i] = 0; // reject, so the traversal goes on to the next hit
  }
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
void ClosestOnTriangle(
  const double p[3], const double a[3], const double b[3], const double c[3], double q[3])
{
  auto sub = [](const double* u, const double* v, double* w)
  {
    w[0] = u[0] - v[0];
    w[1] = u[1] - v[1];
    w[2] = u[2] - v[2];
  };
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto set = [q](const double* base, const double* d1, double s, const double* d2, double t)
  {
    for (int k = 0; k < 3; ++k)
    {
      q[k] = base[k] + s * d1[k] + t * d2[k];
    }
  };
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  sub(b, a, ab);
  sub(c, a, ac);
  sub(p, a, ap);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    set(a, ab, 0.0, ac, 0.0);
    return;
  }
  sub(p, b, bp);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    set(b, ab, 0.0, ac, 0.0);
    return;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    set(a, ab, d1 / (d1 - d3), ac, 0.0);
    return;
  }
  sub(p, c, cp);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    set(c, ab, 0.0, ac, 0.0);
    return;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    set(a, ab, 0.0, ac, d2 / (d2 - d6));
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
  {
    double bc[3];
    sub(c, b, bc);
    set(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)), ab, 0.0);
    return;
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0))
  {
    set(a, ab, 0.0, ac, 0.0); // degenerate triangle
    return;
  }
  set(a, ab, vb / denom, ac, vc / denom);
}

struct ClosestState
{
  const ProxyMesh* Mesh;
  double P[3];
  double Q[3];
  double Distance;
  int Triangle;
};

bool ClosestCallback(RTCPointQueryFunctionArguments* args)
{
  auto* s = static_cast<ClosestState*>(args->userPtr);
  const int* v = s->Mesh->Triangles.data() + 3 * args->primID;
  double q[3];
  ClosestOnTriangle(s->P, s->Mesh->Point(v[0]), s->Mesh->Point(v[1]), s->Mesh->Point(v[2]), q);
  const double d = std::sqrt((q[0] - s->P[0]) * (q[0] - s->P[0]) +
    (q[1] - s->P[1]) * (q[1] - s->P[1]) + (q[2] - s->P[2]) * (q[2] - s->P[2]));
  if (d < s->Distance)
  {
    s->Distance = d;
    s->Triangle = static_cast<int>(args->primID);
    std::copy(q, q + 3, s->Q);
    args->query->radius = static_cast<float>(d) * 1.0001f + 1e-30f;
    return true;
  }
  return false;
}
} // namespace

struct MeshQueries::Internal
{
  const ProxyMesh* Mesh = nullptr;
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
  std::vector<double> Normals; // unit normal per triangle (zero if degenerate)
  double Epsilon = 0.0;        // hits closer than this are one event
  double Size = 1.0;
  std::string Error;
};

MeshQueries::MeshQueries(const ProxyMesh& mesh)
  : Impl(new Internal)
{
  Internal& s = *this->Impl;
  s.Mesh = &mesh;
  s.Device = rtcNewDevice(nullptr);
  if (!s.Device)
  {
    s.Error = "Embree could not create a device";
    return;
  }
  s.Scene = rtcNewScene(s.Device);
  // Robust: rays through edges and vertices must not slip between triangles.
  rtcSetSceneFlags(s.Scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.Scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(s.Device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const std::size_t np = mesh.Points.size() / 3, nt = mesh.Triangles.size() / 3;
  // Embree reads vertex buffers 16 bytes at a time: pad by one vertex.
  float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
    geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), np + 1));
  unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
    geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
  if (!v || !idx)
  {
    rtcReleaseGeometry(geometry);
    s.Error = "Embree could not allocate the mesh buffers";
    return;
  }
  for (std::size_t i = 0; i < 3 * np; ++i)
  {
    v[i] = static_cast<float>(mesh.Points[i]);
  }
  v[3 * np] = v[3 * np + 1] = v[3 * np + 2] = 0.0f;
  std::copy(mesh.Triangles.begin(), mesh.Triangles.end(), idx);
  rtcSetGeometryIntersectFilterFunction(geometry, CollectAllHits);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(s.Scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(s.Scene);
  if (rtcGetDeviceError(s.Device) != RTC_ERROR_NONE)
  {
    s.Error = "Embree could not build the scene";
    return;
  }
  s.Normals.resize(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const double* a = mesh.Point(mesh.Triangles[3 * t]);
    const double* b = mesh.Point(mesh.Triangles[3 * t + 1]);
    const double* c = mesh.Point(mesh.Triangles[3 * t + 2]);
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
      u[0] * w[1] - u[1] * w[0] };
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
    {
      s.Normals[3 * t + k] = len > 0.0 ? n[k] / len : 0.0;
    }
  }
  double magnitude = 0.0;
  for (int k = 0; k < 6; ++k)
  {
    magnitude = std::max(magnitude, std::fabs(mesh.Bounds[k]));
  }
  s.Size = std::max(mesh.Diagonal(), 1e-30);
  // Float vertices: hits of one event agree to a few float ulps of the coordinates.
  s.Epsilon = 1e-6 * (s.Size + magnitude);
}

MeshQueries::~MeshQueries()
{
  if (this->Impl->Scene)
  {
    rtcReleaseScene(this->Impl->Scene);
  }
  if (this->Impl->Device)
  {
    rtcReleaseDevice(this->Impl->Device);
  }
}

bool MeshQueries::Ok() const
{
  return this->Impl->Error.empty();
}

const std::string& MeshQueries::Error() const
{
  return this->Impl->Error;
}

void MeshQueries::Crossings(
  const double origin[3], const double direction[3], std::vector<double>& t) const
{
  const Internal& s = *this->Impl;
  t.clear();
  std::vector<RayHit> hits;
  CollectContext context;
  rtcInitIntersectContext(&context.Context);
  context.Hits = &hits;
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin[0]);
  rh.ray.org_y = static_cast<float>(origin[1]);
  rh.ray.org_z = static_cast<float>(origin[2]);
  rh.ray.dir_x = static_cast<float>(direction[0]);
  rh.ray.dir_y = static_cast<float>(direction[1]);
  rh.ray.dir_z = static_cast<float>(direction[2]);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(s.Scene, &context.Context, &rh);
  if (hits.empty())
  {
    return;
  }
  std::sort(hits.begin(), hits.end(),
    [](const RayHit& a, const RayHit& b)
    { return a.T < b.T || (a.T == b.T && a.Triangle < b.Triangle); });
  // A BVH may hand the same triangle over twice.
  hits.erase(std::unique(hits.begin(), hits.end(),
               [](const RayHit& a, const RayHit& b) { return a.Triangle == b.Triangle; }),
    hits.end());
  std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.T < b.T; });
  const int* tri = s.Mesh->Triangles.data();
  auto adjacent = [tri](unsigned a, unsigned b)
  {
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        if (tri[3 * a + i] == tri[3 * b + j])
        {
          return true;
        }
      }
    }
    return false;
  };
  for (std::size_t i = 0; i < hits.size();)
  {
    std::size_t j = i + 1;
    while (j < hits.size() && hits[j].T - hits[j - 1].T <= s.Epsilon)
    {
      ++j;
    }
    if (j == i + 1)
    {
      t.push_back(hits[i].T);
      i = j;
      continue;
    }
    // Several triangles at one point: one event if they touch each other.
    bool connected = true;
    for (std::size_t a = i + 1; a < j && connected; ++a)
    {
      bool any = false;
      for (std::size_t b = i; b < a && !any; ++b)
      {
        any = adjacent(hits[a].Triangle, hits[b].Triangle);
      }
      connected = any;
    }
    if (!connected)
    {
      for (std::size_t a = i; a < j; ++a)
      {
        t.push_back(hits[a].T);
      }
      i = j;
      continue;
    }
    int front = 0, back = 0;
    double mean = 0.0;
    for (std::size_t a = i; a < j; ++a)
    {
      const double* n = s.Normals.data() + 3 * hits[a].Triangle;
      const double d = n[0] * direction[0] + n[1] * direction[1] + n[2] * direction[2];
      front += d < 0.0;
      back += d > 0.0;
      mean += hits[a].T / static_cast<double>(j - i);
    }
    if (front != back) // crossed; equal counts: the ray only grazes a ridge
    {
      t.push_back(mean);
    }
    i = j;
  }
}

bool MeshQueries::IsInside(const double p[3]) const
{
  // Oblique directions: unlikely to run along the edges of modelled meshes.
  static const double directions[3][3] = { { 0.8520, 0.3915, 0.3475 }, { -0.3069, 0.8902, 0.3365 },
    { 0.2617, -0.3431, 0.9021 } };
  std::vector<double> t;
  int votes = 0;
  for (const auto& d : directions)
  {
    double unit[3];
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k)
    {
      unit[k] = d[k] / len;
    }
    this->Crossings(p, unit, t);
    votes += static_cast<int>(t.size() % 2);
  }
  return votes >= 2;
}

double MeshQueries::ClosestPoint(const double p[3], double q[3], int& triangle) const
{
  ClosestState state;
  state.Mesh = this->Impl->Mesh;
  std::copy(p, p + 3, state.P);
  std::copy(p, p + 3, state.Q);
  state.Distance = std::numeric_limits<double>::infinity();
  state.Triangle = -1;
  RTCPointQuery query;
  query.x = static_cast<float>(p[0]);
  query.y = static_cast<float>(p[1]);
  query.z = static_cast<float>(p[2]);
  query.time = 0.0f;
  query.radius = std::numeric_limits<float>::infinity();
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(this->Impl->Scene, &query, &context, ClosestCallback, &state);
  std::copy(state.Q, state.Q + 3, q);
  triangle = state.Triangle;
  return state.Distance;
}
} // namespace proxygi
