// SoftShadows::VisibilityBatch on every instruction set this CPU runs,
// against Visibility receiver by receiver: random scenes and the hard cases
// (receivers inside spheres, on the rim, grazing, huge and tiny scales,
// coincident centres, zero and NaN radii, NaN receivers), with and without
// the replacement rules, ratios, planes in log space, accumulation above
// the output order, the window, and every exp method, at orders 2-8. The
// batch rounds as the scalar code does (no fused multiply-adds anywhere on
// the way), so blocker counts, seen lists and vectors are equal bit for
// bit; statuses equal. (The scalar result itself moves by more than 1e-5
// of its size in the heavy-overlap cases when every radius grows by one
// ulp, so a looser bound could not tell a changed rounding from a real
// difference: AccuracyTime.md sections 15 and 33.)
#include "pgiSHBatch.h"
#include "pgiSoftShadows.h"
#include "pgiSoftShadowsBatch.h"
#include "pgiTesting.h"

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace proxygi;

namespace
{
struct Case
{
  Blockers B;
  std::vector<float> P, N;
};

Case RandomCase(std::mt19937& rng, float scale, int spheres, bool hard)
{
  Case c;
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), r(0.05f, 0.6f);
  for (int s = 0; s < spheres; ++s)
  {
    c.B.AddSphere(scale * u(rng), scale * u(rng), scale * (0.5f + u(rng)), scale * r(rng));
  }
  if (hard)
  {
    c.B.AddSphere(0.0f, 0.0f, 0.0f, 0.0f);                                    // zero radius
    c.B.AddSphere(0.0f, 0.0f, 0.0f, std::numeric_limits<float>::quiet_NaN()); // NaN radius
    c.B.AddSphere(0.1f * scale, 0.0f, 0.2f * scale, 0.3f * scale);            // twice, coincident
    c.B.AddSphere(0.1f * scale, 0.0f, 0.2f * scale, 0.3f * scale);
  }
  const float origin[3] = { 0, 0, -0.2f * scale }, up[3] = { 0, 0, 1 };
  c.B.AddPlane(origin, up);
  for (int i = 0; i < 203; ++i) // not a multiple of the batch width
  {
    float p[3] = { scale * u(rng), scale * u(rng), scale * 0.6f * u(rng) };
    float n[3] = { u(rng), u(rng), u(rng) };
    if (hard && i % 7 == 0 && spheres > 0)
    {
      // On a sphere's surface (the rim cases), facing along it.
      const int s = i % spheres;
      const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) + 1e-6f;
      p[0] = c.B.X[s] + c.B.R[s] * n[0] / len;
      p[1] = c.B.Y[s] + c.B.R[s] * n[1] / len;
      p[2] = c.B.Z[s] + c.B.R[s] * n[2] / len;
      std::swap(n[0], n[1]);
    }
    if (hard && i == 11)
    {
      p[1] = std::numeric_limits<float>::quiet_NaN();
    }
    if (hard && i % 13 == 0)
    {
      n[0] = n[1] = 0.0f; // straight up or down: grazing caps
    }
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
    {
      c.P.push_back(p[k]);
      c.N.push_back(len > 0.0f ? n[k] / len : (k == 2 ? 1.0f : 0.0f));
    }
  }
  return c;
}
} // namespace

