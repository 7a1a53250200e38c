#include "pgiSphereMath.h"

#include "pgiNelderMead.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxygi
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

double Distance(const double a[3], const double b[3])
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Minimises a convex "maximum distance" function: a few Badoiu-Clarkson
// steps towards the farthest item give a good start, Nelder-Mead polishes.
template <typename Farthest, typename Radius>
void MinimaxCenter(double c[3], double scale, Farthest&& farthest, Radius&& radius)
{
  for (int i = 1; i <= 40; ++i)
  {
    double f[3] = { c[0], c[1], c[2] };
    farthest(c, f);
    for (int k = 0; k < 3; ++k)
    {
      c[k] += (f[k] - c[k]) / (i + 1.0);
    }
  }
  if (scale > 0.0)
  {
    MinimizeNelderMead3(radius, c, 0.05 * scale, 1e-7 * scale, 300);
  }
}
} // namespace

double SphereVolume(double radius)
{
  return 4.0 / 3.0 * Pi * radius * radius * radius;
}

double CenterDistance(const Sphere& a, const Sphere& b)
{
  return Distance(a.Center, b.Center);
}

bool Contains(const Sphere& outer, const Sphere& inner, double tolerance)
{
  return CenterDistance(outer, inner) + inner.Radius <= outer.Radius + tolerance;
}

double LensVolume(const Sphere& a, const Sphere& b)
{
  const double d = CenterDistance(a, b);
  const double ra = a.Radius, rb = b.Radius;
  if (d >= ra + rb)
  {
    return 0.0;
  }
  if (d <= std::fabs(ra - rb))
  {
    return SphereVolume(std::min(ra, rb));
  }
  const double s = ra + rb - d;
  return Pi * s * s * (d * d + 2.0 * d * (ra + rb) - 3.0 * (ra - rb) * (ra - rb)) / (12.0 * d);
}

Sphere BoundPair(const Sphere& a, const Sphere& b)
{
  const double d = CenterDistance(a, b);
  if (d + b.Radius <= a.Radius)
  {
    return a;
  }
  if (d + a.Radius <= b.Radius)
  {
    return b;
  }
  Sphere s;
  s.Radius = 0.5 * (d + a.Radius + b.Radius);
  const double t = d > 0.0 ? (s.Radius - a.Radius) / d : 0.0;
  for (int k = 0; k < 3; ++k)
  {
    s.Center[k] = a.Center[k] + t * (b.Center[k] - a.Center[k]);
  }
  // Round-off must not break containment.
  s.Radius = std::max(
    { s.Radius, Distance(s.Center, a.Center) + a.Radius, Distance(s.Center, b.Center) + b.Radius });
  return s;
}

Sphere BoundPoints(const double* xyz, std::size_t n)
{
  Sphere s = { { 0, 0, 0 }, -1.0 };
  if (n == 0)
  {
    return s;
  }
  double lo[3] = { xyz[0], xyz[1], xyz[2] }, hi[3] = { xyz[0], xyz[1], xyz[2] };
  for (std::size_t i = 1; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], xyz[3 * i + k]);
      hi[k] = std::max(hi[k], xyz[3 * i + k]);
    }
  }
  double c[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
  const double scale = Distance(lo, hi);
  auto radius = [&](const double* q)
  {
    double r2 = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double dx = xyz[3 * i] - q[0], dy = xyz[3 * i + 1] - q[1], dz = xyz[3 * i + 2] - q[2];
      r2 = std::max(r2, dx * dx + dy * dy + dz * dz);
    }
    return r2;
  };
  auto farthest = [&](const double* q, double f[3])
  {
    double best = -1.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double dx = xyz[3 * i] - q[0], dy = xyz[3 * i + 1] - q[1], dz = xyz[3 * i + 2] - q[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 > best)
      {
        best = d2;
        std::copy(xyz + 3 * i, xyz + 3 * i + 3, f);
      }
    }
  };
  MinimaxCenter(c, scale, farthest, radius);
  std::copy(c, c + 3, s.Center);
  s.Radius = std::sqrt(radius(c));
  return s;
}

Sphere BoundSpheres(const std::vector<Sphere>& spheres)
{
  Sphere s = { { 0, 0, 0 }, -1.0 };
  if (spheres.empty())
  {
    return s;
  }
  if (spheres.size() == 1)
  {
    return spheres[0];
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
  {
    lo[k] = std::numeric_limits<double>::max();
    hi[k] = -lo[k];
  }
  double c[3] = { 0, 0, 0 };
  for (const Sphere& t : spheres)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], t.Center[k] - t.Radius);
      hi[k] = std::max(hi[k], t.Center[k] + t.Radius);
      c[k] += t.Center[k] / spheres.size();
    }
  }
  auto radius = [&](const double* q)
  {
    double r = 0.0;
    for (const Sphere& t : spheres)
    {
      r = std::max(r, Distance(q, t.Center) + t.Radius);
    }
    return r;
  };
  auto farthest = [&](const double* q, double f[3])
  {
    double best = -1.0;
    for (const Sphere& t : spheres)
    {
      const double d = Distance(q, t.Center);
      if (d + t.Radius > best)
      {
        best = d + t.Radius;
        // The far side of that sphere, seen from q.
        for (int k = 0; k < 3; ++k)
        {
          f[k] = d > 0.0 ? t.Center[k] + (t.Center[k] - q[k]) * t.Radius / d : t.Center[k];
        }
      }
    }
  };
  MinimaxCenter(c, Distance(lo, hi), farthest, radius);
  // Never worse than merging pairwise.
  Sphere merged = spheres[0];
  for (std::size_t i = 1; i < spheres.size(); ++i)
  {
    merged = BoundPair(merged, spheres[i]);
  }
  std::copy(c, c + 3, s.Center);
  s.Radius = radius(c);
  return s.Radius <= merged.Radius ? s : merged;
}

void BestRigidMotion(const double* rest, const double* moved, std::size_t n, double rotation[3][3],
  double restMean[3], double movedMean[3])
{
  for (int k = 0; k < 3; ++k)
  {
    restMean[k] = movedMean[k] = 0.0;
    for (int j = 0; j < 3; ++j)
    {
      rotation[k][j] = k == j ? 1.0 : 0.0;
    }
  }
  if (n == 0)
  {
    return;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      restMean[k] += rest[3 * i + k] / n;
      movedMean[k] += moved[3 * i + k] / n;
    }
  }
  if (n < 2)
  {
    return;
  }
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    Eigen::Vector3d p, q;
    for (int k = 0; k < 3; ++k)
    {
      p[k] = rest[3 * i + k] - restMean[k];
      q[k] = moved[3 * i + k] - movedMean[k];
    }
    h += p * q.transpose();
  }
  if (h.norm() == 0.0)
  {
    return;
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d v = svd.matrixV();
  const Eigen::Matrix3d& u = svd.matrixU();
  if ((v * u.transpose()).determinant() < 0.0)
  {
    v.col(2) *= -1.0; // no reflections: flip the least constrained axis
  }
  const Eigen::Matrix3d r = v * u.transpose();
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      rotation[a][b] = r(a, b);
    }
  }
}

namespace
{
Eigen::Vector3d SingularValues(const double m[3][3])
{
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a(i, j) = m[i][j];
    }
  }
  return Eigen::JacobiSVD<Eigen::Matrix3d>(a).singularValues();
}
} // namespace

double LargestStretch(const double m[3][3])
{
  return SingularValues(m)[0];
}

double SmallestStretch(const double m[3][3])
{
  return SingularValues(m)[2];
}
} // namespace proxygi
