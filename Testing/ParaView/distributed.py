# pvbatch under MPI: the bunny scene redistributed over the ranks
# (RedistributeDataSet), shaded by the Global Illumination filter, the
# ProxyGI Surface representation and the image-space view; the pictures are
# composited by IceT.
#   mpiexec -np N pvbatch --mpi distributed.py PLUGIN PYTHONDIR MESH.off ENV.exr WORKDIR [fail]
# The reader and the ground source run on rank 0 only (ParaView gives the
# other ranks empty pieces), so RedistributeDataSet spreads the receivers
# and rank 1's part of the bunny shadows rank 0's part of the ground.
# Checked, against the same classes run serially on rank 0 (the proxygi
# package, controller None):
#  - proxies built before the split (Sphere Proxies of the reader's bunny,
#    all on rank 0, gathered): per-vertex Radiance equal to serial (1e-6);
#  - proxies built per piece (Sphere Proxies of the redistributed bunny,
#    the count shared by triangles): within a stated tolerance;
#  - points on partition boundaries (present on two ranks) agree exactly;
#  - np > 1 pictures against the np = 1 run's (WORKDIR/np1, written first).
# "fail": rank 1's receivers get a NaN point; every rank must report it and
# the job must end (ctest's timeout catches a hang).
import os
import sys
import time

plugin, pythondir, mesh, environment, work = [os.path.abspath(a) for a in sys.argv[1:6]]
fail_mode = len(sys.argv) > 6 and sys.argv[6] == "fail"
sys.path.insert(0, pythondir)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paraview.simple
from paraview.simple import *
from paraview import servermanager
import proxygi_scene
from proxygi_scene import check, finish, pixels
from vtkmodules.vtkCommonCore import vtkCommand, vtkOutputWindow
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkTestingRendering import vtkTesting
import proxygi

ranks = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
here = os.path.join(work, "np%d" % ranks)
os.makedirs(here, exist_ok=True)
print("ranks: %d" % ranks)

messages = []


def collect(caller, event, text=None):
    messages.append(str(text) if text is not None else event)


collect.CallDataType = "string0"
for event in (vtkCommand.ErrorEvent, vtkCommand.WarningEvent):
    vtkOutputWindow.GetInstance().AddObserver(event, collect)

LoadPlugin(plugin, remote=False, ns=globals())
bunny, ground, scene, _ = proxygi_scene.build(globals(), mesh)
# Normals of the whole objects, before the split: a point on a cut has one
# normal on both ranks.
bunny_n = GenerateSurfaceNormals(Input=bunny, Splitting=0)
ground_n = GenerateSurfaceNormals(Input=ground, Splitting=0)
# Merged before the split: ParaView 5.11's RedistributeDataSet drops about a
# quarter of a multiblock's cells on 3 ranks (not on 2) unless
# PreservePartitionsInOutput is on; a single dataset is split whole.
objects = MergeBlocks(Input=GroupDatasets(Input=[bunny_n, ground_n]))
spread = RedistributeDataSet(Input=objects)
receivers = ExtractSurface(Input=spread)

def failure():
    # Rank 1's piece gets a NaN coordinate; the others are fine.
    bad = ProgrammableFilter(Input=receivers)
    bad.Script = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
out = self.GetOutput()
out.ShallowCopy(self.GetInput())
if vtkMultiProcessController.GetGlobalController().GetLocalProcessId() == 1:
    from vtkmodules.vtkCommonCore import vtkPoints
    points = vtkPoints()
    points.DeepCopy(out.GetPoints())
    if points.GetNumberOfPoints() > 0:
        points.SetPoint(0, float('nan'), 0.0, 0.0)
    out.SetPoints(points)
