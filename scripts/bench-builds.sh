#!/usr/bin/env bash
# Release builds against each other on an NVIDIA server, as a variant is judged before it
# lands: each build, pipeline and scene in a bench process of its own (rows of a
# many-pipeline run have been measured on a clocked-down H200), without the reference,
# builds taking turns within each round, and one line each: the frame's GPU ms and its
# passes' (the rows of results.md).
#
#   scripts/bench-builds.sh OUT_DIR NAME=BINARY...
#
# A BINARY ending in .gz is unpacked beside itself first (a stripped release binary
# gzipped is about 6 MB, which fits a device's carry where several plain ones do not).
# BENCH_PIPELINES: file stems in pipelines/ (default "visibility_msaa_4x visibility_noaa");
# BENCH_SCENES (default "builtin:dense builtin:lights?count=256"); BENCH_ROUNDS (2);
# BENCH_FRAMES (4: frames per bench round, and `rgraph bench` runs 5 rounds, so 20 frames a
# row; a build from before interleaved rounds measures only BENCH_FRAMES) after BENCH_WARMUP
# (5); BENCH_SIZE (3840x2160). Each run's results.md,
# results.json and output (bench.log) go to OUT_DIR/NAME/PIPELINE-SCENE-rROUND/, the lines to
# OUT_DIR/summary.md; BENCH_ARCHIVE=FILE.tar.gz packs both (every results.md and the
# summary) into one file for machines that hand back few files. The environment is
# scripts/gpu-env.sh's, as for scripts/bench-gpu.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ $# -lt 2 ]; then
  echo "usage: scripts/bench-builds.sh OUT_DIR NAME=BINARY... (a build or more to time)" >&2
  exit 2
fi
out="$1"
shift
pipelines="${BENCH_PIPELINES:-visibility_msaa_4x visibility_noaa}"
scenes="${BENCH_SCENES:-builtin:dense builtin:lights?count=256}"
rounds="${BENCH_ROUNDS:-2}"
frames="${BENCH_FRAMES:-4}"
warmup="${BENCH_WARMUP:-5}"
size="${BENCH_SIZE:-3840x2160}"

names=()
declare -A bins
for build in "$@"; do
  name="${build%%=*}"
  bin="${build#*=}"
  if [ "$name" = "$build" ] || [ -z "$name" ]; then
    echo "bench-builds: '$build' is not NAME=BINARY" >&2
    exit 2
  fi
  if [[ "$bin" == *.gz ]]; then
    gunzip -kf "$bin"
    bin="${bin%.gz}"
    chmod +x "$bin"
  fi
  if [ ! -x "$bin" ]; then
    echo "bench-builds: $name: no executable $bin" >&2
    exit 2
  fi
  names+=("$name")
  bins[$name]="$bin"
done
for pipeline in $pipelines; do
  if [ ! -f "pipelines/$pipeline.ron" ]; then
    echo "bench-builds: no pipelines/$pipeline.ron" >&2
    exit 2
  fi
done

tool=bench-builds
# shellcheck source=scripts/gpu-env.sh
. scripts/gpu-env.sh

mkdir -p "$out"
summary="$out/summary.md"
{
  echo "# scripts/bench-builds.sh: $size, $frames frames a round after $warmup, a process each"
  echo
  echo "| build | pipeline | scene | round | GPU ms | per pass (median) |"
  echo "| --- | --- | --- | --: | --: | --- |"
} > "$summary"
status=0
for round in $(seq 1 "$rounds"); do
  for pipeline in $pipelines; do
    for scene in $scenes; do
      for name in "${names[@]}"; do
        dir="$out/$name/$pipeline-$(echo "$scene" | tr -c 'a-zA-Z0-9\n' '_')-r$round"
        mkdir -p "$dir"
        if ! "${bins[$name]}" bench --pipeline "pipelines/$pipeline.ron" --scene "$scene" \
            --no-reference --frames "$frames" --warmup "$warmup" \
            --width "${size%x*}" --height "${size#*x}" --out-dir "$dir" >"$dir/bench.log" 2>&1; then
          echo "bench-builds: $name, $pipeline, $scene: the bench failed ($dir/bench.log):" >&2
          tail -5 "$dir/bench.log" >&2
          status=1
          continue
        fi
        # The pipeline's row in the scene's table, then in the per-pass table.
        rows=$(grep -E "^\| $pipeline \|" "$dir/results.md" | cut -d'|' -f3)
        frame=$(echo "$rows" | sed -n 1p | xargs)
        passes=$(echo "$rows" | sed -n 2p | xargs)
        line="| $name | $pipeline | $scene | $round | $frame | $passes |"
        echo "$line" >> "$summary"
        echo "$line"
      done
    done
  done
done

if [ -n "${BENCH_ARCHIVE:-}" ]; then
  (cd "$out" && find . -name results.md -o -name summary.md | tar czf - -T -) > "$BENCH_ARCHIVE"
fi
exit "$status"
