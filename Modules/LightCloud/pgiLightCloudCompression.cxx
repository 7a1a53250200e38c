#include "pgiLightCloudCompression.h"

#include "vtk_eigen.h"
#include VTK_EIGEN(Eigenvalues)

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

namespace proxygi
{
namespace
{
struct Random
{
  std::uint64_t State;
  explicit Random(std::uint64_t seed)
    : State(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
  {
  }
  double Next()
  {
    std::uint64_t z = (this->State += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return ((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
  }
};

double Distance2(const float* a, const float* b, int n)
{
  double s = 0.0;
  for (int k = 0; k < n; ++k)
  {
    const double d = static_cast<double>(a[k]) - b[k];
    s += d * d;
  }
  return s;
}
} // namespace

std::vector<std::vector<vtkIdType>> SplitIntoZones(
  const std::vector<double>& points, vtkIdType zoneSize, int maximumZones)
{
  const vtkIdType n = static_cast<vtkIdType>(points.size() / 3);
  std::vector<std::vector<vtkIdType>> zones(1);
  zones[0].resize(static_cast<std::size_t>(n));
  std::iota(zones[0].begin(), zones[0].end(), vtkIdType(0));
  zoneSize = std::max<vtkIdType>(1, zoneSize);
  while (static_cast<int>(zones.size()) < std::max(1, maximumZones))
  {
    auto largest = std::max_element(
      zones.begin(), zones.end(), [](const auto& a, const auto& b) { return a.size() < b.size(); });
    if (static_cast<vtkIdType>(largest->size()) <= zoneSize || largest->size() < 2)
    {
      break;
    }
    std::vector<vtkIdType>& zone = *largest;
    double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
    for (vtkIdType id : zone)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], points[3 * id + a]);
        hi[a] = std::max(hi[a], points[3 * id + a]);
      }
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      axis = hi[a] - lo[a] > hi[axis] - lo[axis] ? a : axis;
    }
    const double middle = 0.5 * (lo[axis] + hi[axis]);
    std::vector<vtkIdType> below, above;
    for (vtkIdType id : zone)
    {
      (points[3 * id + axis] < middle ? below : above).push_back(id);
    }
    if (below.empty() || above.empty())
    {
      // All on one side of the middle (or coincident): split at the median.
      std::vector<vtkIdType> sorted = zone;
      std::stable_sort(sorted.begin(), sorted.end(),
        [&](vtkIdType a, vtkIdType b) { return points[3 * a + axis] < points[3 * b + axis]; });
      const std::size_t half = sorted.size() / 2;
      below.assign(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(half));
      above.assign(sorted.begin() + static_cast<std::ptrdiff_t>(half), sorted.end());
      std::sort(below.begin(), below.end());
      std::sort(above.begin(), above.end());
    }
    zone = std::move(below);
    zones.push_back(std::move(above));
  }
  return zones;
}

MergedLights ClusterLights(const std::vector<const float*>& responses,
  const std::vector<double>& positions, vtkIdType receivers, double w1, double w2,
  const std::vector<char>& visible, int values)
{
  const vtkIdType count = static_cast<vtkIdType>(responses.size());
  const std::size_t n = static_cast<std::size_t>(count);
  // Delta of every pair (complete linkage keeps it exact under merging).
  const double never = std::numeric_limits<double>::infinity();
  std::vector<double> delta(n * n, never);
  using Entry = std::tuple<double, vtkIdType, vtkIdType>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (vtkIdType j = 0; j < count; ++j)
  {
    for (vtkIdType k = j + 1; k < count; ++k)
    {
      const double* p = &positions[3 * j];
      const double* q = &positions[3 * k];
      const double d = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
        (p[2] - q[2]) * (p[2] - q[2]));
      double value = w1 * d + (visible[j * n + k] ? 0.0 : 1.0);
      if (value < 1.0)
      {
        double largest = 0.0;
        const float* a = responses[j];
        const float* b = responses[k];
        for (vtkIdType c = 0; c < receivers && w1 * d + w2 * std::sqrt(largest) < 1.0; ++c)
        {
          largest = std::max(largest, Distance2(a + values * c, b + values * c, values));
        }
        value += w2 * std::sqrt(largest);
      }
      delta[j * n + k] = delta[k * n + j] = value;
      if (value < 1.0)
      {
        queue.emplace(value, j, k);
      }
    }
  }
  // Clusters named by their first light; merged ones are dead.
  std::vector<std::vector<vtkIdType>> members(n);
  std::vector<char> alive(n, 1);
  for (std::size_t j = 0; j < n; ++j)
  {
    members[j] = { static_cast<vtkIdType>(j) };
  }
  while (!queue.empty())
  {
    const auto [value, a, b] = queue.top();
    queue.pop();
    if (!alive[a] || !alive[b] || delta[a * n + b] != value)
    {
      continue; // stale: one side merged since
    }
    // b joins a; a's Delta to every other cluster is the larger of the two.
    alive[b] = 0;
    members[a].insert(members[a].end(), members[b].begin(), members[b].end());
    members[b].clear();
    for (vtkIdType k = 0; k < count; ++k)
    {
      if (!alive[k] || k == a)
      {
        continue;
      }
      const double merged = std::max(delta[a * n + k], delta[b * n + k]);
      delta[a * n + k] = delta[k * n + a] = merged;
      if (merged < 1.0)
      {
        queue.emplace(merged, std::min(a, k), std::max(a, k));
      }
    }
  }
  MergedLights out;
  for (std::size_t j = 0; j < n; ++j)
  {
    if (!alive[j])
    {
      continue;
    }
    std::sort(members[j].begin(), members[j].end());
    double mean[3] = { 0, 0, 0 };
    for (vtkIdType m : members[j])
    {
      for (int a = 0; a < 3; ++a)
      {
        mean[a] += positions[3 * m + a] / static_cast<double>(members[j].size());
      }
    }
    out.Positions.insert(out.Positions.end(), mean, mean + 3);
    out.Members.push_back(std::move(members[j]));
  }
  return out;
}

