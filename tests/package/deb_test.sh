#!/usr/bin/env bash
# ctest `package-deb`: cpack -G DEB writes the three packages; each is
# inspected (dpkg-deb -I / -c), its declared Depends must all be Debian
# packages known to this Debian 12 system, and the program and module are run
# from the packages unpacked into a throwaway root.
#   deb_test.sh BUILD_DIR PYTHON
set -euo pipefail
build=$1 python=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/rsl-deb-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

start=$(date +%s.%N)
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work" >"$work/cpack.log" || { cat "$work/cpack.log"; fail "cpack"; }
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
arch=$(dpkg --print-architecture)
declare -A expect=(
  [rsl]="./usr/bin/rsl ./usr/share/rsl/demos/materials/scene.json ./usr/share/rsl/assets/generated/orb.obj"
  [python3-rsl]="./usr/lib/python3/dist-packages/rsl.cpython-"
  [librsl-dev]="./usr/include/rsl/rsl.h ./usr/lib/cmake/rsl/rslConfig.cmake ./usr/lib/librsl_api.a"
)
packages=(rsl librsl-dev)
[ -n "$python" ] && packages+=(python3-rsl)
for package in "${packages[@]}"; do
  deb="$work/${package}_${version}_${arch}.deb"
  [ -f "$deb" ] || fail "no $deb (cpack wrote: $(ls "$work"/*.deb))"
  echo "== dpkg-deb -I $(basename "$deb")"
  dpkg-deb -I "$deb" | tee "$work/$package.info"
  dpkg-deb -c "$deb" >"$work/$package.contents"
  echo "   $(wc -l <"$work/$package.contents") entries"
  for path in ${expect[$package]}; do
    grep -q " $path" "$work/$package.contents" || fail "$package lacks $path"
  done
  depends=$(dpkg-deb -f "$deb" Depends)
  [ -n "$depends" ] || fail "$package declares no Depends"
  # "libc6 (>= 2.34), libembree3-3 (>= 3.13), python3 (<< 3.12)": the names.
  relations="$depends, $(dpkg-deb -f "$deb" Recommends)"
  for name in $(echo "$relations" | tr ',|' '\n\n' | sed 's/(.*)//; s/ //g' | sort -u); do
    dpkg-query -W -f='${Status}\n' "$name" 2>/dev/null | grep -q "install ok installed" ||
      apt-cache show "$name" >/dev/null 2>&1 || fail "$package depends on '$name', no Debian package here"
  done
  dpkg-deb -x "$deb" "$work/root"
done
grep -q "libembree3-3" "$work/rsl.info" || fail "rsl does not depend on Embree's library package"
[ -z "$python" ] || grep -q "python3-numpy" "$work/python3-rsl.info" || fail "python3-rsl does not depend on python3-numpy"

echo "== run from the unpacked packages"
"$work/root/usr/bin/rsl" --version
"$work/root/usr/bin/rsl" --help >/dev/null
# A demo from the package: its scene files from share/rsl, its frames and field cache in --out alone.
"$work/root/usr/bin/rsl" demo materials --quick --frames 1 --width 24 --height 18 -q --out "$work/demo" >/dev/null ||
  fail "rsl demo from the unpacked package"
ls "$work/demo/.rsl-cache/"*.rslf >/dev/null 2>&1 || fail "rsl demo wrote no field cache into --out"
[ -z "$(find "$work/root/usr/share/rsl" -name .rsl-cache)" ] || fail "rsl demo wrote a cache into share/rsl"
[ -z "$python" ] || PYTHONPATH="$work/root/usr/lib/python3/dist-packages" "$python" -c "import rsl; print('import rsl', rsl.__version__, rsl.build_info()['commit'])"
end=$(date +%s.%N)
awk -v a="$start" -v b="$end" 'BEGIN { printf "cpack + inspection: %.1f s\n", b - a }'
