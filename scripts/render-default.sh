#!/usr/bin/env bash
# Renders the default scene (assets/scenes/default.json: the generated robot on
# its ground plane under the generated sun-and-sky) into out/. Called by
# scripts/quickstart.sh render after the build.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
rsl="$build/rsl"
mkdir -p out
scene=assets/scenes/default.json
time=${RSL_DEFAULT_TIME:-0.5}

echo "== environment → rotatable square lights"
"$rsl" fit assets/generated/sunsky.exr --lights 30 -o out/sunsky_lights.json --preview out/sunsky_fit.png

echo "== ground truth (Embree) at t=$time"
"$rsl" truth "$scene" --time "$time" -o out/default_truth.exr --vertex-out out/default_truth.rslv

echo "== images written:"
ls -1 out/*.png
