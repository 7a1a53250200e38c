"""Judges what proxygi view wrote while it replayed interaction.log: each
key and the lamp's drag must change the picture the way it says, the first
picture and the dragged lamp's must match the committed baselines (VTK's
regression tester), and the error against the cached reference must follow
the knobs.   viewer_check.py WORKDIR BASELINE_DIR"""
import os
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkTestingRendering import vtkTesting

work, baselines = [os.path.abspath(a) for a in sys.argv[1:3]]
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def shot(k):
    reader = vtkPNGReader()
    reader.SetFileName(os.path.join(work, "shot-%d.png" % k))
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(float).reshape(h, w, 3)


log = open(os.path.join(work, "view.log")).read()
count = len(re.findall(r"^wrote .*shot-\d+\.png$", log, re.M))
check(count == 11, "the viewer wrote the 11 screenshots of interaction.log (%d)" % count)
if count != 11:
    print("%d failed" % len(failures))
    sys.exit(1)
S = [None] + [shot(k) for k in range(1, 12)]
h, w = S[1].shape[:2]


def lum(a):
    return a.mean(axis=2)


def left(a):
    return lum(a)[:, : w // 2].mean()


def right(a):
    return lum(a)[:, w // 2 :].mean()


def diff(a, b):
    return np.abs(a - b).mean()


def orange(a):
    return ((a[:, :, 0] - a[:, :, 2]) > 60).mean()


print("      mean luminance per shot: " + " ".join("%.1f" % lum(S[k]).mean() for k in range(1, 12)))
# The exposure follows the picture's 95th percentile, so the background map
# and the lit parts may dim a few levels when the shadows go: not a shadow.
check(lum(S[2]).mean() > lum(S[1]).mean() + 2 and (lum(S[2]) < lum(S[1]) - 6).mean() < 0.03,
      "s: shadows off lightens the picture and darkens almost nothing (%.1f -> %.1f)"
      % (lum(S[1]).mean(), lum(S[2]).mean()))
check(left(S[3]) > left(S[1]) + 8 and abs(right(S[3]) - right(S[1])) < 3,
      "l: the lamp, left of the bunny, lights the left half (%.1f -> %.1f), not the right"
      % (left(S[1]), left(S[3])))
check(right(S[4]) > right(S[3]) + 10 and left(S[4]) < left(S[3]) - 8,
      "drag: the lamp moved right lights the right half (%.1f -> %.1f) and leaves the left (%.1f -> %.1f)"
      % (right(S[3]), right(S[4]), left(S[3]), left(S[4])))
check(orange(S[5]) > 0.05 and orange(S[4]) < 0.01,
      "g: the proxies drawn as glyphs cover %.1f%% of the picture" % (100 * orange(S[5])))
check(diff(S[6], S[1]) < 6 and abs(right(S[6]) - right(S[1])) < 3,
      "b: the image-space pass, which draws no local lights, is the lampless picture within %.1f"
      % diff(S[6], S[1]))
check(re.search(r"local lights are not drawn in the image-space pass", log) is not None,
      "b: the image-space pass says it does not draw the lamp")
check(diff(S[7], S[4]) < 3,
      "b: the GI mapper draws what the CPU filter drew (mean |difference| %.2f of 255)" % diff(S[7], S[4]))
check(diff(S[8], S[7]) > 0.5, "O: SH order 3 changes the picture (%.2f)" % diff(S[8], S[7]))
check(diff(S[9], S[8]) > 0.5 and "32 spheres" in log,
      "N: 32 spheres per mesh change the picture (%.2f)" % diff(S[9], S[8]))
check(lum(S[10]).mean() < lum(S[9]).mean() - 1,
      "i: indirect light off darkens the picture (%.1f -> %.1f)" % (lum(S[9]).mean(), lum(S[10]).mean()))
corner = (np.abs(lum(S[11]) - lum(S[10]))[: int(0.3 * h), : w // 2] > 60).sum()
check(corner > 500, "h: the overlay's text appears top left (%d pixels)" % corner)

# The error against the cached 128-spp reference, logged after every change.
errors = re.findall(r"proxygi view: (error[^\n]*)", log)
values = [float(m.group(1)) if m else None
          for m in (re.search(r": ([0-9.]+)% per vertex", e) for e in errors)]
print("      errors: " + " | ".join(errors[:4]))
check(len(values) >= 4 and values[0] is not None and values[1] is not None
      and values[1] > values[0] + 1,
      "the error follows the knobs: shadows off raises it (%s -> %s)" % tuple((values + [None, None])[:2]))
check(len(values) >= 4 and values[2] is not None and abs(values[2] - values[0]) < 0.05,
      "shadows back on, the error is back (%s)" % ((values + [None] * 3)[2],))
check(len(errors) >= 4 and "no cached reference" in errors[3],
      "with the lamp on there is no cached reference of the scene, and the overlay says so")

for k, name in ((1, "ViewerVertex.png"), (4, "ViewerLampDragged.png")):
    tester = vtkTesting()
    tester.AddArgument("-V")
    tester.AddArgument(os.path.join(baselines, name))
    tester.AddArgument("-T")
    tester.AddArgument(work)
    result = tester.RegressionTest(os.path.join(work, "shot-%d.png" % k), 0.02)
    check(result == vtkTesting.PASSED, "shot %d matches the baseline %s (VTK's regression tester)" % (k, name))

print("%d failed" % len(failures))
if failures:
    sys.exit(1)
