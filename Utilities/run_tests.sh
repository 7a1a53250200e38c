#!/usr/bin/env bash
# Set up, build and run the default test suite (ctest, excluding the tests
# labelled 'slow'). Exits non-zero on any failure. The tests run without a
# display (GL through EGL, llvmpipe or the GPU); one test runs the GLX path
# under a virtual X server (ProxyGI-GLX-OffscreenWindow). No test is retried,
# except that one on the one known flake of Xvfb (the X server refusing the
# connection at start-up; Testing/run_under_xvfb.sh), which is reported.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/build.sh"
cd "$build"
status=0
env -u DISPLAY ctest --output-on-failure --label-exclude slow \
  --parallel "${PROXYGI_JOBS:-2}" "$@" || status=$?
if grep -q "run_under_xvfb: RETRY" Testing/Temporary/LastTest.log 2>/dev/null; then
  echo "run_tests: ProxyGI-GLX-OffscreenWindow was retried once: Xvfb refused the first connection"
fi
exit "$status"
