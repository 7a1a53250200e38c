#!/usr/bin/env bash
# The CPU test suite under AddressSanitizer and UndefinedBehaviorSanitizer:
# ProxyGI's own code instrumented (PROXYGI_SANITIZE), in build-asan/ (or
# $PROXYGI_ASAN_BUILD_DIR), without the ParaView plugin, the Python wrapping
# and the benchmarks. Runs the modules' tests that need no GL (SH, proxies,
# shading, reference, IO, lighting, scene) and the CLI's CPU commands. Any
# sanitizer report fails the test it comes from. Leaks inside the system's
# libraries (Mesa, LLVM, Embree's TBB, OpenEXR) are suppressed by name,
# Testing/Sanitizers/lsan.supp; ours are not.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_ASAN_BUILD_DIR:-$here/build-asan}"
"$here/Utilities/setup.sh"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPROXYGI_SANITIZE="address;undefined" -DPROXYGI_BUILD_PARAVIEW_PLUGIN=OFF \
  -DPROXYGI_WRAP_PYTHON=OFF -DPROXYGI_BUILD_BENCHMARKS=OFF >/dev/null
start=$(date +%s)
cmake --build "$build" --parallel "${PROXYGI_JOBS:-2}"
echo "run_sanitized_tests: built in $(($(date +%s) - start)) s"
cd "$build"
# A report aborts (SIGABRT): a refusal test, which accepts exit codes 1-127,
# cannot mistake it for a refusal.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$here/Testing/Sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1"
env -u DISPLAY ctest --output-on-failure --label-exclude slow --parallel "${PROXYGI_JOBS:-2}" \
  -L "ProxyGISphericalHarmonics|ProxyGIProxies|ProxyGIShading|ProxyGIReference|ProxyGIIO|ProxyGILighting|ProxyGIScene|sanitize" \
  "$@"
