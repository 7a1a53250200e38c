#!/usr/bin/env bash
# Runs a command under a virtual X server of its own (xvfb-run -a). The one
# known flake of that set-up: the X server refuses the first connection at
# start-up. Then, and only then, the command runs once more, and this says so
# (Utilities/run_tests.sh reports it). Any other failure stands.
set -uo pipefail
xvfb_run="${PROXYGI_XVFB_RUN:-xvfb-run}"
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
for attempt in 1 2; do
  "$xvfb_run" -a -s "-screen 0 1280x1024x24" "$@" >"$out" 2>&1
  code=$?
  cat "$out"
  if [ "$code" -ne 0 ] && [ "$attempt" -eq 1 ] &&
    grep -Eq "bad X server connection|Xvfb failed to start|[Cc]annot open display|Can't open display" "$out"; then
    echo "run_under_xvfb: RETRY: the X server refused the connection at start-up; running once more"
    continue
  fi
  exit "$code"
done
