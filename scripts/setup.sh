#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, from Debian's packages, everything ContourMesh needs to build and test; skips what is
# already installed. Safe to run again. Needs root or sudo when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev                       # libsmooth
  libinsighttoolkit5-dev libgdcm-tools  # libreconstruct (GDCM's CMake targets want the tools)
  libtbb-dev                          # libreconstruct: parallel loops (segmentation per slice)
  libvtk9-dev                         # pipelines: mesh I/O, VTK filters, rendering
  libcli11-dev nlohmann-json3-dev     # the contourmesh CLI
  libgtest-dev libbenchmark-dev       # tests and benchmarks
  xvfb xauth libgl1-mesa-dri          # offscreen renders of `contourmesh compare` (VTK draws through X)
  clang libclang-rt-dev llvm          # fuzz targets (scripts/run_fuzzers.sh): clang, libFuzzer, llvm-symbolizer
  strace                              # tests: the atomic writes fsync before they rename (skipped without it)
  python3-dev pybind11-dev python3-numpy python3-pytest python3-vtk9  # the Python module and its tests
  libxml2-utils                       # xmllint: the Slicer module description against its schema
  snakemake                           # the cohort workflow (pipelines/workflows/cohort)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
