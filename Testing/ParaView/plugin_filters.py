# pvbatch: the ProxyGI plugin loaded by path; its readers and filters
# through paraview.simple against the C++ classes' results on the same
# inputs (the proxygi program's sphere set of the same mesh, count, method
# and seed), and bad input that must leave a message and no crash.
#   pvbatch plugin_filters.py PLUGIN PROXYGI MESH.off IMAGE.exr WORKDIR [PYTHONDIR]
# With PYTHONDIR (the proxygi Python package), Reference Illumination is
# checked against vtkPGIReferenceIllumination called directly.
import os
import subprocess
import sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview.simple import *
from proxygi_scene import check, finish
from paraview import servermanager
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

plugin, proxygi, mesh, image, work = sys.argv[1:6]
pythondir = sys.argv[6] if len(sys.argv) > 6 else None
os.makedirs(work, exist_ok=True)
reference = os.path.join(work, "bunny-16-kmeans.vtp")
# The C++ classes' answer: the proxygi program on the same mesh and knobs.
subprocess.run([proxygi, "proxies", mesh, "-n", "16", "--method", "kmeans", "-o", reference],
               check=True, stdout=subprocess.DEVNULL)
import time
start = time.perf_counter()
LoadPlugin(plugin, remote=False, ns=globals())
print("plugin load time: %.3f s" % (time.perf_counter() - start))
check("SphereProxies" in globals() and "ProxyHierarchy" in globals(), "the plugin's filters are in paraview.simple")

# Readers: an .off mesh and an .exr environment by extension.
bunny = OpenDataFile(mesh)
check(bunny is not None and bunny.GetXMLName() == "ProxyGIOFFReader", "OpenDataFile picks the OFF reader")
bunny.UpdatePipeline()
info = bunny.GetDataInformation()
check(info.GetNumberOfPoints() > 30000, "the bunny has %d points" % info.GetNumberOfPoints())
sky = OpenDataFile(image)
sky.UpdatePipeline()
dims = sky.GetDataInformation().GetExtent()
check(dims[1] + 1 == 2 * (dims[3] + 1), "the environment map is 2:1 (%d x %d)" % (dims[1] + 1, dims[3] + 1))

# Sphere Proxies and Proxy Hierarchy, defaults of the C++ classes.
proxies = SphereProxies(Input=bunny)
check(proxies.NumberOfSpheres == 64 and proxies.Method == "Variational" and proxies.Seed == 1,
      "Sphere Proxies defaults match vtkPGISphereSetApproximation")
proxies.NumberOfSpheres = 16
proxies.Method = "KMeans"
proxies.UpdatePipeline()
spheres = servermanager.Fetch(proxies)
reader = vtkXMLPolyDataReader()
reader.SetFileName(reference)
reader.Update()
expected = reader.GetOutput()
check(spheres.GetNumberOfPoints() == expected.GetNumberOfPoints() == 16,
      "16 spheres (%d, C++ %d)" % (spheres.GetNumberOfPoints(), expected.GetNumberOfPoints()))
worst = 0.0
for i in range(min(spheres.GetNumberOfPoints(), expected.GetNumberOfPoints())):
    a, b = spheres.GetPoint(i), expected.GetPoint(i)
    worst = max(worst, max(abs(x - y) for x, y in zip(a, b)))
    ra = spheres.GetPointData().GetArray("Radius").GetTuple1(i)
    rb = expected.GetPointData().GetArray("Radius").GetTuple1(i)
    worst = max(worst, abs(ra - rb))
check(worst <= 1e-6, "centres and radii equal the C++ classes' within 1e-6 (largest difference %.3g)" % worst)

# Occlusion Fit: the same radii as vtkPGIOcclusionFit with the same knobs
# (smaller than the bounding ones), its held-out error lower than before.
fit = OcclusionFit(Input=proxies, Mesh=bunny)
check(fit.Samples == 2048 and fit.Directions == 128 and fit.Iterations == 24 and fit.Seed == 1,
      "Occlusion Fit defaults match vtkPGIOcclusionFit")
