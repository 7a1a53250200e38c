#!/usr/bin/env bash
# Starts an MPI pvserver (RANKS ranks) on a free port, runs the pvpython
# client script against it, stops the server; the client's exit status.
#   client_server.sh MPIEXEC RANKS PVSERVER PVPYTHON SCRIPT ARGS...
# The script gets ARGS then the port. Under run_under_xvfb.sh (one X server
# for server and client).
set -uo pipefail
mpiexec="$1" ranks="$2" pvserver="$3" pvpython="$4" script="$5"
shift 5
port=$((20000 + $$ % 20000))
log="$(mktemp)"
"$mpiexec" --allow-run-as-root --oversubscribe -np "$ranks" "$pvserver" --mpi \
  --server-port="$port" >"$log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null; wait "$server" 2>/dev/null; rm -f "$log"' EXIT
for _ in $(seq 100); do
  grep -q "Accepting connection" "$log" && break
  kill -0 "$server" 2>/dev/null || { cat "$log"; echo "FAIL pvserver did not start"; exit 1; }
  sleep 0.2
done
"$pvpython" "$script" "$@" "$port"
status=$?
echo "--- pvserver:"
grep -v "WARN" "$log" | tail -20
exit "$status"
