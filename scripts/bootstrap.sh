#!/usr/bin/env bash
# ShadowLab set-up on a fresh Debian 12 machine, as root: installs the missing Debian packages, configures
# and builds, then either renders the default dataset (`render`) or runs every test (`test`, what CI runs).
#
#   bash scripts/bootstrap.sh render   # -> out/ (image, buffers.vti, heat maps, stats.json)
#   bash scripts/bootstrap.sh test     # -> ctest, every suite (unit, GPU on llvmpipe, CLI)
#
# Environment: BUILD_DIR (default build), JOBS (default: number of cores).
set -euo pipefail

mode="${1:-}"
if [[ "$mode" != "render" && "$mode" != "test" && "$mode" != "build" ]]; then
  echo "usage: bash scripts/bootstrap.sh render|test|build" >&2
  exit 2
fi
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build}"
jobs="${JOBS:-$(nproc)}"

# Build tools, the libraries of the stack, and Mesa's EGL/llvmpipe for headless rendering.
# python3-imath only silences a Debian packaging warning from Imath's CMake config (it names that file).
# xvfb and xauth: xvfb-run gives the test of `shadowlab view` (tests/cli/ViewTest.cpp) a display; on a desktop the
# viewer opens its window on the desktop's.
packages=(
  cmake g++ make pkg-config
  libvtk9-dev libglm-dev libopenmesh-dev libopenexr-dev python3-imath libgtest-dev
  libegl-dev libgl-dev libglew-dev libegl-mesa0 libgl1-mesa-dri
  nlohmann-json3-dev libcli11-dev libembree-dev libpng-dev
  xvfb xauth
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# RelWithDebInfo with line tables only (-g1, as scripts/sanitize.sh): file:line in every backtrace, and the build
# is a third faster than with full -g (from a clean clone on 2 cores: 10 min 26 s -> 7 min 41 s; shadowlab 125 MB ->
# 25 MB). A debugger session that needs variables: reconfigure with -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g".
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" >/dev/null

# The ParaView test (tests/paraview) runs Debian's pvpython. Its libraries come with `paraview`; its Python modules
# (python3-paraview) conflict with libvtk9-dev (both ship vtkmodules), so the package is unpacked into the build
# directory instead of installed; tests/paraview/run_in_pvpython.py puts its modules first.
if [[ "$mode" == "test" && ! -x "$build_dir/pvpython-root/usr/bin/pvpython" ]]; then
  apt-get update -qq
  if ! dpkg-query -W -f='${Status}' paraview 2>/dev/null | grep -q "install ok installed"; then
    echo "bootstrap: installing paraview (for the ParaView script test)" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends paraview >/dev/null
  fi
  download="$(mktemp -d)"
  chmod 755 "$download" # apt-get download drops privileges to _apt
  (cd "$download" && apt-get download -qq python3-paraview >/dev/null)
  dpkg-deb -x "$download"/python3-paraview_*.deb "$build_dir/pvpython-root"
  rm -rf "$download"
fi

case "$mode" in
  render)
    # Only what it runs: the executable and its libraries, not the test suites.
    cmake --build "$build_dir" -j "$jobs" --target shadowlab
    "$build_dir/shadowlab" render datasets/bunny/scene.json --out out
    ;;
  test)
    cmake --build "$build_dir" -j "$jobs"
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    ;;
  build)
    cmake --build "$build_dir" -j "$jobs"
    ;;
esac
