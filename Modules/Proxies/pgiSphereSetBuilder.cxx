#include "pgiSphereSetBuilder.h"

#include "pgiMeshQueries.h"
#include "pgiNelderMead.h"
#include "pgiProxyMesh.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <random>
#include <unordered_map>

namespace proxygi
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

// Same numbers on every standard library (std distributions are not).
double Uniform01(std::mt19937& rng)
{
  return (static_cast<double>(rng()) + 0.5) / 4294967296.0;
}

double Distance2(const double* a, const double* b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

// Interior sample grid: points on every M-th row, M row spacings apart along x.
struct InteriorGrid
{
  int NI = 0, NJ = 0, NK = 0, M = 1, OJ = 0, OK = 0;
  double X0 = 0.0, Step = 1.0;
  std::vector<int> Node; // sample index or -1, (I * NJ + J) * NK + K
  std::vector<double> Samples;

  void Build(const VolumeRows& rows, const double bounds[6], int resolution)
  {
    const double h = rows.Spacing();
    const double longest =
      std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
    this->M = std::max(1, static_cast<int>(std::lround(longest / std::max(1, resolution) / h)));
    this->Step = this->M * h;
    const double ex = bounds[1] - bounds[0];
    this->NI = std::max(1, static_cast<int>(std::ceil(ex / this->Step)));
    this->X0 = bounds[0] + 0.5 * (ex - (this->NI - 1) * this->Step);
    auto layout = [this](int rowCount, int& count, int& offset)
    {
      count = std::max(1, (rowCount + this->M - 1) / this->M);
      offset = std::max(0, (rowCount - 1 - this->M * (count - 1)) / 2);
    };
    layout(rows.RowsY(), this->NJ, this->OJ);
    layout(rows.RowsZ(), this->NK, this->OK);
    this->Node.assign(static_cast<std::size_t>(this->NI) * this->NJ * this->NK, -1);
    this->Samples.clear();
    if (!rows.Solid())
    {
      return;
    }
    for (int i = 0; i < this->NI; ++i)
    {
      const double x = this->X0 + i * this->Step;
      for (int j = 0; j < this->NJ; ++j)
      {
        const int row = std::min(rows.RowsY() - 1, this->OJ + this->M * j);
        for (int k = 0; k < this->NK; ++k)
        {
          const int col = std::min(rows.RowsZ() - 1, this->OK + this->M * k);
          if (rows.Inside(row, col, x))
          {
            this->Node[(static_cast<std::size_t>(i) * this->NJ + j) * this->NK + k] =
              static_cast<int>(this->Samples.size() / 3);
            this->Samples.insert(this->Samples.end(), { x, rows.RowY(row), rows.RowZ(col) });
          }
        }
      }
    }
  }

  int At(int i, int j, int k) const
  {
    if (i < 0 || j < 0 || k < 0 || i >= this->NI || j >= this->NJ || k >= this->NK)
    {
      return -1;
    }
    return this->Node[(static_cast<std::size_t>(i) * this->NJ + j) * this->NK + k];
  }
};

// Piecewise-linear outside volume V(S(c, r) - T) of growing spheres about a
// fixed centre; beyond the table all new volume is taken to be outside.
struct Profile
{
  std::vector<double> Table;
  double Step = 1.0;

  double operator()(double r) const
  {
    if (r <= 0.0)
    {
      return 0.0;
    }
    const int bins = static_cast<int>(this->Table.size()) - 1;
    const double b = r / this->Step;
    if (b >= bins)
    {
      const double rmax = bins * this->Step;
      return this->Table[bins] + 4.0 / 3.0 * Pi * (r * r * r - rmax * rmax * rmax);
    }
    const int i = static_cast<int>(b);
    const double f = b - i;
    return (1.0 - f) * this->Table[i] + f * this->Table[i + 1];
  }
};
} // namespace

double RowSpacing(const double bounds[6], int resolution)
{
  const double longest =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  return std::max(longest, 1e-30) / std::max(1, resolution);
}

void ComputeInteriorSamples(const VolumeRows& rows, const double meshBounds[6],
  int interiorResolution, std::vector<double>& samples)
{
  InteriorGrid grid;
  grid.Build(rows, meshBounds, interiorResolution);
  samples = grid.Samples;
}

struct SphereSetBuilder::Internal
{
  // The object's triangles, long ones split (elements only; the rows and
  // Embree use the original).
  ProxyMesh Mesh;
  const MeshQueries& Queries;
  SphereSetOptions Options;
  VolumeRows Rows;
  InteriorGrid Grid;
  double Tiny = 0.0;        // outside volume below this is zero (round-off)
  double StrideRows = 16.0; // rows across a sphere's radius, at least

  // Elements: triangles first, then interior samples.
  int NT = 0, NE = 0;
  std::vector<double> Position; // centroid or sample, 3 per element
  std::vector<int> AdjacencyStart, Adjacency;

  Internal(const ProxyMesh& mesh, const MeshQueries& queries, const SphereSetOptions& options)
    : Mesh(mesh)
    , Queries(queries)
    , Options(options)
  {
  }

  const double* Pos(int e) const { return this->Position.data() + 3 * e; }

  // Distance from c to the farthest point of element e.
  double Reach(int e, const double c[3]) const
  {
    if (e < this->NT)
    {
      const int* v = this->Mesh.Triangles.data() + 3 * e;
      return std::sqrt(std::max({ Distance2(this->Mesh.Point(v[0]), c),
        Distance2(this->Mesh.Point(v[1]), c), Distance2(this->Mesh.Point(v[2]), c) }));
    }
    return std::sqrt(Distance2(this->Pos(e), c));
  }