fit.Samples = 256
fit.UpdatePipeline()
fitted = servermanager.Fetch(fit)
field = fitted.GetFieldData()
before = field.GetArray("OcclusionErrorBefore").GetTuple1(0)
after = field.GetArray("OcclusionErrorAfter").GetTuple1(0)
print("      occlusion fit: error %.3f -> %.3f" % (before, after))
check(after < 0.5 * before, "Occlusion Fit halves the spheres' occlusion error (%.3f -> %.3f)" % (before, after))
if pythondir:
    sys.path.insert(0, pythondir)
    import proxygi as pgi
    direct_fit = pgi.vtkPGIOcclusionFit()
    direct_fit.SetInputData(spheres)
    direct_fit.SetMeshData(servermanager.Fetch(bunny))
    direct_fit.SetSamples(256)
    direct_fit.Update()
    a = fitted.GetPointData().GetArray("Radius")
    b = direct_fit.GetOutput().GetPointData().GetArray("Radius")
    worst = max(abs(a.GetTuple1(i) - b.GetTuple1(i)) for i in range(a.GetNumberOfTuples()))
    check(a.GetNumberOfTuples() == 16 and worst == 0.0,
          "Occlusion Fit's radii equal vtkPGIOcclusionFit's (largest difference %.3g)" % worst)

tree = ProxyHierarchy(Input=proxies)
tree.UpdatePipeline()
levels = servermanager.Fetch(tree).GetPointData().GetArray("Level")
check(levels is not None and levels.GetRange()[1] >= 1, "Proxy Hierarchy adds levels above the leaves")

# Global Illumination: the receivers and the proxies as two inputs, the
# classes' defaults, against `proxygi shade` (the same filter in C++) on the
# same mesh and spheres.
gi = GlobalIllumination(Input=bunny, Proxies=proxies)
check(gi.Order == 4 and gi.ExpMethod == "HYB" and gi.Indirect == 1 and gi.IndirectMode == "Unshadowed"
      and list(gi.UniformRadiance) == [1, 1, 1] and list(gi.DefaultAlbedo) == [0.8, 0.8, 0.8],
      "Global Illumination defaults match vtkPGIGISettings and vtkPGILighting")
gi.UpdatePipeline()
shaded = servermanager.Fetch(gi)
plan = shaded.GetFieldData().GetAbstractArray("Plan")
check(plan is not None and plan.GetNumberOfValues() >= 3,
      "the Plan field array says what ran (%d lines)" % (plan.GetNumberOfValues() if plan else 0))
if plan is not None:
    for i in range(plan.GetNumberOfValues()):
        print("      plan: " + plan.GetValue(i))
spheresFile = os.path.join(work, "plugin-spheres.vtp")
SaveData(spheresFile, proxy=proxies)
# The receivers with the normals the filter computed: vtkPolyDataNormals sums
# in thread order, so each side computing its own would differ by round-off.
receiversFile = os.path.join(work, "plugin-receivers.vtp")
SaveData(receiversFile, proxy=gi)
cxxFile = os.path.join(work, "cxx-shade.vtp")
subprocess.run([proxygi, "shade", receiversFile, spheresFile, "-o", cxxFile], check=True,
               stdout=subprocess.DEVNULL)
reader.SetFileName(cxxFile)
reader.Modified()
reader.Update()
cxx = reader.GetOutput()


def largest_difference(name):
    a = shaded.GetPointData().GetArray(name)
    b = cxx.GetPointData().GetArray(name)
    if a is None or b is None or a.GetNumberOfValues() != b.GetNumberOfValues():
        return float("inf")
    return max(abs(a.GetValue(i) - b.GetValue(i)) for i in range(a.GetNumberOfValues()))


for name in ("DirectShadowed", "IndirectProxy", "Radiance", "Visibility"):
    d = largest_difference(name)
    check(d <= 1e-6, "%s equals the C++ filter's within 1e-6 (largest difference %.3g)" % (name, d))

# A knob through the settings sub-proxy and a plane through the repeated property.
gi.Order = 3
gi.BlockerPlanes = [0, 0, -0.06, 0, 1, 0, 0.5, 0.5, 0.5]
gi.UpdatePipeline()
shaded3 = servermanager.Fetch(gi)
check(shaded3.GetPointData().GetArray("Visibility").GetNumberOfComponents() == 9,
      "Order 3 reaches the filter (9 SH coefficients)")
