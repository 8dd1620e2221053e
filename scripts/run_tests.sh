#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Set up a fresh machine, build, and run every test through ctest.
# Usage: scripts/run_tests.sh [release|asan]   (default: release; asan = AddressSanitizer + UBSan)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
scripts/setup.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
# Debian's python3 imports the module of the release tree (the asan tree builds none).
if [ "$preset" = release ]; then scripts/python_path.sh build/release; fi
ctest --preset "$preset"