  bool Covers(const Sphere& s, int e) const
  {
    const double r2 = s.Radius * s.Radius;
    if (e < this->NT)
    {
      const int* v = this->Mesh.Triangles.data() + 3 * e;
      return Distance2(this->Mesh.Point(v[0]), s.Center) <= r2 &&
        Distance2(this->Mesh.Point(v[1]), s.Center) <= r2 &&
        Distance2(this->Mesh.Point(v[2]), s.Center) <= r2;
    }
    return Distance2(this->Pos(e), s.Center) <= r2;
  }

  void Setup()
  {
    const double h = RowSpacing(this->Mesh.Bounds, this->Options.VolumeResolution);
    this->Rows.Build(this->Queries, this->Mesh.Bounds, this->Mesh.Bounds, h);
    this->Grid.Build(this->Rows, this->Mesh.Bounds, this->Options.InteriorResolution);
    this->Tiny = 1e-12 * std::pow(this->Mesh.Diagonal(), 3.0);
    this->Refine();
    this->NT = this->Mesh.NumberOfTriangles();
    const int ni = static_cast<int>(this->Grid.Samples.size() / 3);
    this->NE = this->NT + ni;
    this->Position.resize(3 * static_cast<std::size_t>(this->NE));
    for (int t = 0; t < this->NT; ++t)
    {
      const int* v = this->Mesh.Triangles.data() + 3 * t;
      for (int k = 0; k < 3; ++k)
      {
        this->Position[3 * t + k] =
          (this->Mesh.Point(v[0])[k] + this->Mesh.Point(v[1])[k] + this->Mesh.Point(v[2])[k]) / 3.0;
      }
    }
    std::copy(
      this->Grid.Samples.begin(), this->Grid.Samples.end(), this->Position.begin() + 3 * this->NT);
    this->BuildAdjacency();
  }

  // A triangle is bounded whole by the sphere of its cluster, so one long
  // triangle forces a big sphere. Split triangles at the midpoint of their
  // longest edge until no edge is longer than the interior sample spacing
  // (midpoints shared between neighbours). At most four times the
  // triangles (and 200k more): coarser where that is not enough.
  void Refine()
  {
    const double* b = this->Mesh.Bounds;
    const double longest = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
    const int nt = this->Mesh.NumberOfTriangles();
    const std::size_t cap = 4 * static_cast<std::size_t>(nt) + 200000;
    const ProxyMesh original = this->Mesh;
    for (double edge = longest / std::max(1, this->Options.InteriorResolution); edge <= 2 * longest;
         edge *= 2.0)
    {
      ProxyMesh refined;
      refined.Points = original.Points;
      std::copy(b, b + 6, refined.Bounds);
      std::unordered_map<std::uint64_t, int> midpoints;
      const double limit2 = edge * edge;
      bool fits = true;
      // Explicit stack of (triangle, depth); depth bounds degenerate cases.
      std::vector<std::array<int, 4>> stack;
      for (int t = 0; t < nt && fits; ++t)
      {
        stack.push_back({ original.Triangles[3 * t], original.Triangles[3 * t + 1],
          original.Triangles[3 * t + 2], 0 });
        while (!stack.empty() && fits)
        {
          const std::array<int, 4> tri = stack.back();
          stack.pop_back();
          int longestEdge = 0;
          double longest2 = -1.0;
          for (int e = 0; e < 3; ++e)
          {
            const double d2 = Distance2(refined.Point(tri[e]), refined.Point(tri[(e + 1) % 3]));
            if (d2 > longest2)
            {
              longest2 = d2;
              longestEdge = e;
            }
          }
          if (longest2 <= limit2 || tri[3] >= 40)
          {
            refined.Triangles.insert(refined.Triangles.end(), tri.begin(), tri.begin() + 3);
            fits = refined.Triangles.size() / 3 <= cap;
            continue;
          }
          const int p = tri[longestEdge], q = tri[(longestEdge + 1) % 3],
                    r = tri[(longestEdge + 2) % 3];
          const std::uint64_t key = (static_cast<std::uint64_t>(std::min(p, q)) << 32) |
            static_cast<std::uint32_t>(std::max(p, q));
          auto found = midpoints.find(key);
          int m;
          if (found == midpoints.end())
          {
            m = refined.NumberOfPoints();
            for (int k = 0; k < 3; ++k)
            {
              refined.Points.push_back(0.5 * (refined.Point(p)[k] + refined.Point(q)[k]));
            }
            midpoints.emplace(key, m);
          }
          else
          {
            m = found->second;
          }
          stack.push_back({ p, m, r, tri[3] + 1 });
          stack.push_back({ m, q, r, tri[3] + 1 });
        }
      }
      if (fits)
      {
        this->Mesh = std::move(refined);
        return;
      }
    }
  }

