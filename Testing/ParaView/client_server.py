# pvpython client of a 2-rank MPI pvserver (client_server.sh starts it): the
# bunny scene redistributed over the server's ranks, Global Illumination and
# ProxyGI Surface drawn with the geometry delivered to the client (ParaView's
# default for small data) and drawn on the server (remote rendering).
#   pvpython client_server.py PLUGIN MESH.off ENV.exr WORKDIR PORT
# Checked: the server shades every piece (points on the cuts counted on
# both ranks), and each picture is the same whichever process draws it (a
# ProxyGI Surface the client drew without the server's light once came out
# white and unshadowed), the image-space view included.
import os
import sys

plugin, mesh, environment, work = [os.path.abspath(a) for a in sys.argv[1:5]]
port = int(sys.argv[5])
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paraview.simple
from paraview.simple import *
import proxygi_scene
from proxygi_scene import check, finish, pixels

Connect("localhost", port)
LoadPlugin(plugin, remote=False, ns=globals())
LoadPlugin(plugin, remote=True, ns=globals())
_, _, receivers, proxies = proxygi_scene.redistributed(globals(), mesh)
lit = GlobalIllumination(Input=receivers, Proxies=proxies, EnvironmentFileName=environment)
lit.UpdatePipeline()
receivers.UpdatePipeline()
shaded = lit.GetDataInformation().GetNumberOfPoints()
whole = receivers.GetDataInformation().GetNumberOfPoints()
print("server: %d receivers over its ranks, %d shaded" % (whole, shaded))
check(shaded == whole and shaded > 2401, "the server's ranks shade every piece")

paraview.simple._DisableFirstRenderCameraReset()
settings = GetSettingsProxy("RenderViewSettings")
os.makedirs(work, exist_ok=True)


def pictures(where, threshold):
    settings.RemoteRenderThreshold = threshold
    view = CreateView("RenderView")
    shown = Show(lit, view)
    ColorBy(shown, ("POINTS", "RadianceSRGB"))
    shown.MapScalars = 0
    proxygi_scene.frame(view)
    Render(view)
    SaveScreenshot(os.path.join(work, where + "-filter.png"), view,
                   ImageResolution=proxygi_scene.SIZE)
    Hide(lit, view)
    surface = Show(receivers, view)
    surface.SetRepresentationType("ProxyGI Surface")
    surface.GIProxies = proxies
    surface.GIEnvironmentFileName = environment
    Render(view)
    SaveScreenshot(os.path.join(work, where + "-surface.png"), view,
                   ImageResolution=proxygi_scene.SIZE)
    Delete(view)
    # The image-space view (its GIProxies property names a source that
    # lives on the server only: the client once aborted on it).
    view = proxygi_scene.image_space_view(receivers, proxies, environment)
    Render(view)
    SaveScreenshot(os.path.join(work, where + "-image-space.png"), view,
                   ImageResolution=proxygi_scene.SIZE)
    view.GIProxies = None
    Render(view)
    SaveScreenshot(os.path.join(work, where + "-image-space-unshadowed.png"), view,
                   ImageResolution=proxygi_scene.SIZE)
    Delete(view)


pictures("client", 1e9)  # geometry below the threshold: delivered to the client
pictures("server", 0.0)  # always drawn on the server, IceT-composited
for kind in ("filter", "surface", "image-space"):
    a = pixels(os.path.join(work, "client-%s.png" % kind))
    b = pixels(os.path.join(work, "server-%s.png" % kind))
    diff = abs(a - b)
    lit_pixels = (b.sum(axis=1) > 30).mean()
    print("%s: client-drawn against server-drawn picture: mean %.3f, largest %.0f of 255; "
          "%.1f%% of pixels lit" % (kind, diff.mean(), diff.max(), 100 * lit_pixels))
    check(lit_pixels > 0.2, kind + ": the scene is drawn")
    check(diff.mean() < 1.0 and (diff.max(axis=1) > 10).mean() < 0.01,
          kind + ": the same picture whichever process draws it")
shadow = abs(pixels(os.path.join(work, "server-image-space.png")) -
             pixels(os.path.join(work, "server-image-space-unshadowed.png")))
print("image-space: with proxies against without: mean %.2f, largest %.0f of 255"
      % (shadow.mean(), shadow.max()))
check(shadow.mean() > 1.0, "image-space: the server's pass splats the proxies")
Disconnect()
finish()
