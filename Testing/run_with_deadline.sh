#!/usr/bin/env bash
# Runs a command; if it is still running after SECONDS, prints a backtrace of
# every thread of each process under it (gdb, where installed) and kills
# them, so that a hang (an MPI job whose ranks wait on each other) says where
# it waits instead of leaving a silent ctest timeout. Exit code 124 then.
# Usage: run_with_deadline.sh SECONDS command [args...]
set -uo pipefail
deadline="$1"
shift
"$@" &
child=$!
descendants() {
  local pid
  for pid in $(ps -o pid= --ppid "$1" 2>/dev/null); do
    echo "$pid"
    descendants "$pid"
  done
}
for ((waited = 0; waited < deadline; waited++)); do
  if ! kill -0 "$child" 2>/dev/null; then
    wait "$child"
    exit $?
  fi
  sleep 1
done
echo "run_with_deadline: HANG: still running after ${deadline} s; backtraces follow"
pids="$child $(descendants "$child")"
for pid in $pids; do
  name="$(ps -o comm= -p "$pid" 2>/dev/null)"
  echo "run_with_deadline: process $pid ($name)"
  case "$name" in bash | sh | mpiexec | mpirun | orterun | xvfb-run | Xvfb | sleep) continue ;; esac
  if command -v gdb >/dev/null; then
    gdb -batch -nx -p "$pid" -ex "thread apply all bt 25" 2>/dev/null |
      grep -E "^(Thread|#)" | head -200
  fi
done
kill -9 $pids 2>/dev/null
wait "$child" 2>/dev/null
exit 124