  // Neighbours for the flood fill: triangles sharing a vertex, grid
  // neighbours, and each triangle with the grid samples around its centroid.
  void BuildAdjacency()
  {
    std::vector<std::vector<int>> nb(this->NE);
    const int np = this->Mesh.NumberOfPoints();
    std::vector<int> vstart(np + 1, 0), vtris(3 * static_cast<std::size_t>(this->NT));
    for (int v : this->Mesh.Triangles)
    {
      ++vstart[v + 1];
    }
    std::partial_sum(vstart.begin(), vstart.end(), vstart.begin());
    {
      std::vector<int> fill(vstart.begin(), vstart.end() - 1);
      for (int t = 0; t < this->NT; ++t)
      {
        for (int k = 0; k < 3; ++k)
        {
          vtris[fill[this->Mesh.Triangles[3 * t + k]]++] = t;
        }
      }
    }
    for (int t = 0; t < this->NT; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const int v = this->Mesh.Triangles[3 * t + k];
        for (int i = vstart[v]; i < vstart[v + 1]; ++i)
        {
          if (vtris[i] != t)
          {
            nb[t].push_back(vtris[i]);
          }
        }
      }
    }
    const InteriorGrid& g = this->Grid;
    const double h = this->Rows.Spacing();
    for (int i = 0; i < g.NI; ++i)
    {
      for (int j = 0; j < g.NJ; ++j)
      {
        for (int k = 0; k < g.NK; ++k)
        {
          const int s = g.At(i, j, k);
          if (s < 0)
          {
            continue;
          }
          const int steps[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
          for (const auto& d : steps)
          {
            const int o = g.At(i + d[0], j + d[1], k + d[2]);
            if (o >= 0)
            {
              nb[this->NT + s].push_back(this->NT + o);
              nb[this->NT + o].push_back(this->NT + s);
            }
          }
        }
      }
    }
    if (!g.Samples.empty())
    {
      for (int t = 0; t < this->NT; ++t)
      {
        const double* c = this->Pos(t);
        const double fi = (c[0] - g.X0) / g.Step;
        const double fj = ((c[1] - this->Rows.RowY(0)) / h - g.OJ) / g.M;
        const double fk = ((c[2] - this->Rows.RowZ(0)) / h - g.OK) / g.M;
        const int i0 = static_cast<int>(std::floor(fi)), j0 = static_cast<int>(std::floor(fj)),
                  k0 = static_cast<int>(std::floor(fk));
        for (int corner = 0; corner < 8; ++corner)
        {
          const int s = g.At(i0 + (corner & 1), j0 + ((corner >> 1) & 1), k0 + (corner >> 2));
          if (s >= 0)
          {
            nb[t].push_back(this->NT + s);
            nb[this->NT + s].push_back(t);
          }
        }
      }
    }
    this->AdjacencyStart.assign(this->NE + 1, 0);
    this->Adjacency.clear();
    for (int e = 0; e < this->NE; ++e)
    {
      std::sort(nb[e].begin(), nb[e].end());
      nb[e].erase(std::unique(nb[e].begin(), nb[e].end()), nb[e].end());
      this->AdjacencyStart[e] = static_cast<int>(this->Adjacency.size());
      this->Adjacency.insert(this->Adjacency.end(), nb[e].begin(), nb[e].end());
    }
    this->AdjacencyStart[this->NE] = static_cast<int>(this->Adjacency.size());
  }

  // k-means++ seeding on the element positions.
  std::vector<Sphere> SeedCenters(int k, std::mt19937& rng) const
  {
    std::vector<Sphere> centers;
    std::vector<double> d2(this->NE, std::numeric_limits<double>::max());
    int pick = std::min(this->NE - 1, static_cast<int>(Uniform01(rng) * this->NE));
    for (int c = 0; c < k; ++c)
    {
      Sphere s = { { this->Pos(pick)[0], this->Pos(pick)[1], this->Pos(pick)[2] }, 0.0 };
      centers.push_back(s);
      double total = 0.0;
      for (int e = 0; e < this->NE; ++e)
      {
        d2[e] = std::min(d2[e], Distance2(this->Pos(e), s.Center));
        total += d2[e];
      }
      if (!(total > 0.0))
      {
        break;
      }
      double target = Uniform01(rng) * total;
      pick = this->NE - 1;
      for (int e = 0; e < this->NE; ++e)
      {
        target -= d2[e];
        if (target <= 0.0)
        {
          pick = e;
          break;
        }
      }
    }
    return centers;
  }

  // Constraint points (corners of triangles, samples) of each cluster.
  void GatherPoints(
    const std::vector<int>& assign, int k, std::vector<std::vector<double>>& points) const
  {
    std::vector<std::vector<int>> members(k);
    for (int e = 0; e < this->NE; ++e)
    {
      if (assign[e] >= 0)
      {
        members[assign[e]].push_back(e);
      }
    }
    points.assign(k, std::vector<double>());
    std::vector<int> stamp(this->Mesh.NumberOfPoints(), -1);
    for (int c = 0; c < k; ++c)
    {
      for (int e : members[c])
      {
        if (e < this->NT)
        {
          for (int q = 0; q < 3; ++q)
          {
            const int v = this->Mesh.Triangles[3 * e + q];
            if (stamp[v] != c)
            {
              stamp[v] = c;
              points[c].insert(points[c].end(), this->Mesh.Point(v), this->Mesh.Point(v) + 3);
            }
          }
        }
        else
        {
          points[c].insert(points[c].end(), this->Pos(e), this->Pos(e) + 3);
        }
      }
    }
  }

  static double MaxDistance(const std::vector<double>& pts, const double c[3])
  {
    double r2 = 0.0;
    for (std::size_t i = 0; i < pts.size(); i += 3)
    {
      r2 = std::max(r2, Distance2(pts.data() + i, c));
    }
    return std::sqrt(r2);
  }

