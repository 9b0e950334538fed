#!/usr/bin/env bash
# rgraph bench on an NVIDIA server (H100/H200, no network, no display) in one command, at
# 3840x2160, writing results.json, results.md, charts and images.
#
#   scripts/bench-gpu.sh [OUT_DIR]       default: $OUT if set, else bench/results/h200
#
# The server has no network and no Rust: build the release binary on an x86_64
# development machine (`cargo build --release`) and bring it along, as .gl/bin/rgraph
# (with the Vulkan loader .debs in .gl/, see ../shared/notes/gpu.md) or target/release/rgraph,
# or name it with RGRAPH_BIN. The commit the binary was built from goes in
# RGRAPH_GIT_COMMIT when the server has no git checkout.
#
# Every part times a scene's pipelines together in interleaved rounds (A B C, A B C, ...:
# `rgraph bench --rounds`), each time the median of the round medians, a row whose rounds
# spread by more than 5% flagged with its reasons, and the GPU's clocks sampled per round
# with nvidia-smi (results.md and results.json say all of it). Each part fits one device
# call of 8 minutes at the default frames and rounds (results.json's elapsed_s says how
# long it took); `main` does not, so it is also split by scene.
#
# What runs (BENCH_PARTS picks a subset, e.g. BENCH_PARTS="main-dense lights"):
#   main        every pipeline in pipelines/ on builtin:dense and builtin:lights?count=256
#               (the issue's "dense scene with 256 lights": builtin:dense has 6 lights and
#               no light-count parameter, so the 256-light case is builtin:lights); about
#               ten minutes, longer than one device call: run its halves instead
#   main-dense  `main` on builtin:dense alone, into main-dense (not in the default set)
#   main-lights `main` on builtin:lights?count=256 alone, into main-lights (not in the
#               default set)
#   lights      the light sweep (1..1024: --sweep-max 1024) for noaa, MSAA 4x, per-sample 4x (each with its
#               fragment light passes and its tiled compute pass) and forward MSAA
#   scale       issue 38's cost curves for the default, lean and forward pipelines
#               (visibility_msaa_4x, deferred_msaa_4x_lean, forward_msaa_4x), without a
#               reference: --sweep triangles (builtin:terrain, 10^4..10^8) into
#               scale-triangles, --sweep meshes (builtin:city, 2..99,857) into scale-meshes
#               and --sweep lights (1..65,536) into scale-lights (not in the default set;
#               scale-triangles, scale-meshes and scale-lights run one sweep each)
#   samples     the sample-count sweep (1, 2, 4, 8) of the same pipelines on builtin:dense
#   resolution  720p..2160p of the same pipelines on builtin:dense
#   specialise  the same pipelines on every built-in scene without a reference: each
#               compiled for its scene and, where that differs, for every feature (the
#               savings table in results.md)
#   gbuffer     the G-buffer's cost as its targets are removed one at a time
#               (bench/graphs/gbuffer_cost/), the visibility buffer (rasterised in
#               compute, as visibility_msaa_4x.ron does on a GPU), its depth-only floor
#               and its hardware raster (bench/graphs/visibility_cost/), at 1 and 4
#               samples on builtin:dense and builtin:lights?count=256, into gbuffer-1x
#               and gbuffer-4x
#   every-4x    every 4x pipeline the README's summary table compares (tiled, adaptive, lean,
#               visibility, the fragment light volumes and their FXAA, SSAO and light
#               pre-pass variants) beside forward MSAA and the 1x baselines, on
#               builtin:dense and builtin:lights?count=256, with the reference, into
#               every-4x: 26 rows in about five minutes of an H200 (not in the default set)
#   default     the default pipeline (pipelines/visibility_msaa_4x.ron) beside the G-buffer
#               pipeline it replaces on builtin:dense, builtin:lights?count=256 and each
#               real model named in BENCH_MODELS (paths, e.g. models/FlightHelmet/FlightHelmet.gltf),
#               with the reference, into default; and on builtin:smoke beside
#               particles_low_res.ron at its default count, into default-smoke (issue 35's
#               targets; not in the default set); default/same-image.md holds `rgraph
#               compare` of each scene's two renders (within 1/255 on 99% of pixels)
#   visibility  the visibility pipelines (4x and 1x) against the lean G-buffer and
#               forward MSAA on builtin:dense and builtin:lights?count=256, with the
#               reference (not in the default set)
#   solo        the visibility pipelines and the hardware raster (4x and 1x) each in a
#               bench process of its own, without the reference, into solo-NAME: before
#               interleaved rounds, rows of a many-pipeline run were measured on a
#               clocked-down H200 (its compute tone map at 0.14-0.24 ms instead of 0.08),
#               so the x1x ratios were quoted from these (not in the default set)
#   variants    FXAA, SSAO and the light pre-pass against deferred and forward MSAA on every
#               built-in scene, with the reference (issue 16's rows; not in the default set:
#               BENCH_PARTS=variants)
#   shadows     issue 39's shadow budgets: the default pipeline (its maps rasterised in
#               compute) beside the same file with the hardware drawing them
#               (parts/shadow_maps.ron, a copy made for the run), without the reference, on
#               builtin:dense with every light shadowed into shadow-budget-dense and on
#               builtin:lights?count=256 with 64 into shadow-budget-lights, the default's
#               maps drawn every frame and kept while nothing moves (--param
#               shadow_cache=0,1; the bench's frames are still, so kept after the first)
#               beside the hardware's, drawn every frame; then the atlas
#               side 512..8192 on builtin:spheres and builtin:dense with the reference into
#               shadow-resolution (not in the default set)
#   occlusion   issue 38's two-phase occlusion culling off and on (`--param occlusion=0,1`)
#               in the default pipeline on 10M- and 100k-triangle terrains and builtin:dense,
#               without the reference, into occlusion (not in the default set)
#   micro       issue 38's micro clusters off and on (`--param micro=0,1`: the tile raster
#               alone, then clusters of tiny triangles a triangle an invocation first) in
#               the default pipeline on the same scenes, without the reference, into micro
#               (not in the default set)
#   targets     issue 38's named frames in the default pipeline without shadow maps
#               (`--shadows off`, as the issue measured them), without the reference: the
#               10M- and 100M-triangle terrains, 99,856 meshes (builtin:city?blocks=316)
#               and 100M instanced triangles (builtin:rocks?copies=25202), into targets
#               (not in the default set)
#   particles   seed 001's tables on builtin:smoke, the three particle pipelines
#               (full, low and mixed resolution), FLIP against particles_full_res:
#               particles-scaleS (Table 23-1 at off-screen scales 2x2 and 4x4, the depth
#               downsample's maximum of 2x2 taps) and particles-scaleS-point (the same
#               with point-sampled depth); particles-padP (Table 23-2: scale 2, P extra
#               multiply-adds per particle fragment); particles-extent (Table 23-3: scale
#               2, the effect at 12.5% to 400% of its size, and the break-even extent)
# Each part writes to OUT_DIR/PART (particles to OUT_DIR/particles-*). Frames: BENCH_ROUNDS
# rounds (default 5) of BENCH_FRAMES frames of each pipeline (default 2: ten measured frames
# a pipeline, as before rounds) after BENCH_WARMUP warmup frames (default 2);
# BENCH_GROUP_MEMORY (MiB) bounds the memory of the pipelines timed together (default: 60%
# of the GPU's); BENCH_SIZE (default 3840x2160) for a quick try elsewhere.
#
# BENCH_ARCHIVE=FILE.tar.gz also packs what gets committed (each part's results.json,
# results.md, charts and plan pages, and adapters.txt) into one file, for machines that hand back only a
# few files: e.g. BENCH_ARCHIVE=$OUT/bench-gpu.tar.gz scripts/bench-gpu.sh /tmp/bench-gpu,
# then `tar xzf bench-gpu.tar.gz -C bench/results/h200`. The per-scene images (large at
# 2160p) stay in OUT_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."

