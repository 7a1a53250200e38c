#!/usr/bin/env bash
# Builds ProxyGI's C++ modules, programs and tests against Debian's plain
# VTK 9.1 (libvtk9-dev) and runs the tests that need no GL.
#
# libvtk9-dev cannot share a machine with ParaView's SDK (installing
# python3-paraview removes it), so this runs in a Debian 12 root of its own
# made by debootstrap (no container runtime needed: chroot and bind mounts).
# It is a separate CI step (label 'vtk91'), not part of the default run: the
# first run downloads about 1 GiB of packages and builds the whole tree again.
#
#   Utilities/check_vtk91.sh          make the root if needed, build, test
#   Utilities/check_vtk91.sh --root   only make the root
#   PROXYGI_VTK91_ROOT=DIR            where the root lives (default /var/tmp/proxygi-vtk91)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="${PROXYGI_VTK91_ROOT:-/var/tmp/proxygi-vtk91}"

if [ "$(id -u)" -ne 0 ]; then
  echo "check_vtk91: needs root (debootstrap, chroot, mount)" >&2
  exit 2
fi

packages=(
  build-essential cmake ninja-build pkg-config file python3
  libvtk9-dev
  libembree-dev libopenexr-dev libglm-dev libeigen3-dev libhwy-dev
  libegl-dev libglew-dev libgl1-mesa-dri
  libgtest-dev libbenchmark-dev
)

mounted=()
# A conffile an upgrade in the root touches must not stop dpkg at a prompt.
confold=(-o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold)
cleanup() {
  local k
  for ((k = ${#mounted[@]} - 1; k >= 0; k--)); do umount "${mounted[k]}" 2>/dev/null || true; done
}
trap cleanup EXIT
# What package scripts and the build need inside the root.
mount_system() {
  mkdir -p "$root/proc" "$root/dev/pts" "$root/src"
  mount -t proc proc "$root/proc" && mounted+=("$root/proc")
  mount --bind /dev "$root/dev" && mounted+=("$root/dev")
  mount -t devpts devpts "$root/dev/pts" && mounted+=("$root/dev/pts")
}

# Before anything is mounted in it: debootstrap makes the root's own /dev
# entries, which a bind-mounted /dev would turn into the host's.
bootstrap_root() {
  if ! command -v debootstrap >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap >/dev/null
  fi
  # A root whose debootstrap did not finish is made again from nothing.
  if [ ! -f "$root/.proxygi-bootstrapped" ]; then
    echo "check_vtk91: making a Debian 12 root in $root"
    rm -rf "$root"
    debootstrap --variant=minbase bookworm "$root" >/dev/null
    touch "$root/.proxygi-bootstrapped"
  fi
}

make_root() {
  # The same package sources as this machine.
  if [ -n "$(ls /etc/apt/sources.list.d/ 2>/dev/null)" ]; then
    rm -f "$root/etc/apt/sources.list"
    cp /etc/apt/sources.list.d/* "$root/etc/apt/sources.list.d/"
  fi
  chroot "$root" apt-get update -qq
  # An install cut short before (no /proc then) is finished first.
  chroot "$root" env DEBIAN_FRONTEND=noninteractive dpkg --force-confdef --force-confold \
    --configure -a >/dev/null 2>&1 || true
  echo "check_vtk91: installing ${packages[*]}"
  chroot "$root" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -qq --no-install-recommends "${confold[@]}" "${packages[@]}" >/dev/null
  touch "$root/.proxygi-ready"
}

# Packages added to the list since the root was made.
missing_packages() {
  local p
  for p in "${packages[@]}"; do
    chroot "$root" dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
      echo "$p"
  done
}

# The meshes and maps the tests read (in this tree's ignored Data/).
"$here/Utilities/setup.sh" --data

[ -f "$root/.proxygi-ready" ] || bootstrap_root
mount_system
if [ ! -f "$root/.proxygi-ready" ]; then
  make_root
else
  missing=($(missing_packages))
  if [ ${#missing[@]} -gt 0 ]; then
    echo "check_vtk91: installing ${missing[*]}"
    chroot "$root" env DEBIAN_FRONTEND=noninteractive \
      apt-get install -y -qq --no-install-recommends "${confold[@]}" "${missing[@]}" >/dev/null
  fi
fi
[ "${1:-}" = "--root" ] && exit 0

mount --bind "$here" "$root/src" && mounted+=("$root/src")
mount -o remount,bind,ro "$root/src" 2>/dev/null || true

vtk_version="$(chroot "$root" dpkg-query -W -f='${Version}' libvtk9-dev)"
echo "check_vtk91: libvtk9-dev $vtk_version"

# No ParaView SDK in the root, so the build finds the plain VTK.
chroot "$root" cmake -S /src -B /build -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPROXYGI_PARAVIEW_VTK_DIR=/nonexistent -DPROXYGI_DATA_DIR=/src/Data \
  -DPROXYGI_ALLOW_MISSING_TESTS=ON
chroot "$root" nice cmake --build /build --parallel "${PROXYGI_JOBS:-2}"
# The default suite, GL included (EGL on Mesa needs no X); the root has no
# Xvfb, so the GLX test is left out (said at configure time).
chroot "$root" sh -c 'cd /build && ctest --output-on-failure --label-exclude slow --parallel 2'
