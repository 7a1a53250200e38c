// Each GLSL helper of the GI mapper against its C++ twin, run per vertex on
// the GPU (transform feedback) over random and edge-case inputs, at SH
// orders 3, 4 and 6: basis, cap-log table lookup, ZH rotation, optimal-linear
// lookup, SH square, HYB exp (with and without the range guard acting), the
// self-shadow rules, the whole per-receiver visibility, diffuse transfer and
// both shading paths. Prints the measured errors; fails above the bounds.
#include "pgiGIShaders.h"
#include "pgiOffscreenWindow.h"
#include "pgiSRGB.h"
#include "pgiTesting.h"

#include "pgiEnvironmentShading.h"
#include "pgiIndirectLight.h"
#include "pgiSHBasis.h"
#include "pgiSHExp.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"
#include "pgiSoftShadows.h"
#include "pgiSphericalLights.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
namespace sh = proxygi::sh;

int Vec4s(int floats)
{
  return (floats + 3) / 4;
}

// GLSL: float name[size] filled from pgiIn<first>.. (4 per vec4).
std::string Unpack(const std::string& name, const std::string& size, int count, int first)
{
  std::ostringstream s;
  s << "  float " << name << "[" << size << "];\n";
  for (int i = 0; i < count; ++i)
  {
    s << "  " << name << "[" << i << "] = pgiIn" << first + i / 4 << "[" << i % 4 << "];\n";
  }
  return s.str();
}

// GLSL: pgiOut<first>.. = name[0..count-1], zero padded.
std::string Pack(const std::string& name, int count, int first)
{
  std::ostringstream s;
  for (int k = 0; k < Vec4s(count); ++k)
  {
    s << "  pgiOut" << first + k << " = vec4(";
    for (int c = 0; c < 4; ++c)
    {
      const int i = 4 * k + c;
      s << (c ? ", " : "") << (i < count ? name + "[" + std::to_string(i) + "]" : "0.0");
    }
    s << ");\n";
  }
  return s.str();
}

// Error of a GPU result against a reference, in units of the reference's scale.
struct Stats
{
  double MaxAbs = 0.0;
  double MaxRef = 0.0;
  void Add(double gpu, double ref)
  {
    const double e = std::fabs(gpu - ref);
    MaxAbs = std::isnan(e) ? 1e30 : std::max(MaxAbs, e);
    MaxRef = std::max(MaxRef, std::fabs(ref));
  }
  double Relative() const { return MaxAbs / std::max(MaxRef, 1e-30); }
};

void Report(const char* what, int order, const Stats& s, double bound)
{
  std::printf("  %-34s order %d: max |GPU - C++| %.3g (max |C++| %.3g, relative %.3g)\n", what,
    order, s.MaxAbs, s.MaxRef, s.Relative());
  std::string name = std::string(what) + " order " + std::to_string(order);
  pgitest::Below(s.Relative(), bound, name.c_str(), __FILE__, __LINE__);
}

struct Random
{
  std::mt19937 Engine{ 7 };
  double Uniform(double a, double b)
  {
    return std::uniform_real_distribution<double>(a, b)(Engine);
  }
  void Direction(float d[3])
  {
    std::normal_distribution<double> n;
    double v[3] = { n(Engine), n(Engine), n(Engine) };
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k)
    {
      d[k] = static_cast<float>(v[k] / len);
    }
  }
};

// A log-visibility vector as the kernel sums it: `blockers` random caps,
// spread over the sphere (spread 0) or clustered about one direction.
void RandomLog(Random& random, int order, int blockers, float maxTheta, float spread, float* f)
{
  const sh::CapTables& tables = sh::CapTables::Get(order);
  const int n2 = order * order;
  std::fill(f, f + n2, 0.0f);
  float zh[sh::MaxOrder], v[sh::MaxCoefficients], d[3], centre[3];
  random.Direction(centre);
  std::normal_distribution<double> normal;
  for (int b = 0; b < blockers; ++b)
  {
    random.Direction(d);
    if (spread > 0.0f)
    {
      double len = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        d[k] = centre[k] + spread * static_cast<float>(normal(random.Engine));
        len += d[k] * d[k];
      }
      for (int k = 0; k < 3; ++k)
      {
        d[k] = static_cast<float>(d[k] / std::sqrt(len));
      }
    }
    tables.CapLog(static_cast<float>(random.Uniform(0.01, maxTheta)), zh);
    sh::RotateScaledZonal(order, zh, d[0], d[1], d[2], v);
    for (int i = 0; i < n2; ++i)
    {
      f[i] += v[i];
    }
  }
}
} // namespace

