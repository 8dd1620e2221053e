#!/usr/bin/env bash
# The main job: set up a fresh machine, build the release preset, and run the pipeline on a built-in
# phantom. Writes out/demo.stl and prints a short summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release
build/release/pipelines/contourmesh demo -o out/demo.stl "$@"
