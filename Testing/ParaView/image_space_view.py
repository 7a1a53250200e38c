# pvbatch: the "Render View (ProxyGI image-space GI)" view: ParaView's render
# view with vtkPGIImageSpaceGIPass as its render pass. The representation
# test's scene (bunny and ground as two plain Surface displays of albedo
# 0.8, the bunny's Sphere Proxies, the forest map): the screenshot against a
# committed baseline, and against the ProxyGI Surface representation's
# baseline (per-vertex GI of the same scene: the same formulas, so the mean
# pixel difference is small); the pass's knobs reach it; no proxies.
#   pvbatch image_space_view.py PLUGIN MESH.off ENV.exr BASELINE.png PER_VERTEX.png WORKDIR
import os
import sys
import time

plugin, mesh, environment, baseline, per_vertex, work = [os.path.abspath(a) for a in sys.argv[1:7]]
os.makedirs(work, exist_ok=True)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paraview.simple
from paraview.simple import *
import proxygi_scene
from proxygi_scene import check, finish, pixels
from vtkmodules.vtkTestingRendering import vtkTesting

start = time.perf_counter()
LoadPlugin(plugin, remote=False, ns=globals())
print("plugin load time: %.3f s" % (time.perf_counter() - start))
bunny, ground, scene, proxies = proxygi_scene.build(globals(), mesh)
view = CreateView("ProxyGIImageSpaceRenderView")
for source in (bunny, ground):
    Show(source, view).DiffuseColor = [0.8, 0.8, 0.8]  # the albedo of the per-vertex run
paraview.simple._DisableFirstRenderCameraReset()
proxygi_scene.frame(view)
check(view.GIReceiverScale == "2" and view.GIOrder == 4 and view.GIUpsampling == "Bilateral",
      "defaults match vtkPGIImageSpaceGIPass (%s, %s, %s)" % (view.GIReceiverScale, view.GIOrder, view.GIUpsampling))
view.GIProxies = proxies
view.GIEnvironmentFileName = environment
view.GIExposure = 0.5
start = time.perf_counter()
Render(view)
print("first frame (proxies, bake, passes): %.2f s" % (time.perf_counter() - start))
view.UpdatePropertyInformation()
status = view.GetPropertyValue("GIStatus")
print("      status: " + status)
check("32 proxies" in status and "SHEXP" in status and "1/2" in status,
      "the pass ran with the 32 proxies at 1/2 resolution")

screenshot = os.path.join(work, "ProxyGIImageSpaceView.png")
SaveScreenshot(screenshot, view, ImageResolution=proxygi_scene.SIZE)
tester = vtkTesting()
for argument in ("-V", baseline, "-T", work):
    tester.AddArgument(argument)
check(tester.RegressionTest(screenshot, 0.02) == vtkTesting.PASSED,
      "the screenshot matches the baseline (VTK's regression tester, threshold 0.02)")
difference = abs(pixels(screenshot) - pixels(per_vertex))
check(difference.mean() < 2.0,
      "per-pixel against per-vertex GI of the same scene: mean difference %.2f of 255 (largest %d, "
      "at silhouettes)" % (difference.mean(), difference.max()))

view.GIReceiverScale = 4
Render(view)
view.UpdatePropertyInformation()
check("1/4" in view.GetPropertyValue("GIStatus"), "GI Receiver Scale 4 reaches the pass")
view.GIProxies = None
Render(view)
view.UpdatePropertyInformation()
status = view.GetPropertyValue("GIStatus")
check("0 proxies" in status, "no proxies: " + status)

finish()
