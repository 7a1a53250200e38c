#!/usr/bin/env bash
# ProxyGI set-up: installs the Debian 12 packages the project needs and
# fetches the data sets (meshes, HDR maps) into an ignored folder.
# Idempotent and quiet when everything is already in place.
#
#   Utilities/setup.sh            packages + data
#   Utilities/setup.sh --data     data only
#   Utilities/setup.sh --packages packages only
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data_dir="${PROXYGI_DATA_DIR:-$here/Data}"

# One VTK per machine: ParaView 5.11's SDK (VTK 9.2) serves the C++ modules
# and the ParaView plugin; libvtk9-dev conflicts with python3-paraview.
packages=(
  build-essential cmake ninja-build pkg-config file clang-format
  clang-14 libclang-rt-14-dev clang-tidy-14
  paraview-dev python3-paraview python3-dev
  qtbase5-dev qttools5-dev libqt5x11extras5-dev libqt5svg5-dev
  qtxmlpatterns5-dev-tools libqt5opengl5-dev libdouble-conversion-dev
  libopenmpi-dev libutfcpp-dev
  libembree-dev libopenexr-dev libglm-dev libeigen3-dev
  libegl-dev libglew-dev libosmesa6-dev libgl1-mesa-dri xvfb xauth
  libgtest-dev libbenchmark-dev libhwy-dev
)

want_packages=1
want_data=1
case "${1:-}" in
  --data) want_packages=0 ;;
  --packages) want_data=0 ;;
  "") ;;
  *) echo "usage: $0 [--data|--packages]" >&2; exit 2 ;;
esac

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

install_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# Downloads a .deb without installing it and unpacks it into a scratch folder.
unpack_deb() {
  local pkg="$1" dest="$2"
  local tmp
  tmp="$(mktemp -d)"
  (cd "$tmp" && apt-get download -qq "$pkg" >/dev/null 2>&1) || {
    "${sudo_cmd[@]}" apt-get update -qq
    (cd "$tmp" && apt-get download -qq "$pkg" >/dev/null)
  }
  dpkg -x "$tmp"/"$pkg"_*.deb "$dest"
  rm -rf "$tmp"
}

fetch_data() {
  local meshes="$data_dir/meshes" envs="$data_dir/environments"
  if [ ! -f "$meshes/bunny00.off" ]; then
    echo "setup: fetching meshes (libcgal-demo)"
    local x
    x="$(mktemp -d)"
    unpack_deb libcgal-demo "$x"
    mkdir -p "$meshes"
    tar -xzf "$x/usr/share/doc/libcgal-dev/data.tar.gz" -C "$x"
    cp "$x"/data/meshes/*.off "$meshes"/
    rm -rf "$x"
  fi
  if [ ! -f "$meshes/bent-cylinder.off" ]; then
    mkdir -p "$meshes"
    python3 "$here/Utilities/make_bent_cylinder.py" "$meshes/bent-cylinder.off"
  fi
  if [ ! -f "$envs/forest.exr" ]; then
    echo "setup: fetching HDR environments (blender-data)"
    local x
    x="$(mktemp -d)"
    unpack_deb blender-data "$x"
    mkdir -p "$envs"
    cp "$x"/usr/share/blender/datafiles/studiolights/world/*.exr "$envs"/
    rm -rf "$x"
  fi
}

[ "$want_packages" -eq 1 ] && install_packages
[ "$want_data" -eq 1 ] && fetch_data
exit 0