int TestSoftShadowsBatch(int, char*[])
{
  std::mt19937 rng(17);
  std::vector<Case> cases;
  for (float scale : { 1.0f, 1e-4f, 1e4f })
  {
    for (int spheres : { 0, 1, 9, 40, 70 })
    {
      cases.push_back(RandomCase(rng, scale, spheres, false));
      cases.push_back(RandomCase(rng, scale, spheres, true));
    }
  }
  long compared = 0, withBlockers = 0;
  for (const std::string& target : sh::BatchTargets())
  {
    PGI_CHECK(sh::SetBatchTarget(target));
    // Accumulation orders up to 4, 5-6 and 7-8: the batch against the
    // scalar.
    double worst = 0.0, worstHigh = 0.0, worstHighest = 0.0;
    long withinHighest = 0, totalHighest = 0;
    long within = 0, total = 0, seenDiffer = 0;
    double seenWorst = 0.0;
    long usedDiffer = 0;
    for (int variant = 0; variant < 10; ++variant)
    {
      SoftShadowSettings settings;
      settings.Order = variant >= 8 ? variant - 1 : 2 + variant % 5;
      settings.SelfShadowRules = variant != 1;
      settings.PlanesInLogSpace = variant % 2 == 0;
      settings.AccumulationOrder = variant == 5 ? 6 : 0;
      settings.WindowH = variant == 6 ? -1.0 : 0.0;
      settings.Exp.Method = variant == 7 ? sh::ExpMethod::PSStar : sh::ExpMethod::Hybrid;
      const SoftShadows shadows(settings);
      const int n2 = settings.Order * settings.Order;
      for (Case& c : cases)
      {
        Blockers b = c.B;
        if (variant == 3)
        {
          // Per-band ratios, as hierarchy cuts set them.
          std::uniform_real_distribution<float> ratio(0.6f, 1.4f);
          b.Ratio.resize(b.Spheres() * settings.Order);
          for (float& v : b.Ratio)
          {
            v = ratio(rng);
          }
        }
        const int count = static_cast<int>(c.P.size() / 3);
        std::vector<float> g(count * n2), ref(n2);
        std::vector<sh::Status> status(count);
        std::vector<int> used(count);
        // Stale entries the batch must clear.
        std::vector<std::vector<SeenBlocker>> seen(count, { { 7, 0.1f, { 0, 0, 1 } } });
        std::vector<SeenBlocker> seenRef;
        shadows.VisibilityBatch(count, c.P.data(), c.N.data(), b, g.data(), status.data(),
          used.data(), variant % 2 ? seen.data() : nullptr);
        for (int i = 0; i < count; ++i)
        {
          sh::Status expected;
          const int blockers =
            shadows.Visibility(&c.P[3 * i], &c.N[3 * i], b, ref.data(), expected, &seenRef);
          usedDiffer += blockers != used[i] ? 1 : 0;
          // The blockers seen: the same ones, angles and directions equal
          // (the lists feed the indirect light).
          if (variant % 2)
          {
            seenDiffer += seen[i].size() != seenRef.size() ? 1 : 0;
            for (std::size_t q = 0; q < std::min(seen[i].size(), seenRef.size()); ++q)
            {
              seenDiffer += seen[i][q].Index != seenRef[q].Index ? 1 : 0;
              seenWorst =
                std::max(seenWorst, double(std::fabs(seen[i][q].Theta - seenRef[q].Theta)));
              for (int k = 0; k < 3; ++k)
              {
                seenWorst =
                  std::max(seenWorst, double(std::fabs(seen[i][q].Dir[k] - seenRef[q].Dir[k])));
              }
            }
          }
          PGI_CHECK(status[i] == expected);
          double diff = 0.0, size = 1.0;
          for (int k = 0; k < n2; ++k)
          {
            diff = std::max(diff, std::fabs(double(g[i * n2 + k]) - ref[k]));
            size = std::max(size, std::fabs(double(ref[k])));
            PGI_CHECK(std::isfinite(g[i * n2 + k]));
          }
          const int acc = std::max(settings.Order, settings.AccumulationOrder);
          ++compared;
          withBlockers += blockers > 0 ? 1 : 0;
          if (acc > 6)
          {
            worstHighest = std::max(worstHighest, diff / size);
            withinHighest += diff / size <= 1e-5 ? 1 : 0;
            ++totalHighest;
            continue;
          }
          double& w = acc <= 4 ? worst : worstHigh;
          w = std::max(w, diff / size);
          within += diff / size <= 1e-5 ? 1 : 0;
          ++total;
        }
      }
    }
    std::printf("%s: worst difference %.2e at orders 2-4, %.2e at orders 5-6; %.4f%% of "
                "receivers within 1e-5; blocker counts that differ %ld\n",
      target.c_str(), worst, worstHigh, 100.0 * within / total, usedDiffer);
    PGI_CHECK(worst == 0.0);
    PGI_CHECK(worstHigh == 0.0);
    PGI_CHECK(within == total);
    std::printf("%s: orders 7-8: worst difference %.2e; %.4f%% of receivers within 1e-5\n",
      target.c_str(), worstHighest, 100.0 * withinHighest / totalHighest);
    PGI_CHECK(worstHighest == 0.0);
    PGI_CHECK(usedDiffer == 0);
    std::printf("%s: seen lists: %ld differ, worst angle or direction difference %.2e\n",
      target.c_str(), seenDiffer, seenWorst);
    PGI_CHECK(seenDiffer == 0);
    PGI_CHECK(seenWorst == 0.0);
  }
  std::printf("%ld receivers compared, %ld with blockers in view\n", compared, withBlockers);
  // A receiver on its own proxy where the tangent plane touches it (h = -r
  // to the last bit, from TestRenderingAgreement's overlapping spheres): the
  // rules keep or drop that proxy on the rounding of h, so the batch must
  // round as the scalar code does (no fused multiply-adds there).
  {
    Blockers b;
    const float s[5][4] = { { 0, 0, 1.0f, 0.8f }, { 0.7f, 0.2f, 1.3f, 0.6f },
      { -0.6f, 0.3f, 0.9f, 0.7f }, { 0.1f, -0.7f, 1.6f, 0.5f }, { 0.3f, 0.4f, 0.35f, 0.45f } };
    for (const auto& x : s)
    {
      b.AddSphere(x[0], x[1], x[2], x[3]);
    }
    const float p[3] = { -1.25294757f, 0.170120656f, 1.11631191f };
    const float n[3] = { -0.932782233f, -0.185541928f, 0.309017003f };
    SoftShadowSettings settings;
    const SoftShadows shadows(settings);
    float ref[16], g[16];
    sh::Status status;
    const int expected = shadows.Visibility(p, n, b, ref, status);
    for (const std::string& target : sh::BatchTargets())
    {
      PGI_CHECK(sh::SetBatchTarget(target));
      int used = -1;
      shadows.VisibilityBatch(1, p, n, b, g, &status, &used);
      PGI_CHECK(used == expected);
      double diff = 0.0;
      for (int k = 0; k < 16; ++k)
      {
        diff = std::max(diff, std::fabs(double(g[k]) - ref[k]));
      }
      PGI_CHECK(diff == 0.0);
    }
  }
  PGI_CHECK(withBlockers > compared / 2);
  // The blockers' angular radius (both paths' asin, without fused
  // multiply-adds) against the double asin, both branches and the switch at
  // 0.5: within two float ulps of pi / 2.
  {
    double worstAsin = 0.0;
    for (int i = 0; i <= 200000; ++i)
    {
      const float x = i == 200000 ? 1.0f : static_cast<float>(i) / 200000.0f;
      for (const float v : { x, std::nextafter(0.5f, 0.0f), 0.5f })
      {
        worstAsin = std::max(worstAsin, std::fabs(detail::BlockerAsin(v) - std::asin(double(v))));
      }
    }
    std::printf("BlockerAsin: worst error %.2e rad on [0, 1]\n", worstAsin);
    PGI_BELOW(worstAsin, 2.4e-7);
    PGI_CHECK(std::isnan(detail::BlockerAsin(std::numeric_limits<float>::quiet_NaN())));
  }
  PGI_CHECK(sh::SetBatchTarget(""));
  // Disabled, the batch is the scalar loop.
  sh::SetBatchKernelsEnabled(false);
  PGI_CHECK(std::string(sh::BatchTargetName()) == "scalar");
  sh::SetBatchKernelsEnabled(true);
  return pgitest::Result();
}
