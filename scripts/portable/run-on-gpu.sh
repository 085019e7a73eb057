#!/usr/bin/env bash
# Runs rsl's GPU measurements headless on a Linux server with an NVIDIA GPU,
# from the unpacked archive of scripts/portable-build.sh (this file is its
# run-on-gpu.sh; docs/GPU.md, "Running on an NVIDIA GPU server"):
#   ./run-on-gpu.sh [--quick] [--yard 128,1024] [--out DIR]
# It checks that rsl starts, runs `rsl bench gl` (robot and kitchen; --quick:
# small fields, a smoke test) and `rsl bench gl-costs` (what a read and a
# branch cost on the device), then renders three frames of each yard scene
# with the GPU and the CPU backends. What it prints also goes to DIR/log.txt
# (default results/), the benchmark's JSON lines to DIR/bench-gl.jsonl.
set -euo pipefail
root=$(cd "$(dirname "$0")" && pwd)
rsl=$root/bin/rsl
quick=()
yards=128,1024
out=results
while (($#)); do
  case $1 in
    --quick) quick=(--quick); shift ;;
    --yard) yards=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "run-on-gpu.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
exec > >(tee -a "$out/log.txt") 2>&1

# libglvnd (libEGL.so.1) loads the vendor drivers its JSON files name. Naming
# NVIDIA's alone keeps Mesa's software rasterizer out when both are installed,
# and finds a driver installed outside libglvnd's folders (/usr/local/nvidia).
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then
  for dir in /etc/glvnd/egl_vendor.d /usr/share/glvnd/egl_vendor.d /usr/local/share/glvnd/egl_vendor.d \
             /usr/local/nvidia/share/glvnd/egl_vendor.d; do
    if [ -f "$dir/10_nvidia.json" ]; then
      export __EGL_VENDOR_LIBRARY_FILENAMES=$dir/10_nvidia.json
      break
    fi
  done
fi
echo "EGL vendor: ${__EGL_VENDOR_LIBRARY_FILENAMES:-every driver libglvnd finds (no 10_nvidia.json found)}"
# A driver mounted into a container is often outside the loader's cache.
for dir in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
  if [ -e "$dir/libEGL_nvidia.so.0" ]; then
    export LD_LIBRARY_PATH=$dir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
    break
  fi
done

# The program is built for one x86-64 level (BUILD.txt); on a CPU without its
# instructions it would die of SIGILL at some later point, so check first.
for flag in $(sed -n 's/^cpu flags: //p' "$root/BUILD.txt"); do
  if ! grep -qw "$flag" /proc/cpuinfo; then
    echo "run-on-gpu.sh: this CPU has no $flag, which this build needs (BUILD.txt);" \
      "build the archive with RSL_PORTABLE_MARCH=x86-64-v2" >&2
    exit 1
  fi
done

# The archive's libstdc++ and libgcc_s only where the server's are missing or
# too old (scripts/portable-build.sh says why they are not used first).
if ! "$rsl" --version >/dev/null 2>&1; then
  export LD_LIBRARY_PATH=$root/lib/fallback${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi
if ! "$rsl" --version; then
  cat >&2 <<'EOF'
run-on-gpu.sh: rsl does not start (above). It needs Linux x86-64 with glibc 2.34
or newer, and libglvnd's loaders libEGL.so.1 and libOpenGL.so.0 (Debian and
Ubuntu: apt-get install libegl1 libopengl0) beside the NVIDIA driver.
EOF
  exit 1
fi

scenes=$root/assets/scenes
generated=$root/assets/generated
echo "== rsl bench gl gl-costs ${quick[*]}"
"$rsl" bench gl gl-costs "${quick[@]}" --scenes "$scenes" --generated-assets "$generated" --out "$out/bench-out" |
  tee "$out/bench-gl.jsonl"
device=$(sed -n 's/.*"device":"\([^"]*\)".*/\1/p' "$out/bench-gl.jsonl" | head -1)
echo "OpenGL device: ${device:-none reported}"
if [[ $device == *llvmpipe* || $device == *softpipe* ]]; then
  echo "run-on-gpu.sh: this ran on Mesa's software rasterizer, not on the GPU" >&2
fi

if [ -n "$yards" ]; then
  echo "== yard scenes $yards"
  "$rsl" assets --out "$generated" --yard "$yards"
  for n in ${yards//,/ }; do
    for backend in gl cpu; do
      echo "== yard-$n, $backend: frames t = 0.25, 0.5, 0.75, 30 lights, per-pixel passes off"
      "$rsl" render "$generated/yard-$n.json" --backend "$backend" --frames 0.25:0.75:0.25 -k 30 \
        --pixel-shadows off --no-pixel-highlights -o "$out/yard-$n-$backend.exr"
    done
  done
fi
echo "== results in $out"
