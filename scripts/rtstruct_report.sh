#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The contour route on an RT Structure Set, every ROI: contours, slices, vertices, the tiled volume
# against the slice-wise (radiotherapy) volume, the distance in each slice plane between the surface
# and the drawn contours (unsmoothed, and after `contourmesh run`'s default smoothing), and times.
# Prints a Markdown table (docs/contours.md holds one for the breast structure set).
# Usage: scripts/rtstruct_report.sh [RTSTRUCT] [BUILD_DIR]
#   (defaults: ../shared/data/rtstruct_breast/rtss.dcm, build/release; builds contourmesh)
set -euo pipefail
cd "$(dirname "$0")/.."
input="${1:-../shared/data/rtstruct_breast/rtss.dcm}"
build="${2:-build/release}"
cmake --build "$build" --target contourmesh >/dev/null
cli="$build/pipelines/contourmesh"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# Exit code 2 when an ROI fails: the table says which, so carry on.
"$cli" reconstruct "$input" --roi all -o "$out/tiled" --json --quiet >"$out/tiled.json" 2>"$out/tiled.err" || true
"$cli" run "$input" --roi all -o "$out/smoothed" --json --quiet >"$out/smoothed.json" 2>"$out/smoothed.err" || true

python3 - "$out/tiled.json" "$out/smoothed.json" <<'EOF'
import json, sys

tiled = json.load(open(sys.argv[1]))
smoothed = {r["roi"]["number"]: r for r in json.load(open(sys.argv[2]))["rois"]}
print("| ROI | contours (holes) | slices | vertices | closed, manifold | volume, mm^3 | slice-wise, mm^3 | difference "
      "| unsmoothed in-plane distance: mean / max, mm | smoothed: mean / max, mm | smoothing volume change "
      "| seconds: tile / smooth |")
print("| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for r in tiled["rois"]:
    name = "%d %s" % (r["roi"]["number"], r["roi"]["name"])
    if r["status"] != "ok":
        print("| %s | failed: %s |||||||||||" % (name, r["error"]))
        continue
    s = smoothed.get(r["roi"]["number"], {})
    ok = "yes" if r["is_closed"] and r["is_manifold"] else "**no**"
    after = ("%.2f / %.2f" % (s["contour_deviation_after_mean"], s["contour_deviation_after_max"])
             if s.get("status") == "ok" else "failed")
    change = "%+.2f %%" % s["volume_change_percent"] if s.get("status") == "ok" else "-"
    smooth_time = "%.2f" % s["seconds_smooth"] if s.get("status") == "ok" else "-"
    print("| %s | %d (%d) | %d | %d | %s | %.1f | %.1f | %+.2f %% | %.3f / %.3f | %s | %s | %.2f / %s |" % (
        name, r["contours"], r["hole_contours"], r["slices"], r["vertices"], ok, r["volume"], r["slicewise_volume"],
        r["volume_difference_percent"], r["contour_deviation_mean"], r["contour_deviation_max"], after, change,
        r["seconds_tile"], smooth_time))
for line in tiled.get("skipped", []):
    print("\n%s." % line)
EOF