namespace
{
// One cluster's PCA: mean, eigenvectors (columns, largest first), eigenvalues.
struct ClusterPCA
{
  Eigen::VectorXd Mean;
  Eigen::MatrixXd Vectors;
  Eigen::VectorXd Values;
};

ClusterPCA ComputePCA(
  const std::vector<float>& data, const std::vector<vtkIdType>& rows, int dim, int keep)
{
  ClusterPCA pca;
  const int nv = static_cast<int>(rows.size());
  pca.Mean = Eigen::VectorXd::Zero(dim);
  for (vtkIdType r : rows)
  {
    for (int k = 0; k < dim; ++k)
    {
      pca.Mean[k] += data[static_cast<std::size_t>(r) * dim + k];
    }
  }
  if (nv > 0)
  {
    pca.Mean /= nv;
  }
  keep = std::min({ keep, dim, nv });
  if (keep <= 0)
  {
    pca.Vectors.resize(dim, 0);
    pca.Values.resize(0);
    return pca;
  }
  Eigen::MatrixXd a(nv, dim);
  for (int i = 0; i < nv; ++i)
  {
    for (int k = 0; k < dim; ++k)
    {
      a(i, k) = data[static_cast<std::size_t>(rows[i]) * dim + k] - pca.Mean[k];
    }
  }
  if (nv < dim)
  {
    // Fewer rows than dimensions: the Gram matrix's eigenvectors, mapped.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a * a.transpose());
    pca.Vectors.resize(dim, keep);
    pca.Values.resize(keep);
    for (int q = 0; q < keep; ++q)
    {
      const int idx = nv - 1 - q;
      const double lambda = std::max(0.0, solver.eigenvalues()[idx]);
      Eigen::VectorXd v = a.transpose() * solver.eigenvectors().col(idx);
      const double norm = v.norm();
      pca.Vectors.col(q) = norm > 0.0 ? Eigen::VectorXd(v / norm) : Eigen::VectorXd::Zero(dim);
      pca.Values[q] = norm > 0.0 ? lambda : 0.0;
    }
  }
  else
  {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a.transpose() * a);
    pca.Vectors.resize(dim, keep);
    pca.Values.resize(keep);
    for (int q = 0; q < keep; ++q)
    {
      pca.Vectors.col(q) = solver.eigenvectors().col(dim - 1 - q);
      pca.Values[q] = std::max(0.0, solver.eigenvalues()[dim - 1 - q]);
    }
  }
  return pca;
}

