#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The cohort workflow run for real (snakemake --cores 2) on three small phantoms and one broken scan:
# three meshes, a cohort table that lists the broken case as failed, and the index with four thumbnails.
# Usage: cohort_test.sh CONTOURMESH WORKFLOW_DIR WORK_DIR
set -euo pipefail
cli="$1"; workflow="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work/scans"
for shape in ridge-box branch two-objects; do
  "$cli" phantom --shape "$shape" --spacing 1,1,2 --noise 10 -o "$work/scans/$shape.nii.gz" -q
done
head -c 3000 /dev/zero | tr '\0' 'x' > "$work/scans/broken.nii.gz"   # not an image
cd "$work"
snakemake -s "$workflow/Snakefile" --cores 2 -q \
  --config input="$work/scans" out="$work/out" contourmesh="$cli" threshold=520 > snakemake.log 2>&1 \
  || { cat snakemake.log; echo "FAIL: snakemake stopped"; exit 1; }
fail() { echo "FAIL: $*"; cat "$work/out/cohort.csv" 2>/dev/null; exit 1; }
for shape in ridge-box branch two-objects; do
  [ -s "out/cases/$shape/mesh.stl" ] || fail "no mesh for $shape"
  grep -q "^$shape,ok," out/cohort.csv || fail "$shape is not ok in the table"
  grep -q "^$shape,ok,.*,True," out/cohort.csv || fail "$shape: mesh not closed"
done
[ ! -e out/cases/broken/mesh.stl ] || fail "a mesh was written for the broken scan"
grep -q '^broken,failed,.*not a readable image' out/cohort.csv || fail "the broken case is not listed as failed"
[ "$(wc -l < out/cohort.csv)" -eq 5 ] || fail "the table does not have one row per case"
[ "$(grep -o '<img ' out/index.html | wc -l)" -eq 4 ] || fail "the index does not show four thumbnails"
for c in ridge-box branch two-objects broken; do
  [ -s "out/cases/$c/thumbnail.png" ] || fail "no thumbnail for $c"
done
# creases: "none" (the default) is not passed on; "restore" reaches contourmesh run.
! grep -q '"--creases"' out/cases/ridge-box/summary.json || fail "--creases none was passed to contourmesh"
python3 "$workflow/scripts/run_case.py" --contourmesh "$cli" --case rb --input "$work/scans/ridge-box.nii.gz" \
  --mesh "$work/rb/mesh.stl" --summary "$work/rb/summary.json" --threshold 520 --creases restore > /dev/null
grep -q '"status": "ok"' "$work/rb/summary.json" || fail "the case with --creases restore failed"
grep -A1 '"--creases"' "$work/rb/summary.json" | grep -q '"restore"' || fail "--creases restore was not passed on"
echo "cohort workflow: 3 meshes, broken case listed as failed, index with 4 thumbnails, creases passed on"