  double Outside(const double c[3], double r) const
  {
    // Big spheres integrate over a subset of the rows (cost bounded).
    const double v = this->Rows.OutsideVolume(c, r, this->Rows.StrideFor(r, this->StrideRows));
    return v > this->Tiny ? v : 0.0;
  }

  double Energy(const std::vector<Sphere>& spheres) const
  {
    double e = 0.0;
    for (const Sphere& s : spheres)
    {
      e += this->Outside(s.Center, s.Radius);
    }
    return e;
  }

  bool Report(double fraction) const
  {
    return !this->Options.Progress || this->Options.Progress(fraction);
  }

  // --- Variational method -------------------------------------------------

  // Flood-fill clustering from the sphere centres (radii grow from zero).
  // Radii on entry bound the profile tables; on exit they bound the clusters.
  void Cluster(std::vector<Sphere>& spheres, std::vector<int>& assign) const
  {
    const int k = static_cast<int>(spheres.size());
    const double h = this->Rows.Spacing();
    const double diagonal = this->Mesh.Diagonal();
    std::vector<Profile> profiles(k);
    vtkSMPTools::For(0, k,
      [&](int begin, int end)
      {
        for (int c = begin; c < end; ++c)
        {
          // Radii rarely grow past twice their last value; beyond, costs only
          // need to be large.
          const double rmax = std::min(diagonal, std::max(2.0 * spheres[c].Radius, 0.0) + 4.0 * h);
          const int stride = this->Rows.StrideFor(rmax, this->StrideRows);
          profiles[c].Step = stride * h;
          this->Rows.OutsideProfile(spheres[c].Center, stride * h,
            std::max(1, static_cast<int>(std::ceil(rmax / (stride * h)))), profiles[c].Table,
            stride);
          for (double& v : profiles[c].Table)
          {
            v = v > this->Tiny ? v : 0.0;
          }
        }
      });
    std::vector<double> radius(k, 0.0), base(k, 0.0);
    assign.assign(this->NE, -1);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    std::vector<double> key(this->NE, std::numeric_limits<double>::max());
    // Seeds: the element nearest each centre, not taken by an earlier seed.
    std::vector<char> seeded(this->NE, 0);
    for (int c = 0; c < k; ++c)
    {
      int best = -1;
      double bestD = std::numeric_limits<double>::max();
      for (int e = 0; e < this->NE; ++e)
      {
        const double d = Distance2(this->Pos(e), spheres[c].Center);
        if (!seeded[e] && d < bestD)
        {
          bestD = d;
          best = e;
        }
      }
      if (best >= 0)
      {
        seeded[best] = 1;
        key[best] = 0.0;
        queue.push({ 0.0, best });
      }
    }
    int assigned = 0;
    // Centres as arrays, and each element's squared reach to all of them
    // first: the loop the compiler can vectorise.
    std::vector<double> cx(k), cy(k), cz(k), r2(k, 0.0), reach2(k);
    for (int c = 0; c < k; ++c)
    {
      cx[c] = spheres[c].Center[0];
      cy[c] = spheres[c].Center[1];
      cz[c] = spheres[c].Center[2];
    }
    auto assignOne = [&](int e)
    {
      const int corners = e < this->NT ? 3 : 1;
      const double* p[3];
      if (e < this->NT)
      {
        for (int q = 0; q < 3; ++q)
        {
          p[q] = this->Mesh.Point(this->Mesh.Triangles[3 * e + q]);
        }
      }
      else
      {
        p[0] = this->Pos(e);
      }
      std::fill(reach2.begin(), reach2.end(), 0.0);
      for (int q = 0; q < corners; ++q)
      {
        const double px = p[q][0], py = p[q][1], pz = p[q][2];
        for (int c = 0; c < k; ++c)
        {
          const double dx = px - cx[c], dy = py - cy[c], dz = pz - cz[c];
          reach2[c] = std::max(reach2[c], dx * dx + dy * dy + dz * dz);
        }
      }
      // A sphere already holding the element costs nothing; the nearest wins.
      int chosen = -1;
      double bestReach2 = std::numeric_limits<double>::max();
      for (int c = 0; c < k; ++c)
      {
        if (reach2[c] <= r2[c] && reach2[c] < bestReach2)
        {
          bestReach2 = reach2[c];
          chosen = c;
        }
      }
      // Otherwise (or nearer still, if growth there is free) the least growth.
      const bool held = chosen >= 0;
      const double heldReach2 = bestReach2;
      double bestCost = held ? 0.0 : std::numeric_limits<double>::max();
      for (int c = 0; c < k; ++c)
      {
        if (reach2[c] <= r2[c] || (held && reach2[c] >= heldReach2))
        {
          continue;
        }
        const double d = std::sqrt(reach2[c]);
        double cost = profiles[c](d) - base[c];
        cost = cost > this->Tiny ? cost : 0.0;
        if (cost < bestCost || (cost == bestCost && reach2[c] < bestReach2))
        {
          bestCost = cost;
          bestReach2 = reach2[c];
          chosen = c;
        }
      }
      const double bestReach = std::sqrt(bestReach2);
      assign[e] = chosen;
      if (bestReach > radius[chosen])
      {
        radius[chosen] = bestReach;
        r2[chosen] = bestReach2;
        base[chosen] = profiles[chosen](bestReach);
      }
      ++assigned;
      const double* c = spheres[chosen].Center;
      for (int i = this->AdjacencyStart[e]; i < this->AdjacencyStart[e + 1]; ++i)
      {
        const int n = this->Adjacency[i];
        if (assign[n] < 0)
        {
          const double d = std::sqrt(Distance2(this->Pos(n), c));
          if (d < key[n])
          {
            key[n] = d;
            queue.push({ d, n });
          }
        }
      }
    };
    while (assigned < this->NE)
    {
      while (!queue.empty())
      {
        const Entry top = queue.top();
        queue.pop();
        if (assign[top.second] < 0)
        {
          assignOne(top.second);
        }
      }
      if (assigned < this->NE)
      {
        // A part the flood cannot reach: restart from its element nearest
        // to any centre.
        int best = -1;
        double bestD = std::numeric_limits<double>::max();
        for (int e = 0; e < this->NE; ++e)
        {
          if (assign[e] >= 0)
          {
            continue;
          }
          for (int c = 0; c < k; ++c)
          {
            const double d = Distance2(this->Pos(e), spheres[c].Center);
            if (d < bestD)
            {
              bestD = d;
              best = e;
            }
          }
        }
        key[best] = 0.0;
        queue.push({ 0.0, best });
      }
    }
    for (int c = 0; c < k; ++c)
    {
      spheres[c].Radius = radius[c];
    }
  }

