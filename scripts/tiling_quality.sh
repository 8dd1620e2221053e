#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates the tiling-quality figures of docs/reconstruction.md ("Tiling quality"): builds the
# release preset, then
#   1. contourmesh_tiling_quality on the ten phantoms at 20 HU and on the three real scans of
#      ../shared/data (closed / manifold / Euler characteristic, two-sided Hausdorff and RMS distance of
#      the unsmoothed mesh to the truth, the shelf measure, sliver area, vertices without ids);
#   2. the same on the phantoms with --contour-noise 0.4;
#   3. scripts/route_bench.sh (per-stage times, 1 and 2 threads, contour route against the voxel route
#      with windowed sinc 20, on dicom_series_headneck and the skull phantom at 0.4 x 0.4 x 1 mm), unless
#      --no-bench.
# Writes Markdown to stdout; about 1 minute without the benchmark, 3 more with it.
#   scripts/tiling_quality.sh [--no-bench] [--reps N]
set -euo pipefail
cd "$(dirname "$0")/.."
bench=1
reps=5
while [[ $# -gt 0 ]]; do
  case "$1" in
    --no-bench) bench=0 ;;
    --reps) reps="$2"; shift ;;
    *) echo "usage: scripts/tiling_quality.sh [--no-bench] [--reps N]" >&2; exit 1 ;;
  esac
  shift
done
scripts/setup.sh >/dev/null
cmake --preset release >/dev/null
cmake --build --preset release --target contourmesh_tiling_quality contourmesh_route_bench >/dev/null
tool=build/release/pipelines/contourmesh_tiling_quality
echo "### Phantoms at 20 HU and real scans"
echo
"$tool" --data ../shared/data
echo
echo "### Phantoms with --contour-noise 0.4"
echo
"$tool" --phantoms-only --contour-noise 0.4
if [[ "$bench" == 1 ]]; then
  echo
  echo "### Contour route against voxel route"
  echo
  echo '```'
  build/release/pipelines/bench/contourmesh_route_bench --data ../shared/data --reps "$reps"
  echo '```'
fi
