#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Issue 4's quality bar: feature-region two-sided RMS distance to the true surface, measured over the
# surfaces (mm, within 1.5 mm of a sharp feature), and volume change (%) of each smoothing method on the
# ridge-box, femur and pelvis phantoms (0.7 x 0.7 x 2 mm voxels, 0.5 mm blur, NOISE HU of Gaussian noise),
# one `contourmesh run --json` per cell. Prints a Markdown table.
# Usage: scripts/quality_bar.sh [NOISE_HU] [BUILD_DIR]   (defaults: 20, build/release; builds contourmesh)
set -euo pipefail
cd "$(dirname "$0")/.."
noise="${1:-20}"
build="${2:-build/release}"
cmake --build "$build" --target contourmesh >/dev/null
cli="$build/pipelines/contourmesh"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

rows=(
  "Laplacian (20 its, lambda 0.3)|--method laplacian"
  "Taubin (20 its)|--method taubin"
  "Taubin (40 its)|--method taubin --iterations 40"
  "mean curvature flow (20 its)|--method mcf"
  "paper, the paper's settings (40 its)|--method paper"
  "paper, 40 its, --measure normal --in-slice along-line|--method paper --measure normal --in-slice along-line"
  "paper, 20 its|--method paper --iterations 20"
  "paper, 20 its, --measure normal --in-slice along-line|--method paper --iterations 20 --measure normal --in-slice along-line"
)
phantoms=(ridge-box femur pelvis)
header="| method (noise ${noise} HU) |"
rule="| --- |"
for p in "${phantoms[@]}"; do
  header+=" $p |"
  rule+=" --- |"
done
echo "$header"
echo "$rule"
for row in "${rows[@]}"; do
  name="${row%%|*}"
  read -r -a args <<<"${row#*|}"
  line="| $name |"
  for p in "${phantoms[@]}"; do
    json="$("$cli" run --shape "$p" --noise "$noise" --quiet --json -o "$out/mesh.stl" "${args[@]}")"
    line+=" $(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); print("%.3f / %+.2f" % (d["surface_feature_rms_after"], d["volume_change_percent"]))' "$json") |"
  done
  echo "$line"
done