  // Moves each centre to minimise its outside volume while bounding its
  // cluster (the paper uses Powell's method; Nelder-Mead does the same job).
  double Update(std::vector<Sphere>& spheres, const std::vector<int>& assign) const
  {
    const int k = static_cast<int>(spheres.size());
    std::vector<std::vector<double>> points;
    this->GatherPoints(assign, k, points);
    std::vector<double> outside(k, 0.0);
    const double h = this->Rows.Spacing();
    vtkSMPTools::For(0, k,
      [&](int begin, int end)
      {
        for (int c = begin; c < end; ++c)
        {
          const std::vector<double>& p = points[c];
          Sphere& s = spheres[c];
          if (p.empty())
          {
            s.Radius = 0.0;
            continue;
          }
          auto f = [&](const double* x) { return this->Outside(x, MaxDistance(p, x)); };
          double x[3] = { s.Center[0], s.Center[1], s.Center[2] };
          double fx = f(x);
          // Also try the cluster's mean: the old centre may be far off.
          double mean[3] = { 0, 0, 0 };
          const std::size_t points = p.size() / 3;
          const double n = static_cast<double>(points);
          for (std::size_t i = 0; i < p.size(); i += 3)
          {
            for (int q = 0; q < 3; ++q)
            {
              mean[q] += p[i + q] / n;
            }
          }
          const double fm = f(mean);
          if (fm < fx)
          {
            std::copy(mean, mean + 3, x);
            fx = fm;
          }
          const double r = MaxDistance(p, x);
          if (r > 0.0)
          {
            fx = MinimizeNelderMead3(f, x, 0.25 * r, 0.05 * h, 150);
          }
          std::copy(x, x + 3, s.Center);
          s.Radius = MaxDistance(p, x);
          outside[c] = fx;
        }
      });
    return std::accumulate(outside.begin(), outside.end(), 0.0);
  }

  // Re-places the centres of empty clusters at the element farthest from
  // the centre of the largest cluster.
  bool FillEmpty(std::vector<Sphere>& spheres, const std::vector<int>& assign) const
  {
    const int k = static_cast<int>(spheres.size());
    std::vector<int> count(k, 0);
    for (int a : assign)
    {
      ++count[a];
    }
    bool changed = false;
    for (int c = 0; c < k; ++c)
    {
      if (count[c] > 0)
      {
        continue;
      }
      const int big =
        static_cast<int>(std::max_element(spheres.begin(), spheres.end(),
                           [](const Sphere& a, const Sphere& b) { return a.Radius < b.Radius; }) -
          spheres.begin());
      int far = -1;
      double farD = -1.0;
      for (int e = 0; e < this->NE; ++e)
      {
        if (assign[e] == big)
        {
          const double d = Distance2(this->Pos(e), spheres[big].Center);
          if (d > farD)
          {
            farD = d;
            far = e;
          }
        }
      }
      if (far >= 0)
      {
        std::copy(this->Pos(far), this->Pos(far) + 3, spheres[c].Center);
        spheres[c].Radius = 0.0;
        count[big] = std::max(1, count[big] - 1);
        count[c] = 1;
        changed = true;
      }
    }
    return changed;
  }

