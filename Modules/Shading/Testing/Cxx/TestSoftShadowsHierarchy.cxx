// Hierarchy cuts with ratio vectors (SHEXP 6.3), against the true
// visibility of the leaves' union: the cut costs fewer blockers, comes
// closer than accumulating every leaf (whose overlapping caps add up below
// the SH's resolution), and without ratio vectors the error is larger.
#include "pgiSoftShadows.h"
#include "vtkPGIGlobalIllumination.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "pgiSHZonal.h"
#include "pgiTesting.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

using namespace proxygi;

namespace
{
// 4 x 4 x 4 leaves in clumps: 16 parents of 4 leaves, 4 grandparents, 1 root.
ProxyHierarchy MakeHierarchy()
{
  ProxyHierarchy h;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  auto add = [&h](float x, float y, float z, float r, int level, int parent)
  {
    h.X.push_back(x);
    h.Y.push_back(y);
    h.Z.push_back(z);
    h.R.push_back(r);
    h.Level.push_back(level);
    h.Parent.push_back(parent);
    return static_cast<int>(h.X.size()) - 1;
  };
  const int root = add(0, 0, 3, 2.2f, 3, -1);
  for (int g = 0; g < 4; ++g)
  {
    const float gx = (g % 2 ? 1.0f : -1.0f), gy = (g / 2 ? 1.0f : -1.0f);
    const int grand = add(gx, gy, 3, 1.1f, 2, root);
    for (int p = 0; p < 4; ++p)
    {
      const float px = gx + 0.5f * (p % 2 ? 1 : -1), py = gy + 0.5f * (p / 2 ? 1 : -1);
      const int parent = add(px, py, 3, 0.55f, 1, grand);
      for (int l = 0; l < 4; ++l)
      {
        add(px + 0.2f * u(rng), py + 0.2f * u(rng), 3 + 0.2f * u(rng), 0.2f, 0, parent);
      }
    }
  }
  return h;
}

double Radiance(const SoftShadows& s, const Blockers& b, const float p[3], const float n[3])
{
  float g[sh::MaxCoefficients], h[sh::MaxCoefficients];
  sh::Status status;
  s.Visibility(p, n, b, g, status);
  sh::DiffuseTransfer(s.GetOrder(), n[0], n[1], n[2], h);
  return sh::Dot(s.GetOrder() * s.GetOrder(), h, g);
}

// The same for a receiver facing up, with the true visibility of the union
// of the spheres: 1/pi int V cos over the hemisphere (dw = d(cos) dphi),
// 256 x 512 directions, times the unshadowed radiance.
double TrueRadiance(const SoftShadows& s, const Blockers& b, const float p[3])
{
  constexpr int Rows = 256, Columns = 512;
  const float up[3] = { 0, 0, 1 };
  double sum = 0.0;
  for (int i = 0; i < Rows; ++i)
  {
    const double z = (i + 0.5) / Rows, side = std::sqrt(1 - z * z);
    for (int j = 0; j < Columns; ++j)
    {
      const double phi = 2 * 3.14159265358979 * (j + 0.5) / Columns;
      const double w[3] = { side * std::cos(phi), side * std::sin(phi), z };
      bool blocked = false;
      for (std::size_t k = 0; k < b.Spheres() && !blocked; ++k)
      {
        const double e[3] = { b.X[k] - p[0], b.Y[k] - p[1], b.Z[k] - p[2] };
        const double along = e[0] * w[0] + e[1] * w[1] + e[2] * w[2];
        blocked = along > 0 &&
          e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - along * along < double(b.R[k]) * b.R[k];
      }
      sum += blocked ? 0.0 : z;
    }
  }
  return Radiance(s, Blockers(), p, up) * sum * 2 / (Rows * Columns);
}
} // namespace