plan3 = shaded3.GetFieldData().GetAbstractArray("Plan")
check(any("1 planes" in plan3.GetValue(i) for i in range(plan3.GetNumberOfValues())),
      "the blocker plane reaches the filter")
# The shadowed bounce's own order reaches the filter too.
gi.IndirectMode = "Shadowed"
gi.IndirectOrder = 2
gi.UpdatePipeline()
plan2 = servermanager.Fetch(gi).GetFieldData().GetAbstractArray("Plan")
check(any("the bounce at SH order 2 (shadows at 3)" in plan2.GetValue(i)
          for i in range(plan2.GetNumberOfValues())),
      "IndirectOrder 2 reaches the filter (the bounce at SH order 2)")
# The accuracy budget chooses the knobs and the plan says so.
gi.ErrorBudget = 0.5
gi.UpdatePipeline()
planb = servermanager.Fetch(gi).GetFieldData().GetAbstractArray("Plan")
check(any(planb.GetValue(i).startswith("budget: order ") and "predicted error" in planb.GetValue(i)
          for i in range(planb.GetNumberOfValues())),
      "ErrorBudget reaches the filter (the plan's budget line)")
gi.ErrorBudget = 0.0
gi.IndirectMode = "Unshadowed"
gi.IndirectOrder = 0
gi.EnvironmentFileName = image
gi.UpdatePipeline()
lit = servermanager.Fetch(gi).GetPointData().GetArray("Radiance").GetRange(0)
check(lit[1] > 0.0 and lit[1] != shaded3.GetPointData().GetArray("Radiance").GetRange(0)[1],
      "the environment file lights the bunny (red up to %.3g)" % lit[1])

# Reference Illumination: the Embree ground truth, 8 paths per vertex, the
# same seed as the class called directly on the same receivers.
reference_filter = ReferenceIllumination(Input=bunny, Samples=8, MaxBounces=1)
check(reference_filter.Samples == 8 and reference_filter.Seed == 1 and reference_filter.UseProxies == 0,
      "Reference Illumination's properties (Samples, Seed 1, UseProxies off)")
reference_filter.UpdatePipeline()
traced = servermanager.Fetch(reference_filter)
samples = traced.GetFieldData().GetArray("Samples")
check(traced.GetPointData().GetArray("Radiance") is not None and samples is not None
      and samples.GetTuple1(0) == 8, "Reference Illumination traced 8 samples per vertex")
if pythondir:
    sys.path.insert(0, pythondir)
    import proxygi as pgi
    direct = pgi.vtkPGIReferenceIllumination()
    direct.SetInputData(servermanager.Fetch(bunny))
    direct.SetSamples(8)
    direct.Update()
    a = traced.GetPointData().GetArray("Radiance")
    b = direct.GetOutput().GetPointData().GetArray("Radiance")
    worst = max(abs(a.GetValue(i) - b.GetValue(i)) for i in range(a.GetNumberOfValues())) \
        if a.GetNumberOfValues() == b.GetNumberOfValues() else float("inf")
    check(worst <= 1e-6, "Reference Illumination equals vtkPGIReferenceIllumination within 1e-6 "
          "(largest difference %.3g)" % worst)

# Bad input: a missing file, zero spheres. Messages, no crash, the session goes on.
missing = ProxyGIOFFReader(FileName="/nonexistent/mesh.off")
missing.UpdatePipeline()
check(missing.GetDataInformation().GetNumberOfPoints() == 0, "a missing .off file gives no output")
broken = ProxyGIOpenEXRReader(FileName=mesh)  # not an OpenEXR file
broken.UpdatePipeline()
check(broken.GetDataInformation().GetNumberOfPoints() == 0, "a corrupt .exr file gives no output")
gi.EnvironmentFileName = "/nonexistent/sky.exr"
gi.UpdatePipeline()
check(gi.GetDataInformation().GetNumberOfPoints() == 0, "a missing environment file: an error, no output")
gi.EnvironmentFileName = ""
gi.UpdatePipeline()
check(gi.GetDataInformation().GetNumberOfPoints() > 0, "the session goes on (uniform sky again)")
proxies.NumberOfSpheres = 0  # clamped to 1 by the class
proxies.UpdatePipeline()
check(proxies.GetDataInformation().GetNumberOfPoints() >= 1, "zero spheres asked: the class's bound (1)")

finish()
