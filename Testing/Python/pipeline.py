# pvpython: a ProxyGI pipeline from plain VTK calls through the proxygi
# package (the modules wrapped against ParaView's VTK). A ground under one
# sphere proxy in a uniform sky, where the point under the sphere has a
# closed form: a sphere of radius r at distance d over a receiver facing it
# hides a cap of half-angle asin(r/d), so the exit radiance is
# albedo * L * (1 - (r/d)^2). Then the bunny's proxies and GI through the
# same classes the C++ tests use, a knob through GetSettings(), errors.
#   pvpython pipeline.py PYTHONDIR MESH.off
import math
import sys

sys.path.insert(0, sys.argv[1])
mesh = sys.argv[2]
import proxygi
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersSources import vtkPlaneSource

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


ground = vtkPlaneSource()
ground.SetOrigin(-2, -2, 0)
ground.SetPoint1(2, -2, 0)
ground.SetPoint2(-2, 2, 0)
ground.SetResolution(40, 40)
r, h = 0.5, 1.0
points = vtkPoints()
points.InsertNextPoint(0, 0, h)
radius = vtkDoubleArray()
radius.SetName("Radius")
radius.InsertNextValue(r)
sphere = vtkPolyData()
sphere.SetPoints(points)
sphere.GetPointData().AddArray(radius)

gi = proxygi.vtkPGIGlobalIllumination()
gi.SetInputConnection(ground.GetOutputPort())
gi.SetInputData(1, sphere)
gi.GetSettings().IndirectOff()
gi.GetSettings().SetOrder(6)
gi.Update()
out = gi.GetOutput()
below = out.FindPoint(0, 0, 0)
value = out.GetPointData().GetArray("Radiance").GetTuple3(below)[0]
exact = 0.8 * (1.0 - (r / h) ** 2)
check(abs(value - exact) <= 0.02 * exact,
      "under the sphere: %.4f, closed form %.4f (order 6, within 2%%)" % (value, exact))
far = out.GetPointData().GetArray("Radiance").GetTuple3(out.FindPoint(-2, -2, 0))[0]
check(far > value and far <= 0.8 + 1e-6, "far from it less shadowed: %.4f" % far)

# The bunny: proxies and GI through the wrapped classes; knobs reach them.
reader = proxygi.vtkPGIOFFReader()
reader.SetFileName(mesh)
fit = proxygi.vtkPGISphereSetApproximation()
fit.SetInputConnection(reader.GetOutputPort())
fit.SetMethodToKMeans()
fit.SetNumberOfSpheres(16)
fit.Update()
check(fit.GetOutput().GetNumberOfPoints() == 16, "16 sphere proxies of the bunny")
shade = proxygi.vtkPGIGlobalIllumination()
shade.SetInputConnection(reader.GetOutputPort())
shade.SetInputConnection(1, fit.GetOutputPort())
shade.GetSettings().SetOrder(3)
shade.Update()
visibility = shade.GetOutput().GetPointData().GetArray("Visibility")
check(visibility is not None and visibility.GetNumberOfComponents() == 9,
      "Order 3 from Python: 9 SH coefficients per vertex")
plan = shade.GetOutput().GetFieldData().GetAbstractArray("Plan")
check(plan is not None and plan.GetNumberOfValues() > 0, "the Plan says what ran: " + (plan.GetValue(0) if plan else ""))
radiance = shade.GetOutput().GetPointData().GetArray("Radiance")
low, high = radiance.GetRange(0)
check(math.isfinite(low) and math.isfinite(high) and 0.0 <= low < high <= 1.0,
      "the bunny's red radiance in [%.3f, %.3f]" % (low, high))

# Errors reach Python as VTK errors, no exception, no crash.
errors = []
bad = proxygi.vtkPGIOFFReader()
bad.SetFileName("/nonexistent/mesh.off")
bad.AddObserver(vtkCommand.ErrorEvent, lambda *args: errors.append(args))
bad.Update()
check(len(errors) == 1 and bad.GetOutput().GetNumberOfPoints() == 0, "a missing file is one error")

print("%d failed" % len(failures))
if failures:
    sys.exit(1)
