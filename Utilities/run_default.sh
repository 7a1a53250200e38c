#!/usr/bin/env bash
# The main job: set up, build, render the default scene (the bunny over a
# plane under the forest map) with per-vertex SH soft shadows, one-bounce
# indirect light and local lights, write out/default.png, print the plan,
# the time and the error against the Embree reference (computed once and
# cached in out/cache). Offscreen: EGL without a display (the GPU where
# there is one), the X server's window with one. Extra arguments go to
# 'proxygi render' (e.g. a scene file: Testing/Data/objects-on-plane.json).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/build.sh"
mkdir -p "$here/out"
# The accuracy budget chooses the knobs: the fastest settings the budget
# model predicts within 6% of Embree, checked against Embree at 16 samples
# per vertex (proxygi render --error, --check). Given --mode, --error or
# --time, the arguments are the user's alone.
budget=(--error 6% --check 16)
for arg in "$@"; do
  case "$arg" in
    --mode|--error|--time) budget=() ;;
  esac
done
exec "$build/bin/proxygi" render -o "$here/out/default.png" \
  --cache "$here/out/cache" "${budget[@]}" "$@"