  // Descent on the sphere set itself: each sphere in turn (largest outside
  // volume first) is re-fitted to the elements no other sphere covers, then
  // hands the others over. Coverage holds at every step and no sphere's
  // outside volume grows, so the sum only falls. Returns the energy.
  double Shrink(std::vector<Sphere>& spheres, std::vector<int>& assign) const
  {
    const int k = static_cast<int>(spheres.size());
    std::vector<double> outside(k);
    for (int c = 0; c < k; ++c)
    {
      outside[c] = this->Outside(spheres[c].Center, spheres[c].Radius);
    }
    std::vector<int> order(k);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(
      order.begin(), order.end(), [&](int a, int b) { return outside[a] > outside[b]; });
    std::vector<std::vector<int>> members(k);
    for (int e = 0; e < this->NE; ++e)
    {
      members[assign[e]].push_back(e);
    }
    const double h = this->Rows.Spacing();
    std::vector<int> necessary, handed, to;
    std::vector<double> pts;
    for (int c : order)
    {
      necessary.clear();
      handed.clear();
      to.clear();
      for (int e : members[c])
      {
        int cover = -1;
        for (int o = 0; o < k && cover < 0; ++o)
        {
          if (o != c && spheres[o].Radius > 0.0 && this->Covers(spheres[o], e))
          {
            cover = o;
          }
        }
        if (cover < 0)
        {
          necessary.push_back(e);
        }
        else
        {
          handed.push_back(e);
          to.push_back(cover);
        }
      }
      if (handed.empty())
      {
        continue;
      }
      pts.clear();
      for (int e : necessary)
      {
        if (e < this->NT)
        {
          for (int q = 0; q < 3; ++q)
          {
            const double* p = this->Mesh.Point(this->Mesh.Triangles[3 * e + q]);
            pts.insert(pts.end(), p, p + 3);
          }
        }
        else
        {
          pts.insert(pts.end(), this->Pos(e), this->Pos(e) + 3);
        }
      }
      Sphere s = spheres[c];
      double f = 0.0;
      if (!pts.empty())
      {
        auto objective = [&](const double* x) { return this->Outside(x, MaxDistance(pts, x)); };
        double x[3] = { s.Center[0], s.Center[1], s.Center[2] };
        const double r = MaxDistance(pts, x);
        f = objective(x);
        if (r > 0.0)
        {
          f = MinimizeNelderMead3(objective, x, 0.25 * r, 0.05 * h, 150);
        }
        std::copy(x, x + 3, s.Center);
        s.Radius = MaxDistance(pts, x);
      }
      else
      {
        s.Radius = 0.0; // redundant: every element is covered elsewhere
      }
      if (f >= outside[c])
      {
        continue;
      }
      spheres[c] = s;
      outside[c] = f;
      members[c] = necessary;
      for (std::size_t i = 0; i < handed.size(); ++i)
      {
        assign[handed[i]] = to[i];
        members[to[i]].push_back(handed[i]);
      }
    }
    return std::accumulate(outside.begin(), outside.end(), 0.0);
  }

  // One round: cluster, fix empty clusters, update the centres, shrink.
  // Returns the energy.
  double Round(std::vector<Sphere>& spheres, std::vector<int>& assign) const
  {
    for (int attempt = 0; attempt < 3; ++attempt)
    {
      this->Cluster(spheres, assign);
      if (!this->FillEmpty(spheres, assign))
      {
        break;
      }
    }
    this->Update(spheres, assign);
    return this->Shrink(spheres, assign);
  }

