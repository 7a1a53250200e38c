#!/usr/bin/env python3
"""Objects alone under several lights: the GI filter with each mesh's own
shadows and bounce traced once (vtkPGISelfVisibility) against the self-shadow
rules, both against the Embree reference of the same vertices.

    python3 self_visibility_sweep.py BUILD_DIR DATA_DIR [mesh ...] [--spp N]

Prints a Markdown table: per mesh and light, relative RMSE of the direct
light and of the total (one bounce), rules -> traced, the filter's time
and the trace's. Needs ProxyGI's Python modules (BUILD_DIR/lib/python3/...).
"""
import sys
import time

args = [a for a in sys.argv[1:] if not a.startswith("--")]
spp = 512
if "--spp" in sys.argv:
    spp = int(sys.argv[sys.argv.index("--spp") + 1])
    args.remove(str(spp))
build, data = args[0], args[1]
meshes = args[2:] or ["cow", "dino", "elephant", "bear", "hand", "mushroom", "elk", "fandisk"]
sys.path.insert(0, build + "/lib/python3/dist-packages")

import numpy as np
import proxygi
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals

lights = [("uniform sky", None), ("forest map", "forest.exr"), ("sunset map", "sunset.exr")]


def rel(a, b):
    return float(np.sqrt(((a - b) ** 2).sum() / (b ** 2).sum()))


def arr(data, name):
    return vtk_to_numpy(data.GetPointData().GetArray(name)).astype(float)


print("| mesh | vertices | light | direct: rules | direct: traced | total: rules | total: traced"
      " | filter (s): rules | traced | trace (s) |")
print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
for name in meshes:
    reader = proxygi.vtkPGIOFFReader()
    reader.SetFileName(f"{data}/meshes/{name}.off")
    normals = vtkPolyDataNormals()
    normals.SetInputConnection(reader.GetOutputPort())
    normals.SplittingOff()
    normals.AutoOrientNormalsOff()
    normals.Update()
    mesh = normals.GetOutput()
    proxies = proxygi.vtkPGISphereSetApproximation()
    proxies.SetInputData(mesh)
    proxies.SetNumberOfSpheres(64)
    proxies.Update()
    sampled = proxygi.vtkPGISphereLightSampler()  # surface samples: the shadowed bounce
    sampled.SetInputData(mesh)
    sampled.SetProxiesConnection(proxies.GetOutputPort())
    sampled.Update()
    t0 = time.perf_counter()
    self_vis = proxygi.vtkPGISelfVisibility()
    self_vis.SetInputData(mesh)
    self_vis.SetSamples(256)
    self_vis.Update()
    trace = time.perf_counter() - t0
    for label, env in lights:
        lighting = proxygi.vtkPGILighting()
        if env:
            lighting.SetEnvironmentFileName(f"{data}/environments/{env}")
        reference = proxygi.vtkPGIReferenceIllumination()
        reference.SetInputData(mesh)
        reference.SetLighting(lighting)
        reference.SetSamples(spp)
        reference.Update()
        truth = reference.GetOutput()
        row = {}
        for mode, receivers in (("rules", mesh), ("traced", self_vis.GetOutput())):
            gi = proxygi.vtkPGIGlobalIllumination()
            gi.SetInputData(receivers)
            gi.SetProxiesConnection(sampled.GetOutputPort())
            gi.SetLighting(lighting)
            gi.GetSettings().SetIndirectModeToShadowed()
            gi.Update()  # the first update builds the tables
            gi.Modified()
            t0 = time.perf_counter()
            gi.Update()
            seconds = time.perf_counter() - t0
            out = gi.GetOutput()
            row[mode] = (rel(arr(out, "DirectShadowed"), arr(truth, "DirectShadowed")),
                         rel(arr(out, "Radiance"), arr(truth, "Radiance")), seconds)
        r, t = row["rules"], row["traced"]
        print(f"| {name} | {mesh.GetNumberOfPoints()} | {label} | {100 * r[0]:.1f}% | "
              f"{100 * t[0]:.1f}% | {100 * r[1]:.1f}% | {100 * t[1]:.1f}% | {r[2]:.3f} | "
              f"{t[2]:.3f} | {trace:.2f} |", flush=True)
