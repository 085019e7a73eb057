#!/usr/bin/env bash
# Installs a configured and built rsl build folder into a prefix, writing
# nothing into the build folder, so it works from a read-only one:
#   scripts/install.sh BUILD_DIR PREFIX [COMPONENT]
# (COMPONENT: program, development or python; default: all.) It is
# `cmake --install BUILD_DIR --prefix PREFIX` except that CMake 3.25's
# install script writes install_manifest.txt into the build folder; here the
# manifest goes to a temporary folder and is thrown away.
set -euo pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: scripts/install.sh BUILD_DIR PREFIX [COMPONENT]" >&2
  exit 2
fi
[ -f "$1/cmake_install.cmake" ] || { echo "install.sh: $1/cmake_install.cmake does not exist: not a configured build folder" >&2; exit 2; }
build=$(cd "$1" && pwd -P) prefix=$2 component=${3:-}
work=$(mktemp -d "${TMPDIR:-/tmp}/rsl-install.XXXXXX")
trap 'rm -rf "$work"' EXIT

# The one line of the generated script that writes into the build folder.
manifest_line='file(WRITE "'"$build"'/${CMAKE_INSTALL_MANIFEST}"'
script=$(<"$build/cmake_install.cmake")
case $script in
  *"$manifest_line"*) ;;
  *) echo "install.sh: $build/cmake_install.cmake does not write its manifest as CMake 3.25 does; use cmake --install" >&2; exit 1 ;;
esac
printf '%s\n' "${script//"$manifest_line"/file(WRITE \"$work/\${CMAKE_INSTALL_MANIFEST\}\"}" >"$work/cmake_install.cmake"
cmake -DCMAKE_INSTALL_PREFIX="$prefix" ${component:+-DCMAKE_INSTALL_COMPONENT="$component"} -P "$work/cmake_install.cmake"