// Vectors per cluster: greedy by eigenvalue per row, within the budget.
std::vector<int> Allocate(
  const std::vector<ClusterPCA>& pcas, const std::vector<int>& sizes, double budget)
{
  const int c = static_cast<int>(pcas.size());
  std::vector<int> counts(static_cast<std::size_t>(c), 0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry> queue;
  for (int k = 0; k < c; ++k)
  {
    if (sizes[k] > 0 && pcas[k].Values.size() > 0)
    {
      queue.emplace(pcas[k].Values[0] / sizes[k], k);
    }
  }
  double used = 0.0;
  while (!queue.empty())
  {
    const int k = queue.top().second;
    queue.pop();
    if (used + sizes[k] > budget + 1e-9)
    {
      continue;
    }
    used += sizes[k];
    ++counts[k];
    if (counts[k] < pcas[k].Values.size())
    {
      queue.emplace(pcas[k].Values[counts[k]] / sizes[k], k);
    }
  }
  return counts;
}

// Error of row x reconstructed by cluster pca with `count` vectors.
double RowError(const float* x, const ClusterPCA& pca, int count, int dim)
{
  Eigen::VectorXd d(dim);
  for (int k = 0; k < dim; ++k)
  {
    d[k] = x[k] - pca.Mean[k];
  }
  double e = d.squaredNorm();
  for (int q = 0; q < count; ++q)
  {
    const double w = pca.Vectors.col(q).dot(d);
    e -= w * w;
  }
  return std::max(0.0, e);
}
} // namespace

