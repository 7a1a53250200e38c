#!/usr/bin/env bash
# The CPU test suite under the sanitizers, ProxyGI's own code instrumented
# (PROXYGI_SANITIZE), without the ParaView plugin, the Python wrapping and
# the benchmarks:
#   Utilities/run_sanitized_tests.sh [address|thread] [CTEST-ARGS...]
# address (default): AddressSanitizer and UBSan in build-asan/ (or
#   $PROXYGI_ASAN_BUILD_DIR). Runs the modules' tests that need no GL (SH,
#   proxies, shading, reference, IO, lighting, scene) and the CLI's CPU
#   commands. Leaks inside the system's libraries (Mesa, LLVM, Embree's TBB,
#   OpenEXR) are suppressed by name, Testing/Sanitizers/lsan.supp; ours are
#   not.
# thread: ThreadSanitizer in build-tsan/ (or $PROXYGI_TSAN_BUILD_DIR), the
#   same module tests (not the CLI's). Embree and TBB are not instrumented:
#   the reports from inside them are suppressed, Testing/Sanitizers/tsan.supp.
# Any sanitizer report aborts the process and so fails its test.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode=address
if [ "${1:-}" = address ] || [ "${1:-}" = thread ]; then
  mode="$1"
  shift
fi
labels="ProxyGISphericalHarmonics|ProxyGIProxies|ProxyGIShading|ProxyGIReference|ProxyGIIO|ProxyGILighting|ProxyGIScene"
targets=()
if [ "$mode" = address ]; then
  build="${PROXYGI_ASAN_BUILD_DIR:-$here/build-asan}"
  sanitize="address;undefined"
  labels="$labels|sanitize"
else
  build="${PROXYGI_TSAN_BUILD_DIR:-$here/build-tsan}"
  sanitize="thread"
  for m in SphericalHarmonics Proxies Shading Reference IO Lighting Scene; do
    targets+=("ProxyGI${m}CxxTests")
  done
  targets=(--target "${targets[@]}")
fi
"$here/Utilities/setup.sh"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPROXYGI_SANITIZE="$sanitize" -DPROXYGI_BUILD_PARAVIEW_PLUGIN=OFF \
  -DPROXYGI_WRAP_PYTHON=OFF -DPROXYGI_BUILD_BENCHMARKS=OFF >/dev/null
start=$(date +%s)
cmake --build "$build" --parallel "${PROXYGI_JOBS:-2}" "${targets[@]}"
echo "run_sanitized_tests ($mode): built in $(($(date +%s) - start)) s"
cd "$build"
# A report aborts (SIGABRT): a refusal test, which accepts exit codes 1-127,
# cannot mistake it for a refusal.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$here/Testing/Sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1"
export TSAN_OPTIONS="suppressions=$here/Testing/Sanitizers/tsan.supp:halt_on_error=1:abort_on_error=1"
env -u DISPLAY ctest --output-on-failure --label-exclude slow --parallel "${PROXYGI_JOBS:-2}" \
  -L "$labels" "$@"
