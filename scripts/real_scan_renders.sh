#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The real-scan pictures of docs/real_scans.md: for each CT of ../shared/data, the contour route's
# unsmoothed tiling (`contourmesh reconstruct`), the contour route with the default smoothing
# (`contourmesh run`) and 3D Slicer's voxel route (threshold, flying edges, windowed sinc 20), side by
# side from one camera zoomed on a place where contours split or merge, by contourmesh_scan_render
# under xvfb-run. Writes docs/real_scans/*.png (150-300 KB each). About 1 minute.
#   scripts/real_scan_renders.sh [OUTPUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-docs/real_scans}"
data=../shared/data
cmake --preset release >/dev/null
cmake --build --preset release --target contourmesh contourmesh_scan_render >/dev/null
cli=build/release/pipelines/contourmesh
render=build/release/pipelines/contourmesh_scan_render
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# name volume threshold focus distance azimuth elevation
scan() {
  local name="$1" volume="$2" threshold="$3" focus="$4" distance="$5" azimuth="$6" elevation="$7"
  "$cli" reconstruct "$volume" --threshold "$threshold" -o "$work/$name-tiled.vtp" -q
  "$cli" run "$volume" --threshold "$threshold" -o "$work/$name-smoothed.vtp" -q
  xvfb-run -a "$render" "$volume" --threshold "$threshold" \
    --mesh "$work/$name-tiled.vtp" "contour route, tiled (unsmoothed)" \
    --mesh "$work/$name-smoothed.vtp" "contour route, default smoothing" \
    --focus "$focus" --distance "$distance" --azimuth "$azimuth" --elevation "$elevation" \
    --size 1200x400 --color-levels 32 -o "$out/$name.png"
  echo "wrote $out/$name.png"
}

# Head and neck, 300 HU: the left wall of the skull where an outer layer parts from it.
scan headneck "$data/dicom_series_headneck" 300 20,-170,-507 170 -35 15
scan headneck_wall "$data/dicom_series_headneck" 300 40,-175,-505 120 -50 -10
# Abdomen, 300 HU: the lumbar spine (processes and end plates).
scan abdomen "$data/totalsegmentator_ct/example_ct.nii.gz" 300 -5,-120,300 220 0 10
# headsq at quarter resolution, 1150 (raw values): the face, orbits and nasal cavity.
scan headsq "$data/headsq_quarter/headsq_quarter.mhd" 1150 100,40,45 200 0 10
