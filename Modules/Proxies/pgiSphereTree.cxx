#include "pgiSphereTree.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace proxygi
{
namespace
{
double Uniform01(std::mt19937& rng)
{
  return (static_cast<double>(rng()) + 0.5) / 4294967296.0;
}

double Distance2(const double* a, const double* b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

} // namespace

std::vector<int> LloydClusters(const double* points, vtkIdType n,
  std::vector<std::array<double, 3>>& centres, int iterations, bool everyCentre)
{
  const int k = static_cast<int>(centres.size());
  std::vector<int> assign(n, -1);
  std::vector<int> byAxis(k);
  std::vector<double> alongAxis(k);
  for (int iteration = 0; iteration < iterations && k > 0; ++iteration)
  {
    // The centres in order along one axis: a point's search walks out from
    // its own coordinate and stops where that coordinate alone is farther
    // than the best so far. The nearest centre (the lowest index among
    // equals) is the full scan's.
    bool finite = true;
    for (int c = 0; c < k; ++c)
    {
      finite = finite && std::isfinite(centres[c][0]) && std::isfinite(centres[c][1]) &&
        std::isfinite(centres[c][2]);
    }
    // Along the axis the centres spread most.
    int axis = 0;
    double widest = -1.0;
    for (int q = 0; finite && q < 3; ++q)
    {
      double lo = centres[0][q], hi = lo;
      for (int c = 1; c < k; ++c)
      {
        lo = std::min(lo, centres[c][q]);
        hi = std::max(hi, centres[c][q]);
      }
      if (hi - lo > widest)
      {
        widest = hi - lo;
        axis = q;
      }
    }
    std::iota(byAxis.begin(), byAxis.end(), 0);
    if (finite)
    {
      std::sort(byAxis.begin(), byAxis.end(),
        [&](int a, int b) {
          return centres[a][axis] < centres[b][axis] ||
            (centres[a][axis] == centres[b][axis] && a < b);
        });
    }
    for (int c = 0; c < k; ++c)
    {
      alongAxis[c] = centres[byAxis[c]][axis];
    }
    std::atomic<bool> changed(false);
    vtkSMPTools::For(0, n,
      [&](vtkIdType first, vtkIdType last)
      {
        bool mine = false;
        for (vtkIdType i = first; i < last; ++i)
        {
          const double* point = points + 3 * i;
          int best = 0;
          double bestD = std::numeric_limits<double>::max();
          const auto consider = [&](int c)
          {
            const double d = Distance2(point, centres[c].data());
            if (d < bestD || (d == bestD && c < best))
            {
              bestD = d;
              best = c;
            }
          };
          if (!everyCentre && finite && std::isfinite(point[0]) && std::isfinite(point[1]) &&
            std::isfinite(point[2]))
          {
            // The last assignment first: a tight bound from the start.
            if (assign[i] >= 0)
            {
              consider(assign[i]);
            }
            const int start =
              static_cast<int>(std::lower_bound(alongAxis.begin(), alongAxis.end(), point[axis]) -
                alongAxis.begin());
            for (int q = start; q < k; ++q)
            {
              const double dx = alongAxis[q] - point[axis];
              if (dx * dx > bestD)
              {
                break;
              }
              consider(byAxis[q]);
            }
            for (int q = start - 1; q >= 0; --q)
            {
              const double dx = point[axis] - alongAxis[q];
              if (dx * dx > bestD)
              {
                break;
              }
              consider(byAxis[q]);
            }
          }
          else
          {
            for (int c = 0; c < k; ++c)
            {
              consider(c);
            }
          }
          mine = mine || assign[i] != best;
          assign[i] = best;
        }
        if (mine)
        {
          changed = true;
        }
      });
    if (!changed)
    {
      break;
    }
    std::vector<std::array<double, 3>> sum(k, { 0.0, 0.0, 0.0 });
    std::vector<vtkIdType> count(k, 0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int q = 0; q < 3; ++q)
      {
        sum[assign[i]][q] += points[3 * i + q];
      }
      ++count[assign[i]];
    }
    for (int c = 0; c < k; ++c)
    {
      for (int q = 0; count[c] > 0 && q < 3; ++q)
      {
        centres[c][q] = sum[c][q] / count[c];
      }
    }
  }
  return assign;
}

namespace
{
// Lloyd clustering of sphere centres into k groups (k-means++ seeds).
std::vector<int> ClusterCenters(const std::vector<Sphere>& s, int k, std::mt19937& rng)
{
  const int n = static_cast<int>(s.size());
  std::vector<std::array<double, 3>> centers;
  std::vector<double> d2(n, std::numeric_limits<double>::max());
  int pick = std::min(n - 1, static_cast<int>(Uniform01(rng) * n));
  while (static_cast<int>(centers.size()) < k)
  {
    centers.push_back({ s[pick].Center[0], s[pick].Center[1], s[pick].Center[2] });
    double total = 0.0;
    for (int i = 0; i < n; ++i)
    {
      d2[i] = std::min(d2[i], Distance2(s[i].Center, centers.back().data()));
      total += d2[i];
    }
    if (!(total > 0.0))
    {
      break;
    }
    double target = Uniform01(rng) * total;
    pick = n - 1;
    for (int i = 0; i < n; ++i)
    {
      target -= d2[i];
      if (target <= 0.0)
      {
        pick = i;
        break;
      }
    }
  }
  std::vector<double> points(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    std::copy(s[i].Center, s[i].Center + 3, &points[3 * static_cast<std::size_t>(i)]);
  }
  return LloydClusters(points.data(), n, centers, 50);
}

// Evens out Lloyd's clusters: a lone member joins the nearest other cluster,
// a cluster of more than 2 * branching splits along its farthest pair. Keeps
// every parent between 2 and 2 * branching children (when n allows).
void Balance(const std::vector<Sphere>& s, std::vector<int>& assign, int branching)
{
  const int n = static_cast<int>(s.size());
  // Merges never make a cluster too big and splits shrink the biggest, so
  // this ends; the guard only bounds the work.
  for (int guard = 0, changed = 1; changed && guard < 4 * n + 4; ++guard)
  {
    changed = 0;
    std::vector<std::vector<int>> members;
    for (int i = 0; i < n; ++i)
    {
      if (assign[i] >= static_cast<int>(members.size()))
      {
        members.resize(assign[i] + 1);
      }
      members[assign[i]].push_back(i);
    }
    members.erase(std::remove_if(members.begin(), members.end(),
                    [](const std::vector<int>& m) { return m.empty(); }),
      members.end());
    for (std::size_t c = 0; c < members.size(); ++c)
    {
      for (int i : members[c])
      {
        assign[i] = static_cast<int>(c);
      }
    }
    auto centre = [&](const std::vector<int>& m, double out[3])
    {
      out[0] = out[1] = out[2] = 0.0;
      for (int i : m)
      {
        for (int q = 0; q < 3; ++q)
        {
          out[q] += s[i].Center[q] / m.size();
        }
      }
    };
    for (std::size_t c = 0; c < members.size() && !changed; ++c)
    {
      if (members[c].size() == 1 && members.size() > 1)
      {
        const int lone = members[c][0];
        int best = -1;
        double bestD = std::numeric_limits<double>::max();
        for (std::size_t o = 0; o < members.size(); ++o)
        {
          if (o == c || members[o].size() >= 2 * static_cast<std::size_t>(branching))
          {
            continue;
          }
          double m[3];
          centre(members[o], m);
          const double d = Distance2(s[lone].Center, m);
          if (d < bestD)
          {
            bestD = d;
            best = static_cast<int>(o);
          }
        }
        if (best >= 0)
        {
          assign[lone] = best;
          changed = 1;
        }
      }
      else if (members[c].size() > 2 * static_cast<std::size_t>(branching))
      {
        // Two seeds: the member farthest from the centre, then the one
        // farthest from it; each member goes to the nearer seed.
        const std::vector<int>& m = members[c];
        double mid[3];
        centre(m, mid);
        int a = m[0], b = m[0];
        for (int i : m)
        {
          a = Distance2(s[i].Center, mid) > Distance2(s[a].Center, mid) ? i : a;
        }
        for (int i : m)
        {
          b = Distance2(s[i].Center, s[a].Center) > Distance2(s[b].Center, s[a].Center) ? i : b;
        }
        const int fresh = static_cast<int>(members.size());
        for (int i : m)
        {
          if (Distance2(s[i].Center, s[b].Center) < Distance2(s[i].Center, s[a].Center))
          {
            assign[i] = fresh;
          }
        }
        changed = 1;
      }
    }
  }
}
} // namespace

void BuildSphereTree(std::vector<Sphere>& nodes, std::vector<int>& level,
  std::vector<long long>& parent, int branching, std::uint32_t seed)
{
  branching = std::max(2, branching);
  level.assign(nodes.size(), 0);
  parent.assign(nodes.size(), -1);
  std::vector<long long> current(nodes.size());
  std::iota(current.begin(), current.end(), 0);
  std::mt19937 rng(seed);
  for (int depth = 1; current.size() > 1; ++depth)
  {
    const int n = static_cast<int>(current.size());
    const int k = std::max(
      1, std::min(n - 1, static_cast<int>(std::lround(static_cast<double>(n) / branching))));
    std::vector<Sphere> spheres;
    spheres.reserve(current.size());
    for (long long i : current)
    {
      spheres.push_back(nodes[i]);
    }
    std::vector<int> assign = ClusterCenters(spheres, k, rng);
    Balance(spheres, assign, branching);
    const int groups = 1 + *std::max_element(assign.begin(), assign.end());
    std::vector<std::vector<int>> members(groups);
    for (int i = 0; i < n; ++i)
    {
      members[assign[i]].push_back(i);
    }
    std::vector<long long> next;
    for (const std::vector<int>& group : members)
    {
      if (group.empty())
      {
        continue;
      }
      std::vector<Sphere> children;
      children.reserve(group.size());
      for (int i : group)
      {
        children.push_back(spheres[i]);
      }
      const long long id = static_cast<long long>(nodes.size());
      nodes.push_back(BoundSpheres(children));
      level.push_back(depth);
      parent.push_back(-1);
      for (int i : group)
      {
        parent[current[i]] = id;
      }
      next.push_back(id);
    }
    current.swap(next);
  }
}

void RefitSphereTree(
  std::vector<Sphere>& nodes, const std::vector<int>& level, const std::vector<long long>& parent)
{
  const std::size_t n = nodes.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return level[a] < level[b]; });
  std::vector<char> started(n, 0);
  // Children in ascending level order reach their parents after being
  // refitted themselves; each merge is the exact bound of the pair.
  for (std::size_t i : order)
  {
    const long long p = parent[i];
    if (p < 0)
    {
      continue;
    }
    if (!started[p])
    {
      nodes[p] = nodes[i];
      started[p] = 1;
    }
    else
    {
      nodes[p] = BoundPair(nodes[p], nodes[i]);
    }
  }
}

