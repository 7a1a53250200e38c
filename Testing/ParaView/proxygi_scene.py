"""The ParaView tests' and benchmarks' scene: the bunny standing on z = 0 (as
the default scene places it) on a 2,401-vertex ground, 32 k-means Sphere
Proxies of the bunny, and the camera the baselines were taken with."""
from paraview.simple import GroupDatasets, Plane, Transform

SIZE = [320, 240]


def build(plugin, mesh):
    """Returns (bunny, ground, scene, proxies); scene groups bunny and ground.
    plugin: the namespace LoadPlugin filled (its readers and filters)."""
    bunny = Transform(Input=plugin["ProxyGIOFFReader"](FileName=mesh))
    bunny.Transform.Rotate = [90, 0, 0]
    bunny.Transform.Translate = [0, 0, 0.494]
    ground = Plane(Origin=[-1.5, -1.5, 0], Point1=[1.5, -1.5, 0], Point2=[-1.5, 1.5, 0],
                   XResolution=48, YResolution=48)
    scene = GroupDatasets(Input=[bunny, ground])
    proxies = plugin["SphereProxies"](Input=bunny, NumberOfSpheres=32, Method="KMeans")
    return bunny, ground, scene, proxies


def frame(view, size=SIZE):
    """Black background, no axes, the baselines' camera (call after the first Show)."""
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.CameraPosition = [2.1, -2.5, 1.4]
    view.CameraFocalPoint = [0.0, 0.0, 0.3]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30
