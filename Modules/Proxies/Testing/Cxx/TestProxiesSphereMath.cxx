// Sphere geometry and the hierarchy on synthetic data: lens volumes against
// Monte Carlo, pairwise and minimal bounds against known answers, the rigid
// fit against a known motion, and the tree's bounding, depth and branching
// before and after the leaves move.
#include "pgiSphereMath.h"
#include "pgiSphereTree.h"

#include "pgiTesting.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace
{
constexpr double Pi = 3.14159265358979323846;

double Uniform(std::mt19937& rng, double lo, double hi)
{
  return lo + (hi - lo) * ((rng() + 0.5) / 4294967296.0);
}

double Distance(const double* a, const double* b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}
} // namespace

int TestProxiesSphereMath(int, char*[])
{
  using namespace proxygi;
  std::mt19937 rng(7);

  // Lens volume: closed form against Monte Carlo in the smaller sphere.
  const Sphere a = { { 0, 0, 0 }, 1.0 }, b = { { 1.2, 0.3, -0.2 }, 0.7 };
  int hits = 0;
  const int samples = 400000;
  for (int i = 0; i < samples; ++i)
  {
    double p[3];
    do
    {
      for (double& v : p)
      {
        v = Uniform(rng, -1.0, 1.0);
      }
    } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1.0);
    const double q[3] = { b.Center[0] + b.Radius * p[0], b.Center[1] + b.Radius * p[1],
      b.Center[2] + b.Radius * p[2] };
    hits += Distance(q, a.Center) <= a.Radius;
  }
  const double mc = SphereVolume(b.Radius) * hits / samples;
  std::printf("lens volume %.5f, Monte Carlo %.5f\n", LensVolume(a, b), mc);
  PGI_NEAR(LensVolume(a, b), mc, 4.0 * std::sqrt(mc * SphereVolume(b.Radius) / samples));
  PGI_NEAR(LensVolume(a, { { 3, 0, 0 }, 1.0 }), 0.0, 0.0);
  PGI_NEAR(LensVolume(a, { { 0.1, 0, 0 }, 0.5 }), SphereVolume(0.5), 1e-12);
  // Two unit spheres one radius apart: 5 pi / 12.
  PGI_NEAR(LensVolume(a, { { 1, 0, 0 }, 1.0 }), 5.0 * Pi / 12.0, 1e-12);

  // Pairwise bound: exact for separate spheres, the outer one if nested.
  const Sphere pair = BoundPair(a, { { 4, 0, 0 }, 1.0 });
  PGI_NEAR(pair.Radius, 3.0, 1e-12);
  PGI_NEAR(pair.Center[0], 2.0, 1e-12);
  const Sphere nested = BoundPair(a, { { 0.2, 0, 0 }, 0.5 });
  PGI_NEAR(nested.Radius, 1.0, 0.0);
  for (int i = 0; i < 1000; ++i)
  {
    Sphere s = { { Uniform(rng, -2, 2), Uniform(rng, -2, 2), Uniform(rng, -2, 2) },
      Uniform(rng, 0.01, 2) };
    Sphere t = { { Uniform(rng, -2, 2), Uniform(rng, -2, 2), Uniform(rng, -2, 2) },
      Uniform(rng, 0.01, 2) };
    const Sphere u = BoundPair(s, t);
    if (!PGI_CHECK(Contains(u, s) && Contains(u, t)))
    {
      break;
    }
  }

  // Near-minimal bounds: points on a sphere, spheres on a ring.
  std::vector<double> points;
  for (int i = 0; i < 2000; ++i)
  {
    const double z = Uniform(rng, -1, 1), phi = Uniform(rng, 0, 2 * Pi);
    const double s = std::sqrt(1 - z * z);
    points.insert(points.end(), { 3 + 2 * s * std::cos(phi), -1 + 2 * s * std::sin(phi), 2 * z });
  }
  const Sphere fit = BoundPoints(points.data(), points.size() / 3);
  std::printf("bound of 2000 points on a radius-2 sphere: radius %.5f centre %.4f %.4f %.4f\n",
    fit.Radius, fit.Center[0], fit.Center[1], fit.Center[2]);
  PGI_BELOW(fit.Radius, 2.0 * 1.005);
  PGI_NEAR(fit.Center[0], 3.0, 0.02);
  for (std::size_t i = 0; i < points.size(); i += 3)
  {
    if (!PGI_CHECK(Distance(points.data() + i, fit.Center) <= fit.Radius))
    {
      break;
    }
  }
  std::vector<Sphere> ring;
  ring.reserve(12);
  for (int i = 0; i < 12; ++i)
  {
    ring.push_back({ { 5 * std::cos(2 * Pi * i / 12), 5 * std::sin(2 * Pi * i / 12), 1 }, 1.0 });
  }
  const Sphere ringBound = BoundSpheres(ring);
  PGI_NEAR(ringBound.Radius, 6.0, 0.03);
  for (const Sphere& s : ring)
  {
    PGI_CHECK(Contains(ringBound, s, 1e-12));
  }

  // Rigid fit recovers a rotation about a tilted axis and a translation.
  {
    const double angle = 1.1, axis[3] = { 0.48, 0.6, 0.64 };
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const double r[3][3] = {
      { t * axis[0] * axis[0] + c, t * axis[0] * axis[1] - s * axis[2],
        t * axis[0] * axis[2] + s * axis[1] },
      { t * axis[0] * axis[1] + s * axis[2], t * axis[1] * axis[1] + c,
        t * axis[1] * axis[2] - s * axis[0] },
      { t * axis[0] * axis[2] - s * axis[1], t * axis[1] * axis[2] + s * axis[0],
        t * axis[2] * axis[2] + c },
    };
    std::vector<double> rest, moved;
    for (int i = 0; i < 20; ++i)
    {
      const double p[3] = { Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1) };
      rest.insert(rest.end(), p, p + 3);
      for (int k = 0; k < 3; ++k)
      {
        moved.push_back(r[k][0] * p[0] + r[k][1] * p[1] + r[k][2] * p[2] + (k + 1.0));
      }
    }
    double fitR[3][3], ma[3], mb[3];
    BestRigidMotion(rest.data(), moved.data(), 20, fitR, ma, mb);
    double worst = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        worst = std::max(worst, std::fabs(fitR[i][j] - r[i][j]));
      }
    }
    PGI_BELOW(worst, 1e-10);
    // moved = R (rest - ma) + mb with ma, mb the two centroids, so the
    // translation is mb - R ma = (1, 2, 3).
    for (int k = 0; k < 3; ++k)
    {
      double restMean = 0.0, movedMean = 0.0;
      for (int i = 0; i < 20; ++i)
      {
        restMean += rest[3 * i + k] / 20.0;
        movedMean += moved[3 * i + k] / 20.0;
      }
      PGI_NEAR(ma[k], restMean, 1e-12);
      PGI_NEAR(mb[k], movedMean, 1e-12);
      // Exact up to rounding; 1e-9 allows 3 |ma| times the rotation's 1e-10.
      PGI_NEAR(
        mb[k] - (fitR[k][0] * ma[0] + fitR[k][1] * ma[1] + fitR[k][2] * ma[2]), k + 1.0, 1e-9);
    }
    const double m[3][3] = { { 2, 0, 0 }, { 0, 3, 0 }, { 0, 0, 0.5 } };
    PGI_NEAR(LargestStretch(m), 3.0, 1e-12);
    PGI_NEAR(SmallestStretch(m), 0.5, 1e-12);
  }

  // Hierarchy over 500 random spheres: bounding, depth ~ log4(500), 2 to 8
  // children per parent, about 4 on average.
  std::vector<Sphere> nodes;
  nodes.reserve(500);
  for (int i = 0; i < 500; ++i)
  {
    nodes.push_back(
      { { Uniform(rng, 0, 10), Uniform(rng, 0, 10), Uniform(rng, 0, 3) }, Uniform(rng, 0.1, 0.6) });
  }
  std::vector<int> level;
  std::vector<long long> parent;
  BuildSphereTree(nodes, level, parent, 4, 1);
  SphereTreeStats stats = AnalyseSphereTree(nodes, level, parent);
  std::printf("500 leaves: %d parents, depth %d, branching mean %.2f (min %d, max %d), "
              "violation %.3g\n",
    stats.Parents, stats.Depth, stats.MeanBranching, stats.MinBranching, stats.MaxBranching,
    stats.MaximumViolation);
  PGI_CHECK(stats.Roots == 1);
  PGI_CHECK(stats.Leaves == 500);
  PGI_CHECK(stats.Depth >= 4 && stats.Depth <= 6);
  PGI_CHECK(stats.MeanBranching >= 3.0 && stats.MeanBranching <= 5.0);
  PGI_CHECK(stats.MinBranching >= 2 && stats.MaxBranching <= 8);
  PGI_BELOW(stats.MaximumViolation, 1e-9);
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    if (parent[i] >= 0 && !PGI_CHECK(level[parent[i]] == level[i] + 1))
    {
      break;
    }
  }
  // Leaves move; the refit restores bounding (before it, some poke out).
  for (std::size_t i = 0; i < 500; ++i)
  {
    for (double& c : nodes[i].Center)
    {
      c += Uniform(rng, -1.0, 1.0);
    }
  }
  PGI_CHECK(AnalyseSphereTree(nodes, level, parent).MaximumViolation > 0.1);
  RefitSphereTree(nodes, level, parent);
  stats = AnalyseSphereTree(nodes, level, parent);
  std::printf("after moving the leaves and refitting: violation %.3g\n", stats.MaximumViolation);
  PGI_BELOW(stats.MaximumViolation, 1e-9);

  // Degenerate cases: one leaf is its own root; two leaves get one parent.
  std::vector<Sphere> one = { a };
  BuildSphereTree(one, level, parent);
  PGI_CHECK(one.size() == 1 && parent[0] == -1);
  std::vector<Sphere> two = { a, b };
  BuildSphereTree(two, level, parent);
  PGI_CHECK(two.size() == 3 && parent[0] == 2 && parent[1] == 2 && level[2] == 1);
  PGI_CHECK(Contains(two[2], a, 1e-12) && Contains(two[2], b, 1e-12));

  // Lloyd's clusters search the centres along one axis from each point's
  // last centre: the same clusters and centres as scanning every centre
  // (ties to the lowest index), on scattered, gridded (many ties), flat and
  // non-finite points.
  {
    int differ = 0, runs = 0;
    for (int kind = 0; kind < 4; ++kind)
    {
      std::vector<double> points;
      for (int i = 0; i < 3000; ++i)
      {
        if (kind == 1)
        {
          // A grid: equidistant centres tie.
          const int x = i % 10, y = (i / 10) % 10, z = i / 100;
          points.insert(points.end(), { double(x), double(y), double(z) });
        }
        else
        {
          points.insert(points.end(),
            { Uniform(rng, -5, 5), Uniform(rng, -1, 1), kind == 2 ? 0.0 : Uniform(rng, -3, 3) });
        }
      }
      if (kind == 3)
      {
        points[30] = std::nan("");
        points[61] = HUGE_VAL;
      }
      for (const int k : { 1, 7, 64 })
      {
        std::vector<std::array<double, 3>> seeds(k), mine(k), theirs(k);
        for (int c = 0; c < k; ++c)
        {
          const int i = (c * 2999) / std::max(1, k - 1) % 3000;
          seeds[c] = { points[3 * i], points[3 * i + 1], points[3 * i + 2] };
        }
        mine = theirs = seeds;
        const std::vector<int> fast = LloydClusters(points.data(), 3000, mine, 6);
        const std::vector<int> slow = LloydClusters(points.data(), 3000, theirs, 6, true);
        ++runs;
        bool same = fast == slow;
        for (int c = 0; same && c < k; ++c)
        {
          for (int q = 0; q < 3; ++q)
          {
            same = same &&
              (mine[c][q] == theirs[c][q] || (std::isnan(mine[c][q]) && std::isnan(theirs[c][q])));
          }
        }
        differ += same ? 0 : 1;
      }
    }
    std::printf(
      "Lloyd's clusters: %d of %d runs differ from scanning every centre\n", differ, runs);
    PGI_CHECK(differ == 0);
  }
  return pgitest::Result();
}