  // Teleportation: split the cluster of largest outside volume along its
  // farthest pair, delete the sphere overlapping the others most. `rank`
  // picks the rank-th worst cluster, so a rejected move is not repeated.
  void Teleport(std::vector<Sphere>& spheres, const std::vector<int>& assign, int rank) const
  {
    const int k = static_cast<int>(spheres.size());
    std::vector<double> error(k);
    for (int c = 0; c < k; ++c)
    {
      error[c] = this->Outside(spheres[c].Center, spheres[c].Radius);
    }
    std::vector<int> order(k);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return error[a] > error[b]; });
    const int worst = order[rank % k];
    int victim = -1;
    double most = -1.0;
    for (int c = 0; c < k; ++c)
    {
      if (c == worst)
      {
        continue;
      }
      if (!(spheres[c].Radius > 0.0))
      {
        victim = c; // redundant already (Shrink emptied it): the best victim
        break;
      }
      double shared = 0.0;
      for (int o = 0; o < k; ++o)
      {
        if (o != c)
        {
          shared += LensVolume(spheres[c], spheres[o]);
        }
      }
      const double ratio = shared / SphereVolume(spheres[c].Radius);
      if (ratio > most)
      {
        most = ratio;
        victim = c;
      }
    }
    if (victim < 0)
    {
      return;
    }
    // Farthest pair, approximately: two sweeps.
    int a = -1, b = -1;
    double da = -1.0, db = -1.0;
    for (int e = 0; e < this->NE; ++e)
    {
      if (assign[e] == worst)
      {
        const double d = Distance2(this->Pos(e), spheres[worst].Center);
        if (d > da)
        {
          da = d;
          a = e;
        }
      }
    }
    if (a < 0)
    {
      return;
    }
    for (int e = 0; e < this->NE; ++e)
    {
      if (assign[e] == worst)
      {
        const double d = Distance2(this->Pos(e), this->Pos(a));
        if (d > db)
        {
          db = d;
          b = e;
        }
      }
    }
    std::copy(this->Pos(a), this->Pos(a) + 3, spheres[worst].Center);
    std::copy(this->Pos(b), this->Pos(b) + 3, spheres[victim].Center);
    spheres[worst].Radius = 0.5 * std::sqrt(db);
    spheres[victim].Radius = 0.5 * std::sqrt(db);
  }

  bool RunVariational(int k, SphereSetResult& result)
  {
    std::mt19937 rng(this->Options.Seed);
    std::vector<Sphere> spheres = this->SeedCenters(k, rng);
    // First profile range: spheres of a k-th of the bounding box volume.
    const double* b = this->Mesh.Bounds;
    const double box = std::max(
      (b[1] - b[0]) * (b[3] - b[2]) * (b[5] - b[4]), std::pow(this->Mesh.Diagonal(), 3) * 1e-6);
    for (Sphere& s : spheres)
    {
      s.Radius = std::cbrt(3.0 * box / (4.0 * Pi * spheres.size()));
    }
    std::vector<int> assign;
    std::vector<Sphere> best;
    std::vector<int> bestAssign;
    double bestEnergy = std::numeric_limits<double>::max();
    int stall = 0, failures = 0, iterations = 0;
    const int maxIterations = std::max(1, this->Options.MaximumIterations);
    // Progress means at least 0.1% less outside volume.
    auto progress = [&bestEnergy](double e) { return e < bestEnergy * (1.0 - 1e-3); };
    while (iterations < maxIterations && bestEnergy > this->Tiny)
    {
      if (!this->Report(static_cast<double>(iterations) / maxIterations))
      {
        result.Aborted = true;
        return false;
      }
      if (stall < 2)
      {
        const double e = this->Round(spheres, assign);
        ++iterations;
        stall = progress(e) ? 0 : stall + 1;
        if (e < bestEnergy)
        {
          bestEnergy = e;
          best = spheres;
          bestAssign = assign;
        }
        continue;
      }
      // Stalled: teleport from the best state; keep the move if it helps.
      if (failures >= this->Options.MaximumTeleportFailures || k < 2)
      {
        break;
      }
      std::vector<Sphere> trial = best;
      std::vector<int> trialAssign;
      this->Cluster(trial, trialAssign);
      this->Teleport(trial, trialAssign, failures);
      ++result.Teleports;
      std::vector<Sphere> trialBest;
      std::vector<int> trialBestAssign;
      double trialEnergy = std::numeric_limits<double>::max();
      for (int i = 0; i < 3 && iterations < maxIterations; ++i)
      {
        const double e = this->Round(trial, trialAssign);
        ++iterations;
        if (e < trialEnergy)
        {
          trialEnergy = e;
          trialBest = trial;
          trialBestAssign = trialAssign;
        }
      }
      if (!trialBest.empty() && progress(trialEnergy))
      {
        ++result.TeleportsAccepted;
        bestEnergy = trialEnergy;
        best = trialBest;
        bestAssign = trialBestAssign;
        spheres = trial;
        failures = 0;
        stall = 0;
      }
      else
      {
        ++failures;
      }
    }
    if (!best.empty())
    {
      for (int pass = 0; pass < 20; ++pass)
      {
        const double before = bestEnergy;
        bestEnergy = this->Shrink(best, bestAssign);
        if (!(bestEnergy < before * (1.0 - 1e-3)))
        {
          break;
        }
      }
    }
    result.Iterations = iterations;
    result.Spheres = best;
    return true;
  }

  // --- Baselines ------------------------------------------------------------

  // Octree cells holding elements, split greedily (largest outside volume
  // first) while the count stays within k. Each sphere is its cell's
  // circumsphere, enlarged where a triangle of the cell reaches out of it.
  bool RunOctree(int k, SphereSetResult& result)
  {
    struct Cell
    {
      double Center[3];
      double Half;
      int Depth;
      std::vector<int> Elements;
      Sphere Bound;
      double Outside;
    };
    const double* b = this->Mesh.Bounds;
    const double half =
      0.5 * std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4], 1e-30 }) * (1.0 + 1e-9);
    auto finish = [this](Cell& cell)
    {
      cell.Bound.Radius = std::sqrt(3.0) * cell.Half;
      std::copy(cell.Center, cell.Center + 3, cell.Bound.Center);
      for (int e : cell.Elements)
      {
        cell.Bound.Radius = std::max(cell.Bound.Radius, this->Reach(e, cell.Center));
      }
      cell.Outside = this->Outside(cell.Bound.Center, cell.Bound.Radius);
    };
    std::vector<Cell> cells(1);
    cells[0].Half = half;
    cells[0].Depth = 0;
    for (int q = 0; q < 3; ++q)
    {
      cells[0].Center[q] = 0.5 * (b[2 * q] + b[2 * q + 1]);
    }
    cells[0].Elements.resize(this->NE);
    std::iota(cells[0].Elements.begin(), cells[0].Elements.end(), 0);
    finish(cells[0]);
    std::vector<char> frozen(1, 0);
    int count = 1;
    for (int step = 0;; ++step)
    {
      if (step % 8 == 0 && !this->Report(static_cast<double>(count) / k))
      {
        result.Aborted = true;
        return false;
      }
      int pick = -1;
      for (std::size_t c = 0; c < cells.size(); ++c)
      {
        if (!frozen[c] && (pick < 0 || cells[c].Outside > cells[pick].Outside))
        {
          pick = static_cast<int>(c);
        }
      }
      if (pick < 0)
      {
        break;
      }
      Cell parent = cells[pick];
      std::vector<Cell> children(8);
      for (int o = 0; o < 8; ++o)
      {
        children[o].Half = 0.5 * parent.Half;
        children[o].Depth = parent.Depth + 1;
        for (int q = 0; q < 3; ++q)
        {
          children[o].Center[q] = parent.Center[q] + (((o >> q) & 1) ? 0.5 : -0.5) * parent.Half;
        }
      }
      for (int e : parent.Elements)
      {
        const double* p = this->Pos(e);
        int o = 0;
        for (int q = 0; q < 3; ++q)
        {
          o |= (p[q] >= parent.Center[q] ? 1 : 0) << q;
        }
        children[o].Elements.push_back(e);
      }
      children.erase(std::remove_if(children.begin(), children.end(),
                       [](const Cell& c) { return c.Elements.empty(); }),
        children.end());
      if (count + static_cast<int>(children.size()) - 1 > k || parent.Depth >= 20)
      {
        frozen[pick] = 1; // splitting it would overshoot: keep it whole
        continue;
      }
      for (Cell& c : children)
      {
        finish(c);
      }
      count += static_cast<int>(children.size()) - 1;
      cells[pick] = std::move(children[0]);
      for (std::size_t c = 1; c < children.size(); ++c)
      {
        cells.push_back(std::move(children[c]));
        frozen.push_back(0);
      }
    }
    result.Spheres.clear();
    for (const Cell& c : cells)
    {
      result.Spheres.push_back(c.Bound);
    }
    result.Iterations = count;
    return true;
  }

  // Lloyd's k-means on element positions (k-means++ seeds), then the
  // near-minimal bounding sphere of each cluster.
  bool RunKMeans(int k, SphereSetResult& result)
  {
    std::mt19937 rng(this->Options.Seed);
    std::vector<Sphere> centers = this->SeedCenters(k, rng);
    k = static_cast<int>(centers.size());
    std::vector<int> assign(this->NE, -1);
    int iterations = 0;
    for (; iterations < std::max(1, this->Options.MaximumIterations); ++iterations)
    {
      if (!this->Report(static_cast<double>(iterations) / this->Options.MaximumIterations))
      {
        result.Aborted = true;
        return false;
      }
      std::vector<char> changed(this->NE, 0);
      vtkSMPTools::For(0, this->NE,
        [&](int begin, int end)
        {
          for (int e = begin; e < end; ++e)
          {
            int best = 0;
            double bestD = std::numeric_limits<double>::max();
            for (int c = 0; c < k; ++c)
            {
              const double d = Distance2(this->Pos(e), centers[c].Center);
              if (d < bestD)
              {
                bestD = d;
                best = c;
              }
            }
            changed[e] = assign[e] != best;
            assign[e] = best;
          }
        });
      if (iterations > 0 && std::find(changed.begin(), changed.end(), 1) == changed.end())
      {
        break;
      }
      std::vector<double> sum(3 * k, 0.0);
      std::vector<int> count(k, 0);
      for (int e = 0; e < this->NE; ++e)
      {
        for (int q = 0; q < 3; ++q)
        {
          sum[3 * assign[e] + q] += this->Pos(e)[q];
        }
        ++count[assign[e]];
      }
      for (int c = 0; c < k; ++c)
      {
        if (count[c] > 0)
        {
          for (int q = 0; q < 3; ++q)
          {
            centers[c].Center[q] = sum[3 * c + q] / count[c];
          }
        }
      }
      // Empty clusters restart at the element farthest from its centre.
      for (int c = 0; c < k; ++c)
      {
        if (count[c] == 0)
        {
          int far = 0;
          double farD = -1.0;
          for (int e = 0; e < this->NE; ++e)
          {
            const double d = Distance2(this->Pos(e), centers[assign[e]].Center);
            if (d > farD && count[assign[e]] > 1)
            {
              farD = d;
              far = e;
            }
          }
          --count[assign[far]];
          assign[far] = c;
          count[c] = 1;
          std::copy(this->Pos(far), this->Pos(far) + 3, centers[c].Center);
        }
      }
    }
    std::vector<std::vector<double>> points;
    this->GatherPoints(assign, k, points);
    result.Spheres.assign(k, Sphere());
    vtkSMPTools::For(0, k,
      [&](int begin, int end)
      {
        for (int c = begin; c < end; ++c)
        {
          result.Spheres[c] = BoundPoints(points[c].data(), points[c].size() / 3);
        }
      });
    result.Iterations = iterations;
    return true;
  }
};

