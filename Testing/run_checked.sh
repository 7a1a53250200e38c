#!/usr/bin/env bash
# Runs a test command and judges it by its exit code AND its output, since
# CTest's PASS_REGULAR_EXPRESSION alone throws the exit code away.
#
#   run_checked.sh [--exit N|refused] [--pass REGEX]... [--fail REGEX]... [--last REGEX] -- COMMAND...
#
#   --exit N        the exit code it must return (default 0); 'refused': any
#                   code from 1 to 127 (a refusal, not a crash by a signal)
#   --pass REGEX    must match some line of the output (each one given)
#   --fail REGEX    must match no line of the output
#   --last REGEX    must match the last non-empty line of standard output
# Output goes through unchanged; the verdict is the last line.
set -uo pipefail
want_exit=0
pass=() fail=() last=""
while [ $# -gt 0 ]; do
  case "$1" in
    --exit) want_exit="$2"; shift 2 ;;
    --pass) pass+=("$2"); shift 2 ;;
    --fail) fail+=("$2"); shift 2 ;;
    --last) last="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "run_checked: unknown option $1" >&2; exit 2 ;;
  esac
done
[ $# -gt 0 ] || { echo "run_checked: no command" >&2; exit 2; }

out="$(mktemp)" err="$(mktemp)"
trap 'rm -f "$out" "$err"' EXIT
"$@" >"$out" 2>"$err"
code=$?
cat "$out"
cat "$err" >&2

problems=()
if [ "$want_exit" = refused ]; then
  { [ "$code" -ge 1 ] && [ "$code" -le 127 ]; } || problems+=("exit code $code, expected a refusal (1-127)")
elif [ "$code" -ne "$want_exit" ]; then
  problems+=("exit code $code, expected $want_exit")
fi
# grep reads the files itself: in a pipe, grep -q exiting early would fail
# the pipe under pipefail and turn a match into a miss.
for re in "${pass[@]}"; do
  grep -Eqh -- "$re" "$out" "$err" || problems+=("no line matches '$re'")
done
for re in "${fail[@]}"; do
  grep -Eqh -- "$re" "$out" "$err" && problems+=("a line matches '$re'")
done
if [ -n "$last" ]; then
  final="$(grep -v '^[[:space:]]*$' "$out" | tail -n 1)"
  grep -Eq -- "$last" <<<"$final" || problems+=("last line '$final' does not match '$last'")
fi
if [ ${#problems[@]} -gt 0 ]; then
  printf 'run_checked: FAILED: %s\n' "${problems[@]}" >&2
  exit 1
fi
echo "run_checked: passed (exit $code)"
exit 0
