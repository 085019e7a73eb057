#!/usr/bin/env bash
# One-command set-up on Debian 12: install packages (if missing), configure and
# build in Release, then either render the default scene or run the test suite.
#   scripts/quickstart.sh render   → images in out/
#   scripts/quickstart.sh test     → ctest, the whole suite
# Idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-render}
build=${RSL_BUILD_DIR:-build}

packages=(build-essential cmake ninja-build pkg-config ccache
  libembree-dev libglfw3-dev libglm-dev libopenexr-dev libeigen3-dev libtinygltf-dev catch2
  libtbb-dev libstb-dev nlohmann-json3-dev libcli11-dev libimgui-dev libfmt-dev
  libgl-dev libegl-dev libopengl-dev libgl1-mesa-dri xvfb xauth
  glslang-tools  # the Khronos reference GLSL compiler (tests/gl/shader_reference_test.cpp)
  pybind11-dev python3-dev python3-numpy python3-matplotlib dpkg-dev file
  clang-14 libclang-rt-14-dev)  # the sanitizer build and the fuzzers (scripts/sanitize.sh, scripts/fuzz.sh)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "== installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# ccache shares objects between clones of the tree (a CI run in a fresh
# clone reuses what the session built): paths under the tree are hashed
# relative to it, and the build folder's own path is left out.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
echo "== configure + build ($build, Release, for this machine's CPU)"
# The program runs where it is built, so it may use this CPU's extensions
# (RSL_NATIVE=ON, as docs/RESULTS.md measured); packages for other machines
# come from a build with the default, portable flags (docs/API.md, "Packages").
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRSL_NATIVE=ON >/dev/null
if [ "$mode" = render ]; then
  # Rendering needs only the program and the generated assets, not the tests.
  cmake --build "$build" --parallel "$(nproc)" --target rsl generated_assets
else
  cmake --build "$build" --parallel "$(nproc)"
fi

case "$mode" in
  render)
    scripts/render-default.sh "$build"
    ;;
  test)
    cd "$build"
    ctest --output-on-failure --parallel "$(nproc)" --timeout 900
    ;;
  *)
    echo "usage: $0 render|test" >&2
    exit 2
    ;;
esac
