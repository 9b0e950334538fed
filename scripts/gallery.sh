#!/usr/bin/env bash
# Renders the README's gallery of real glTF models with `rgraph render` at its defaults
# (the default pipeline, default lighting for files without lights), into docs/gallery/.
#
#   scripts/gallery.sh MODELS_DIR
#
# MODELS_DIR holds the models as their repositories ship them (see
# ../shared/notes/real-assets.md; none but AlphaBlendModeTest is committed here, for
# their size or licence): bevyengine/bevy assets/models/{FlightHelmet,animated/Fox.glb,
# DepthOfFieldExample} and googlestadia/PorQue4K assets/models/DamagedHelmet.
set -euo pipefail
models=${1:?usage: scripts/gallery.sh MODELS_DIR}
cd "$(dirname "$0")/.."
cargo build --release --quiet
out=docs/gallery
mkdir -p "$out"
render() {
    local name=$1 scene=$2
    shift 2
    echo "== $name: rgraph render --scene $scene $*" >&2
    ./target/release/rgraph render --scene "$scene" --width 1280 --height 720 "$@" \
        --out "$out/$name.png" 2>&1 | grep -E "warning|error" >&2 || true
}
render flight_helmet "$models/FlightHelmet/FlightHelmet.gltf"
render damaged_helmet "$models/DamagedHelmet/glTF/DamagedHelmet.gltf"
render fox "$models/animated/Fox.glb"
render alpha_blend_mode_test tests/fixtures/AlphaBlendModeTest/AlphaBlendModeTest.glb
render depth_of_field_exposure_1 "$models/DepthOfFieldExample/DepthOfFieldExample.glb"
render depth_of_field_exposure_auto "$models/DepthOfFieldExample/DepthOfFieldExample.glb" \
    --exposure auto
# An animation as a strip of frames: 0, 0.5, 1 and 1.5 s (docs/reference/scenes.md).
./target/release/rgraph render --scene tests/fixtures/AnimatedCubes/AnimatedCubes.gltf \
    --animation dance --time 0..1.5 --frames 4 --width 480 --height 270 \
    --out "$out/animated_cubes_%04d.png" 2>&1 | grep -E "warning|error" >&2 || true
# A skinned walk turning about the fox: 0, 0.2, 0.4 and 0.6 s seen from 0, 90, 180 and
# 270 degrees.
./target/release/rgraph render --scene "$models/animated/Fox.glb" --animation Walk \
    --time 0..0.6 --frames 4 --orbit 270 --width 480 --height 270 \
    --out "$out/fox_walk_%04d.png" 2>&1 | grep -E "warning|error" >&2 || true
