// The batched SH kernels on every instruction set this CPU runs, against
// their scalar twins lane by lane: the square, the summed rotated cap logs,
// the averaged bounce's per-proxy weights (and their scalar path), and the
// exp (HYB vectorised, the other methods lane by lane), with non-finite and
// zero lanes mixed in.
// The square, the summed cap logs and the exp equal the scalar code bit for
// bit (no fused multiply-adds: HYB's squarings would double any difference
// per step); the bounce's weights equal their scalar twin's, and within 1e-5
// of their size of the rotated caps' dot products; statuses equal.
#include "pgiSHBasis.h"
#include "pgiSHBatch.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"
#include "pgiTesting.h"

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace proxygi::sh;

namespace
{
constexpr int W = BatchWidth;

// Largest lane difference over the lane's largest magnitude (at least 1).
double LaneError(int n2, const float* soa, int lane, const float* reference)
{
  double diff = 0.0, size = 1.0;
  for (int i = 0; i < n2; ++i)
  {
    diff = std::max(diff, std::fabs(double(soa[i * W + lane]) - reference[i]));
    size = std::max(size, std::fabs(double(reference[i])));
  }
  return diff / size;
}

// Log-visibility-like inputs: sums of `caps` random cap logs, so |f^| runs
// from none to heavy overlap and HYB takes 0 to several squarings.
void RandomLogs(int order, std::mt19937& rng, float* f, float* aos)
{
  const CapTables& tables = CapTables::Get(order);
  const int n2 = NumCoefficients(order);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), angle(0.0f, 1.5f);
  std::uniform_int_distribution<int> caps(0, 40);
  for (int k = 0; k < W; ++k)
  {
    float sum[MaxCoefficients] = {}, zh[MaxOrder], v[MaxCoefficients];
    const int count = caps(rng);
    for (int c = 0; c < count; ++c)
    {
      float d[3] = { u(rng), u(rng), u(rng) };
      const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-6f;
      tables.CapLog(angle(rng), zh);
      RotateScaledZonal(order, zh, d[0] / len, d[1] / len, d[2] / len, v);
      for (int i = 0; i < n2; ++i)
      {
        sum[i] += v[i];
      }
    }
    for (int i = 0; i < n2; ++i)
    {
      f[i * W + k] = sum[i];
      aos[k * n2 + i] = sum[i];
    }
  }
}
} // namespace

