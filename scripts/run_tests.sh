#!/usr/bin/env bash
# Set up a fresh machine, build, and run every test through ctest.
# Usage: scripts/run_tests.sh [release|asan]   (default: release; asan = AddressSanitizer + UBSan)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
scripts/setup.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset"
