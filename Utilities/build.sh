#!/usr/bin/env bash
# Configures and builds ProxyGI into build/ (or $PROXYGI_BUILD_DIR), after the
# set-up script. Two cores: the build runs two jobs.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/setup.sh"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" --parallel "${PROXYGI_JOBS:-2}"