int TestRenderingGLSLTwins(int, char*[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  std::printf("window: %s\n", description.c_str());
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!PGI_CHECK(gl != nullptr))
  {
    return pgitest::Result();
  }
  window->Render(); // the context and VTK's GL state
  proxygi::gpu::GLSLHarness harness(gl);
  Random random;
  const int samples = 600;

  for (int order : { 3, 4, 6 })
  {
    const int n2 = order * order;
    const std::string N2 = "PGI_SH_N2", NO = "PGI_SH_ORDER";
    const sh::CapTables& tables = sh::CapTables::Get(order);
    std::vector<float> in, out;
    auto run = [&](const std::string& body, int inputs, int outputs) -> bool
    {
      const bool ok = harness.Run(order, "", body, inputs, outputs, in, out);
      if (!ok)
      {
        std::printf("FAILED harness: %s\n", harness.GetError().c_str());
        ++pgitest::Failures();
      }
      return ok;
    };

    // The driver's built-ins the kernel uses, against double precision: the
    // floor under every other comparison.
    if (order == 4)
    {
      in.assign(4 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        in[4 * s] = static_cast<float>(random.Uniform(0.0, 1.0));       // asin
        in[4 * s + 1] = static_cast<float>(random.Uniform(-20.0, 1.0)); // exp
        in[4 * s + 2] = static_cast<float>(random.Uniform(1e-3, 40.0)); // log2
      }
      in[0] = 1.0f;
      in[4] = 0.5f;
      in[8] = 0.0f;
      if (run("  pgiOut0 = vec4(asin(pgiIn0.x), exp(pgiIn0.y), log2(pgiIn0.z), "
              "sqrt(pgiIn0.z));\n  pgiOut1 = vec4(pgiAsin(pgiIn0.x), 0.0, 0.0, 0.0);\n",
            1, 2))
      {
        double worst[5] = { 0, 0, 0, 0, 0 };
        for (int s = 0; s < samples; ++s)
        {
          const double ref[5] = { std::asin(double(in[4 * s])), std::exp(double(in[4 * s + 1])),
            std::log2(double(in[4 * s + 2])), std::sqrt(double(in[4 * s + 2])),
            std::asin(double(in[4 * s])) };
          for (int k = 0; k < 5; ++k)
          {
            const double scale =
              k == 1 ? std::max(ref[k], 1e-30) : std::max(std::fabs(ref[k]), 1.0);
            worst[k] = std::max(worst[k], std::fabs(out[8 * s + k] - ref[k]) / scale);
          }
        }
        std::printf("  built-ins vs double: asin %.3g abs, exp %.3g rel, log2 %.3g abs, sqrt %.3g; "
                    "pgiAsin %.3g abs\n",
          worst[0], worst[1], worst[2], worst[3], worst[4]);
        PGI_BELOW(worst[4], 1e-6); // ours, whatever the driver's asin does
        PGI_BELOW(worst[1], 1e-4);
      }
    }

    // Basis, against the double-precision basis (the float one is within it).
    {
      in.assign(4 * samples, 0.0f);
      const float poles[][3] = { { 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 }, { 0, 1, 0 } };
      for (int s = 0; s < samples; ++s)
      {
        if (s < 4)
        {
          std::copy(poles[s], poles[s] + 3, &in[4 * s]);
        }
        else
        {
          random.Direction(&in[4 * s]);
        }
      }
      const int outs = Vec4s(n2);
      if (run("  float y[PGI_SH_N2];\n  pgiSHBasis(pgiIn0.xyz, y);\n" + Pack("y", n2, 0), 1, outs))
      {
        Stats stats;
        for (int s = 0; s < samples; ++s)
        {
          double y[sh::MaxCoefficients];
          sh::EvaluateBasis<double>(order, in[4 * s], in[4 * s + 1], in[4 * s + 2], y);
          for (int i = 0; i < n2; ++i)
          {
            stats.Add(out[4 * outs * s + i], y[i]);
          }
        }
        Report("pgiSHBasis vs EvaluateBasis", order, stats, 2e-6);
      }
    }

    // Cap-log table lookup and the ZH rotation, over the whole range and past it.
    {
      in.assign(4 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        const float theta = s == 0 ? 0.0f
          : s == 1                 ? static_cast<float>(sh::CapTables::MaxAngle)
          : s == 2                 ? 2.0f
                   : static_cast<float>(random.Uniform(0.0, sh::CapTables::MaxAngle));
        in[4 * s] = theta;
        random.Direction(&in[4 * s + 1]);
      }
      const int zhOuts = Vec4s(order), vOuts = Vec4s(n2);
      const std::string body =
        "  float zh[PGI_SH_ORDER];\n  pgiCapLog(pgiIn0.x, zh);\n"
        "  float v[PGI_SH_N2];\n  pgiRotateScaledZonal(zh, pgiIn0.yzw, v);\n" +
        Pack("zh", order, 0) + Pack("v", n2, zhOuts);
      if (run(body, 1, zhOuts + vOuts))
      {
        Stats lookup, rotation;
        const int stride = 4 * (zhOuts + vOuts);
        for (int s = 0; s < samples; ++s)
        {
          float zh[sh::MaxOrder], v[sh::MaxCoefficients];
          tables.CapLog(in[4 * s], zh);
          sh::RotateScaledZonal(order, zh, in[4 * s + 1], in[4 * s + 2], in[4 * s + 3], v);
          for (int l = 0; l < order; ++l)
          {
            lookup.Add(out[stride * s + l], zh[l]);
          }
          for (int i = 0; i < n2; ++i)
          {
            rotation.Add(out[stride * s + 4 * zhOuts + i], v[i]);
          }
        }
        Report("pgiCapLog vs CapTables::CapLog", order, lookup, 2e-6);
        Report("pgiRotateScaledZonal vs C++", order, rotation, 4e-6);
      }
    }

    // Cap-visibility and averaged-indirect D(theta) lookups, and the
    // averaged radiance of a proxy (image-space indirect light).
    {
      in.assign(4 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        const float theta = s == 0 ? 0.0f
          : s == 1                 ? static_cast<float>(sh::CapTables::MaxAngle)
          : s == 2                 ? 2.0f
                   : static_cast<float>(random.Uniform(0.0, sh::CapTables::MaxAngle));
        in[4 * s] = theta;
        random.Direction(&in[4 * s + 1]);
      }
      const int zhOuts = Vec4s(order);
      // Radiance SH the GLSL and the C++ both build from i.
      auto radiance = [](int i, int c)
      { return c == 0 ? 0.5f - 0.05f * float(i) : (c == 1 ? 0.02f * float(i * i % 7) : 0.3f); };
      const std::string body =
        "  float vis[PGI_SH_ORDER];\n  pgiCapVisibility(pgiIn0.x, vis);\n"
        "  float d[PGI_SH_ORDER];\n  pgiAveragedIndirect(pgiIn0.x, d);\n"
        "  vec3 r[PGI_SH_N2];\n"
        "  for (int i = 0; i < PGI_SH_N2; ++i)\n"
        "  {\n"
        "    r[i] = vec3(0.5 - 0.05 * float(i), 0.02 * float(i * i % 7), 0.3);\n"
        "  }\n"
        "  vec3 kappa = pgiAveragedRadiance(pgiIn0.x, pgiIn0.yzw, r);\n" +
        Pack("vis", order, 0) + Pack("d", order, zhOuts) + "  pgiOut" + std::to_string(2 * zhOuts) +
        " = vec4(kappa, 0.0);\n";
      if (run(body, 1, 2 * zhOuts + 1))
      {
        Stats visibility, averaged, kappa;
        const int stride = 4 * (2 * zhOuts + 1);
        const sh::IndirectTables& indirect = sh::IndirectTables::Get(order);
        std::vector<float> rc(n2);
        for (int s = 0; s < samples; ++s)
        {
          float zv[sh::MaxOrder], zd[sh::MaxOrder];
          tables.CapVisibility(in[4 * s], zv);
          indirect.AveragedIndirect(in[4 * s], zd);
          for (int l = 0; l < order; ++l)
          {
            visibility.Add(out[stride * s + l], zv[l]);
            averaged.Add(out[stride * s + 4 * zhOuts + l], zd[l]);
          }
          for (int c = 0; c < 3; ++c)
          {
            for (int i = 0; i < n2; ++i)
            {
              rc[i] = radiance(i, c);
            }
            kappa.Add(out[stride * s + 8 * zhOuts + c],
              indirect.AveragedRadiance(in[4 * s], &in[4 * s + 1], rc.data()));
          }
        }
        Report("pgiCapVisibility vs CapTables", order, visibility, 2e-6);
        Report("pgiAveragedIndirect vs IndirectTables", order, averaged, 2e-6);
        Report("pgiAveragedRadiance vs IndirectTables", order, kappa, 1e-5);
      }
    }

    // Optimal-linear lookup, including past the fitted range.
    {
      in.assign(4 * samples, 0.0f);
      const double maxNorm = tables.GetOptimalLinearMaxNorm();
      for (int s = 0; s < samples; ++s)
      {
        in[4 * s] = s == 0 ? 0.0f : static_cast<float>(random.Uniform(0.0, 1.2 * maxNorm));
      }
      if (run("  float a, b;\n  pgiOptimalLinear(pgiIn0.x, a, b);\n  pgiOut0 = vec4(a, b, 0.0, "
              "0.0);\n",
            1, 1))
      {
        Stats stats;
        for (int s = 0; s < samples; ++s)
        {
          float a, b;
          tables.OptimalLinear(in[4 * s], a, b);
          stats.Add(out[4 * s], a);
          stats.Add(out[4 * s + 1], b);
        }
        Report("pgiOptimalLinear vs C++", order, stats, 2e-6);
      }
    }

    // SH square (generated from the tensor) and HYB exp, on log-visibility
    // vectors of 1 to 12 caps spread out (what the kernel meets), then of 20
    // to 100 caps clustered about one direction, where the range guard acts.
    for (int crowd = 0; crowd < 2; ++crowd)
    {
      const int ins = Vec4s(n2);
      in.assign(4 * ins * samples, 0.0f);
      int guarded = 0;
      std::vector<std::vector<float>> fs(samples, std::vector<float>(n2));
      for (int s = 0; s < samples; ++s)
      {
        const int blockers = crowd ? 20 + s % 81 : 1 + s % 12;
        RandomLog(random, order, blockers, crowd ? 0.5f : 1.0f, crowd ? 0.1f : 0.0f, fs[s].data());
        std::copy(fs[s].begin(), fs[s].end(), &in[4 * ins * s]);
      }
      // Two runs: both at once pass the transform-feedback limit at order 6.
      std::vector<float> squares;
      const bool ran = run(Unpack("f", N2, n2, 0) +
          "  float sq[PGI_SH_N2];\n  pgiSHSquare(f, sq);\n" + Pack("sq", n2, 0),
        ins, ins);
      squares.swap(out);
      if (ran &&
        run(Unpack("f", N2, n2, 0) + "  float g[PGI_SH_N2];\n  pgiExpHybrid(f, g);\n" +
            Pack("g", n2, 0),
          ins, ins))
      {
        Stats square, exp;
        const sh::TripleProduct& tp = sh::TripleProduct::Get(order);
        const int stride = 4 * ins;
        for (int s = 0; s < samples; ++s)
        {
          float sq[sh::MaxCoefficients], g[sh::MaxCoefficients], unguarded[sh::MaxCoefficients];
          // The C++ square of the same float input, accumulated in double
          // so the bound measures the GPU's rounding, not the CPU's.
          std::vector<double> fd(fs[s].begin(), fs[s].end());
          double sqd[sh::MaxCoefficients];
          tp.Square(fd.data(), sqd);
          tp.Square(fs[s].data(), sq);
          for (int i = 0; i < n2; ++i)
          {
            square.Add(squares[stride * s + i], sqd[i]);
          }
          sh::Exp(order, fs[s].data(), g);
          sh::ExpOptions noGuard;
          noGuard.RangeGuard = false;
          sh::Exp(order, fs[s].data(), unguarded, noGuard);
          bool differs = false;
          for (int i = 0; i < n2; ++i)
          {
            exp.Add(out[stride * s + i], g[i]);
            differs = differs || std::fabs(g[i] - unguarded[i]) > 1e-4f * std::fabs(g[0]);
          }
          guarded += differs ? 1 : 0;
        }
        Report(crowd ? "pgiSHSquare (clustered caps)" : "pgiSHSquare vs TripleProduct", order,
          square, 2e-6);
        std::printf("    (range guard acted on %d of %d inputs)\n", guarded, samples);
        Report(crowd ? "pgiExpHybrid (clustered, guard)" : "pgiExpHybrid vs sh::Exp (HYB)", order,
          exp, crowd ? 2e-3 : 1e-4);
        if (crowd)
        {
          PGI_CHECK(guarded > 0); // the guard path was exercised
        }
      }
    }

    // Self-shadow rules: spheres around the tangent plane, receivers inside.
    if (order == 4)
    {
      in.assign(12 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        float* row = &in[12 * s];
        random.Direction(row + 4); // normal
        for (int k = 0; k < 3; ++k)
        {
          row[k] = static_cast<float>(random.Uniform(-1, 1));     // receiver
          row[8 + k] = static_cast<float>(random.Uniform(-1, 1)); // centre
        }
        row[11] = static_cast<float>(random.Uniform(0.05, 1.5)); // radius
      }
      const std::string body = "  vec3 c = pgiIn2.xyz;\n  float r = pgiIn2.w;\n"
                               "  bool kept = pgiReplaceBlocker(pgiIn0.xyz, pgiIn1.xyz, c, r);\n"
                               "  pgiOut0 = vec4(c, kept ? r : -1.0);\n";
      if (run(body, 3, 1))
      {
        Stats stats;
        int agree = 0, kept = 0;
        for (int s = 0; s < samples; ++s)
        {
          const float* row = &in[12 * s];
          float c[3] = { row[8], row[9], row[10] }, r = row[11];
          const bool k = proxygi::ReplaceBlocker(row, row + 4, c, r);
          const bool gpuKept = out[4 * s + 3] >= 0.0f;
          agree += k == gpuKept ? 1 : 0;
          if (k && gpuKept)
          {
            ++kept;
            for (int q = 0; q < 3; ++q)
            {
              stats.Add(out[4 * s + q], c[q]);
            }
            stats.Add(out[4 * s + 3], r);
          }
        }
        std::printf("  pgiReplaceBlocker: same keep/drop decision for %d of %d (%d kept)\n", agree,
          samples, kept);
        PGI_CHECK(agree >= samples - 2); // ties at h = +-r may round either way
        Report("pgiReplaceBlocker vs ReplaceBlocker", order, stats, 1e-5);
      }
    }

    // The whole per-receiver visibility against SoftShadows::Visibility, and
    // the shading paths against EnvironmentShading (product matrix).
    {
      proxygi::Blockers blockers;
      std::vector<float> spheres;
      for (int b = 0; b < 7; ++b)
      {
        const float x = static_cast<float>(random.Uniform(-1, 1)),
                    y = static_cast<float>(random.Uniform(-1, 1)),
                    z = static_cast<float>(random.Uniform(0.2, 1.5)),
                    r = static_cast<float>(random.Uniform(0.1, 0.6));
        blockers.AddSphere(x, y, z, r);
        spheres.insert(spheres.end(), { x, y, z, r });
      }
      const float planeO[3] = { 0, 0, -0.5f }, planeN[3] = { 0, 0, 1 };
      blockers.AddPlane(planeO, planeN);
      const std::vector<float> planes = { 0, 0, -0.5f, 0, 0, 1 };
      std::vector<double> lr(n2), lg(n2), lb(n2);
      for (int i = 0; i < n2; ++i)
      {
        lr[i] = i == 0 ? 3.0 : random.Uniform(-0.5, 0.5);
        lg[i] = i == 0 ? 2.5 : random.Uniform(-0.5, 0.5);
        lb[i] = i == 0 ? 2.0 : random.Uniform(-0.5, 0.5);
      }
      harness.Resources().SetOrder(gl, order);
      harness.Resources().SetBlockers(spheres, planes);
      harness.Resources().SetLight(lr.data(), lg.data(), lb.data());
      harness.Resources().SetSettings(proxygi::gpu::KernelSettings());
      in.assign(8 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        for (int k = 0; k < 3; ++k)
        {
          in[8 * s + k] = static_cast<float>(random.Uniform(-1.5, 1.5));
        }
        in[8 * s + 2] = static_cast<float>(random.Uniform(-0.5, 1.5)); // some inside spheres
        random.Direction(&in[8 * s + 4]);
      }
      const int gOuts = Vec4s(n2);
      const std::string body = "  float g[PGI_SH_N2];\n"
                               "  int used = pgiVisibility(pgiIn0.xyz, pgiIn1.xyz, g);\n"
                               "  pgiOut0 = vec4(pgiShade(pgiIn1.xyz, g), float(used));\n"
                               "  pgiOut1 = vec4(pgiShadeUnshadowed(pgiIn1.xyz), 0.0);\n" +
        Pack("g", n2, 2);
      std::vector<float> transfers;
      const bool ran =
        run("  float h[PGI_SH_N2];\n  pgiDiffuseTransfer(pgiIn1.xyz, h);\n" + Pack("h", n2, 0), 2,
          gOuts);
      transfers.swap(out);
      if (ran && run(body, 2, 2 + gOuts))
      {
        proxygi::SoftShadowSettings settings;
        settings.Order = order;
        const proxygi::SoftShadows shadows(settings);
        const proxygi::EnvironmentShading shading(
          order, lr.data(), lg.data(), lb.data(), proxygi::EnvironmentShading::Path::ProductMatrix);
        Stats visibility, shaded, unshadowed, transfer;
        int sameUsed = 0;
        const int stride = 4 * (2 + gOuts);
        for (int s = 0; s < samples; ++s)
        {
          const float* p = &in[8 * s];
          const float* nrm = &in[8 * s + 4];
          float g[sh::MaxCoefficients], h[sh::MaxCoefficients], rgb[3], flat[3];
          sh::Status status;
          const int used = shadows.Visibility(p, nrm, blockers, g, status);
          shading.Shade(nrm, g, rgb);
          shading.ShadeUnshadowed(nrm, flat);
          sh::DiffuseTransfer(order, nrm[0], nrm[1], nrm[2], h);
          const float* row = &out[stride * s];
          sameUsed += static_cast<int>(row[3]) == used ? 1 : 0;
          for (int c = 0; c < 3; ++c)
          {
            shaded.Add(row[c], rgb[c]);
            unshadowed.Add(row[4 + c], flat[c]);
          }
          for (int i = 0; i < n2; ++i)
          {
            visibility.Add(row[8 + i], g[i]);
            transfer.Add(transfers[4 * gOuts * s + i], h[i]);
          }
        }
        std::printf(
          "  pgiVisibility: same number of blockers for %d of %d receivers\n", sameUsed, samples);
        PGI_CHECK(sameUsed >= samples - 2);
        Report("pgiVisibility vs SoftShadows", order, visibility, 2e-4);
        Report("pgiDiffuseTransfer vs C++", order, transfer, 2e-6);
        Report("pgiShade vs Shade (matrix path)", order, shaded, 2e-4);
        Report("pgiShadeUnshadowed vs C++", order, unshadowed, 2e-6);
      }

      // Planes carried by the light (PLANES_IN_LIGHT): the visibility
      // without the planes in log space, light 1 (a second light, as
      // LightAbovePlanes would build it) and which receivers it serves; the
      // one-bounce unshadowed indirect light (averaged operator, xi) from
      // proxies with albedo and a plane with albedo, against
      // IndirectExitRadiance.
      std::vector<double> ar(n2), ag(n2), ab(n2);
      for (int i = 0; i < n2; ++i)
      {
        ar[i] = i == 0 ? 2.0 : random.Uniform(-0.4, 0.4);
        ag[i] = i == 0 ? 1.8 : random.Uniform(-0.4, 0.4);
        ab[i] = i == 0 ? 1.5 : random.Uniform(-0.4, 0.4);
      }
      harness.Resources().SetLightAbovePlanes(ar.data(), ag.data(), ab.data());
      proxygi::Blockers lit;
      std::vector<float> albedos;
      for (std::size_t b = 0; b < blockers.Spheres(); ++b)
      {
        const float a[3] = { static_cast<float>(random.Uniform(0, 1)),
          static_cast<float>(random.Uniform(0, 1)), b == 3 ? 0.0f : 0.5f };
        lit.AddSphere(blockers.X[b], blockers.Y[b], blockers.Z[b], blockers.R[b], a);
        albedos.insert(albedos.end(), a, a + 3);
      }
      const float planeAlbedo[3] = { 0.6f, 0.5f, 0.4f };
      lit.AddPlane(planeO, planeN, planeAlbedo);
      const proxygi::SecondaryLights secondary(order, lr.data(), lg.data(), lb.data(), &lit);
      std::vector<float> response(3 * n2), planeAlbedos(3 * proxygi::gpu::MaxPlanes, 0.0f);
      for (int i = 0; i < n2; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          response[3 * i + c] = secondary.Response[c * n2 + i];
        }
      }
      std::copy(planeAlbedo, planeAlbedo + 3, planeAlbedos.begin());
      const std::string declarations = proxygi::gpu::IndirectLibrarySource() +
        "\nuniform vec3 pgiTwinAlbedo[" + std::to_string(blockers.Spheres()) + "];\n";
      const std::string lightBody = std::string("  vec3 p = pgiIn0.xyz, n = pgiIn1.xyz;\n") +
        "  float g[PGI_SH_N2], gLog[PGI_SH_N2];\n"
        "  int used = pgiVisibilityOf(p, n, false, g);\n"
        "  pgiOut0 = vec4(pgiShadeOf(1, n, g), float(used));\n"
        "  pgiOut1 = vec4(pgiShadeUnshadowedOf(1, n), pgiAboveEveryPlane(p) ? 1.0 : 0.0);\n"
        "  int usedLog = pgiVisibility(p, n, gLog);\n"
        "  vec4 sum = vec4(0.0);\n"
        "  for (int s = 0; s < pgiNumProxies; ++s)\n"
        "  {\n"
        "    vec4 sphere = texelFetch(pgiProxyTexture,\n"
        "      ivec2(s % pgiProxyTextureWidth, s / pgiProxyTextureWidth), 0);\n"
        "    sum += pgiProxyIndirectTerm(p, n, sphere, pgiTwinAlbedo[s]);\n"
        "  }\n"
        "  pgiOut2 = vec4(usedLog >= 0 ? pgiResolveIndirect(p, n, sum, gLog[0]) : vec3(0.0), "
        "float(usedLog));\n"
        "  pgiOut3 = vec4(pgiPlaneShadowScale(p, n, 0, false), 0.0);\n" +
        Pack("g", n2, 4);
      const auto uniforms = [&](vtkShaderProgram* program)
      {
        program->SetUniform3fv(
          "pgiTwinAlbedo", static_cast<int>(blockers.Spheres()), albedos.data());
        program->SetUniform3fv("pgiResponse", n2, response.data());
        program->SetUniform3fv("pgiPlaneAlbedo", proxygi::gpu::MaxPlanes, planeAlbedos.data());
        program->SetUniformf("pgiPlaneTolerance", 0.0f);
      };
      // Orders 3 and 4 (at 6 the shader is the costliest of the test to
      // compile on llvmpipe, and its parts are checked at 6 above).
      const bool lightRan =
        order <= 4 && harness.Run(order, declarations, lightBody, 2, 4 + gOuts, in, out, uniforms);
      if (lightRan)
      {
        proxygi::SoftShadowSettings settings;
        settings.Order = order;
        const proxygi::SoftShadows shadowsLog(settings);
        settings.PlanesInLogSpace = false;
        const proxygi::SoftShadows shadows(settings);
        const proxygi::EnvironmentShading above(
          order, ar.data(), ag.data(), ab.data(), proxygi::EnvironmentShading::Path::ProductMatrix);
        const proxygi::EnvironmentShading open(
          order, lr.data(), lg.data(), lb.data(), proxygi::EnvironmentShading::Path::ProductMatrix);
        Stats visibility, shaded, unshadowed, bounce, planeScale;
        int scaled = 0;
        int sameUsed = 0, sameAbove = 0;
        const int stride = 4 * (4 + gOuts);
        std::vector<proxygi::SeenBlocker> seen;
        for (int s = 0; s < samples; ++s)
        {
          const float* p = &in[8 * s];
          const float* nrm = &in[8 * s + 4];
          float g[sh::MaxCoefficients], rgb[3], flat[3], indirect[3];
          sh::Status status;
          const int used = shadows.Visibility(p, nrm, lit, g, status);
          above.Shade(nrm, g, rgb);
          above.ShadeUnshadowed(nrm, flat);
          const bool isAbove = lit.AboveEveryPlane(p);
          seen.clear();
          shadowsLog.Visibility(p, nrm, lit, g, status, &seen);
          if (status != sh::Status::Ok)
          {
            seen.clear();
          }
          proxygi::IndirectExitRadiance(
            proxygi::IndirectOperator::Averaged, secondary, lit, seen, g[0], nrm, indirect);
          const float* row = &out[stride * s];
          sameUsed += static_cast<int>(row[3]) == used ? 1 : 0;
          sameAbove += (row[7] > 0.5f) == isAbove ? 1 : 0;
          for (int c = 0; c < 3; ++c)
          {
            shaded.Add(row[c], rgb[c]);
            unshadowed.Add(row[4 + c], flat[c]);
            bounce.Add(row[8 + c], indirect[c]);
          }
          float scale[3];
          proxygi::PlaneShadowScale(shadows, open, lit, 0, p, nrm, scale);
          for (int c = 0; c < 3; ++c)
          {
            planeScale.Add(row[12 + c], scale[c]);
          }
          scaled += scale[0] < 0.99f ? 1 : 0;
          shadows.Visibility(p, nrm, lit, g, status);
          for (int i = 0; i < n2; ++i)
          {
            visibility.Add(row[16 + i], g[i]);
          }
        }
        std::printf("  pgiVisibilityOf (planes in the light): same number of blockers for %d of "
                    "%d receivers; pgiAboveEveryPlane agrees for %d\n",
          sameUsed, samples, sameAbove);
        PGI_CHECK(sameUsed >= samples - 2);
        PGI_CHECK(sameAbove == samples);
        Report("pgiVisibilityOf (no planes)", order, visibility, 2e-4);
        Report("pgiShadeOf(1) vs Shade", order, shaded, 2e-4);
        Report("pgiShadeUnshadowedOf(1) vs C++", order, unshadowed, 2e-6);
        Report("pgiProxyIndirectTerm+Resolve", order, bounce, 2e-4);
        std::printf("  pgiPlaneShadowScale: %d of %d receivers see a shadowed plane point\n",
          scaled, samples);
        PGI_CHECK(scaled > samples / 20);
        Report("pgiPlaneShadowScale vs C++", order, planeScale, 2e-4);
      }
      else if (order <= 4)
      {
        std::printf("FAILED harness: %s\n", harness.GetError().c_str());
        ++pgitest::Failures();
      }
      harness.Resources().SetLightAbovePlanes(nullptr, nullptr, nullptr);
    }

    // The analytic spherical-light L_H (local lights) against
    // AnalyticLightTables::Evaluate (float path): normals, directions all
    // round (some below the horizon, some at the zenith), angular radii
    // over the table.
    {
      harness.Resources().SetAnalyticLightTable(true);
      const sh::AnalyticLightTables& lobes = sh::AnalyticLightTables::Get(order);
      in.assign(8 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        random.Direction(&in[8 * s]);
        random.Direction(&in[8 * s + 4]);
        if (s % 50 == 0)
        {
          std::copy(&in[8 * s], &in[8 * s] + 3, &in[8 * s + 4]); // light at the zenith
        }
        in[8 * s + 3] = static_cast<float>(random.Uniform(0.0, 0.5 * sh::Pi));
      }
      if (run("  float lh[PGI_SH_N2];\n"
              "  pgiAnalyticLight(pgiIn0.xyz, pgiIn1.xyz, pgiIn0.w, lh);\n" +
              Pack("lh", n2, 0),
            2, Vec4s(n2)))
      {
        Stats lh;
        for (int s = 0; s < samples; ++s)
        {
          const float* row = &in[8 * s];
          float ref[sh::MaxCoefficients];
          lobes.Evaluate(row, row + 4, row[3], ref);
          for (int i = 0; i < n2; ++i)
          {
            lh.Add(out[4 * Vec4s(n2) * s + i], ref[i]);
          }
        }
        Report("pgiAnalyticLight vs Evaluate", order, lh, 2e-4);
      }

      // pgiLocalLights against proxygi::LocalLightsRadiance: three sphere
      // lights (one small enough to fall below the table's first node) and
      // two point lights over receivers in a box, unshadowed and shadowed by
      // a visibility both sides build from the same formula.
      proxygi::LocalEmitters lights;
      const double centres[5][3] = { { 0.5, 0.2, 3.0 }, { -2.0, 1.0, 1.5 }, { 1.5, -1.5, 0.8 },
        { 0.0, 0.0, 4.0 }, { -1.0, -2.0, 2.0 } };
      const double radii[5] = { 0.6, 0.02, 0.3, 0.0, 0.0 };
      const double power[5][3] = { { 5, 4, 3 }, { 200, 200, 100 }, { 2, 6, 2 }, { 30, 30, 30 },
        { 10, 0, 5 } };
      std::vector<float> lightUniform(4 * 16, 0.0f), radianceUniform(3 * 16, 0.0f);
      for (int k = 0; k < 5; ++k)
      {
        const bool point = radii[k] == 0.0;
        lights.Add(centres[k], radii[k], power[k], point);
        for (int c = 0; c < 3; ++c)
        {
          lightUniform[4 * k + c] = static_cast<float>(centres[k][c]);
          radianceUniform[3 * k + c] = static_cast<float>(power[k][c]);
        }
        lightUniform[4 * k + 3] = point ? -1.0f : static_cast<float>(radii[k]);
      }
      in.assign(8 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        for (int c = 0; c < 3; ++c)
        {
          in[8 * s + c] = static_cast<float>(random.Uniform(-2.5, 2.5));
        }
        random.Direction(&in[8 * s + 4]);
      }
      const auto visibilityOf = [](int i)
      {
        return (i == 0 ? 0.6f * std::sqrt(4.0f * static_cast<float>(sh::Pi)) : 0.0f) +
          0.2f * std::sin(static_cast<float>(i) + 1.0f);
      };
      const std::string body =
        "  float g[PGI_SH_N2];\n"
        "  for (int i = 0; i < PGI_SH_N2; ++i)\n"
        "  {\n"
        "    g[i] = (i == 0 ? 0.6 * pgiSqrtFourPi : 0.0) + 0.2 * sin(float(i) + 1.0);\n"
        "  }\n"
        "  pgiOut0 = vec4(pgiLocalLights(pgiIn0.xyz, pgiIn1.xyz, false, g), 0.0);\n"
        "  pgiOut1 = vec4(pgiLocalLights(pgiIn0.xyz, pgiIn1.xyz, true, g), 0.0);\n";
      const double minTheta = harness.Resources().GetAnalyticLightMinTheta();
      const auto localUniforms = [&](vtkShaderProgram* program)
      {
        program->SetUniformi("pgiNumLocalLights", 5);
        program->SetUniform4fv("pgiLocalLight", 16, lightUniform.data());
        program->SetUniform3fv("pgiLocalRadiance", 16, radianceUniform.data());
        program->SetUniformf("pgiLobeMinTheta", static_cast<float>(minTheta));
      };
      if (harness.Run(order, "", body, 2, 2, in, out, localUniforms))
      {
        float g[sh::MaxCoefficients];
        for (int i = 0; i < n2; ++i)
        {
          g[i] = visibilityOf(i);
        }
        Stats open, shadowed;
        for (int s = 0; s < samples; ++s)
        {
          const double p[3] = { in[8 * s], in[8 * s + 1], in[8 * s + 2] };
          float litOpen[3], litShadowed[3];
          proxygi::LocalLightsRadiance(lights, lobes, p, &in[8 * s + 4], nullptr, litOpen);
          proxygi::LocalLightsRadiance(lights, lobes, p, &in[8 * s + 4], g, litShadowed);
          for (int c = 0; c < 3; ++c)
          {
            open.Add(out[8 * s + c], litOpen[c]);
            shadowed.Add(out[8 * s + 4 + c], litShadowed[c]);
          }
        }
        Report("pgiLocalLights (unshadowed) vs LocalLightsRadiance", order, open, 2e-4);
        Report("pgiLocalLights (shadowed) vs LocalLightsRadiance", order, shadowed, 2e-4);
      }
      else
      {
        std::printf("FAILED harness: %s\n", harness.GetError().c_str());
        ++pgitest::Failures();
      }
      harness.Resources().SetAnalyticLightTable(false);
    }

    // pgiEncodeSRGB (pgiSRGB.glsl, in the library and the mapper's surface
    // pass) against proxygi::EncodeSRGB: linear values over [-0.1, 1.1]
    // (both clamp), the linear toe included.
    if (order == 4)
    {
      const int count = 4 * samples;
      std::vector<float> linear(count), encoded;
      for (int i = 0; i < count; ++i)
      {
        linear[i] = -0.1f + 1.2f * static_cast<float>(i) / static_cast<float>(count - 1);
      }
      linear[1] = 0.002f; // below the toe's end (0.0031308)
      if (harness.Run(order, "",
            "  pgiOut0 = vec4(pgiEncodeSRGB(pgiIn0.xyz), pgiEncodeSRGB(pgiIn0.www).x);\n", 1, 1,
            linear, encoded))
      {
        Stats srgb;
        for (int i = 0; i < count; ++i)
        {
          srgb.Add(encoded[i], proxygi::EncodeSRGB(linear[i]));
        }
        Report("pgiEncodeSRGB vs EncodeSRGB", order, srgb, 2e-6);
      }
      else
      {
        std::printf("FAILED harness: %s\n", harness.GetError().c_str());
        ++pgitest::Failures();
      }
    }

    // The shadowed bounce's second pass (pgiGISphericalLights.glsl) against
    // ShadowedIndirect::ExitRadiance: 9 and 96 random spherical lights, three
    // overlapping spheres per object (they do not block each other), random
    // radiance SH and reflection ratios, a ground plane in log space or not,
    // per-sphere and per-object blocking; receivers above the plane, some
    // inside lights. 96 lights: more than the 64 the C++ twin caches exps
    // for, three words of blocker-set bits. (Not more on llvmpipe: it ends
    // every loop of an invocation after 65535 iterations in all, which ~130
    // lights seen at once exceed; see Documentation/Rendering.md.) Also
    // w_theta . Lc against SphericalLightRadiance.
    for (int lightCount = 9; order <= 4 && lightCount <= 96; lightCount += 87)
    {
      proxygi::SphericalLights lights;
      lights.Order = order;
      std::vector<float> spheres;
      float centre[3] = { 0, 0, 0 };
      for (int i = 0; i < lightCount; ++i)
      {
        if (i % 3 == 0) // an object: three spheres about a centre
        {
          centre[0] = static_cast<float>(random.Uniform(-1.0, 1.0));
          centre[1] = static_cast<float>(random.Uniform(-1.0, 1.0));
          centre[2] = static_cast<float>(random.Uniform(0.8, 1.3));
        }
        const float x = centre[0] + static_cast<float>(random.Uniform(-0.4, 0.4)),
                    y = centre[1] + static_cast<float>(random.Uniform(-0.4, 0.4)),
                    z = centre[2] + static_cast<float>(random.Uniform(-0.3, 0.3)),
                    r = static_cast<float>(random.Uniform(0.25, 0.6));
        lights.Add(x, y, z, r, i / 3);
        spheres.insert(spheres.end(), { x, y, z, r });
        lights.ReflectionRatio.push_back(static_cast<float>(random.Uniform(0.5, 1.5)));
        for (int c = 0; c < 3; ++c)
        {
          for (int k = 0; k < n2; ++k)
          {
            lights.Radiance.push_back(
              static_cast<float>(k == 0 ? random.Uniform(1.0, 3.0) : random.Uniform(-0.3, 0.3)));
          }
        }
      }
      lights.Finish();
      int intersecting = 0;
      for (char v : lights.Intersects)
      {
        intersecting += v;
      }
      const float planeO[3] = { 0, 0, 0 }, planeN[3] = { 0, 0, 1 };
      proxygi::Blockers ground;
      ground.AddPlane(planeO, planeN);
      harness.Resources().SetBlockers(spheres, { 0, 0, 0, 0, 0, 1 });
      in.assign(12 * samples, 0.0f);
      for (int s = 0; s < samples; ++s)
      {
        float* row = &in[12 * s];
        row[0] = static_cast<float>(random.Uniform(-1.8, 1.8));
        row[1] = static_cast<float>(random.Uniform(-1.8, 1.8));
        row[2] = static_cast<float>(random.Uniform(0.02, 1.8));
        row[3] = s % 2 == 0 ? 1.0f : 0.0f; // planes in log space
        random.Direction(row + 4);
        row[7] = static_cast<float>(s % lightCount); // a light for pgiSphericalLightRadiance
        random.Direction(row + 8);
        row[11] = static_cast<float>(random.Uniform(0.0, 0.5 * sh::Pi));
      }
      const std::string body =
        "  pgiOut0 = vec4(pgiShadowedIndirect(pgiIn0.xyz, pgiIn1.xyz, pgiIn0.w > 0.5), 0.0);\n"
        "  pgiOut1 = vec4(pgiSphericalLightRadiance(pgiIn2.w, pgiIn2.xyz, int(pgiIn1.w)), 0.0);\n";
      const sh::IndirectTables& indirectTables = sh::IndirectTables::Get(order);
      for (bool perObject : { false, true })
      {
        harness.Resources().SetSphericalLights(&lights, perObject);
        if (!harness.Run(
              order, proxygi::gpu::SphericalLightsLibrarySource(lightCount), body, 3, 2, in, out))
        {
          std::printf("FAILED harness: %s\n", harness.GetError().c_str());
          ++pgitest::Failures();
          continue;
        }
        proxygi::SoftShadowSettings settings;
        settings.Order = order;
        const auto blocking = perObject ? proxygi::SphericalLightBlocking::PerObject
                                        : proxygi::SphericalLightBlocking::PerSphere;
        const proxygi::ShadowedIndirect inLog(settings, blocking);
        settings.PlanesInLogSpace = false;
        const proxygi::ShadowedIndirect inLight(settings, blocking);
        proxygi::SphericalLightScratch scratch;
        Stats exit, weight;
        int lit = 0;
        for (int s = 0; s < samples; ++s)
        {
          const float* row = &in[12 * s];
          float rgb[3];
          (row[3] > 0.5f ? inLog : inLight)
            .ExitRadiance(lights, true, nullptr, &ground, row, row + 4, rgb, scratch);
          lit += rgb[0] + rgb[1] + rgb[2] > 0.0f ? 1 : 0;
          const int light = static_cast<int>(row[7]);
          for (int c = 0; c < 3; ++c)
          {
            exit.Add(out[8 * s + c], rgb[c]);
            weight.Add(out[8 * s + 4 + c],
              indirectTables.SphericalLightRadiance(
                row[11], row + 8, &lights.Radiance[(light * 3 + c) * n2]));
          }
        }
        std::printf(
          "  pgiShadowedIndirect (%d lights, %s): %d of %d receivers lit, %d intersecting "
          "pairs\n",
          lightCount, perObject ? "per object" : "per sphere", lit, samples, intersecting / 2);
        PGI_CHECK(lit > samples / 2);
        PGI_CHECK(intersecting > 0);
        Report(perObject ? "pgiShadowedIndirect, per object" : "pgiShadowedIndirect, per sphere",
          order, exit, 2e-4);
        Report("pgiSphericalLightRadiance vs C++", order, weight, 2e-6);
      }
      harness.Resources().SetSphericalLights(nullptr, false);
    }
  }
  return pgitest::Result();
}
