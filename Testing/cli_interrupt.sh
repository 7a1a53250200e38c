#!/usr/bin/env bash
# Ctrl-C during long work: `proxygi reference`, `proxygi proxies` and
# `proxygi render` (building a scene's proxies) get SIGINT two seconds into
# their work; each must stop, say it, exit 130 and leave no output file (nor
# a temporary one, nor a cache entry) behind. Then the same runs
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
  left=$( (ls "$work" | grep -v '\.log$' | grep -v '^cache$'; find "$work/cache" -type f 2>/dev/null) | tr '\n' ' ')
  if [ "$status" -eq "$expected" ] && grep -q "interrupted .*nothing written" "$work/$name.log" &&
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
check render 130 "$proxygi" render --mode vertex --no-error --cache "$work/cache" -o "$work/render.png"
# Without a terminal, progress is a line now and then.
grep -q "^proxygi render: building the proxies of 'bunny': 0%" "$work/render.log" &&
  echo "ok    render shows the proxies' progress as lines" ||
  { echo "FAIL  render showed no progress lines"; failures=$((failures + 1)); }
# Not interrupted: the files appear (small budgets).
"$proxygi" reference --size 16x12 --spp 1 -o "$work/ref.exr" >/dev/null 2>&1 &&
  [ -f "$work/ref.exr" ] && echo "ok    reference without Ctrl-C writes its file" ||
  { echo "FAIL  reference without Ctrl-C"; failures=$((failures + 1)); }
echo "$failures failed"
[ "$failures" -eq 0 ]
