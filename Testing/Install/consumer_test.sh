#!/usr/bin/env bash
# Uses ProxyGI as a program outside its tree would, from an installed tree
# (install) or from the .deb packages (deb):
#   consumer_test.sh install BUILD SOURCE WORK
#   consumer_test.sh deb     BUILD SOURCE WORK
# install: cmake --install to a prefix, moves the prefix (relocatable), then
# builds the consumer project (each installed header alone, find_package's
# refusals) and the examples with only ProxyGI_DIR set, and runs them.
# deb: cpack -G DEB, checks the packages' dependencies, unpacks them with
# dpkg -x, runs proxygi --version and the examples built against them.
set -euo pipefail
mode="$1" build="$2" source="$3" work="$4"
rm -rf "$work"
mkdir -p "$work"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)

fail() { echo "FAILED: $*" >&2; exit 1; }

case "$mode" in
  install)
    cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
    mv "$work/prefix" "$work/moved"
    prefix="$work/moved"
    ;;
  deb)
    (cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/packages") >"$work/cpack.log" \
      || { cat "$work/cpack.log"; fail "cpack"; }
    runtime=$(ls "$work"/packages/proxygi_*.deb 2>/dev/null | head -1)
    dev=$(ls "$work"/packages/proxygi-dev_*.deb 2>/dev/null | head -1)
    [ -n "$runtime" ] && [ -n "$dev" ] || fail "expected proxygi and proxygi-dev packages in $work/packages"
    for deb in "$runtime" "$dev"; do
      echo "$(basename "$deb"): Depends: $(dpkg-deb -f "$deb" Depends)"
    done
    depends=$(dpkg-deb -f "$runtime" Depends)
    for want in libembree3 libopenexr 'libstdc\+\+6' "paraview|libvtk9"; do
      grep -Eq "$want" <<<"$depends" || fail "proxygi does not depend on $want"
    done
    grep -q "proxygi (= " <<<"$(dpkg-deb -f "$dev" Depends)" || fail "proxygi-dev does not depend on proxygi"
    # The paths alone (a link's line goes on with "-> target").
    runtime_files="$(dpkg-deb -c "$runtime" | awk '{print $6}')"
    dev_files="$(dpkg-deb -c "$dev" | awk '{print $6}')"
    grep -q "usr/bin/proxygi$" <<<"$runtime_files" || fail "proxygi package has no usr/bin/proxygi"
    grep -Eq "usr/lib/libProxyGIShading\.so\.[0-9]+\.[0-9]+$" <<<"$runtime_files" \
      || fail "proxygi package has no versioned libraries"
    grep -q "usr/lib/libProxyGIShading.so$" <<<"$runtime_files" \
      && fail "the runtime package holds the development link libProxyGIShading.so"
    grep -q "usr/lib/libProxyGIShading.so$" <<<"$dev_files" || fail "proxygi-dev has no libProxyGIShading.so"
    grep -q "\.h$" <<<"$runtime_files" && fail "the runtime package holds headers"
    grep -q "ProxyGIConfig.cmake$" <<<"$dev_files" || fail "proxygi-dev has no ProxyGIConfig.cmake"
    grep -q "include/proxygi/vtkPGIGlobalIllumination.h$" <<<"$dev_files" || fail "proxygi-dev has no headers"
    dpkg -x "$runtime" "$work/root"
    dpkg -x "$dev" "$work/root"
    prefix="$work/root/usr"
    "$prefix/bin/proxygi" --version | tee "$work/version.txt"
    grep -q "^proxygi [0-9]" "$work/version.txt" || fail "proxygi --version"
    ;;
  *) fail "mode must be install or deb" ;;
esac

config_dir="$prefix/lib/cmake/proxygi"
[ -f "$config_dir/ProxyGIConfig.cmake" ] && [ -f "$config_dir/ProxyGIConfigVersion.cmake" ] \
  || fail "no ProxyGIConfig.cmake / ProxyGIConfigVersion.cmake in $config_dir"
# What is installed is the public API: no test harness, no private units.
for private in pgiGIShaders.h pgiTesting.h pgiHardScenes.h pgiSphereSetBuilder.h pgiMeshQueries.h; do
  [ ! -e "$prefix/include/proxygi/$private" ] || fail "private header $private is installed"
done
[ -z "$(find "$prefix" -name '*.glsl')" ] || fail "GLSL files are installed (shaders are compiled in)"

# Only ProxyGI_DIR: no VTK_DIR, no path into the build or source tree.
cmake -S "$source/Testing/Install" -B "$work/consumer" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DProxyGI_DIR="$config_dir" \
  -DPROXYGI_EXAMPLES_DIR="$source/Examples" >"$work/configure.log" \
  || { cat "$work/configure.log"; fail "configuring the consumer"; }
grep "ProxyGI \|installed headers" "$work/configure.log"
cmake --build "$work/consumer" --parallel 2 >"$work/build.log" \
  || { tail -50 "$work/build.log"; fail "building the consumer"; }
# The examples' own CMakeLists, alone, as a user copies them.
cmake -S "$source/Examples" -B "$work/examples" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DProxyGI_DIR="$config_dir" >"$work/examples-configure.log" \
  || { cat "$work/examples-configure.log"; fail "configuring Examples alone"; }

# The examples built against the installed tree run from there.
bin="$work/consumer/examples"
# (Captured first: grep -q closing the pipe early would fail it under pipefail.)
loaded="$(ldd "$bin/SoftShadowOfSphere")"
grep -q "$prefix/lib/libProxyGISphericalHarmonics" <<<"$loaded" \
  || fail "SoftShadowOfSphere does not load the installed library"
"$bin/SoftShadowOfSphere"
if [ -x "$bin/ExampleGIMapper" ]; then
  (cd "$work" && env -u DISPLAY "$bin/ExampleGIMapper" "$work/gi-mapper.png") | tee "$work/mapper.txt"
  grep -q "GI on the GPU: 4225 vertices, 1 proxies" "$work/mapper.txt" || fail "ExampleGIMapper did not run GI"
fi
if [ -x "$bin/LightCloudMapper" ]; then
  (cd "$work" && env -u DISPLAY "$bin/LightCloudMapper" "$source/Testing/Data/cornell-box.json" \
    "$work/light-cloud") | tee "$work/cloud.txt"
  grep -q "^frame 2: light cloud on the GPU" "$work/cloud.txt" \
    || fail "LightCloudMapper did not relight on the GPU"
fi
echo "consumer ($mode): passed"
