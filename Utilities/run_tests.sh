#!/usr/bin/env bash
# Set up, build and run the default test suite (ctest, excluding the tests
# labelled 'slow'). Exits non-zero on any failure. Without a display the
# rendering tests get a virtual X server (xvfb-run).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/build.sh"
cd "$build"
run=()
if [ -z "${DISPLAY:-}" ]; then run=(xvfb-run -a -s "-screen 0 1280x1024x24"); fi
# A GL test sometimes aborts at start-up under xvfb (seen 2 in ~6 runs, under
# investigation); a failed test gets one more try.
"${run[@]}" ctest --output-on-failure --repeat until-pass:2 --label-exclude slow --parallel "${PROXYGI_JOBS:-2}" "$@"
