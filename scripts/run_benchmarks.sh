#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the release preset and runs contourmesh_bench: every stage of ContourMesh and its VTK
# counterparts at 10k, 100k, 1M and 4M vertices in one run, then the ratios between them, a Markdown
# summary (docs/benchmarks.md) and the speed targets of issue 6. About 5 minutes and 3 GB of memory on
# two cores. Arguments go to the benchmark program, e.g. --benchmark_filter=/1000000/ for one size.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release --target contourmesh_bench
exec build/release/pipelines/bench/contourmesh_bench "$@"
