// proxygi render --analytic: the built-in analytic scene, a sphere floating over a plane
// under a uniform white sky, plane shaded per pixel with SH soft shadows
// (tabulated cap log, SH exp, diffuse transfer), compared with the closed
// form E = pi (1 - (r/d)^2 cos(beta)), valid because the sphere never dips
// below any plane point's horizon when its height >= its radius.
#include "proxygiCommands.h"
#include "proxygiImage.h"
#include "proxygiProgress.h"

#include "pgiSHExp.h"
#include "pgiSHTables.h"
#include "pgiSHZonal.h"

#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkSMPTools.h>
#include <vtkUnsignedCharArray.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace proxygi
{
namespace cli
{
using namespace proxygi::sh;

namespace
{
const char* Usage = R"(usage: proxygi render [scene.json] [options]

Renders a scene (default: the bunny over a ground plane under the forest map)
with per-vertex SH soft shadows, one-bounce indirect light from the proxies
and planes, and local lights, on the GPU (vtkPGIGIPolyDataMapper; EGL without
a display) or on the CPU (vtkPGIGlobalIllumination); prints what ran, the time
per stage and the per-vertex error against the Embree reference of the same
scene (computed once, cached). One set of GI settings drives every mode; a
setting the mode's backend cannot honour is printed as "not honoured: ...",
an option a mode has no use for as "note: ... does not apply".

  -o FILE             output PNG (default proxygi-render.png)
  --cache DIR         proxies and references are cached here (proxygi-cache)
  --error E           accuracy budget: the fastest settings predicted to stay
                      within E of Embree (5% or 0.05; relative RMSE per vertex)
  --time T            time budget: the most accurate settings predicted to
                      shade in T (200ms or 0.2s); with --error, the fastest
                      meeting both. Either one chooses the order, the bounce's
                      order and model, the spheres and the self-visibility
                      among those the model holds (the knobs given stay as
                      given) and, with --mode auto, the route: the CPU filter
                      or the GPU mapper (the latter where the model's GPU times
                      are of this kind of GL renderer); --mode vertex or gpu
                      keeps that route. It prints the prediction, what it
                      traded away, and the measured result
  --budget-model FILE the model from 'proxygi calibrate' (default: the one
                      that ships, measured on a 2-core machine)
  --check N           check the budget's choice against Embree at N samples
                      per vertex (16 is enough: its noise is taken out; a GPU
                      mapper's choice is run once to read it back): the
                      model's errors and times for this scene are scaled by
                      what the check finds and, if that changes the choice
                      (the route too, with --mode auto), the scene is shaded
                      again with the new one and the better of the two kept
  --order N           SH order 2..8 (default 6 in vertex mode, 4 in the GPU
                      modes; the GPU mapper runs up to 6, the image-space
                      pass up to 4, and says so)
  --method M          exp method: HYB (default), OL, PS*, PS (the GPU modes
                      run HYB and say so)
  --spheres N         proxy spheres per mesh (default 64)
  --proxy-fit F       the spheres' radii: occlusion (default: the bounding
                      spheres scaled so that they block what the mesh blocks,
                      by Embree rays around it, vtkPGIOcclusionFit; fitted
                      once and cached) or bounding (every point of the mesh
                      inside a sphere)
  --indirect M        one-bounce light: shadowed (spherical lights, Guerrero
                      2008; default in vertex and gpu), unshadowed (Sloan 2007;
                      default and only one in image-space), off
  --blocking B        the shadowed bounce's spherical lights are blocked per
                      sphere (default) or per object (the lights of one
                      object never block each other; vtkPGIGISettings::
                      SphericalLightBlocking)
  --indirect-order N  the shadowed bounce's SH order (vertex mode; default 4,
                      0: --order); below --order it is cheaper: the bounce is
                      smooth, its second pass costs ~N^4 per light and vertex
  --hierarchy DEG     hierarchy cuts (vertex mode): receiver clusters use the
                      cut whose spheres subtend less than DEG (default 25 in
                      vertex mode, 0 = all leaves; 0 in the GPU modes)
  --self-visibility N vertex mode: each mesh's own shadows from N Embree rays
                      per vertex, traced once and cached (vtkPGISelfVisibility),
                      instead of its own proxies under the self-shadow rules
                      (default 256; 0: the rules)
  --bright-lights on|off  vertex mode: the map's compact peaks (a sun, lamps)
                      taken out as distant lights with their own sharp shadows
                      (default on; the plan says what was taken and why)
  --bright-shadows R  their shadows: rays (default: against the scene's meshes,
                      Embree) or proxies (the light's cone against the spheres)
  --bright-rays N     rays per light and vertex (default 16: the penumbra)
  --plane-directions N  vertex mode: directions each vertex averages the
                      ground's shadowed light over for its bounce (default
                      64; 0: one ground point, the GPU's way)
  --background B      map (default: the environment behind the scene, at the
                      picture's exposure, as Embree's image shows it) or none
  --size WxH          image size (default: the scene's)
  --reference-spp N   samples per vertex of the reference (default 1024)
  --exposure E        tone-mapping scale (default: 95th percentile to 0.8)
  --no-error          skip the reference and the error
  --vtp PREFIX        also write each object's per-vertex arrays to PREFIX-<name>.vtp
  --mode M            auto (default): vertex where the GL renderer is a
                      software one (llvmpipe, softpipe, swrast: there the CPU
                      filter is the faster route and GL only draws), else gpu;
                      gpu: per-vertex GI on the GPU (the GI mapper;
                      every leaf sphere, no hierarchy cuts);
                      vertex: per-vertex radiance from the CPU filter (with the
                      plan and the direct light's own error);
                      image-space: the GPU image-space pass (receiver buffer,
                      splatting, HYB exp, indirect, bilateral upsampling), with
                      per-pass times
  --scale N           image-space receiver buffer at 1/N of the window (1, 2, 4, 8; 2)
  --pixel-error       also compare the picture per pixel with Embree's image
                      (always on in image-space mode)
  --pixel-reference-spp N   samples per pixel of that image (default 256)
  --reference-png FILE      write that image, tone-mapped like the render

proxygi render --analytic [options]

Renders the built-in analytic scene (a sphere of radius R at height H over a
plane, uniform sky of radiance 1, diffuse albedo A), seen from above. The
plane's radiance comes from SH soft shadows; the closed form gives its error.

  -o FILE          output PNG (default proxygi-render.png)
  --size N         image width and height in pixels (default 512)
  --order N        SH order 2..8 (default 4)
  --method M       exp method: HYB (default), OL, PS*, PS
  --degree P       series degree for PS and PS* (default 2)
  --radius R       sphere radius (default 1)
  --height H       sphere centre height, H >= R (default 1.5)
  --albedo A       diffuse albedo of the plane (default 0.8)
  --extent W       the image spans [-W, W]^2 of the plane (default 4)
)";

struct Scene
{
  double Radius = 1.0, Height = 1.5, Albedo = 0.8, Extent = 4.0;
};

} // namespace

int RunRender(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  if (Flag(args, "--analytic"))
  {
    if (!KnownOptions(args, "render",
          { "--size", "--order", "--degree", "--radius", "--height", "--albedo", "--extent", "-o",
            "--method" },
          { "--analytic", "--help" }))
    {
      return 2;
    }
    return RunRenderAnalytic(args);
  }
  if (!KnownOptions(args, "render",
        { "-o", "--reference-png", "--mode", "--budget-model", "--check", "--error", "--time",
          "--order", "--spheres", "--reference-spp", "--method", "--indirect", "--hierarchy",
          "--scale", "--self-visibility", "--bright-lights", "--background", "--bright-shadows",
          "--bright-rays", "--plane-directions", "--indirect-order", "--proxy-fit", "--blocking",
          "--pixel-reference-spp", "--exposure", "--cache", "--vtp", "--size" },
        { "--no-error", "--pixel-error", "--help" }))
  {
    return 2;
  }
  return RunRenderScene(args, Positional(args, { "--no-error", "--analytic", "--pixel-error" }));
}

int RunRenderAnalytic(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  bool ok = true;
  Scene scene;
  const int size = static_cast<int>(NumberOption(args, "--size", 512, ok));
  const int order = static_cast<int>(NumberOption(args, "--order", 4, ok));
  const int degree = static_cast<int>(NumberOption(args, "--degree", 2, ok));
  scene.Radius = NumberOption(args, "--radius", scene.Radius, ok);
  scene.Height = NumberOption(args, "--height", scene.Height, ok);
  scene.Albedo = NumberOption(args, "--albedo", scene.Albedo, ok);
  scene.Extent = NumberOption(args, "--extent", scene.Extent, ok);
  const std::string output = Option(args, "-o", "proxygi-render.png");
  const std::string methodName = Option(args, "--method", "HYB");
  if (!ok || !HasExtension("render", "-o", output, { ".png" }))
  {
    return 2;
  }
  ExpOptions expOptions;
  expOptions.Degree = degree;
  if (methodName == "HYB")
  {
    expOptions.Method = ExpMethod::Hybrid;
  }
  else if (methodName == "OL")
  {
    expOptions.Method = ExpMethod::OL;
  }
  else if (methodName == "PS*")
  {
    expOptions.Method = ExpMethod::PSStar;
  }
  else if (methodName == "PS")
  {
    expOptions.Method = ExpMethod::PS;
  }
  else
  {
    vtkLogF(ERROR, "proxygi render: unknown --method '%s'", methodName.c_str());
    return 2;
  }
  if (size < 8 || size > 8192 || order < 2 || order > MaxOrder || !(scene.Radius > 0.0) ||
    !(scene.Height >= scene.Radius) || !(scene.Albedo >= 0.0 && scene.Albedo <= 1.0) ||
    !(scene.Extent > 0.0) || degree < 1 || degree > 16)
  {
    vtkLogF(ERROR,
      "proxygi render: need 8 <= size <= 8192, 2 <= order <= %d, radius > 0, height >= radius, "
      "0 <= albedo <= 1, extent > 0, 1 <= degree <= 16",
      MaxOrder);
    return 2;
  }

  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const CapTables& tables = CapTables::Get(order);
  const auto t1 = Clock::now();

  // Uniform sky: L * g = g, so radiance = albedo * H(N) . g, N = +z.
  const int n2 = NumCoefficients(order);
  float transfer[MaxCoefficients];
  DiffuseTransfer(order, 0.0f, 0.0f, 1.0f, transfer);
  for (int i = 0; i < n2; ++i)
  {
    transfer[i] *= static_cast<float>(scene.Albedo);
  }

  const vtkIdType pixels = static_cast<vtkIdType>(size) * size;
  std::vector<float> shaded(pixels), exact(pixels);
  std::vector<unsigned char> isPlane(pixels);
  std::atomic<int> failures(0);
  const double cx = 0.0, cy = 0.0, cz = scene.Height, r = scene.Radius;
  const double pixelSize = 2.0 * scene.Extent / size;

  const auto t2 = Clock::now();
  vtkSMPTools::For(0, pixels,
    [&](vtkIdType begin, vtkIdType end)
    {
      float zh[MaxOrder], f[MaxCoefficients], g[MaxCoefficients];
      for (vtkIdType p = begin; p < end; ++p)
      {
        const vtkIdType row = p / size, column = p % size;
        const double x = -scene.Extent + (static_cast<double>(column) + 0.5) * pixelSize;
        const double y = scene.Extent - (static_cast<double>(row) + 0.5) * pixelSize;
        const double dx = cx - x, dy = cy - y, dz = cz;
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (dx * dx + dy * dy < r * r)
        {
          // Seen from above, the sphere's top: open sky over its upper
          // hemisphere, E = pi (1 + n_z) / 2. Not part of the comparison.
          const double nz = std::sqrt(1.0 - (dx * dx + dy * dy) / (r * r));
          shaded[p] = exact[p] = static_cast<float>(scene.Albedo * 0.5 * (1.0 + nz));
          isPlane[p] = 0;
          continue;
        }
        const double d = std::sqrt(d2);
        const float theta = static_cast<float>(std::asin(r / d));
        tables.CapLog(theta, zh);
        RotateScaledZonal(order, zh, float(dx / d), float(dy / d), float(dz / d), f);
        if (Exp(order, f, g, expOptions) != Status::Ok)
        {
          ++failures;
        }
        shaded[p] = Dot(n2, transfer, g);
        exact[p] = static_cast<float>(scene.Albedo * (1.0 - (r * r / d2) * (dz / d)));
        isPlane[p] = 1;
      }
    });
  const auto t3 = Clock::now();

  double sumSq = 0.0, sumRef = 0.0, maxErr = 0.0;
  vtkIdType planePixels = 0;
  vtkNew<vtkImageData> image;
  image->SetDimensions(size, size, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    if (isPlane[p])
    {
      const double e = static_cast<double>(shaded[p]) - exact[p];
      sumSq += e * e;
      sumRef += static_cast<double>(exact[p]) * exact[p];
      maxErr = std::max(maxErr, std::fabs(e));
      ++planePixels;
    }
    // vtkImageData rows run bottom-up; pixel rows were laid out top-down.
    const vtkIdType row = size - 1 - p / size, col = p % size;
    unsigned char* out = rgb + 3 * (row * size + col);
    out[0] = out[1] = out[2] = ToSRGB8(shaded[p]);
  }
  if (!WritePNG(image, output))
  {
    vtkLogF(ERROR, "proxygi render: could not write %s", output.c_str());
    return 1;
  }

  const auto ms = [](Clock::time_point a, Clock::time_point b)
  { return std::chrono::duration<double, std::milli>(b - a).count(); };
  const double shadeMs = ms(t2, t3);
  std::printf("scene: built-in analytic - sphere r=%g at height %g over a plane, uniform sky "
              "L=1, albedo %g\n",
    scene.Radius, scene.Height, scene.Albedo);
  std::printf("settings: SH order %d, exp %s, %dx%d pixels (%lld plane receivers), %d threads\n",
    order, ExpMethodName(expOptions.Method), size, size, static_cast<long long>(planePixels),
    vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("time: tables %.1f ms (built once), shading %.1f ms (%.0f ns per receiver)\n",
    ms(t0, t1), shadeMs, 1e6 * shadeMs / std::max<vtkIdType>(1, planePixels));
  std::printf("error against the closed form: relative RMSE %.3f%%, max |error| %.4f "
              "(radiance units)\n",
    100.0 * std::sqrt(sumSq / std::max(sumRef, 1e-300)), maxErr);
  std::printf("wrote %s\n", output.c_str());
  if (failures > 0)
  {
    std::fprintf(
      stderr, "proxygi render: %d receivers reported non-finite SH input\n", failures.load());
    return 1;
  }
  return 0;
}

} // namespace cli
} // namespace proxygi
