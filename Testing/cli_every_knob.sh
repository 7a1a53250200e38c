#!/usr/bin/env bash
# Every knob of `proxygi render` in every mode either changes the output
# (the picture or the per-vertex arrays differ from the mode's baseline run)
# or the program says it does not apply / is not honoured. A knob expected
# to change the output that leaves it bit for bit equal fails, as does a
# run whose output lacks the expected sentence or that exits non-zero.
#
#   cli_every_knob.sh PROXYGI WORKDIR CACHE
set -uo pipefail
proxygi="$1" work="$2" cache="$3"
mkdir -p "$work"
common=(--size 64x48 --spheres 16 --cache "$cache")
# VTK's Python (python3-paraview) reads the per-vertex files.
python=/usr/bin/python3
failures=0 checks=0

# Baselines: the GPU one on the unshadowed bounce (the shadowed program is
# the slowest to compile on llvmpipe; the knob --indirect shadowed covers it).
declare -A base=(
  [vertex]="--mode vertex"
  [gpu]="--mode gpu --indirect unshadowed"
  [image-space]="--mode image-space"
)

run() { # name mode extra-args... ; writes $work/<name>.{png,log}[, vtp]
  local name="$1" mode="$2"; shift 2
  local vtp=()
  [ "$mode" != image-space ] && vtp=(--vtp "$work/$name")
  # shellcheck disable=SC2086
  "$proxygi" render ${base[$mode]} "${common[@]}" "${vtp[@]}" -o "$work/$name.png" "$@" \
    >"$work/$name.log" 2>&1
}

differs() { # a b: the picture or any object's per-vertex Radiance differs (beyond round-off)
  local a="$1" b="$2"
  cmp -s "$work/$a.png" "$work/$b.png" || return 0
  for f in "$work/$a"-*.vtp; do
    [ -e "$f" ] || continue
    # The files also hold the plan with its timings: compare the radiance.
    "$python" - "$f" "$work/$b${f#"$work/$a"}" <<'PY' || return 0
import sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
def radiance(path):
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    a = r.GetOutput().GetPointData().GetArray("Radiance")
    return [a.GetValue(i) for i in range(a.GetNumberOfValues())] if a else None
a, b = radiance(sys.argv[1]), radiance(sys.argv[2])
# Runs agree to float round-off only (parallel SH projection sums): a
# knob must move some value by more than 1e-4 of the brightest.
if a is None or b is None or len(a) != len(b):
    sys.exit(a != b)
peak = max(max(abs(x) for x in a), 1e-30)
sys.exit(0 if max(abs(x - y) for x, y in zip(a, b)) <= 1e-4 * peak else 1)
PY
  done
  return 1
}

check() { # mode expectation knob-args... ; expectation: changes | says:REGEX
  local mode="$1" expect="$2"; shift 2
  local name noerror=(--no-error)
  name="$(printf '%s' "$mode $*" | tr -c 'A-Za-z0-9' '_')"
  # Knobs of the error need the error on: "+error" drops --no-error.
  if [ "${1:-}" = "+error" ]; then noerror=(); shift; fi
  checks=$((checks + 1))
  if ! run "$name" "$mode" "${noerror[@]}" "$@"; then
    echo "FAIL  $mode $*: exit code $? ($(tail -1 "$work/$name.log"))"
    failures=$((failures + 1))
    return
  fi
  case "$expect" in
    changes)
      if differs "base-$mode" "$name"; then
        echo "ok    $mode $*: changes the output"
      else
        echo "FAIL  $mode $*: the output is unchanged and nothing says why"
        failures=$((failures + 1))
      fi ;;
    says:*)
      local re="${expect#says:}" line
      line="$(grep -E -m1 -e "$re" "$work/$name.log")"
      if [ -n "$line" ]; then
        echo "ok    $mode $*: says \"$line\""
      else
        echo "FAIL  $mode $*: no line matches /$re/"
        failures=$((failures + 1))
      fi ;;
  esac
}

