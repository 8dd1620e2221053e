#!/usr/bin/env bash
# Regenerates docs/results.md and docs/results/ from a real run of `contourmesh compare --phantom all`
# (every phantom at the default resolution and noise), under xvfb-run when there is no X display.
# Usage: scripts/make_results.sh [BUILD_DIR]   (default build/release; contourmesh is built first)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
nice -n 10 cmake --build "$build" --target contourmesh
cli="$build/pipelines/contourmesh"
args=(compare --phantom all --out docs/results --markdown docs/results.md --render-size 400x300 --color-levels 32
      --repeat 3 --note "Made by scripts/make_results.sh, which builds contourmesh and runs this command (under xvfb-run when there is no display). Timings are wall-clock seconds on the machine that ran it, the fastest of 3 runs; they vary with its load. The real scans of ../shared/data, contour route and voxel route side by side: [real_scans.md](real_scans.md).")
if [ -n "${DISPLAY:-}" ]; then
  "$cli" "${args[@]}"
else
  # A private authority file: xvfb-run's default lives in /tmp, where a cleanup by someone else would
  # cut VTK off the server in the middle of the run.
  auth="$(mktemp -d)"
  trap 'rm -rf "$auth"' EXIT
  xvfb-run -a -f "$auth/xauthority" "$cli" "${args[@]}"
fi
du -sh docs/results
