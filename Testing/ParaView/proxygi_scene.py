"""The ParaView tests' and benchmarks' scene: the bunny standing on z = 0 (as
the default scene places it) on a 2,401-vertex ground, 32 k-means Sphere
Proxies of the bunny, and the camera the baselines were taken with; and the
tests' checks (check, pixels, finish)."""
import sys

from paraview.simple import GroupDatasets, Plane, Transform
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

SIZE = [320, 240]


def build(plugin, mesh, fit=False):
    """Returns (bunny, ground, scene, proxies); scene groups bunny and ground.
    plugin: the namespace LoadPlugin filled (its readers and filters).
    fit: place any mesh instead (as it is oriented, largest extent 1, centred
    above the origin, bottom on z = 0); the baselines use the bunny's own
    placement."""
    reader = plugin["ProxyGIOFFReader"](FileName=mesh)
    bunny = Transform(Input=reader)
    if fit:
        reader.UpdatePipeline()
        b = reader.GetDataInformation().GetBounds()
        scale = 1.0 / max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
        bunny.Transform.Scale = [scale] * 3
        bunny.Transform.Translate = [-0.5 * (b[0] + b[1]) * scale, -0.5 * (b[2] + b[3]) * scale,
                                     -b[4] * scale]
    else:
        bunny.Transform.Rotate = [90, 0, 0]
        bunny.Transform.Translate = [0, 0, 0.494]
    ground = Plane(Origin=[-1.5, -1.5, 0], Point1=[1.5, -1.5, 0], Point2=[-1.5, 1.5, 0],
                   XResolution=48, YResolution=48)
    scene = GroupDatasets(Input=[bunny, ground])
    proxies = plugin["SphereProxies"](Input=bunny, NumberOfSpheres=32, Method="KMeans")
    return bunny, ground, scene, proxies


def redistributed(plugin, mesh):
    """The distributed runs' scene: returns (bunny_n, ground_n, receivers,
    proxies). Normals of the whole objects before the split (a point on a
    cut has one normal on both ranks); the blocks merged before
    RedistributeDataSet (ParaView 5.11's drops cells of a multiblock on 3
    ranks); 32 k-means proxies of the whole bunny."""
    from paraview.simple import (ExtractSurface, GenerateSurfaceNormals, MergeBlocks,
                                 RedistributeDataSet)
    bunny, ground, _, _ = build(plugin, mesh)
    bunny_n = GenerateSurfaceNormals(Input=bunny, Splitting=0)
    ground_n = GenerateSurfaceNormals(Input=ground, Splitting=0)
    objects = MergeBlocks(Input=GroupDatasets(Input=[bunny_n, ground_n]))
    receivers = ExtractSurface(Input=RedistributeDataSet(Input=objects))
    proxies = plugin["SphereProxies"](Input=bunny_n, NumberOfSpheres=32, Method="KMeans")
    return bunny_n, ground_n, receivers, proxies


def image_space_view(receivers, proxies, environment):
    """A framed image-space view of the receivers with these proxies and map."""
    from paraview.simple import CreateView, Show
    view = CreateView("ProxyGIImageSpaceRenderView")
    Show(receivers, view)
    view.GIProxies = proxies
    view.GIEnvironmentFileName = environment
    frame(view)
    return view


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


failures = []


def check(ok, what):
    """One line per check: 'ok' or 'FAIL' (the tests' FAIL pattern)."""
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def pixels(path):
    """A PNG's RGB values as an N x 3 float array."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)


def finish():
    """Prints the tests' PASS line; exits 1 on failures. No sys.exit(0): pvbatch
    exited that way after rendering tears its X context down twice
    (GLXBadContext, exit status 1)."""
    print("%d failed" % len(failures))
    if failures:
        sys.exit(1)