for mode in vertex gpu image-space; do
  if ! run "base-$mode" "$mode" --no-error; then
    echo "FAIL  baseline of --mode $mode: $(tail -3 "$work/base-$mode.log")"
    exit 1
  fi
  [ -s "$work/base-$mode.png" ] || { echo "FAIL  -o: no picture in --mode $mode"; exit 1; }
  if [ "$mode" != image-space ] && ! ls "$work/base-$mode"-*.vtp >/dev/null 2>&1; then
    echo "FAIL  --vtp: no per-vertex files in --mode $mode"; exit 1
  fi
  echo "ok    $mode: baseline (-o and --vtp written)"
  check "$mode" changes --order 3
  check "$mode" changes --spheres 24
  check "$mode" changes --indirect off
  check "$mode" changes --size 80x60
  check "$mode" changes --exposure 3
done

check vertex changes --order 8
check gpu 'says:^not honoured: Order: order 8 is outside 2\.\.6' --order 8
check image-space 'says:^not honoured: Order: order 6 is outside 2\.\.4' --order 6
check vertex changes --method OL
check gpu 'says:^not honoured: ExpMethod: OL is not available' --method OL
check image-space 'says:^not honoured: ExpMethod: PS\* is not available' --method 'PS*'
check vertex changes --indirect unshadowed
check gpu changes --indirect shadowed
check image-space 'says:^not honoured: IndirectMode: shadowed' --indirect shadowed
check vertex changes --hierarchy 0
check vertex changes --self-visibility 0
check gpu 'says:^note: --self-visibility does not apply to --mode gpu' --self-visibility 0
check vertex changes --bright-lights off
check vertex changes --bright-shadows proxies
check vertex changes --bright-rays 4
check gpu 'says:^note: --bright-lights does not apply to --mode gpu' --bright-lights off
check image-space 'says:^note: --bright-shadows does not apply to --mode image-space' \
  --bright-shadows proxies
check gpu 'says:^note: --bright-rays does not apply to --mode gpu' --bright-rays 4
check vertex changes --indirect-order 2
check gpu 'says:^not honoured: IndirectOrder: the bounce runs at the shading order' \
  --indirect shadowed --indirect-order 2
check gpu "says:^note: --indirect-order does not apply to --indirect unshadowed" --indirect-order 2
check image-space 'says:^note: --indirect-order does not apply to --mode image-space' \
  --indirect-order 2
# On this one-object scene per-object blocking leaves the output bit for
# bit as per sphere (measured); the plan must say it ran.
check vertex 'says:^plan: indirect light \(shadowed\): second pass over [0-9]+ receivers, per-object blocking' \
  --blocking object
check gpu 'says:^note: --blocking does not apply to --indirect unshadowed' --blocking object
check image-space 'says:^note: --blocking does not apply to --mode image-space' --blocking object
check vertex changes --plane-directions 0
check vertex changes --plane-directions 16
check gpu changes --plane-directions 0
check image-space 'says:^note: --plane-directions does not apply to --mode image-space' \
  --plane-directions 0
for mode in vertex gpu image-space; do
  check "$mode" changes --background none
  check "$mode" changes --proxy-fit bounding
done
check gpu 'says:^not honoured: HierarchyAngle' --hierarchy 25
check image-space 'says:^not honoured: HierarchyAngle' --hierarchy 25
check vertex 'says:^note: --scale does not apply to --mode vertex' --scale 4
check gpu 'says:^note: --scale does not apply to --mode gpu' --scale 4
check image-space changes --scale 4
check vertex 'says:^note: --reference-spp does not apply to --mode vertex \(--no-error\)' \
  --reference-spp 8
check vertex 'says:error against the Embree reference \(8 samples' +error --reference-spp 8
check gpu 'says:error against the Embree reference \(8 samples' +error --reference-spp 8
check image-space 'says:^note: --reference-spp does not apply to --mode image-space' \
  --reference-spp 8
check image-space 'says:^note: --vtp does not apply to --mode image-space' --vtp "$work/none"
check gpu 'says:^note: --pixel-reference-spp does not apply to --mode gpu' \
  +error --reference-spp 8 --pixel-reference-spp 8
check vertex 'says:per pixel against the Embree image \(8 samples' \
  +error --reference-spp 8 --pixel-error --pixel-reference-spp 8
check image-space 'says:per pixel against the Embree image \(8 samples' \
  +error --pixel-reference-spp 8
check image-space "says:^wrote .*Embree's image" \
  +error --pixel-reference-spp 8 --reference-png "$work/embree.png"
check gpu "says:^note: --reference-png does not apply to --mode gpu" \
  --reference-png "$work/none.png"

echo "$checks knob checks, $failures failed"
[ "$failures" -eq 0 ]
