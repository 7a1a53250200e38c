#!/usr/bin/env bash
# clang-tidy 14 over ProxyGI's own sources (.clang-tidy: bugprone,
# performance, modernize-use-override, as errors), with the compile commands
# of build/ (or $PROXYGI_BUILD_DIR; Utilities/build.sh makes it). Run by
# Utilities/run_tests.sh after the default suite (PROXYGI_CLANG_TIDY=0 skips
# it). Fails on any diagnostic.
#   Utilities/run_clang_tidy.sh [FILE-REGEX]   (default: every source of ours)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
if ! command -v run-clang-tidy-14 >/dev/null 2>&1; then
  echo "run_clang_tidy: run-clang-tidy-14 is missing (Utilities/setup.sh installs clang-tidy-14)" >&2
  exit 2
fi
if [ ! -f "$build/compile_commands.json" ]; then
  echo "run_clang_tidy: no $build/compile_commands.json (configure the build first)" >&2
  exit 2
fi
regex="${1:-$here/(Modules|Applications|Testing|Examples|Benchmarks|Plugins)/}"
start=$(date +%s)
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
status=0
run-clang-tidy-14 -p "$build" -j "${PROXYGI_JOBS:-2}" -quiet "$regex" >"$log" 2>&1 || status=$?
files=$(grep -c "^clang-tidy-14 \|^clang-tidy " "$log" || true)
# Each diagnostic once (a header's appear once per source that includes it).
found=$(sed 's/\x1b\[[0-9;]*m//g' "$log" | grep -E "^[^ ]+:[0-9]+:[0-9]+: (warning|error): " | sort -u || true)
if [ -n "$found" ]; then
  echo "$found"
  echo "run_clang_tidy: $(echo "$found" | wc -l) diagnostics in $files sources ($(($(date +%s) - start)) s)"
  exit 1
fi
if [ "$status" -ne 0 ]; then
  sed 's/\x1b\[[0-9;]*m//g' "$log" | tail -30
  echo "run_clang_tidy: clang-tidy failed (exit $status) without a diagnostic"
  exit 1
fi
echo "run_clang_tidy: $files sources clean ($(($(date +%s) - start)) s)"
