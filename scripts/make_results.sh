#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates docs/results.md and docs/results/ from a real run of `contourmesh compare --phantom all`:
# every phantom at the default resolution in the three noise regimes (CT noise at 20 and 60 HU, contour
# noise of 0.4 mm at 20 HU), means over seeds 1-3, with the verdicts of the default, under xvfb-run when
# there is no X display. The run goes to a scratch tree first, so that a failed run leaves the committed
# results as they were. It takes a while (about half an hour on two busy cores); it is not part of ctest.
# Usage: scripts/make_results.sh [BUILD_DIR]   (default build/release; contourmesh is built first)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
nice -n 10 cmake --build "$build" --target contourmesh
cli="$(pwd)/$build/pipelines/contourmesh"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/docs"
args=(compare --phantom all --regimes all --seeds 1-3 --out docs/results --markdown docs/results.md
      --render-size 400x300 --color-levels 32 --render-methods cross-slice,voxel-windowed-sinc,none
      --repeat 3
      --note "Made by scripts/make_results.sh, which builds contourmesh and runs this command (under xvfb-run when there is no display). Timings are wall-clock seconds on the machine that ran it, the fastest of 3 runs, averaged over the seeds; they vary with its load. The real scans of ../shared/data, contour route and voxel route side by side: [real_scans.md](real_scans.md).")
start=$(date +%s)
cd "$scratch"
if [ -n "${DISPLAY:-}" ]; then
  nice -n 10 "$cli" "${args[@]}"
else
  # A private authority file: xvfb-run's default lives in /tmp, where a cleanup by someone else would
  # cut VTK off the server in the middle of the run.
  nice -n 10 xvfb-run -a -f "$scratch/xauthority" "$cli" "${args[@]}"
fi
cd - >/dev/null
# The run is complete: replace the committed results.
rm -rf docs/results
mv "$scratch/docs/results" docs/results
mv "$scratch/docs/results.md" docs/results.md
echo "make_results.sh: $(( $(date +%s) - start )) s"
du -sh docs/results
