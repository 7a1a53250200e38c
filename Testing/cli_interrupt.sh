#!/usr/bin/env bash
# Ctrl-C during long work: `proxygi reference` and `proxygi proxies` get
# SIGINT two seconds into their work; each must stop, say it, exit 130 and
# leave no output file (nor a temporary one) behind. Then the same runs
# without an interrupt write their files: the interrupted ones were cut
# short, not finished.
#   cli_interrupt.sh PROXYGI MESH.off WORKDIR
set -uo pipefail
proxygi="$1" mesh="$2" work="$3"
rm -rf "$work" && mkdir -p "$work"
failures=0

check() { # name expected-status command...
  local name=$1 expected=$2
  shift 2
  "$@" >"$work/$name.log" 2>&1 &
  local pid=$!
  sleep 2
  kill -INT "$pid" 2>/dev/null
  wait "$pid"
  local status=$?
  local left
  left=$(ls "$work" | grep -v '\.log$' | tr '\n' ' ')
  if [ "$status" -eq "$expected" ] && grep -q "interrupted after .* nothing written" "$work/$name.log" &&
    [ -z "$left" ]; then
    echo "ok    $name: exit $status, '$(grep interrupted "$work/$name.log")', no file"
  else
    echo "FAIL  $name: exit $status (expected $expected), files left: [$left]"
    sed 's/^/      /' "$work/$name.log" | tail -5
    failures=$((failures + 1))
  fi
}

check reference 130 "$proxygi" reference --size 320x240 --spp 256 -o "$work/ref.exr"
check proxies 130 "$proxygi" proxies "$mesh" -n 64 -o "$work/spheres.vtp"
# Not interrupted: the files appear (small budgets).
"$proxygi" reference --size 16x12 --spp 1 -o "$work/ref.exr" >/dev/null 2>&1 &&
  [ -f "$work/ref.exr" ] && echo "ok    reference without Ctrl-C writes its file" ||
  { echo "FAIL  reference without Ctrl-C"; failures=$((failures + 1)); }
echo "$failures failed"
[ "$failures" -eq 0 ]
