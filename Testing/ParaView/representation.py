# pvbatch: the ProxyGI Surface representation. The bunny on a ground, one
# multiblock (two blocks), the bunny's Sphere Proxies casting the shadows,
# the forest map as light: the screenshot against the committed baseline
# (VTK's regression tester), the representation's per-vertex radiance and
# picture against the C++ classes (proxygi Python package) on the same
# inputs, the Global Illumination filter's picture of the same scene, caching (a camera move reuses the GI, new proxies recompute it),
# and bad input (missing .exr, NaN proxies, no proxies) that must leave a
# message and the session going.
#   pvbatch representation.py PLUGIN PYTHONDIR MESH.off ENV.exr BASELINE.png WORKDIR
import os
import sys
import time

plugin, pythondir, mesh, environment, baseline, work = [os.path.abspath(a) for a in sys.argv[1:7]]
sys.path.insert(0, pythondir)
os.makedirs(work, exist_ok=True)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paraview.simple
from paraview.simple import *
import proxygi_scene
from proxygi_scene import check, finish, pixels
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkCommand, vtkFloatArray, vtkOutputWindow
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkRenderingCore import vtkActor
from vtkmodules.vtkTestingRendering import vtkTesting
import proxygi

# Every error and warning, to check that bad input is said.
messages = []


def collect(caller, event, text=None):
    messages.append(str(text) if text is not None else event)


collect.CallDataType = "string0"
output_window = vtkOutputWindow.GetInstance()
for event in (vtkCommand.ErrorEvent, vtkCommand.WarningEvent):
    output_window.AddObserver(event, collect)

start = time.perf_counter()
LoadPlugin(plugin, remote=False, ns=globals())
print("plugin load time: %.3f s" % (time.perf_counter() - start))


bunny, ground, scene, proxies = proxygi_scene.build(globals(), mesh)
view = CreateView("RenderView")
display = Show(scene, view)
# After Show (the first Show resets the camera), and the first Render must
# not reset it either.
paraview.simple._DisableFirstRenderCameraReset()
proxygi_scene.frame(view)
check("ProxyGI Surface" in display.GetProperty("Representation").Available,
      "ProxyGI Surface is offered for the multiblock")
# Offered for the other geometry representations too (image, unstructured).
for what, other in (("an image", OpenDataFile(environment)),
                    ("an unstructured grid", Clip(Input=bunny))):
    other_display = Show(other, view)
    check("ProxyGI Surface" in other_display.GetProperty("Representation").Available,
          "ProxyGI Surface is offered for %s (%s)" % (what, other.GetDataInformation().GetDataSetTypeAsString()))
    Hide(other, view)
    Delete(other)
display.SetRepresentationType("ProxyGI Surface")
display.GIProxies = proxies
display.GIEnvironmentFileName = environment
check(display.GIOrder == 4 and display.GIIndirect == 1 and display.GIAutomaticProxies == 32
      and display.GIExposure == 1.0, "defaults match vtkPGIGISettings and the mapper")
display.GIExposure = 0.5  # the forest map is brighter than the image's range
start = time.perf_counter()
Render(view)
print("first frame (proxies, bake, GI): %.2f s" % (time.perf_counter() - start))
representation = display.GetClientSideObject().GetActiveRepresentation()
mapper = representation.GetActor().GetMapper()
check(mapper.IsA("vtkPGIGICompositePolyDataMapper"), "the representation draws with %s" % mapper.GetClassName())
status = mapper.GetGIStatus()
print("      status: " + status)
check("32 proxies" in status and mapper.GetNumberOfGIUpdates() >= 2,
      "the GI pass ran for both blocks' helpers with the 32 proxies")

screenshot = os.path.join(work, "ProxyGISurface.png")
SaveScreenshot(screenshot, view, ImageResolution=[320, 240])
tester = vtkTesting()
tester.AddArgument("-V")
tester.AddArgument(os.path.abspath(baseline))
tester.AddArgument("-T")
tester.AddArgument(work)
result = tester.RegressionTest(screenshot, 0.02)
check(result == vtkTesting.PASSED, "the screenshot matches the baseline (VTK's regression tester, threshold 0.02)")

