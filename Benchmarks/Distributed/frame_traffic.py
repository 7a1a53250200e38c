# The bytes and seconds of one frame under MPI pvbatch (frame_traffic.sh runs
# it with FRAMES = 0 and FRAMES = K and takes the difference of the ranks'
# mpi-traffic counts, so set-up and shut-down cancel).
#   mpiexec -np N pvbatch --mpi frame_traffic.py PLUGIN PYTHONDIR MESH.off ENV.exr MODE FRAMES
# MODE: filter (the CPU filter's colours, IceT only), surface (ProxyGI
# Surface), image-space (the image-space view), moving (ProxyGI Surface, the
# proxies moved every frame by a Transform after their gather).
import os
import sys
import time

plugin, pythondir, mesh, environment = [os.path.abspath(a) for a in sys.argv[1:5]]
mode, frames = sys.argv[5], int(sys.argv[6])
sys.path.insert(0, pythondir)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing",
                                "ParaView"))
import paraview.simple
from paraview.simple import *
import proxygi_scene

LoadPlugin(plugin, remote=False, ns=globals())
_, _, receivers, proxies = proxygi_scene.redistributed(globals(), mesh)
paraview.simple._DisableFirstRenderCameraReset()
moved = None
if mode == "filter":
    view = CreateView("RenderView")
    lit = GlobalIllumination(Input=receivers, Proxies=proxies, EnvironmentFileName=environment)
    shown = Show(lit, view)
    ColorBy(shown, ("POINTS", "RadianceSRGB"))
    shown.MapScalars = 0
elif mode in ("surface", "moving"):
    view = CreateView("RenderView")
    surface = Show(receivers, view)
    surface.SetRepresentationType("ProxyGI Surface")
    if mode == "moving":
        moved = Transform(Input=proxies)
        moved.Transform.Translate = [0.0, 0.0, 0.0]
        surface.GIProxies = moved
    else:
        surface.GIProxies = proxies
    surface.GIEnvironmentFileName = environment
elif mode == "image-space":
    view = proxygi_scene.image_space_view(receivers, proxies, environment)
proxygi_scene.frame(view)
Render(view)
start = time.perf_counter()
for f in range(frames):
    view.CameraPosition = [2.1 + 0.01 * (f + 1), -2.5, 1.4]
    if moved is not None:
        moved.Transform.Translate = [0.002 * (f + 1), 0.0, 0.0]
    Render(view)
if frames:
    print("frame-time: %s %.4f s per frame (%d frames)" % (mode, (time.perf_counter() - start) / frames,
                                                          frames))
