#!/usr/bin/env bash
# Runs a command under a virtual X server of its own (xvfb-run -a).
# -noreset: by default Xvfb resets when its last client disconnects, and a
# connection made during the reset fails ("bad X server connection"). Under
# load that hit one test in ten, and it hung MPI pvbatch: a rank whose
# display check failed turned ParaView's remote rendering off, so rank 0
# rendered alone and waited in a collective the others never entered. If
# the X server still refuses a connection at start-up, the command runs
# once more, and this says so (Utilities/run_tests.sh reports it). Any
# other failure stands.
set -uo pipefail
xvfb_run="${PROXYGI_XVFB_RUN:-xvfb-run}"
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
for attempt in 1 2; do
  # Streamed as it comes, so that a run killed by a timeout still shows how
  # far it got.
  "$xvfb_run" -a -s "-screen 0 1280x1024x24 -noreset" "$@" 2>&1 | tee "$out"
  code=${PIPESTATUS[0]}
  if [ "$code" -ne 0 ] && [ "$attempt" -eq 1 ] &&
    grep -Eq "bad X server connection|Xvfb failed to start|[Cc]annot open display|Can't open display" "$out"; then
    echo "run_under_xvfb: RETRY: the X server refused the connection at start-up; running once more"
    continue
  fi
  exit "$code"
done