# Caching: a camera move re-renders only; new proxies recompute.
updates = mapper.GetNumberOfGIUpdates()
camera = GetActiveCamera()
camera.Azimuth(20)
Render(view)
check(mapper.GetNumberOfGIUpdates() == updates, "a camera move reuses the GI (%d passes)" % updates)
camera.Azimuth(-20)
Render(view)
# A knob and the light recompute it.
for prop, value, back, said in (("GIOrder", 3, 4, "order 3"), ("GIEnvironmentScale", 2.0, 1.0, "scene")):
    updates = mapper.GetNumberOfGIUpdates()
    setattr(display, prop, value)
    Render(view)
    check(mapper.GetNumberOfGIUpdates() > updates and said in mapper.GetGIStatus(),
          "%s = %s recomputes the GI (%s)" % (prop, value, mapper.GetGIStatus().split(" | ")[0]))
    setattr(display, prop, back)
    Render(view)

# The accuracy budget: the mappers choose among the model's GPU-mapper
# candidates and say so; none: the order as set again.
display.GIErrorBudget = 0.5
Render(view)
check("budget: GPU mapper: order " in mapper.GetGIStatus(),
      "GIErrorBudget chooses a mapper candidate (%s)" % mapper.GetGIStatus().split("; budget: ")[-1][:80])
display.GIErrorBudget = 0.0
Render(view)
check("budget:" not in mapper.GetGIStatus() and "order 4" in mapper.GetGIStatus(),
      "no budget: the order as set")

# The C++ classes on the same inputs: the blocks the representation drew,
# its proxies and the forest map, through vtkPGIGIPolyDataMapper (one
# actor per block) in a window of the same size and camera.
drawn = mapper.GetInputDataObject(0, 0)
blocks = []
iterator = drawn.NewIterator()
iterator.InitTraversal()
while not iterator.IsDoneWithTraversal():
    blocks.append(iterator.GetCurrentDataObject())
    iterator.GoToNextItem()
check(len(blocks) == 2, "two blocks drawn (%d)" % len(blocks))
spheres = vtkPolyData()
spheres.DeepCopy(mapper.GetProxies())
light = proxygi.vtkPGILighting()
light.SetEnvironmentFileName(environment)
# In the view's own renderer (same context, same camera), the representation hidden.
Hide(scene, view)
renderer = view.GetRenderer()
plain, actors = [], []
for block in blocks:
    one = proxygi.vtkPGIGIPolyDataMapper()
    one.SetInputData(block)
    one.SetProxies(spheres)
    one.SetLighting(light)
    one.SetExposure(0.5)
    actor = vtkActor()
    actor.SetMapper(one)
    renderer.AddActor(actor)
    plain.append(one)
    actors.append(actor)
Render(view)
cxx_picture = os.path.join(work, "ProxyGISurface-cxx.png")
SaveScreenshot(cxx_picture, view, ImageResolution=[320, 240])
worst = 0.0
for block, one in zip(blocks, plain):
    ours, theirs = vtkFloatArray(), vtkFloatArray()
    if not (mapper.GetPerVertexResults(block, ours) and one.GetPerVertexResults(theirs)) \
            or ours.GetNumberOfValues() != theirs.GetNumberOfValues():
        worst = float("inf")
        break
    for i in range(ours.GetNumberOfValues()):
        worst = max(worst, abs(ours.GetValue(i) - theirs.GetValue(i)))
check(worst <= 1e-6, "per-vertex radiance equals the C++ mapper's within 1e-6 (largest difference %.3g)" % worst)
compare = vtkTesting()
compare.AddArgument("-V")
compare.AddArgument(cxx_picture)
compare.AddArgument("-T")
compare.AddArgument(work)
result = compare.RegressionTest(screenshot, 0.02)
check(result == vtkTesting.PASSED, "the representation's picture agrees with the C++ mapper's (threshold 0.02)")
# Their GL objects go while the view's context is alive.
for actor in actors:
    actor.ReleaseGraphicsResources(view.GetRenderWindow())
    renderer.RemoveActor(actor)
del plain, actors, actor, one
Show(scene, view)
Render(view)

