#!/usr/bin/env bash
# Runs the benchmarks (with their accuracy counters) and rewrites the
# generated tables of Documentation/AccuracyTime.md. Not part of the tests.
#   Utilities/run_benchmarks.sh [build-dir]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-${PROXYGI_BUILD_DIR:-$here/build}}"
out="$build/bench"
mkdir -p "$out"
"$build/bin/ProxyGIBenchSH" --benchmark_min_time=0.2 --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/sh.json" --benchmark_out_format=json
python3 "$here/Utilities/bench_report.py" "$out/sh.json" "$here/Documentation/AccuracyTime.md"

# Accuracy against time of every GI knob, against the Embree reference
# (minutes: references are cached in $out/cache). Its figure goes to
# Documentation/figures, its table into the report.
if [ -x "$build/bin/ProxyGISweepGI" ]; then
  run=()
  if [ -z "${DISPLAY:-}" ]; then run=(xvfb-run -a -s "-screen 0 1280x1024x24"); fi
  mkdir -p "$here/Documentation/figures"
  "${run[@]}" "$build/bin/ProxyGISweepGI" --cache "$out/cache" \
    --out "$here/Documentation/figures/gi-sweep" \
    "$here/Testing/Data/sphere-over-plane.json" "$here/Testing/Data/objects-on-plane.json" \
    "$here/Testing/Data/bent-cylinder.json"
  python3 "$here/Utilities/bench_report.py" --section gi-sweep \
    "$here/Documentation/figures/gi-sweep.md" "$here/Documentation/AccuracyTime.md"
fi

# Light-cloud relighting per frame, CPU filter against the GPU mapper
# (AccuracyTime section 18 quotes the table).
if [ -x "$build/bin/ProxyGIBenchLightCloudMapper" ]; then
  mkdir -p "$here/Documentation/figures"
  env -u DISPLAY "$build/bin/ProxyGIBenchLightCloudMapper" \
    --out "$here/Documentation/figures/lightcloud-frame-time.md"
fi
