#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: set up a fresh machine, build the release preset, and run the whole pipeline on the
# built-in femur phantom (CT volume with noise -> contours -> mesh -> the default smoothing).
# Writes out/femur.stl and prints a short summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release
scripts/python_path.sh build/release   # python3 -c "import contourmesh" works from here on
build/release/pipelines/contourmesh run -o out/femur.stl "$@"