int TestSoftShadowsHierarchy(int, char*[])
{
  ProxyHierarchy h = MakeHierarchy();
  PGI_CHECK(h.Finish());
  PGI_CHECK(h.Roots.size() == 1);
  Blockers leaves;
  for (std::size_t i = 0; i < h.X.size(); ++i)
  {
    if (h.Level[i] == 0)
    {
      leaves.AddSphere(h.X[i], h.Y[i], h.Z[i], h.R[i]);
    }
  }
  SoftShadowSettings settings;
  const SoftShadows shadows(settings);
  const float up[3] = { 0, 0, 1 };

  // Receiver clusters on the ground far enough away for the cut to coarsen,
  // against the true visibility of the leaves' union. Every leaf's own log
  // adds its cap where the caps overlap (each is below the SH's
  // resolution); the cut's nodes block their leaves' union.
  double worstRatio = 0.0, worstPlain = 0.0, worstLeaves = 0.0;
  std::size_t cutSize = 0;
  for (float cx : { 6.0f, 9.0f, -8.0f })
  {
    const float pR[3] = { cx, 1.0f, 0.0f }, rR = 1.0f;
    Blockers cut = CutHierarchy(h, pR, rR, pR, up, 25.0f * 3.14159265f / 180.0f, 4, true);
    cutSize = std::max(cutSize, cut.Spheres());
    Blockers plain = cut;
    plain.Ratio.clear();
    for (int k = 0; k < 10; ++k)
    {
      const float p[3] = { pR[0] + 0.7f * std::cos(1.3f * k), pR[1] + 0.7f * std::sin(2.1f * k),
        0.0f };
      const double exact = TrueRadiance(shadows, leaves, p);
      worstRatio = std::max(worstRatio, std::fabs(Radiance(shadows, cut, p, up) - exact));
      worstPlain = std::max(worstPlain, std::fabs(Radiance(shadows, plain, p, up) - exact));
      worstLeaves = std::max(worstLeaves, std::fabs(Radiance(shadows, leaves, p, up) - exact));
    }
  }
  std::printf("hierarchy cut (25 deg): up to %zu of %zu leaves' worth of blockers; largest "
              "radiance error against the leaves' union %.4f with ratio vectors, %.4f without, "
              "%.4f with every leaf\n",
    cutSize, leaves.Spheres(), worstRatio, worstPlain, worstLeaves);
  PGI_CHECK(cutSize < leaves.Spheres());
  PGI_BELOW(worstRatio, 0.005);
  PGI_BELOW(worstRatio, 0.5 * worstLeaves);
  PGI_CHECK(worstRatio < worstPlain);

  // Under the blockers the cut descends (4 grandparents at 25 degrees), and
  // with a small threshold it reaches the leaves.
  {
    const float pR[3] = { 0, 0, 0 };
    Blockers cut = CutHierarchy(h, pR, 0.5f, pR, up, 25.0f * 3.14159265f / 180.0f, 4, true);
    Blockers fine = CutHierarchy(h, pR, 0.5f, pR, up, 2.0f * 3.14159265f / 180.0f, 4, true);
    std::printf("cluster under the blockers: cut of %zu spheres at 25 degrees, %zu at 2\n",
      cut.Spheres(), fine.Spheres());
    PGI_CHECK(cut.Spheres() == 4);
    PGI_CHECK(fine.Spheres() == leaves.Spheres());
    double worst = 0.0, worstLeaves = 0.0;
    for (int k = 0; k < 10; ++k)
    {
      const float p[3] = { 0.4f * std::cos(1.3f * k), 0.4f * std::sin(0.7f * k), 0.0f };
      const double exact = TrueRadiance(shadows, leaves, p);
      worst = std::max(worst, std::fabs(Radiance(shadows, cut, p, up) - exact));
      worstLeaves = std::max(worstLeaves, std::fabs(Radiance(shadows, leaves, p, up) - exact));
    }
    std::printf("  largest radiance error under the blockers against the leaves' union: %.4f "
                "with the 25-degree cut, %.4f with every leaf\n",
      worst, worstLeaves);
    PGI_BELOW(worst, 0.05);
  }
  // A receiver that owns none of the spheres under a row of heavily
  // overlapping ones (an arch's tube): every sphere is below the SH's
  // resolution, the exp of summed logs blocks far more than their union,
  // and ScaleCutToUnion brings the cut's blocked share to the union's.
  {
    Blockers row;
    for (int k = 0; k < 12; ++k)
    {
      row.AddSphere(-1.0f + 2.0f * static_cast<float>(k) / 11.0f, 0.0f, 0.8f, 0.25f);
    }
    double worstBefore = 0.0, worstAfter = 0.0;
    float smallest = 1.0f;
    for (const float x : { 0.0f, 0.4f, -0.9f })
    {
      const float p[3] = { x, 0.2f, 0.0f };
      Blockers cut = row;
      const double exact = TrueRadiance(shadows, row, p);
      const double before = std::fabs(Radiance(shadows, cut, p, up) - exact);
      smallest = std::min(smallest, ScaleCutToUnion(cut, row, shadows, p, up));
      worstBefore = std::max(worstBefore, before);
      worstAfter = std::max(worstAfter, std::fabs(Radiance(shadows, cut, p, up) - exact));
    }
    // One sphere (18 degrees): its exp of log blocks a little more than
    // its cap, and is brought to it; an empty cut is left alone.
    Blockers one = row;
    one.X.resize(1), one.Y.resize(1), one.Z.resize(1), one.R.resize(1);
    one.X[0] = 0.0f;
    const float p[3] = { 0.0f, 0.2f, 0.0f };
    const double oneExact = TrueRadiance(shadows, one, p);
    const double oneBefore = std::fabs(Radiance(shadows, one, p, up) - oneExact);
    const float lone = ScaleCutToUnion(one, one, shadows, p, up);
    const double oneAfter = std::fabs(Radiance(shadows, one, p, up) - oneExact);
    const double unshadowed = Radiance(shadows, Blockers(), p, up);
    std::printf("under a row of 12 overlapping spheres: largest radiance error against their "
                "union %.4f, %.4f with the cut scaled (logs x %.3f at least); one sphere: "
                "%.4f, %.4f (x %.3f)\n",
      worstBefore, worstAfter, smallest, oneBefore, oneAfter, lone);
    PGI_BELOW(worstAfter, 0.02 * unshadowed);
    PGI_BELOW(worstAfter, 0.3 * worstBefore);
    PGI_BELOW(smallest, 0.9f);
    PGI_BELOW(oneAfter, 0.01 * unshadowed);
    Blockers none;
    PGI_NEAR(ScaleCutToUnion(none, row, shadows, p, up), 1.0, 0.0);
  }
  // The union's share tests each sphere against the directions its cone can
  // reach: the same count as every direction against every sphere, for
  // random spheres around tilted receivers, spheres straddling or below the
  // receiver's plane, a receiver inside a sphere, tiny, huge and grazing
  // spheres, and a sphere at the receiver itself.
  {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), r01(0.0f, 1.0f);
    int cases = 0, mismatches = 0;
    double coveredSum = 0.0;
    for (int trial = 0; trial < 200; ++trial)
    {
      Blockers set;
      const float p[3] = { u(rng), u(rng), u(rng) };
      float n[3] = { u(rng), u(rng), u(rng) };
      const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (float& c : n)
      {
        c /= len;
      }
      const int count = 1 + trial % 24;
      for (int k = 0; k < count; ++k)
      {
        const float scale = trial % 5 == 0 ? 1e-3f : (trial % 7 == 0 ? 50.0f : 1.0f);
        set.AddSphere(p[0] + 3.0f * u(rng), p[1] + 3.0f * u(rng), p[2] + 3.0f * u(rng),
          scale * (0.02f + 0.8f * r01(rng)));
      }
      if (trial % 9 == 0)
      {
        set.AddSphere(p[0], p[1], p[2], 0.3f); // the receiver inside
      }
      if (trial % 11 == 0)
      {
        set.AddSphere(p[0], p[1], p[2], 0.0f); // at the receiver, no radius
      }
      if (trial % 13 == 0)
      {
        // Grazing: centred on the receiver's plane.
        float t[3] = { n[1], -n[0], 0.0f };
        set.AddSphere(p[0] + 2.0f * t[0], p[1] + 2.0f * t[1], p[2], 0.2f);
      }
      for (const int directions : { 512, 2048 })
      {
        const double pruned = UnionCoveredShare(set, p, n, directions);
        const double every = UnionCoveredShare(set, p, n, directions, true);
        ++cases;
        mismatches += pruned == every ? 0 : 1;
        coveredSum += every;
      }
    }
    std::printf("union's share: %d of %d cases differ from every-pair testing (mean share "
                "%.3f)\n",
      mismatches, cases, coveredSum / cases);
    PGI_CHECK(mismatches == 0);
    PGI_CHECK(coveredSum > 0.1 * cases); // the cases do cover something
    Blockers nan;
    nan.AddSphere(std::nanf(""), 0.0f, 1.0f, 0.5f);
    nan.AddSphere(0.0f, 0.0f, 1.0f, 0.5f);
    const float origin[3] = { 0, 0, 0 };
    const double withNaN = UnionCoveredShare(nan, origin, up, 512);
    PGI_CHECK(std::isfinite(withNaN) && withNaN > 0.0 && withNaN < 1.0);
  }
  // Through the filter: proxies with Level and Parent arrays, a receiver
  // plane; the cut at 25 degrees against all leaves.
  {
    vtkNew<vtkPolyData> proxies;
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> radius;
    vtkNew<vtkIntArray> level, parent;
    radius->SetName("Radius");
    level->SetName("Level");
    parent->SetName("Parent");
    for (std::size_t i = 0; i < h.X.size(); ++i)
    {
      points->InsertNextPoint(h.X[i], h.Y[i], h.Z[i]);
      radius->InsertNextValue(h.R[i]);
      level->InsertNextValue(h.Level[i]);
      parent->InsertNextValue(h.Parent[i]);
    }
    proxies->SetPoints(points);
    proxies->GetPointData()->AddArray(radius);
    proxies->GetPointData()->AddArray(level);
    proxies->GetPointData()->AddArray(parent);
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(-12, -12, 0);
    plane->SetPoint1(12, -12, 0);
    plane->SetPoint2(-12, 12, 0);
    plane->SetResolution(96, 96);
    vtkNew<vtkPGIGlobalIllumination> all, cut;
    // A reflecting wall: cut blockers must carry the planes' albedo too.
    const double wallOrigin[3] = { 0, 14, 0 }, wallNormal[3] = { 0, -1, 0 },
                 wallAlbedo[3] = { 0.5, 0.5, 0.5 };
    for (vtkPGIGlobalIllumination* gi : { all.Get(), cut.Get() })
    {
      gi->SetInputConnection(plane->GetOutputPort());
      gi->SetProxiesData(proxies);
      gi->AddBlockerPlane(wallOrigin, wallNormal, wallAlbedo);
    }
    cut->GetSettings()->SetHierarchyAngle(25);
    cut->GetSettings()->SetReceiversPerCluster(64);
    all->Update();
    cut->Update();
    vtkDataArray* a = all->GetOutput()->GetPointData()->GetArray("DirectShadowed");
    vtkDataArray* b = cut->GetOutput()->GetPointData()->GetArray("DirectShadowed");
    double sq = 0, ref = 0, worst = 0, sumAll = 0, sumCut = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      const double d = b->GetComponent(i, 0) - a->GetComponent(i, 0);
      sq += d * d;
      ref += a->GetComponent(i, 0) * a->GetComponent(i, 0);
      worst = std::max(worst, std::fabs(d));
      sumAll += a->GetComponent(i, 0);
      sumCut += b->GetComponent(i, 0);
    }
    // The cut was made: the plan's average cut is smaller than the leaf
    // set, and shading through it differs (a filter ignoring the angle
    // would give 0 difference).
    double cutSize = -1.0, leaves = -1.0;
    for (const std::string& line : cut->GetPlan())
    {
      std::printf("  plan: %s\n", line.c_str());
      std::sscanf(line.c_str(),
        "hierarchy: %*d receiver clusters, cuts of %lf spheres on average "
        "(of %lf leaves)",
        &cutSize, &leaves);
    }
    std::printf("filter with hierarchy (25 deg) against all leaves: relative RMSE %.3f%%, max "
                "%.4f, mean ratio %.4f\n",
      100 * std::sqrt(sq / ref), worst, sumCut / sumAll);
    PGI_CHECK(leaves > 1.0 && cutSize >= 1.0 && cutSize < 0.9 * leaves);
    PGI_CHECK(worst > 1e-5);
    // The cut's nodes block their leaves' union, less than every leaf's
    // overlapping caps (above: closer to the truth), and no more.
    PGI_BELOW(std::sqrt(sq / ref), 0.025);
    PGI_BELOW(worst, 0.05);
    PGI_CHECK(sumCut > sumAll);
    // Indirect light through the cut: parents reflect with their leaves'
    // mean albedo, so the cut's bounce stays close to the leaves'.
    vtkDataArray* ia = all->GetOutput()->GetPointData()->GetArray("IndirectProxy");
    vtkDataArray* ib = cut->GetOutput()->GetPointData()->GetArray("IndirectProxy");
    double isq = 0, iref = 0;
    for (vtkIdType i = 0; i < ia->GetNumberOfTuples(); ++i)
    {
      const double d = ib->GetComponent(i, 0) - ia->GetComponent(i, 0);
      isq += d * d;
      iref += ia->GetComponent(i, 0) * ia->GetComponent(i, 0);
    }
    std::printf("indirect with hierarchy (25 deg) against all leaves: relative RMSE %.3f%%\n",
      100 * std::sqrt(isq / iref));
    PGI_CHECK(iref > 0.0);
    PGI_BELOW(std::sqrt(isq / iref), 0.05);
    // With ObjectId arrays the plane's receivers own none of the spheres:
    // their clusters' cuts are scaled to the leaves' union, and the plan
    // says so; the plane comes out a little brighter under the clumps
    // (they are far: the nodes' own union already holds there).
    vtkNew<vtkPolyData> ground, owned;
    ground->DeepCopy(plane->GetOutput());
    owned->DeepCopy(proxies);
    for (vtkPolyData* data : { ground.Get(), owned.Get() })
    {
      vtkNew<vtkIntArray> ids;
      ids->SetName("ObjectId");
      ids->SetNumberOfTuples(data->GetNumberOfPoints());
      ids->FillValue(data == ground.Get() ? 1 : 0);
      data->GetPointData()->AddArray(ids);
    }
    vtkNew<vtkPGIGlobalIllumination> scaled;
    scaled->SetInputData(ground);
    scaled->SetProxiesData(owned);
    scaled->AddBlockerPlane(wallOrigin, wallNormal, wallAlbedo);
    scaled->GetSettings()->SetHierarchyAngle(25);
    scaled->GetSettings()->SetReceiversPerCluster(64);
    scaled->Update();
    bool said = false;
    for (const std::string& line : scaled->GetPlan())
    {
      said = said ||
        line.find("clusters of receivers without proxies scaled to their blockers' union") !=
          std::string::npos;
    }
    PGI_CHECK(said);
    vtkDataArray* c = scaled->GetOutput()->GetPointData()->GetArray("DirectShadowed");
    double darker = 0.0, brighter = 0.0;
    for (vtkIdType i = 0; i < c->GetNumberOfTuples(); ++i)
    {
      darker = std::max(darker, b->GetComponent(i, 0) - c->GetComponent(i, 0));
      brighter = std::max(brighter, c->GetComponent(i, 0) - b->GetComponent(i, 0));
    }
    std::printf("plane owning no spheres, cut scaled to the union: up to %.4f brighter, %.2e "
                "darker than the plain cut\n",
      brighter, darker);
    PGI_CHECK(brighter > 1e-4);
    PGI_BELOW(darker, 0.002);
  }

  // Broken links are refused.
  ProxyHierarchy broken = h;
  broken.Parent[5] = 5;
  PGI_CHECK(!broken.Finish());
  return pgitest::Result();
}
