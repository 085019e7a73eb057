#!/usr/bin/env bash
# ctest `package-install-embed`: scripts/install.sh (cmake --install that
# writes nothing into the build folder) into a temporary prefix, then
# examples/embed configured and built as a separate project against that
# prefix only (find_package(rsl)), run, and its image checked with the
# installed `rsl compare`; the installed Python module imports. The package
# needs neither GLFW nor ImGui (the viewer that uses them is the program's):
# its CMake files name neither, and embed is configured and built with their
# development files hidden (in a mount namespace of this test's own).
#   install_embed_test.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$1 source=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/rsl-install-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }
number_after() { sed -n "s/^$1 \([0-9.eE+-]*\).*/\1/p" | head -1; }
less_than() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

start=$(date +%s.%N)
# scripts/install.sh from the build folder mounted read-only (in a mount
# namespace of this test's own), as from a build tree the installer cannot write.
if unshare -m true 2>/dev/null; then
  unshare -m bash -c 'set -e
    mount --bind "$1" "$1" && mount -o remount,bind,ro "$1"
    if touch "$1/.rsl-write-probe" 2>/dev/null; then rm -f "$1/.rsl-write-probe"; echo "the build folder is still writable"; exit 1; fi
    "$2/scripts/install.sh" "$1" "$3"' install "$build" "$source" "$prefix" >"$work/install.log" 2>&1 \
    || { cat "$work/install.log"; fail "scripts/install.sh from the read-only build folder"; }
  echo "installed from the build folder mounted read-only"
else
  echo "WARN: unshare -m refused (no CAP_SYS_ADMIN): installing from the build folder as it is, not read-only"
  "$source/scripts/install.sh" "$build" "$prefix" >"$work/install.log"
fi
echo "== installed tree"
(cd "$prefix" && find . -type f | sort)
for f in bin/rsl include/rsl/rsl.h include/rsl/error.h include/rsl/version.h lib/cmake/rsl/rslConfig.cmake \
         lib/cmake/rsl/rslConfigVersion.cmake lib/cmake/rsl/rslTargets.cmake lib/librsl_api.a; do
  [ -e "$prefix/$f" ] || fail "not installed: $f"
done
# Only the public headers: the stage headers stay in the source tree.
[ "$(find "$prefix/include" -type f | wc -l)" -eq 3 ] || fail "headers other than <rsl/rsl.h>, <rsl/error.h>, <rsl/version.h> installed"
"$prefix/bin/rsl" --version | tee "$work/version.txt"
grep -q "^rsl [0-9]" "$work/version.txt" || fail "rsl --version"
if grep -il "glfw\|imgui" "$prefix"/lib/cmake/rsl/*.cmake; then fail "the CMake package names GLFW or ImGui"; fi

# `without_window_libraries CMD...`: CMD with GLFW's and ImGui's headers,
# CMake package and pkg-config files hidden, where a mount namespace is allowed.
hide_window_libraries=0
if unshare -m true 2>/dev/null; then hide_window_libraries=1; fi
without_window_libraries() {
  if [ "$hide_window_libraries" = 0 ]; then "$@"; return; fi
  unshare -m bash -c 'set -e
    for d in /usr/include/GLFW /usr/include/imgui /usr/lib/*/cmake/glfw3; do
      if [ -d "$d" ]; then mount -t tmpfs none "$d"; fi
    done
    for f in /usr/lib/*/pkgconfig/imgui.pc /usr/lib/*/pkgconfig/glfw3.pc; do
      if [ -e "$f" ]; then mount --bind /dev/null "$f"; fi
    done
    if [ -e /usr/include/GLFW/glfw3.h ] || [ -e /usr/include/imgui/imgui.h ]; then
      echo "GLFW or ImGui headers still visible"; exit 1
    fi
    "$@"' hide "$@"
}

echo "== examples/embed against $prefix"
if [ "$hide_window_libraries" = 1 ]; then
  echo "GLFW's and ImGui's development files hidden"