ClusteredPCACode ClusteredPCA(const std::vector<float>& data, vtkIdType rows, int dimension,
  int clusters, double vectorsPerRow, int iterations, std::uint64_t seed)
{
  ClusteredPCACode code;
  code.Dimension = dimension;
  const int dim = dimension;
  const int c = static_cast<int>(std::max<vtkIdType>(1, std::min<vtkIdType>(clusters, rows)));
  if (rows <= 0 || dim <= 0)
  {
    return code;
  }
  const double budget = std::max(0.0, vectorsPerRow) * static_cast<double>(rows);
  // Enough eigenvectors for any allocation the budget allows.
  const int keep = std::min(dim, static_cast<int>(std::ceil(vectorsPerRow)) * 4 + 8);
  auto row = [&](vtkIdType r) { return data.data() + static_cast<std::size_t>(r) * dim; };

  // k-means++ seeds, then Lloyd.
  Random random(seed);
  std::vector<vtkIdType> seeds = { static_cast<vtkIdType>(random.Next() * rows) % rows };
  std::vector<double> nearest(static_cast<std::size_t>(rows), std::numeric_limits<double>::max());
  while (static_cast<int>(seeds.size()) < c)
  {
    double total = 0.0;
    for (vtkIdType r = 0; r < rows; ++r)
    {
      nearest[r] = std::min(nearest[r], Distance2(row(r), row(seeds.back()), dim));
      total += nearest[r];
    }
    if (!(total > 0.0))
    {
      break; // fewer distinct rows than clusters
    }
    double pick = random.Next() * total;
    vtkIdType chosen = rows - 1;
    for (vtkIdType r = 0; r < rows; ++r)
    {
      pick -= nearest[r];
      if (pick <= 0.0)
      {
        chosen = r;
        break;
      }
    }
    seeds.push_back(chosen);
  }
  const int k = static_cast<int>(seeds.size());
  std::vector<std::vector<double>> means(static_cast<std::size_t>(k));
  for (int q = 0; q < k; ++q)
  {
    means[q].assign(row(seeds[q]), row(seeds[q]) + dim);
  }
  code.Cluster.assign(static_cast<std::size_t>(rows), 0);
  for (int lloyd = 0; lloyd < 10; ++lloyd)
  {
    for (vtkIdType r = 0; r < rows; ++r)
    {
      double best = std::numeric_limits<double>::max();
      for (int q = 0; q < k; ++q)
      {
        double s = 0.0;
        const float* x = row(r);
        for (int d = 0; d < dim; ++d)
        {
          s += (x[d] - means[q][d]) * (x[d] - means[q][d]);
        }
        if (s < best)
        {
          best = s;
          code.Cluster[r] = q;
        }
      }
    }
    std::vector<int> sizes(static_cast<std::size_t>(k), 0);
    for (auto& m : means)
    {
      std::fill(m.begin(), m.end(), 0.0);
    }
    for (vtkIdType r = 0; r < rows; ++r)
    {
      ++sizes[code.Cluster[r]];
      for (int d = 0; d < dim; ++d)
      {
        means[code.Cluster[r]][d] += row(r)[d];
      }
    }
    for (int q = 0; q < k; ++q)
    {
      for (double& v : means[q])
      {
        v = sizes[q] ? v / sizes[q] : v;
      }
    }
  }

  // Reclustering by reconstruction error.
  std::vector<ClusterPCA> pcas(static_cast<std::size_t>(k));
  std::vector<int> counts;
  std::vector<std::vector<vtkIdType>> members(static_cast<std::size_t>(k));
  std::vector<int> sizes(static_cast<std::size_t>(k));
  auto analyse = [&]()
  {
    for (auto& m : members)
    {
      m.clear();
    }
    for (vtkIdType r = 0; r < rows; ++r)
    {
      members[code.Cluster[r]].push_back(r);
    }
    for (int q = 0; q < k; ++q)
    {
      sizes[q] = static_cast<int>(members[q].size());
      pcas[q] = ComputePCA(data, members[q], dim, keep);
    }
    counts = Allocate(pcas, sizes, budget);
  };
  for (int pass = 0; pass < std::max(0, iterations); ++pass)
  {
    analyse();
    code.Iterations = pass + 1;
    int moved = 0;
    std::vector<double> errors(static_cast<std::size_t>(rows));
    for (vtkIdType r = 0; r < rows; ++r)
    {
      int best = code.Cluster[r];
      double bestError = RowError(row(r), pcas[best], counts[best], dim);
      for (int q = 0; q < k; ++q)
      {
        if (q == best || sizes[q] == 0)
        {
          continue;
        }
        const double e = RowError(row(r), pcas[q], counts[q], dim);
        if (e < bestError * (1.0 - 1e-9))
        {
          bestError = e;
          best = q;
        }
      }
      errors[r] = bestError;
      if (best != code.Cluster[r])
      {
        code.Cluster[r] = best;
        ++moved;
      }
    }
    // An emptied cluster takes the worst-reconstructed row.
    std::vector<int> now(static_cast<std::size_t>(k), 0);
    for (vtkIdType r = 0; r < rows; ++r)
    {
      ++now[code.Cluster[r]];
    }
    for (int q = 0; q < k; ++q)
    {
      if (now[q] == 0 && rows > k)
      {
        const vtkIdType worst =
          static_cast<vtkIdType>(std::max_element(errors.begin(), errors.end()) - errors.begin());
        --now[code.Cluster[worst]];
        code.Cluster[worst] = q;
        now[q] = 1;
        errors[worst] = 0.0;
        ++moved;
      }
    }
    if (moved == 0)
    {
      break;
    }
  }
  analyse();

  // The code: means, the allotted vectors, each row's weights.
  code.BasisStart.assign(static_cast<std::size_t>(k), 0);
  code.BasisCount = counts;
  int total = 0;
  for (int q = 0; q < k; ++q)
  {
    code.BasisStart[q] = total;
    total += counts[q];
    for (int d = 0; d < dim; ++d)
    {
      code.Means.push_back(static_cast<float>(pcas[q].Mean[d]));
    }
  }
  code.Basis.resize(static_cast<std::size_t>(total) * dim);
  for (int q = 0; q < k; ++q)
  {
    for (int v = 0; v < counts[q]; ++v)
    {
      for (int d = 0; d < dim; ++d)
      {
        code.Basis[static_cast<std::size_t>(code.BasisStart[q] + v) * dim + d] =
          static_cast<float>(pcas[q].Vectors(d, v));
      }
    }
  }
  code.WeightStart.resize(static_cast<std::size_t>(rows));
  std::vector<float> decoded(static_cast<std::size_t>(dim));
  for (vtkIdType r = 0; r < rows; ++r)
  {
    const int q = code.Cluster[r];
    code.WeightStart[r] = static_cast<int>(code.Weights.size());
    for (int v = 0; v < counts[q]; ++v)
    {
      double w = 0.0;
      for (int d = 0; d < dim; ++d)
      {
        w += pcas[q].Vectors(d, v) * (row(r)[d] - pcas[q].Mean[d]);
      }
      code.Weights.push_back(static_cast<float>(w));
    }
    DecodeRow(code, r, decoded.data());
    code.SquaredError += Distance2(row(r), decoded.data(), dim);
    for (int d = 0; d < dim; ++d)
    {
      code.Squared += static_cast<double>(row(r)[d]) * row(r)[d];
    }
  }
  return code;
}

void DecodeRow(const ClusteredPCACode& code, vtkIdType row, float* out)
{
  const int dim = code.Dimension;
  const int q = code.Cluster[row];
  const float* mean = &code.Means[static_cast<std::size_t>(q) * dim];
  std::copy(mean, mean + dim, out);
  for (int v = 0; v < code.BasisCount[q]; ++v)
  {
    const float w = code.Weights[code.WeightStart[row] + v];
    const float* b = &code.Basis[static_cast<std::size_t>(code.BasisStart[q] + v) * dim];
    for (int d = 0; d < dim; ++d)
    {
      out[d] += w * b[d];
    }
  }
}
} // namespace proxygi