# The CPU filter on the same scene: Global Illumination on each block with
# the same proxies and light, coloured by its RadianceSRGB bytes (Map Scalars
# off) in a view of the same camera: the picture the representation drew.
cpu_view = CreateView("RenderView")
shaded = []
for block in (bunny, ground):
    lit = GlobalIllumination(Input=block, Proxies=proxies, EnvironmentFileName=environment,
                             ColorExposure=0.5)
    shown = Show(lit, cpu_view)
    ColorBy(shown, ("POINTS", "RadianceSRGB"))
    shown.MapScalars = 0
    shown.Ambient, shown.Diffuse = 1.0, 0.0  # the colours as they are, unlit
    shaded.append(lit)
proxygi_scene.frame(cpu_view)
Render(cpu_view)
cpu_picture = os.path.join(work, "GlobalIllumination-filter.png")
SaveScreenshot(cpu_picture, cpu_view, ImageResolution=proxygi_scene.SIZE)
difference = abs(pixels(cpu_picture) - pixels(screenshot))
check(difference.mean() < 1.0,
      "the Global Illumination filter's picture against the representation's: mean difference "
      "%.3f of 255 (largest %d)" % (difference.mean(), difference.max()))
Delete(cpu_view)
del cpu_view
SetActiveView(view)

# New proxies recompute the GI; no proxies and no automatic ones: no shadows.
updates = mapper.GetNumberOfGIUpdates()
proxies.NumberOfSpheres = 16
Render(view)
check(mapper.GetNumberOfGIUpdates() > updates and "16 proxies" in mapper.GetGIStatus(),
      "new proxies recompute the GI: " + mapper.GetGIStatus())

# Bad input: each leaves a message and the session going.


def said(text):
    found = [m for m in messages if text in m]
    return found[0].strip().splitlines()[-1] if found else None


del messages[:]
display.GIEnvironmentFileName = "/nonexistent/sky.exr"
Render(view)
check(said("cannot read the environment file") is not None,
      "a missing .exr is said (%s)" % said("cannot read"))
display.GIEnvironmentFileName = mesh  # not an OpenEXR file
del messages[:]
Render(view)
check(said("cannot read the environment file") is not None,
      "a corrupt .exr is said (%s)" % said("cannot read"))
display.GIEnvironmentFileName = environment
nan = ProgrammableSource(OutputDataSetType="vtkPolyData")
nan.Script = """
from vtkmodules.vtkCommonCore import vtkPoints, vtkDoubleArray
out = self.GetPolyDataOutput()
points = vtkPoints()
radius = vtkDoubleArray()
radius.SetName("Radius")
for x, r in ((0.0, 0.3), (float("nan"), 0.2)):
    points.InsertNextPoint(x, 0.0, 0.5)
    radius.InsertNextValue(r)
out.SetPoints(points)
out.GetPointData().AddArray(radius)
"""
display.GIProxies = nan
del messages[:]
Render(view)
check(said("Proxies ignored") is not None and "0 proxies" in mapper.GetGIStatus(),
      "NaN proxies are said and ignored (%s)" % said("Proxies ignored"))
sky = OpenDataFile(environment)
del messages[:]
try:
    display.GIProxies = sky  # an image, not sphere proxies
    Render(view)
except Exception as error:
    messages.append(str(error))
check(len(messages) > 0, "proxies of the wrong type are said (%s)"
      % (messages[0].strip().splitlines()[-1] if messages else "nothing"))
display.GIProxies = None
display.GIAutomaticProxies = 0
Render(view)
status = mapper.GetGIStatus()
check("0 proxies" in status and "SHEXP" in status, "no proxies: GI without shadows (%s)" % status)
display.GIAutomaticProxies = 16
Render(view)
check("16 proxies" in mapper.GetGIStatus(), "automatic proxies fitted to the surface: " + mapper.GetGIStatus())
SaveScreenshot(os.path.join(work, "ProxyGISurface-automatic.png"), view, ImageResolution=[320, 240])
Render(view)
check(mapper.GetNumberOfGIUpdates() > 0 and "16 proxies" in mapper.GetGIStatus(), "the session goes on")

# Drop our references to the view's objects before ParaView tears it down.
del mapper, representation, compare, tester
finish()