else
  echo "WARN: unshare -m refused (no CAP_SYS_ADMIN): embed built with GLFW's and ImGui's development files visible"
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
without_window_libraries cmake -S "$source/examples/embed" -B "$work/embed" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "${launcher[@]}" >"$work/embed-configure.log"
# It must have found the installed package, not the build tree.
grep -q "^rsl_DIR:PATH=$prefix/lib/cmake/rsl$" "$work/embed/CMakeCache.txt" || fail "embed found rsl elsewhere: $(grep rsl_DIR "$work/embed/CMakeCache.txt")"
without_window_libraries cmake --build "$work/embed" >"$work/embed-build.log" || { cat "$work/embed-build.log"; fail "embed does not build"; }
"$work/embed/embed" "$source/assets/generated/sunsky.exr" "$work/out" | tee "$work/embed.txt"
for f in first last last_truth; do [ -s "$work/out/$f.exr" ] && [ -s "$work/out/$f.png" ] || fail "embed wrote no $f.exr/.png"; done

echo "== its images, by the installed rsl compare"
"$prefix/bin/rsl" compare "$work/out/last.exr" "$work/out/last_truth.exr" | tee "$work/truth.txt"
"$prefix/bin/rsl" compare "$work/out/last.exr" "$work/out/first.exr" | tee "$work/moved.txt"
error=$(number_after "relative L2:" <"$work/truth.txt")
moved=$(number_after "relative L2:" <"$work/moved.txt")
covered=$(sed -n 's/.*over \([0-9]*\) covered pixels.*/\1/p' "$work/truth.txt")
# The last frame is the truth's up to the RSL approximation (30 lights, light
# fields); the ball has rolled 1 m and the sky turned 105°, so the first frame is not.
[ "${covered:-0}" -gt 5000 ] || fail "the image covers ${covered:-0} of 19200 pixels"
less_than "$error" 0.15 || fail "last frame against its truth: relative L2 $error ≥ 0.15"
less_than 0.10 "$moved" || fail "first and last frames differ by only $moved: nothing moved"

echo "== the figures docs/API.md quotes for this run"
# "(measured: P% over the pixels, V% over the vertices) ... (M%: the ball rolled)",
# each within one unit of the last digit printed there (builds for other CPUs
# round differently).
api=$(tr '\n' ' ' <"$source/docs/API.md")
vertices=$(sed -n 's/.*last frame against the ground truth: relative L2 \([0-9.eE+-]*\).*/\1/p' "$work/embed.txt" | head -1)
check_quoted() {  # name, measured fraction, the doc's sentence pattern around one "([0-9.]+)%"
  quoted=$(printf '%s' "$api" | sed -n "s/.*$3.*/\1/p")
  [ -n "$quoted" ] || fail "docs/API.md no longer quotes the $1 (pattern: $3)"
  awk -v q="$quoted" -v m="$2" 'BEGIN { d = length(q) - index(q, "."); if (index(q, ".") == 0) d = 0;
      u = 10 ^ -d; e = 100 * m - q; exit !(e <= u && -e <= u) }' ||
    fail "docs/API.md quotes the $1 as $quoted%; this run measured $(awk -v m="$2" 'BEGIN { printf "%.2f", 100 * m }')%"
  echo "API.md's $1: $quoted% (measured $2)"
}
check_quoted "pixels' error" "$error" 'measured: *\([0-9.]*\)% over the pixels'
check_quoted "vertices' error" "$vertices" 'over the pixels, *\([0-9.]*\)% over the vertices'
check_quoted "first-to-last difference" "$moved" '(\([0-9.]*\)%: the ball rolled'

echo "== the installed Python module"
if [ -n "$python" ]; then
  PYTHONPATH="$prefix/lib/python3/dist-packages" "$python" -c "import rsl, sys; print('import rsl:', rsl.__file__, rsl.__version__); sys.exit(not rsl.__file__.startswith('$prefix'))"
else
  echo "(this build has no Python module: RSL_BUILD_PYTHON=OFF)"
fi

end=$(date +%s.%N)
awk -v a="$start" -v b="$end" 'BEGIN { printf "install + embed build + run: %.1f s\n", b - a }'
