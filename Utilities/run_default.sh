#!/usr/bin/env bash
# The main job: set up, build, render the default scene (the bunny over a
# plane under the forest map) with SH soft shadows, write out/default.png,
# print time and the error against the Embree reference (computed once and
# cached in out/cache). Extra arguments go to 'proxygi render'.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/build.sh"
mkdir -p "$here/out"
run=()
# No display: render offscreen through a virtual X server.
if [ -z "${DISPLAY:-}" ]; then run=(xvfb-run -a -s "-screen 0 1280x1024x24"); fi
exec "${run[@]}" "$build/bin/proxygi" render -o "$here/out/default.png" \
  --cache "$here/out/cache" "$@"
