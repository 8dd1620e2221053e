#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer targets (the "fuzz" preset: clang, ASan + UBSan) and runs them, one per core.
# Usage: scripts/run_fuzzers.sh [SECONDS_PER_TARGET] [TARGET...]
#   SECONDS_PER_TARGET  default 30 (CI); docs/robustness.md quotes 600-second runs.
#   TARGET              fuzz_read_stl fuzz_read_ply fuzz_read_vtp fuzz_read_obj fuzz_tiling fuzz_features
#                       (default: all)
# CONTOURMESH_FUZZ_SEED=N fixes libFuzzer's random seed (CI sets it, so that a run can be repeated).
# Each target starts from its seeds and regression inputs (tests/fuzz/corpus, tests/fuzz/regressions);
# what it discovers goes to build/fuzz/corpus/<target> (kept between runs, never into the source tree)
# and a crashing input to build/fuzz/artifacts/<target>/. Exits 1 when a target finds something.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_read_stl fuzz_read_ply fuzz_read_vtp fuzz_read_obj fuzz_tiling fuzz_features)
fi

scripts/setup.sh
cmake --preset fuzz >/dev/null
nice -n 10 cmake --build --preset fuzz

export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
bin=build/fuzz/fuzz
# Runs target $1 for $seconds s; writes its one-line verdict to build/fuzz/$1.result and exits non-zero
# when it found something.
fuzz_one() {
  local t="$1"
  local corpus="build/fuzz/corpus/$t" artifacts="build/fuzz/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  local inputs=("$corpus" "tests/fuzz/corpus/$t")
  [ -d "tests/fuzz/regressions/$t" ] && inputs+=("tests/fuzz/regressions/$t")
  # Dictionaries for the text formats; for the decoded targets, room for the bytes a big case needs
  # (libFuzzer otherwise starts from the largest seed's length and grows it slowly).
  local extra=()
  [ -n "${CONTOURMESH_FUZZ_SEED:-}" ] && extra+=(-seed="$CONTOURMESH_FUZZ_SEED")
  case "$t" in
    fuzz_read_stl) extra+=(-dict=tests/fuzz/dict/stl.dict) ;;
    fuzz_read_ply) extra+=(-dict=tests/fuzz/dict/ply.dict) ;;
    fuzz_read_obj) extra+=(-dict=tests/fuzz/dict/obj.dict) ;;
    fuzz_read_vtp) extra+=(-dict=tests/fuzz/dict/vtp.dict) ;;
    fuzz_tiling) extra+=(-max_len=2048 -len_control=0) ;;
    fuzz_features) extra+=(-max_len=256 -len_control=0) ;;
  esac
  local log="build/fuzz/$t.log" result="build/fuzz/$t.result" status
  set +e
  nice -n 10 "$bin/$t" -max_total_time="$seconds" -rss_limit_mb=4096 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" "${extra[@]}" "${inputs[@]}" >"$log" 2>&1
  status=$?
  set -e
  local execs cov
  execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -oE '(#[0-9]+).*cov: [0-9]+ ft: [0-9]+ corp: [0-9]+/[0-9]+[a-zA-Z]*' "$log" | tail -1 |
        grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+/[0-9]+[a-zA-Z]*' || echo "cov: ?")
  if [ "$status" -ne 0 ]; then
    { echo "fuzz: $t FAILED (exit $status) after $execs runs; log: $log"
      grep -E 'ERROR|contract violated|runtime error|Test unit written' "$log" | head -5 || true; } >"$result"
    return 1
  fi
  echo "fuzz: $t ok: $execs runs, $cov" >"$result"
}

# The targets run side by side, as many at a time as there are cores (CONTOURMESH_FUZZ_JOBS to choose):
# each is one process of one thread, and each still gets its $seconds.
jobs_max="${CONTOURMESH_FUZZ_JOBS:-$(nproc)}"
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  echo "fuzz: $t for $seconds s"
  rm -f "build/fuzz/$t.result"
  fuzz_one "$t" &
done
wait || true
failed=()
for t in "${targets[@]}"; do
  # The verdict files tell (a target that died before writing one failed too).
  if [ -f "build/fuzz/$t.result" ]; then cat "build/fuzz/$t.result"; else echo "fuzz: $t FAILED (no verdict)"; fi
  if ! grep -q " ok: " "build/fuzz/$t.result" 2>/dev/null; then failed+=("$t"); fi
done

if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: findings in ${failed[*]}: reproduce with $bin/<target> <artifact>; see docs/robustness.md"
  exit 1
fi
echo "fuzz: all ${#targets[@]} targets ran $seconds s without a finding"
