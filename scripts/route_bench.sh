#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the release preset and runs contourmesh_route_bench: the contour route (segmentation, tiling,
# default smoothing) against the voxel route (threshold, island/hole clean-up, flying edges, windowed
# sinc) on the head-and-neck DICOM series at 300 HU and the skull phantom at 0.4 x 0.4 x 1 mm, stage
# by stage, at 1 thread and at every core, in one run (docs/benchmarks.md). About 3 minutes on two
# cores. Arguments go to the program: --reps N (default 5), --threads N, --case headneck|skull|all.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release --target contourmesh_route_bench
exec build/release/pipelines/bench/contourmesh_route_bench --data ../shared/data "$@"
