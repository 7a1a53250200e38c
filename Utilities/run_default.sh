#!/usr/bin/env bash
# The main job: set up, build, render the default scene, write the image,
# print time and error. Extra arguments go to 'proxygi render'.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PROXYGI_BUILD_DIR:-$here/build}"
"$here/Utilities/build.sh"
mkdir -p "$here/out"
exec "$build/bin/proxygi" render -o "$here/out/default.png" "$@"