out="${1:-${OUT:-bench/results/h200}}"
parts="${BENCH_PARTS:-main lights samples resolution specialise}"
frames="${BENCH_FRAMES:-2}"
rounds="${BENCH_ROUNDS:-5}"
warmup="${BENCH_WARMUP:-2}"
size="${BENCH_SIZE:-3840x2160}"
width="${size%x*}"
height="${size#*x}"

bin="${RGRAPH_BIN:-}"
if [ -z "$bin" ]; then
  for candidate in .gl/bin/rgraph target/release/rgraph; do
    if [ -x "$candidate" ]; then bin="$candidate"; break; fi
  done
fi
if [ -z "$bin" ] || [ ! -x "$bin" ]; then
  echo "bench-gpu: no rgraph binary: build it with \`cargo build --release\` on a development" \
       "machine and bring it as .gl/bin/rgraph or target/release/rgraph (or set RGRAPH_BIN)" >&2
  exit 2
fi

tool=bench-gpu
# shellcheck source=scripts/gpu-env.sh
. scripts/gpu-env.sh

mkdir -p "$out"
# Which adapters the server has, for the record (the bench prints the one it used).
"$bin" adapters >"$out/adapters.txt" 2>&1 || true

core=(--pipeline pipelines/deferred_noaa.ron --pipeline pipelines/deferred_msaa_4x.ron
      --pipeline pipelines/deferred_per_sample_4x.ron --pipeline pipelines/deferred_noaa_tiled.ron
      --pipeline pipelines/deferred_msaa_4x_tiled.ron --pipeline pipelines/deferred_per_sample_4x_tiled.ron
      --pipeline pipelines/forward_msaa_4x.ron)
