#!/usr/bin/env bash
# Builds `rsl` as a self-contained archive for a Linux x86-64 server that has
# none of the Debian packages (a GPU server; docs/GPU.md, "Running on an
# NVIDIA GPU server"):
#   scripts/portable-build.sh [OUTDIR]   → OUTDIR/rsl-portable-<version>-x86_64.tar.gz (default out/)
# The archive's top folder holds
#   bin/rsl           the program, its RPATH $ORIGIN/../lib
#   lib/              every shared library it needs, except glibc's and the GL/EGL loaders
#   lib/fallback/     libstdc++ and libgcc_s, used only where the server's are too old
#   assets/           the scene files and the project's generated assets
#   run-on-gpu.sh     checks the server, then runs `rsl bench gl` and the yard scenes headless
# Environment: RSL_PORTABLE_BUILD_DIR (default build-portable), RSL_PORTABLE_MARCH
# (default x86-64-v3), RSL_JOBS (default: the cores).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out}
build=${RSL_PORTABLE_BUILD_DIR:-build-portable}
# One x86-64 level, not -march=native: the build machine's AVX-512 would end
# the program with SIGILL on a server (or a virtual machine) without it.
# x86-64-v3 (AVX2, FMA: Intel since Haswell, AMD since Zen) because `rsl
# bench` sets the CPU renderer beside the GPU, and its vectorized loops run
# twice as fast there as at x86-64-v2 (yard-128 frames: 101 against 197 ms;
# native AVX-512: 84 ms). RSL_PORTABLE_MARCH=x86-64-v2 is for older CPUs;
# run-on-gpu.sh checks the server's CPU for the flags cpu_flags lists.
march=${RSL_PORTABLE_MARCH:-x86-64-v3}
case $march in
  x86-64-v2) cpu_flags="sse4_2 popcnt" ;;
  x86-64-v3) cpu_flags="avx2 fma bmi2 movbe" ;;
  x86-64-v4) cpu_flags="avx512f avx512bw avx512dq avx512vl" ;;
  *) echo "portable-build: RSL_PORTABLE_MARCH is x86-64-v2, x86-64-v3 or x86-64-v4" >&2; exit 2 ;;
esac
jobs=${RSL_JOBS:-$(nproc)}

# ccache shares objects between clones of the tree, as in scripts/quickstart.sh.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
echo "== configure + build ($build: Release, -march=$march, the rsl program only)"
# The program finds its libraries through a DT_RPATH of $ORIGIN/../lib
# (--disable-new-dtags), not a DT_RUNPATH: an executable's RUNPATH serves only
# its own direct dependencies, so libOpenEXR would look for libImath, and
# libglfw for libX11, in the server's folders; an RPATH serves them all.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRSL_NATIVE=OFF -DRSL_MARCH="$march" \
  -DRSL_BUILD_TESTS=OFF -DRSL_BUILD_PYTHON=OFF -DRSL_BUILD_GL=ON \
  -DCMAKE_BUILD_WITH_INSTALL_RPATH=ON -DCMAKE_INSTALL_RPATH='$ORIGIN/../lib' \
  -DCMAKE_EXE_LINKER_FLAGS=-Wl,--disable-new-dtags >/dev/null
cmake --build "$build" --parallel "$jobs" --target rsl

version=$(sed -n 's/^rsl \([0-9][0-9.]*\)$/\1/p' <("$build/rsl" --version))
name=rsl-portable-$version-x86_64
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stage=$work/$name
mkdir -p "$stage/bin" "$stage/lib/fallback" "$stage/assets"
cp "$build/rsl" "$stage/bin/rsl"

# The libraries, as the dynamic loader resolves them here. Left out: glibc
# (libc, libm, libdl, libpthread, librt, ld-linux: the server's must match its
# kernel, and the program needs glibc ≥ 2.34), and libglvnd's GL/EGL loaders
# (libEGL, libOpenGL, libGLdispatch, libGL, libGLX), which must be the
# server's so that they find its vendor driver (NVIDIA's libEGL_nvidia).
# libstdc++ and libgcc_s go into lib/fallback, off the RPATH: the program and
# its libraries need GLIBCXX_3.4.29 (GCC 11; BUILD.txt names the versions),
# which every system with glibc ≥ 2.34 has, and the server's own copy can be
# newer than this one and needed by its driver's libraries, which share the
# process. run-on-gpu.sh puts lib/fallback on LD_LIBRARY_PATH only when rsl
# does not start without it.
glibc='^(libc|libm|libdl|libpthread|librt|libresolv|libutil|libmvec|libanl|libnsl|ld-linux-x86-64)\.so'
loaders='^(libGL|libGLX|libEGL|libGLdispatch|libOpenGL|libGLESv1_CM|libGLESv2)\.so'
ldd "$stage/bin/rsl" | awk '$2 == "=>" {print $1, $3}' | while read -r soname path; do
  if [ "$path" = "not" ]; then
    echo "portable-build: $soname not found on this machine" >&2
    exit 1
  fi
  if [[ $soname =~ $glibc || $soname =~ $loaders ]]; then continue; fi
  case $soname in
    libstdc++.so.*|libgcc_s.so.*) cp -L "$path" "$stage/lib/fallback/$soname" ;;
    *) cp -L "$path" "$stage/lib/$soname" ;;
  esac
done

# The scenes that need only the generated assets (../generated/…; the bunny
# and the instanced scene name meshes of ../shared), and those assets, written
# by the program just built: this also checks that it runs.
mkdir -p "$stage/assets/scenes"
cp $(grep -L 'shared/assets' assets/scenes/*.json) "$stage/assets/scenes/"
"$stage/bin/rsl" assets --out "$stage/assets/generated" >/dev/null
cp scripts/portable/run-on-gpu.sh "$stage/run-on-gpu.sh"
# The newest glibc and libstdc++ symbol versions that the program and lib/ use.
newest() { objdump -T "$stage/bin/rsl" "$stage"/lib/*.so* | grep -o "$1_[0-9.]*" | sort -uV | tail -1; }
{
  "$stage/bin/rsl" --version
  echo "built: $(date -u +%Y-%m-%d) on $(. /etc/os-release && echo "$PRETTY_NAME"), -march=$march"
  echo "needs: Linux x86-64 ($march), glibc with $(newest GLIBC), libstdc++ with $(newest GLIBCXX)" \
    "(else lib/fallback's), libglvnd's libEGL.so.1 and libOpenGL.so.0, a GL driver"
  echo "cpu flags: $cpu_flags"
} >"$stage/BUILD.txt"

mkdir -p "$out"
archive=$out/$name.tar.gz
tar -C "$work" --owner=0 --group=0 -czf "$archive.tmp" "$name"
mv "$archive.tmp" "$archive"
echo "$archive: $(du -h "$archive" | cut -f1), $(find "$stage/lib" -name '*.so*' | wc -l) libraries"