"""
    proxies = SphereProxies(Input=bunny, NumberOfSpheres=32, Method="KMeans")
    lit = GlobalIllumination(Input=bad, Proxies=proxies, EnvironmentFileName=environment)
    start = time.perf_counter()
    lit.UpdatePipeline()
    print("failed update returned after %.2f s" % (time.perf_counter() - start))
    said = [m for m in messages if "rank 1" in m and "NaN" in m]
    check(len(said) > 0, "rank 0 reports rank 1's error: %s" % (said[0].strip() if said else messages))
    check(lit.GetDataInformation().GetNumberOfPoints() == 0, "no output on any rank")


def distributed():
    # Per rank: what each holds (ProcessIds), for the record.
    pieces = servermanager.Fetch(ProcessIdScalars(Input=receivers))
    owners = pieces.GetPointData().GetArray("ProcessId")
    counts = [0] * ranks
    for i in range(owners.GetNumberOfTuples()):
        counts[int(owners.GetTuple1(i))] += 1
    print("receiver points per rank: %s" % counts)
    if ranks > 1:
        check(all(c > 0 for c in counts), "RedistributeDataSet gave every rank receivers")
    check(sum(counts) >= 40107, "no receiver lost in the split (%d points in all)" % sum(counts))


    def serial_reference(proxy_source):
        """The whole scene through the C++ classes on this rank alone."""
        whole = vtkAppendPolyData()
        for part in (bunny_n, ground_n):
            data = vtkPolyData()
            data.ShallowCopy(servermanager.Fetch(part))
            whole.AddInputData(data)
        whole.Update()
        spheres = proxygi.vtkPGISphereSetApproximation()
        spheres.SetController(None)
        whole_bunny = vtkPolyData()
        whole_bunny.ShallowCopy(servermanager.Fetch(proxy_source))
        spheres.SetInputData(whole_bunny)
        spheres.SetMethodToKMeans()
        spheres.SetNumberOfSpheres(32)
        light = proxygi.vtkPGILighting()
        light.SetEnvironmentFileName(environment)
        gi = proxygi.vtkPGIGlobalIllumination()
        gi.SetController(None)
        gi.SetInputConnection(whole.GetOutputPort())
        gi.SetProxiesConnection(spheres.GetOutputPort())
        gi.SetLighting(light)
        gi.Update()
        return gi.GetOutput()


    def by_position(data, owner_array=None):
        """{position: [(owner, radiance), ...]}"""
        table = {}
        radiance = data.GetPointData().GetArray("Radiance")
        owner = data.GetPointData().GetArray(owner_array) if owner_array else None
        for i in range(data.GetNumberOfPoints()):
            key = data.GetPoint(i)
            table.setdefault(key, []).append((int(owner.GetTuple1(i)) if owner else 0,
                                              radiance.GetTuple3(i)))
        return table


    serial = by_position(serial_reference(bunny_n))
    timings = {}
    for name, proxies, tolerance in (
            ("proxies before the split", SphereProxies(Input=bunny_n, NumberOfSpheres=32, Method="KMeans"), 1e-6),
            ("proxies per piece", SphereProxies(Input=ExtractSurface(Input=MergeBlocks(
                Input=RedistributeDataSet(Input=bunny_n))), NumberOfSpheres=32, Method="KMeans"), 0.08)):
        start = time.perf_counter()
        proxies.UpdatePipeline()
        build = time.perf_counter() - start
        builder = proxies.GetClientSideObject()
        lit = GlobalIllumination(Input=receivers, Proxies=proxies, EnvironmentFileName=environment,
                                 ColorExposure=0.5)
        start = time.perf_counter()
        lit.UpdatePipeline()
        shading = time.perf_counter() - start
        filt = lit.GetClientSideObject()
        plan = filt.GetOutput().GetFieldData().GetAbstractArray("Plan")
        plan_lines = [plan.GetValue(i) for i in range(plan.GetNumberOfValues())] if plan else []
        print("%s: %d global spheres; proxy build %.3f s (of it all-gather %.4f s, %d bytes in); "
              "GI filter %.3f s (rank 0: %.4f s in collectives, %d bytes in)"
              % (name, proxies.GetDataInformation().GetNumberOfPoints() // max(1, ranks),
                 build, builder.GetGatherTime(), builder.GetGatheredBytes(), shading,
                 filt.GetCommunicationTime(), filt.GetCommunicationBytes()))
        for line in plan_lines:
            if line.startswith("distributed") or line.startswith("normals"):
                print("      plan: " + line)
        timings[name] = (build, builder.GetGatherTime(), shading)
        distributed = by_position(servermanager.Fetch(ProcessIdScalars(Input=lit)), "ProcessId")
        shared = seams = 0
        for key, values in distributed.items():
            if len(values) > 1:
                shared += 1
                seams += any(v[1] != values[0][1] for v in values[1:])
        print("      %d points on partition boundaries (on several ranks), %d disagree" % (shared, seams))
        check(seams == 0, "%s: boundary points agree exactly across ranks" % name)
        if ranks > 1:
            check(shared > 0, "%s: the partition has boundary points" % name)
        num = den = 0.0
        worst = 0.0
        missing = 0
        for key, values in serial.items():
            if key not in distributed:
                missing += 1
                continue
            a, b = distributed[key][0][1], values[0][1]
            for c in range(3):
                num += (a[c] - b[c]) ** 2
                den += b[c] ** 2
                worst = max(worst, abs(a[c] - b[c]))
        rmse = (num / den) ** 0.5 if den > 0 else float("inf")
        check(missing == 0, "%s: every serial point is shaded by some rank (%d missing)" % (name, missing))
        check(rmse <= tolerance, "%s: Radiance against the serial run: relative RMSE %.3g, worst %.3g "
              "(tolerance %.3g)" % (name, rmse, worst, tolerance))
        Delete(lit)

    # Pictures: the CPU filter's colours, ProxyGI Surface and the image-space
    # view, composited by IceT; np > 1 against the np = 1 run's.
    proxies = SphereProxies(Input=bunny_n, NumberOfSpheres=32, Method="KMeans")
    lit = GlobalIllumination(Input=receivers, Proxies=proxies, EnvironmentFileName=environment,
                             ColorExposure=0.5)
    pictures = {}
    view = CreateView("RenderView")
    # A rank that failed ParaView's display check turns distributed rendering
    # off everywhere; the first render would then hang (rank 0 alone in a
    # collective), so stop here and say why.
    if ranks > 1 and not view.GetClientSideObject().GetRemoteRenderingAvailable():
        check(False, "ParaView's distributed rendering is available on every rank (a rank could not "
              "connect to the X server: is Xvfb running with -noreset?)")
        finish()
    shown = Show(lit, view)
    ColorBy(shown, ("POINTS", "RadianceSRGB"))
    shown.MapScalars = 0
    shown.Ambient, shown.Diffuse = 1.0, 0.0
    paraview.simple._DisableFirstRenderCameraReset()
    proxygi_scene.frame(view)
    Render(view)
    start = time.perf_counter()
    for _ in range(5):
        view.StillRender()
    composite = (time.perf_counter() - start) / 5
    print("a still frame of the filter's colours (drawing and IceT compositing): %.4f s" % composite)
    pictures["filter"] = view
    surface_view = CreateView("RenderView")
    surface = Show(receivers, surface_view)
    surface.SetRepresentationType("ProxyGI Surface")
    surface.GIProxies = proxies
    surface.GIEnvironmentFileName = environment
    surface.GIExposure = 0.5
    proxygi_scene.frame(surface_view)
    Render(surface_view)
    surface.UpdatePropertyInformation()
    status = surface.GetPropertyValue("GIStatus")
    print("ProxyGI Surface status (rank 0): " + status)
    check("32 proxies" in status, "the representation shades with the 32 global proxies on rank 0")
    pictures["surface"] = surface_view
    image_view = CreateView("ProxyGIImageSpaceRenderView")
    Show(receivers, image_view).DiffuseColor = [0.8, 0.8, 0.8]
    proxygi_scene.frame(image_view)
    image_view.GIProxies = proxies
    image_view.GIEnvironmentFileName = environment
    image_view.GIExposure = 0.5
    Render(image_view)
    image_view.UpdatePropertyInformation()
    status = image_view.GetPropertyValue("GIStatus")
    print("image-space view status (rank 0): " + status)
    check("32 proxies" in status, "the image-space pass splats the 32 global proxies on rank 0")
    pictures["image-space"] = image_view


    def save(name, v):
        picture = os.path.join(here, "%s.png" % name)
        SaveScreenshot(picture, v, ImageResolution=proxygi_scene.SIZE)
        return picture


    saved = {name: save(name, v) for name, v in pictures.items()}
    # The image-space pass at full resolution (no upsampling between ranks' edges).
    image_view.GIReceiverScale = 1
    Render(image_view)
    saved["image-space-full-resolution"] = save("image-space-full-resolution", image_view)
    for name, picture in saved.items():
        serial_picture = os.path.join(work, "np1", "%s.png" % name)
        if ranks == 1:
            continue
        if not os.path.exists(serial_picture):
            check(False, "%s: the np = 1 picture %s exists (run np = 1 first)" % (name, serial_picture))
            continue
        difference = abs(pixels(picture) - pixels(serial_picture))
        tester = vtkTesting()
        for argument in ("-V", serial_picture, "-T", here):
            tester.AddArgument(argument)
        passed = tester.RegressionTest(picture, 0.02) == vtkTesting.PASSED
        worst = difference.max(axis=1)
        check(passed, "%s: composited picture against np = 1 (VTK's tester, threshold 0.02; mean "
              "difference %.3f of 255, largest %d; %.2f%% of pixels differ by more than 2, %.2f%% by "
              "more than 10)" % (name, difference.mean(), difference.max(), 100.0 * (worst > 2).mean(),
                                  100.0 * (worst > 10).mean()))


# No sys.exit on success: under MPI it ends rank 0 without MPI_Finalize.
if fail_mode:
    failure()
else:
    distributed()
finish()