variants=(--pipeline pipelines/deferred_noaa.ron --pipeline pipelines/deferred_noaa_fxaa.ron
          --pipeline pipelines/deferred_msaa_4x.ron --pipeline pipelines/deferred_msaa_4x_fxaa.ron
          --pipeline pipelines/deferred_msaa_4x_ssao.ron --pipeline pipelines/light_prepass_msaa_4x.ron
          --pipeline pipelines/deferred_msaa_4x_tiled.ron --pipeline pipelines/forward_msaa_4x.ron)
every_4x=()
for p in deferred_noaa deferred_noaa_tiled visibility_noaa deferred_msaa_4x deferred_msaa_4x_tiled \
    deferred_msaa_4x_adaptive deferred_msaa_4x_lean deferred_per_sample_4x_tiled \
    deferred_msaa_4x_fxaa deferred_msaa_4x_ssao light_prepass_msaa_4x visibility_msaa_4x \
    forward_msaa_4x; do
  every_4x+=(--pipeline "pipelines/$p.ron")
done
common=(--frames "$frames" --rounds "$rounds" --warmup "$warmup")
if [ -n "${BENCH_GROUP_MEMORY:-}" ]; then common+=(--group-memory "$BENCH_GROUP_MEMORY"); fi
status=0
for part in $parts; do
  echo "bench-gpu: $part -> $out/$part" >&2
  case "$part" in
    main)
      "$bin" bench --scene builtin:dense --scene 'builtin:lights?count=256' \
        --width "$width" --height "$height" "${common[@]}" --out-dir "$out/main" || status=$?
      ;;
    main-dense|main-lights)
      scene=builtin:dense
      [ "$part" = main-lights ] && scene='builtin:lights?count=256'
      "$bin" bench --scene "$scene" --width "$width" --height "$height" "${common[@]}" \
        --out-dir "$out/$part" || status=$?
      ;;
    lights)
      "$bin" bench --sweep lights --sweep-max 1024 "${core[@]}" --width "$width" --height "$height" \
        "${common[@]}" --out-dir "$out/lights" || status=$?
      ;;
    scale|scale-triangles|scale-meshes|scale-lights)
      sweeps="triangles meshes lights"
      [ "$part" != scale ] && sweeps="${part#scale-}"
      for sweep in $sweeps; do
        "$bin" bench --sweep "$sweep" --pipeline pipelines/visibility_msaa_4x.ron \
          --pipeline pipelines/deferred_msaa_4x_lean.ron --pipeline pipelines/forward_msaa_4x.ron \
          --width "$width" --height "$height" "${common[@]}" --out-dir "$out/scale-$sweep" || status=$?
      done
      ;;
    samples)
      "$bin" bench --sweep samples --scene builtin:dense "${core[@]}" --width "$width" --height "$height" \
        "${common[@]}" --out-dir "$out/samples" || status=$?
      ;;
    resolution)
      "$bin" bench --sweep resolution --scene builtin:dense "${core[@]}" "${common[@]}" \
        --out-dir "$out/resolution" || status=$?
      ;;
    specialise)
      "$bin" bench "${core[@]}" --no-reference --width "$width" --height "$height" "${common[@]}" \
        --out-dir "$out/specialise" || status=$?
      ;;
    gbuffer)
      steps=()
      for graph in bench/graphs/gbuffer_cost/*.ron pipelines/visibility_msaa_4x.ron \
          bench/graphs/visibility_cost/depth_only.ron bench/graphs/visibility_cost/hardware_raster.ron; do
        steps+=(--pipeline "$graph")
      done
      for samples in 1 4; do
        "$bin" bench "${steps[@]}" --samples "$samples" --scene builtin:dense \
          --scene 'builtin:lights?count=256' --no-reference --width "$width" --height "$height" \
          "${common[@]}" --out-dir "$out/gbuffer-${samples}x" || status=$?
      done
      ;;
    every-4x)
      "$bin" bench "${every_4x[@]}" --scene builtin:dense --scene 'builtin:lights?count=256' \
        --width "$width" --height "$height" "${common[@]}" --out-dir "$out/every-4x" || status=$?
      ;;
    default)
      models=()
      for model in ${BENCH_MODELS:-}; do models+=(--scene "$model"); done
      "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --pipeline pipelines/deferred_msaa_4x.ron \
        --scene builtin:dense --scene 'builtin:lights?count=256' "${models[@]}" \
        --width "$width" --height "$height" "${common[@]}" --out-dir "$out/default" || status=$?
      # Issue 35's "same image as deferred_msaa_4x within 1/255 on at least 99% of pixels",
      # on this GPU: each scene's two renders held against each other.
      for scene_dir in "$out/default"/*/; do
        [ -f "$scene_dir/visibility_msaa_4x.png" ] || continue
        echo "- $(basename "$scene_dir"): $("$bin" compare "$scene_dir/visibility_msaa_4x.png" \
          "$scene_dir/deferred_msaa_4x.png" --tolerance 1 --at-least 99 2>&1 | tr '\n' ' ')"
      done > "$out/default/same-image.md"
      "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --pipeline pipelines/particles_low_res.ron \
        --scene builtin:smoke --reference pipelines/particles_full_res.ron \
        --width "$width" --height "$height" "${common[@]}" --out-dir "$out/default-smoke" || status=$?
      ;;
    visibility)
      visibility=()
      for p in visibility_msaa_4x visibility_noaa deferred_msaa_4x_lean forward_msaa_4x; do
        visibility+=(--pipeline "pipelines/$p.ron")
      done
      "$bin" bench "${visibility[@]}" --scene builtin:dense --scene 'builtin:lights?count=256' \
        --width "$width" --height "$height" "${common[@]}" --out-dir "$out/visibility" \
        || status=$?
      ;;
    solo)
      # Each in a process of its own: a GPU that ran many pipelines before may clock down.
      for run in pipelines/visibility_msaa_4x.ron:4 pipelines/visibility_noaa.ron:1 \
          bench/graphs/visibility_cost/hardware_raster.ron:4 \
          bench/graphs/visibility_cost/hardware_raster.ron:1; do
        graph=${run%:*} samples=${run#*:}
        name=$(basename "$graph" .ron)
        [ "$name" = hardware_raster ] && name="hardware_raster_${samples}x"
        "$bin" bench --pipeline "$graph" --samples "$samples" --scene builtin:dense \
          --scene 'builtin:lights?count=256' --no-reference --width "$width" --height "$height" \
          "${common[@]}" --out-dir "$out/solo-$name" || status=$?
      done
      ;;
    variants)
      "$bin" bench "${variants[@]}" --width "$width" --height "$height" "${common[@]}" \
        --out-dir "$out/variants" || status=$?
      ;;
    shadows)
      hardware=pipelines/visibility_hw_shadows.ron
      sed 's#parts/shadow_maps_compute.ron#parts/shadow_maps.ron#' pipelines/visibility_msaa_4x.ron \
        > "$hardware"
      for budget in dense:builtin:dense:9 'lights:builtin:lights?count=256:64'; do
        name=${budget%%:*} rest=${budget#*:}
        scene=${rest%:*} lights=${rest##*:}
        "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --pipeline "$hardware" \
          --scene "$scene" --shadowed-lights "$lights" --param shadow_cache=0,1 --no-reference \
          --width "$width" --height "$height" "${common[@]}" --out-dir "$out/shadow-budget-$name" \
          || status=$?
      done
      rm -f "$hardware"
      "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --scene builtin:spheres \
        --scene builtin:dense --param shadow_map=512,1024,2048,4096,8192 --width "$width" \
        --height "$height" "${common[@]}" --out-dir "$out/shadow-resolution" || status=$?
      ;;
    occlusion)
      "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --scene 'builtin:terrain?cells=2236' \
        --scene 'builtin:terrain?cells=224' --scene builtin:dense --param occlusion=0,1 \
        --no-reference --width "$width" --height "$height" "${common[@]}" \
        --out-dir "$out/occlusion" || status=$?
      ;;
    micro)
      "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --scene 'builtin:terrain?cells=2236' \
        --scene 'builtin:terrain?cells=224' --scene builtin:dense --param micro=0,1 \
        --no-reference --width "$width" --height "$height" "${common[@]}" \
        --out-dir "$out/micro" || status=$?
      ;;
    targets)
      "$bin" bench --pipeline pipelines/visibility_msaa_4x.ron --scene 'builtin:terrain?cells=2236' \
        --scene 'builtin:terrain?cells=7071' --scene 'builtin:city?blocks=316' \
        --scene 'builtin:rocks?copies=25202' --shadows off \
        --no-reference --width "$width" --height "$height" "${common[@]}" \
        --out-dir "$out/targets" || status=$?
      ;;
    particles)
      particles=(--pipeline pipelines/particles_full_res.ron --pipeline pipelines/particles_low_res.ron
                 --pipeline pipelines/particles_mixed_res.ron)
      for scale in 2 4; do
        for taps in 2 1; do
          suffix=""
          [ "$taps" = 1 ] && suffix="-point"
          "$bin" bench --scene builtin:smoke "${particles[@]}" --param scale="$scale" \
            --param depth_taps="$taps" --reference pipelines/particles_full_res.ron \
            --width "$width" --height "$height" "${common[@]}" \
            --out-dir "$out/particles-scale$scale$suffix" || status=$?
        done
      done
      for pad in 0 64 256; do
        "$bin" bench --scene builtin:smoke "${particles[@]}" --param scale=2 --param pad="$pad" \
          --no-reference --width "$width" --height "$height" "${common[@]}" \
          --out-dir "$out/particles-pad$pad" || status=$?
      done
      extents=()
      for extent in 12 25 50 100 200 400; do extents+=(--scene "builtin:smoke?extent=$extent"); done
      "$bin" bench "${extents[@]}" "${particles[@]}" --param scale=2 --no-reference \
        --width "$width" --height "$height" "${common[@]}" --out-dir "$out/particles-extent" \
        || status=$?
      ;;
    *)
      echo "bench-gpu: unknown part \"$part\" (main, main-dense, main-lights, default, lights, scale, scale-SWEEP, samples, resolution, specialise, gbuffer, every-4x, visibility, solo, variants, shadows, occlusion, micro, targets, particles)" >&2
      status=2
      ;;
  esac
done
if [ -n "${BENCH_ARCHIVE:-}" ]; then
  archive="$(realpath -m "$BENCH_ARCHIVE")"
  # Each part's files, and its plans as pages one level down (SCENE/PIPELINE.plan.html,
  # about 60 kB each), which results.md links.
  (cd "$out" && find . -maxdepth 3 \( -name '*.plan.html' -o \( ! -path './*/*/*' \( \
     -name results.json -o -name results.md -o -name pareto.png -o -name passes.png \
     -o -name scaling.png -o -name adapters.txt -o -name same-image.md \) \) \) \
     -print0 | tar czf "$archive" --null -T -)
  echo "bench-gpu: packed $BENCH_ARCHIVE" >&2
fi
exit "$status"
