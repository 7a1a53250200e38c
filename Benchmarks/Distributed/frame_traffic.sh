#!/usr/bin/env bash
# Bytes and seconds per frame of the distributed pictures, per mode and rank
# count: two pvbatch runs per case (0 and FRAMES frames) under the
# mpi-traffic counter (LD_PRELOAD); bytes per frame = the difference of the
# ranks' summed sends / FRAMES.
#   frame_traffic.sh BUILD_DIR DATA_DIR [FRAMES] [RANKS...]
set -euo pipefail
build="$1" data="$2" frames="${3:-10}"
shift $(($# < 3 ? $# : 3))
ranks=("${@:-2 3}")
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mpicc -shared -fPIC -O2 -o "$work/libmpi_traffic.so" "$here/mpi_traffic.c"
plugin="$build/lib/proxygi/plugins/ProxyGI/ProxyGI.so"
run() { # ranks mode frames -> summed bytes and messages; the frame-time line
  "$here/../../Testing/run_under_xvfb.sh" mpiexec --allow-run-as-root --oversubscribe \
    -x LD_PRELOAD="$work/libmpi_traffic.so" -np "$1" pvbatch --mpi "$here/frame_traffic.py" \
    "$plugin" "$build/lib/python3/dist-packages" "$data/meshes/bunny00.off" \
    "$data/environments/forest.exr" "$2" "$3" >"$work/out" 2>&1 || { cat "$work/out"; exit 1; }
  grep -h "frame-time" "$work/out" || true
  awk '/^mpi-traffic:/ { b += $5; m += $8 } END { printf "%d %d\n", b, m }' "$work/out" >"$work/sum"
}
printf "| ranks | mode | bytes per frame (all ranks) | messages per frame | seconds per frame |\n"
printf "|---|---|---|---|---|\n"
for np in ${ranks[*]}; do
  for mode in filter surface moving image-space; do
    run "$np" "$mode" 0 >/dev/null
    read -r b0 m0 <"$work/sum"
    seconds="$(run "$np" "$mode" "$frames" | awk '{ print $3 }')"
    read -r b1 m1 <"$work/sum"
    printf "| %d | %s | %.0f | %.1f | %s |\n" "$np" "$mode" "$(((b1 - b0) / frames))" \
      "$(((m1 - m0) / frames))" "$seconds"
  done
done