SphereTreeStats AnalyseSphereTree(const std::vector<Sphere>& nodes, const std::vector<int>& level,
  const std::vector<long long>& parent)
{
  SphereTreeStats stats;
  const std::size_t n = nodes.size();
  std::vector<int> children(n, 0);
  stats.MaximumViolation = -std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < n; ++i)
  {
    stats.Depth = std::max(stats.Depth, level[i]);
    stats.Leaves += level[i] == 0;
    if (parent[i] < 0)
    {
      ++stats.Roots;
      continue;
    }
    ++children[parent[i]];
    std::size_t guard = 0;
    for (long long a = parent[i]; a >= 0 && guard < n; a = parent[a], ++guard)
    {
      const double v =
        std::sqrt(Distance2(nodes[i].Center, nodes[a].Center)) + nodes[i].Radius - nodes[a].Radius;
      stats.MaximumViolation = std::max(stats.MaximumViolation, v);
    }
  }
  if (stats.MaximumViolation == -std::numeric_limits<double>::max())
  {
    stats.MaximumViolation = 0.0;
  }
  long long total = 0;
  stats.MinBranching = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < n; ++i)
  {
    if (level[i] > 0)
    {
      ++stats.Parents;
      total += children[i];
      stats.MinBranching = std::min(stats.MinBranching, children[i]);
      stats.MaxBranching = std::max(stats.MaxBranching, children[i]);
    }
  }
  if (stats.Parents == 0)
  {
    stats.MinBranching = 0;
  }
  stats.MeanBranching = stats.Parents ? static_cast<double>(total) / stats.Parents : 0.0;
  return stats;
}
bool GetSphereTree(vtkPolyData* proxies, std::vector<Sphere>& nodes, std::vector<int>& level,
  std::vector<long long>& parent, std::string& error)
{
  nodes.clear();
  level.clear();
  parent.clear();
  if (!proxies)
  {
    error = "no proxies";
    return false;
  }
  const vtkIdType n = proxies->GetNumberOfPoints();
  vtkDataArray* radius = proxies->GetPointData()->GetArray("Radius");
  if (!radius && n > 0)
  {
    error = "proxies need a \"Radius\" point array";
    return false;
  }
  vtkDataArray* levels = proxies->GetPointData()->GetArray("Level");
  vtkDataArray* parents = proxies->GetPointData()->GetArray("Parent");
  for (vtkIdType i = 0; i < n; ++i)
  {
    Sphere s;
    proxies->GetPoint(i, s.Center);
    s.Radius = radius->GetTuple1(i);
    nodes.push_back(s);
    level.push_back(levels ? static_cast<int>(levels->GetTuple1(i)) : 0);
    const long long p = parents ? static_cast<long long>(parents->GetTuple1(i)) : -1;
    if (p >= n || p == i)
    {
      error = "point " + std::to_string(i) + " has an invalid Parent " + std::to_string(p);
      return false;
    }
    parent.push_back(p);
  }
  return true;
}

void SetSphereGeometry(vtkPolyData* proxies, const std::vector<Sphere>& nodes)
{
  vtkDataArray* radius = proxies->GetPointData()->GetArray("Radius");
  vtkPoints* points = proxies->GetPoints();
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), nodes[i].Center);
    radius->SetTuple1(static_cast<vtkIdType>(i), nodes[i].Radius);
  }
  points->Modified();
  radius->Modified();
  proxies->Modified();
}
} // namespace proxygi
