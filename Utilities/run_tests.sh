#!/usr/bin/env bash
# Set up, build and run the default test suite (ctest, excluding the tests
# labelled 'slow'). Exits non-zero on any failure.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/build.sh"
cd "$build"
ctest --output-on-failure --label-exclude slow --parallel "${PROXYGI_JOBS:-2}" "$@"
