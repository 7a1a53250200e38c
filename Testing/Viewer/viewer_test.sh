#!/bin/bash
# proxygi view under Xvfb (run by run_under_xvfb.sh): a 128-spp reference of
# the default scene cached first (proxygi render), then the viewer replays
# interaction.log (recorded-interaction format of vtkInteractorEventRecorder)
# and viewer_check.py judges its screenshots and log.
#   viewer_test.sh PROXYGI PYTHON WORKDIR CACHE BASELINE_DIR
set -u
proxygi=$1 python=$2 work=$3 cache=$4 baselines=$5
here="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$work" && mkdir -p "$work"
common=(--size 320x240 --reference-spp 128 --cache "$cache")
if ! "$proxygi" render --mode vertex "${common[@]}" -o "$work/render.png" >"$work/render.log" 2>&1; then
  cat "$work/render.log"
  echo "FAIL  proxygi render could not cache the reference"
  exit 1
fi
"$proxygi" view --mode vertex --no-overlay "${common[@]}" --play "$here/interaction.log" \
  --screenshot "$work/shot" >"$work/view.log" 2>&1
status=$?
cat "$work/view.log"
echo "proxygi view exit status $status"
[ "$status" -eq 0 ] || exit 1
exec "$python" "$here/viewer_check.py" "$work" "$baselines"
