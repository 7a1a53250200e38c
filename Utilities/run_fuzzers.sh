#!/usr/bin/env bash
# Runs the libFuzzer harnesses (Testing/Fuzz) for a while each:
#   Utilities/run_fuzzers.sh [SECONDS per harness, default 600] [HARNESS...]
# HARNESS: OFFReader SceneJSON EXRReader ProxiesVTP (default: all). Builds
# them with clang 14, ASan and UBSan in build-fuzz/ (or
# $PROXYGI_FUZZ_BUILD_DIR), starts from the committed corpus
# (Testing/Fuzz/Corpus/HARNESS) plus what earlier runs found in
# build-fuzz/fuzz/HARNESS/corpus, and runs $PROXYGI_FUZZ_JOBS harnesses at
# once (default 2). Findings (crashes, hangs > 10 s, more than 2 GiB of
# memory) land in build-fuzz/fuzz/HARNESS/findings/; the script prints the
# executions per harness and fails when any harness found something. A
# finding, once fixed, goes into Testing/Fuzz/Corpus/HARNESS, named after
# what it broke, and the ProxyGI-FuzzCorpus-HARNESS test replays it.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_FUZZ_BUILD_DIR:-$here/build-fuzz}"
seconds="${1:-600}"
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(OFFReader SceneJSON EXRReader ProxiesVTP)
"$here/Utilities/setup.sh"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DPROXYGI_FUZZ=ON \
  -DPROXYGI_SANITIZE="address;undefined" -DPROXYGI_BUILD_PARAVIEW_PLUGIN=OFF \
  -DPROXYGI_WRAP_PYTHON=OFF -DPROXYGI_BUILD_BENCHMARKS=OFF >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("pgiFuzz$h"); done
cmake --build "$build" --parallel "${PROXYGI_JOBS:-2}" --target "${targets[@]}"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$here/Testing/Sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1"
extra_seeds() {
  # The scene files the tests use are seeds of the scene parser too.
  [ "$1" = SceneJSON ] && echo "$here/Testing/Data"
  return 0
}
run_one() {
  local h="$1" work="$build/fuzz/$1"
  mkdir -p "$work/corpus" "$work/findings"
  # -fork would survive a finding and go on; one process stops at the first,
  # which is what a fix-and-rerun loop wants.
  "$build/bin/pgiFuzz$h" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$work/findings/" \
    "$work/corpus" "$here/Testing/Fuzz/Corpus/$h" $(extra_seeds "$h") >"$work/log" 2>&1 || true
  local runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
  local found
  found=$(find "$work/findings" -type f | wc -l)
  echo "run_fuzzers: $h: ${runs:-?} executions in $seconds s, $(ls "$work/corpus" | wc -l) corpus inputs, $found findings"
}
jobs_at_once="${PROXYGI_FUZZ_JOBS:-2}"
for h in "${harnesses[@]}"; do
  run_one "$h" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_at_once" ]; do wait -n; done
done
wait
status=0
for h in "${harnesses[@]}"; do
  if [ -n "$(find "$build/fuzz/$h/findings" -type f)" ]; then
    echo "run_fuzzers: $h findings (see $build/fuzz/$h/log):"
    find "$build/fuzz/$h/findings" -type f
    status=1
  fi
done
exit $status
