# pvbatch: frame times in ParaView's render view while orbiting, the ProxyGI
# Surface representation against ParaView's plain Surface, all in one run
# (ratios to the plain Surface of this run). The scene of the representation
# test: the bunny (37,706 vertices) on a 2,401-vertex ground, one multiblock,
# 32 k-means proxies, the forest map, order 4, one bounce.
#   pvbatch frame_times.py PLUGIN PYTHONDIR MESH.off ENV.exr FRAMES [SIZE] [OUT.md]
# Modes:
#   surface   ParaView's Surface (VTK lighting)
#   cached    ProxyGI Surface, GI computed once, reused while orbiting
#   recompute ProxyGI Surface with GIAlwaysRecompute: the GI pass every frame
#   moving    ProxyGI Surface with the proxies moved every frame: pipeline,
#             delivery, bake and GI pass every frame
#   imagespace the image-space GI view (its passes run every frame), receiver
#             buffer at 1/2 and 1/4 of the view
import os
import statistics
import sys
import time

import paraview.simple
from paraview.simple import *

plugin, pythondir, mesh, environment = sys.argv[1:5]
frames = int(sys.argv[5]) if len(sys.argv) > 5 else 30
size = int(sys.argv[6]) if len(sys.argv) > 6 else 512
table = sys.argv[7] if len(sys.argv) > 7 else None
sys.path.insert(0, pythondir)
import proxygi  # noqa: F401 (the mapper's Python class)

start = time.perf_counter()
LoadPlugin(plugin, remote=False, ns=globals())
load = time.perf_counter() - start
paraview.simple._DisableFirstRenderCameraReset()

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing", "ParaView"))
import proxygi_scene

# Another mesh than the bunny is placed by its bounds (largest extent 1).
bunny, ground, scene, proxies = proxygi_scene.build(
    globals(), mesh, fit=os.path.basename(mesh) != "bunny00.off")
moved = Transform(Input=proxies)

view = CreateView("RenderView")
display = Show(scene, view)
proxygi_scene.frame(view, [size, size])


def orbit(step=None, on=None):
    on = on or view
    camera = on.GetActiveCamera()
    times = []
    for k in range(frames):
        camera.Azimuth(360.0 / frames)
        if step:
            step(k)
        start = time.perf_counter()
        Render(on)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


results = []
display.SetRepresentationType("Surface")
Render(view)
orbit()  # warm-up
results.append(("surface", "ParaView's Surface", orbit()))

display.SetRepresentationType("ProxyGI Surface")
display.GIProxies = moved
display.GIEnvironmentFileName = environment
display.GIExposure = 0.5
start = time.perf_counter()
Render(view)
first = time.perf_counter() - start
mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
orbit()
passes = mapper.GetNumberOfGIUpdates()
results.append(("cached", "ProxyGI Surface, GI cached", orbit()))
cached_passes = mapper.GetNumberOfGIUpdates() - passes

display.GIAlwaysRecompute = 1
Render(view)
results.append(("recompute", "ProxyGI Surface, GI pass every frame", orbit()))
display.GIAlwaysRecompute = 0


def move(k):
    moved.Transform.Translate = [0.02 * ((k % 10) - 5), 0, 0]


Render(view)
results.append(("moving", "ProxyGI Surface, proxies moved every frame", orbit(move)))

# The image-space view: its passes run every frame by design.
Hide(scene, view)
spaced = CreateView("ProxyGIImageSpaceRenderView")
for source in (bunny, ground):
    Show(source, spaced)
proxygi_scene.frame(spaced, [size, size])
spaced.GIProxies = proxies
spaced.GIEnvironmentFileName = environment
spaced.GIExposure = 0.5
Render(spaced)
orbit(on=spaced)
results.append(("imagespace", "image-space GI view (receivers 1/2)", orbit(on=spaced)))
spaced.GIReceiverScale = 4
Render(spaced)
results.append(("imagespace4", "image-space GI view (receivers 1/4)", orbit(on=spaced)))

surface = results[0][2]
lines = ["| mode | median frame time (ms) | ratio to Surface |", "|---|---|---|"]
for key, what, t in results:
    lines.append("| %s | %.1f | %.2f |" % (what, 1000 * t, t / surface))
info = [
    "mesh %s: %d vertices and a %d-vertex ground, environment %s" % (
        os.path.basename(mesh), bunny.GetDataInformation().GetNumberOfPoints(),
        ground.GetDataInformation().GetNumberOfPoints(), os.path.basename(environment)),
    "plugin load time: %.3f s" % load,
    "first ProxyGI frame (bake and GI pass): %.2f s" % first,
    "GI passes while orbiting cached: %d over %d frames" % (cached_passes, frames),
    "%d frames of %dx%d per mode, median; renderer: %s" % (
        frames, size, size, view.GetRenderWindow().ReportCapabilities().splitlines()[1].strip()
        if view.GetRenderWindow().ReportCapabilities() else "?"),
]
text = "\n".join(lines + [""] + info)
print(text)
if table:
    with open(table, "w") as f:
        f.write(text + "\n")
