#!/usr/bin/env bash
# Renders the default scene (assets/scenes/default.json: the generated walking
# robot on its ground plane under the generated sun and sky) into out/, with
# the RSL renderer and with the Embree ground truth, and their difference.
# Called by scripts/quickstart.sh render after the build.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
rsl="$build/rsl"
mkdir -p out
scene=assets/scenes/default.json
time=${RSL_DEFAULT_TIME:-0.5}

echo "== environment → 30 rotatable square lights (paper Figure 6 style preview)"
"$rsl" fit assets/generated/sunsky.exr --lights 30 -o out/sunsky_lights.json --preview out/sunsky_fit.png

echo "== visibility fields (baked once, then cached in assets/scenes/.rsl-cache)"
"$rsl" bake "$scene"

echo "== RSL renderer (CPU), 30 lights, t=$time"
"$rsl" render "$scene" --time "$time" --lights 30 -o out/default.exr --vertex-out out/default.rslv

echo "== Embree ground truth, same frame (per pixel for the image, per vertex for the .rslv)"
"$rsl" truth "$scene" --time "$time" --per-pixel -o out/default_truth.exr --vertex-out out/default_truth.rslv

echo "== error of the RSL frame against the truth"
"$rsl" compare out/default.rslv out/default_truth.rslv
"$rsl" compare out/default.exr out/default_truth.exr --error-image out/default_error.png

echo "== images written:"
ls -1 out/*.png