int TestSHBatch(int, char*[])
{
  const std::vector<std::string> targets = BatchTargets();
  std::printf("batched kernels dispatch to %s; compiled and supported:", BatchTargetName());
  for (const std::string& t : targets)
  {
    std::printf(" %s", t.c_str());
  }
  std::printf("\n");
  PGI_CHECK(!targets.empty());
  PGI_CHECK(!SetBatchTarget("no such target"));
  std::mt19937 rng(5);
  std::normal_distribution<float> normal;
  for (const std::string& target : targets)
  {
    PGI_CHECK(SetBatchTarget(target));
    PGI_CHECK(target == BatchTargetName());
    double worstSquare = 0.0, worstCaps = 0.0, worstWeights = 0.0, worstExp[4] = { 0, 0, 0, 0 };
    long twinDiffer = 0;
    for (int order = 1; order <= MaxOrder; ++order)
    {
      const int n2 = NumCoefficients(order);
      const TripleProduct& tp = TripleProduct::Get(order);
      alignas(64) float f[MaxCoefficients * W], out[MaxCoefficients * W];
      float aos[MaxCoefficients * W], ref[MaxCoefficients];
      for (int trial = 0; trial < 20; ++trial)
      {
        // Square.
        for (int i = 0; i < n2 * W; ++i)
        {
          f[i] = normal(rng);
        }
        BatchSquare(order, f, out);
        for (int k = 0; k < W; ++k)
        {
          float lane[MaxCoefficients];
          for (int i = 0; i < n2; ++i)
          {
            lane[i] = f[i * W + k];
          }
          tp.Square(lane, ref);
          worstSquare = std::max(worstSquare, LaneError(n2, out, k, ref));
        }
        // Summed rotated cap logs, some lanes skipping some blockers. Every
        // other pair of trials puts each blocker's lanes within a few table
        // rows of each other (neighbouring receivers: the rows are loaded
        // and permuted), the others anywhere (gathered).
        const CapTables& tables = CapTables::Get(order);
        constexpr int Count = 7;
        alignas(64) float theta[Count * W], dx[Count * W], dy[Count * W], dz[Count * W];
        float ratios[Count * MaxOrder];
        std::uniform_real_distribution<float> angle(-0.3f, 1.7f), u(-1.0f, 1.0f), r(0.5f, 1.5f),
          jitter(0.0f, 0.03f);
        const bool coherent = trial % 4 >= 2;
        float blockerAngle[Count];
        for (float& a : blockerAngle)
        {
          a = angle(rng);
        }
        for (int i = 0; i < Count * W; ++i)
        {
          // Beyond pi/2 clamps like CapLog; 0.03 is about 5 rows.
          theta[i] = coherent ? blockerAngle[i / W] + jitter(rng) : angle(rng);
          float d[3] = { u(rng), u(rng), u(rng) };
          const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-6f;
          dx[i] = d[0] / len;
          dy[i] = d[1] / len;
          dz[i] = d[2] / len;
          if (theta[i] < 0.0f && i % 3 == 0)
          {
            dx[i] = std::numeric_limits<float>::quiet_NaN(); // skipped: must not leak
          }
        }
        for (float& v : ratios)
        {
          v = r(rng);
        }
        const bool withRatios = trial % 2 == 1;
        std::fill(out, out + n2 * W, 0.5f);
        BatchAddCaps(tables, order, Count, theta, dx, dy, dz, withRatios ? ratios : nullptr, out);
        for (int k = 0; k < W; ++k)
        {
          float sum[MaxCoefficients], zh[MaxOrder], v[MaxCoefficients];
          std::fill(sum, sum + n2, 0.5f);
          for (int b = 0; b < Count; ++b)
          {
            if (!(theta[b * W + k] >= 0.0f))
            {
              continue;
            }
            tables.CapLog(theta[b * W + k], zh);
            for (int l = 0; withRatios && l < order; ++l)
            {
              zh[l] *= ratios[b * order + l];
            }
            RotateScaledZonal(order, zh, dx[b * W + k], dy[b * W + k], dz[b * W + k], v);
            for (int i = 0; i < n2; ++i)
            {
              sum[i] += v[i];
            }
          }
          worstCaps = std::max(worstCaps, LaneError(n2, out, k, sum));
        }
        // The averaged bounce's weights: the cap's irradiance weight and
        // each channel's averaged radiance per proxy, against CapVisibility,
        // the rotated cap and AveragedRadiances; skipped lanes zero.
        {
          // A stream of its own: the other kernels' inputs stay as they were.
          std::mt19937 weightsRng(1000 * order + trial);
          const IndirectTables& indirect = IndirectTables::Get(order);
          alignas(64) float th[W], wx[W], wy[W], wz[W], weights[W], kappas[3 * W];
          float h[MaxCoefficients], radiances[3 * MaxCoefficients];
          float axis[3] = { u(weightsRng), u(weightsRng), u(weightsRng) };
          const float len =
            std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]) + 1e-6f;
          DiffuseTransfer(order, axis[0] / len, axis[1] / len, axis[2] / len, h);
          for (float& v : radiances)
          {
            v = normal(weightsRng);
          }
          for (int k = 0; k < W; ++k)
          {
            th[k] = k == 6 ? -1.0f : angle(weightsRng); // beyond pi/2 clamps; one lane skipped
            // The caps' directions, past those their skipped lanes made NaN.
            int row = 0;
            while (std::isnan(dx[row * W + k]) && row + 1 < Count)
            {
              ++row;
            }
            wx[k] = dx[row * W + k];
            wy[k] = dy[row * W + k];
            wz[k] = dz[row * W + k];
          }
          wx[6] = std::numeric_limits<float>::quiet_NaN(); // skipped: must not leak
          BatchIndirectWeights(
            tables, indirect, order, th, wx, wy, wz, h, 3, radiances, weights, kappas);
          // With the kernels off, the scalar twin runs: held to the same.
          alignas(64) float scalarWeights[W], scalarKappas[3 * W];
          SetBatchKernelsEnabled(false);
          BatchIndirectWeights(
            tables, indirect, order, th, wx, wy, wz, h, 3, radiances, scalarWeights, scalarKappas);
          SetBatchKernelsEnabled(true);
          for (int k = 0; k < W; ++k)
          {
            // The batch rounds as its scalar twin: equal, skipped lanes too.
            twinDiffer += weights[k] == scalarWeights[k] ? 0 : 1;
            for (int c = 0; c < 3; ++c)
            {
              twinDiffer += kappas[c * W + k] == scalarKappas[c * W + k] ? 0 : 1;
            }
            if (!(th[k] >= 0.0f))
            {
              PGI_CHECK(weights[k] == 0.0f && kappas[k] == 0.0f && kappas[2 * W + k] == 0.0f);
              PGI_CHECK(scalarWeights[k] == 0.0f && scalarKappas[k] == 0.0f &&
                scalarKappas[2 * W + k] == 0.0f);
              continue;
            }
            float zh[MaxOrder], cap[MaxCoefficients];
            tables.CapVisibility(th[k], zh);
            zh[0] = static_cast<float>(4.0 * Pi) - zh[0];
            for (int l = 1; l < order; ++l)
            {
              zh[l] = -zh[l];
            }
            RotateScaledZonal(order, zh, wx[k], wy[k], wz[k], cap);
            const float weight = Dot(n2, h, cap);
            PGI_CHECK(std::isfinite(weights[k]) && std::isfinite(kappas[k]));
            const float d[3] = { wx[k], wy[k], wz[k] };
            const float* channels[3] = { radiances, radiances + n2, radiances + 2 * n2 };
            float kappa[3];
            indirect.AveragedRadiances(th[k], d, 3, channels, kappa);
            const double scale = std::max(1.0, double(std::fabs(weight)));
            worstWeights = std::max(worstWeights, std::fabs(weights[k] - weight) / scale);
            worstWeights = std::max(worstWeights, std::fabs(scalarWeights[k] - weight) / scale);
            for (int c = 0; c < 3; ++c)
            {
              const double size = std::max(1.0, double(std::fabs(kappa[c])));
              worstWeights = std::max(worstWeights, std::fabs(kappas[c * W + k] - kappa[c]) / size);
              worstWeights =
                std::max(worstWeights, std::fabs(scalarKappas[c * W + k] - kappa[c]) / size);
            }
          }
        }
        // Exp, every method; lane 3 NaN, lane 4 infinite, lane 5 zero.
        RandomLogs(order, rng, f, aos);
        for (int i = 0; i < n2; ++i)
        {
          f[i * W + 5] = 0.0f;
          aos[5 * n2 + i] = 0.0f;
        }
        f[(n2 - 1) * W + 3] = aos[3 * n2 + n2 - 1] = std::numeric_limits<float>::quiet_NaN();
        f[4] = aos[4 * n2] = -std::numeric_limits<float>::infinity();
        const ExpMethod methods[4] = { ExpMethod::Hybrid, ExpMethod::OL, ExpMethod::PSStar,
          ExpMethod::PS };
        for (int m = 0; m < 4; ++m)
        {
          ExpOptions options;
          options.Method = methods[m];
          Status status[W];
          BatchExp(order, f, out, options, status);
          for (int k = 0; k < W; ++k)
          {
            const Status expected = Exp(order, &aos[k * n2], ref, options);
            PGI_CHECK(status[k] == expected);
            worstExp[m] = std::max(worstExp[m], LaneError(n2, out, k, ref));
          }
        }
      }
    }
    std::printf("%s: worst lane error: square %.2e, caps %.2e, bounce weights %.2e, exp HYB "
                "%.2e, OL %.2e, PS* %.2e, PS %.2e\n",
      target.c_str(), worstSquare, worstCaps, worstWeights, worstExp[0], worstExp[1], worstExp[2],
      worstExp[3]);
    PGI_CHECK(worstSquare == 0.0);
    PGI_CHECK(worstCaps == 0.0);
    PGI_BELOW(worstWeights, 1e-5);
    std::printf(
      "%s: bounce weights unequal to the scalar twin's: %ld\n", target.c_str(), twinDiffer);
    PGI_CHECK(twinDiffer == 0);
    for (double e : worstExp)
    {
      PGI_CHECK(e == 0.0);
    }
  }
  PGI_CHECK(SetBatchTarget(""));
  return pgitest::Result();
}