SphereSetBuilder::SphereSetBuilder(
  const ProxyMesh& mesh, const MeshQueries& queries, const SphereSetOptions& options)
  : Impl(new Internal(mesh, queries, options))
{
  this->Impl->Setup();
}

SphereSetBuilder::~SphereSetBuilder() = default;

const VolumeRows& SphereSetBuilder::Rows() const
{
  return this->Impl->Rows;
}

const std::vector<double>& SphereSetBuilder::InteriorSamples() const
{
  return this->Impl->Grid.Samples;
}

int SphereSetBuilder::NumberOfElements() const
{
  return this->Impl->NE;
}

bool SphereSetBuilder::Run(int count, SphereSetResult& result)
{
  Internal& s = *this->Impl;
  result = SphereSetResult();
  result.MeshVolume = s.Rows.Volume();
  const int k = std::max(1, std::min(count, s.NE));
  bool ok = false;
  switch (s.Options.Method)
  {
    case SphereMethod::Octree:
      ok = s.RunOctree(k, result);
      break;
    case SphereMethod::KMeans:
      ok = s.RunKMeans(k, result);
      break;
    case SphereMethod::Variational:
    default:
      ok = s.RunVariational(k, result);
      break;
  }
  if (!ok)
  {
    return false;
  }
  // Drop spheres of empty clusters. The slack (a few float ulps of the mesh
  // size) keeps the bound through round-off, float copies of the mesh
  // included.
  const double slack = 1e-6 * s.Mesh.Diagonal();
  std::vector<Sphere> kept;
  for (Sphere& sphere : result.Spheres)
  {
    if (sphere.Radius >= 0.0 && std::isfinite(sphere.Radius))
    {
      sphere.Radius += slack;
      kept.push_back(sphere);
    }
  }
  result.Spheres.swap(kept);
  result.OutsideVolume = s.Energy(result.Spheres);
  s.Report(1.0);
  return true;
}
} // namespace proxygi
