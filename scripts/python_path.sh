#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Makes `import contourmesh` work in Debian's python3 without further steps: writes contourmesh.pth,
# pointing at the package a build tree holds (default build/release/python), into the site-packages
# directory Debian's python3 reads under /usr/local (/usr/local/lib/python3.X/dist-packages). Called by
# run_main.sh and run_tests.sh after the build. Needs root or sudo when that directory is not writable;
# without either it prints the PYTHONPATH to use instead.
set -euo pipefail
cd "$(dirname "$0")/.."
package_dir="$(pwd)/${1:-build/release}/python"
python=/usr/bin/python3
if [ ! -f "$package_dir/contourmesh/__init__.py" ]; then
  echo "python_path: no contourmesh package in $package_dir (build first)" >&2
  exit 1
fi
site=$("$python" -c 'import site; print(next(p for p in site.getsitepackages() if p.startswith("/usr/local/")))')
pth="$site/contourmesh.pth"
if [ -f "$pth" ] && [ "$(cat "$pth")" = "$package_dir" ]; then exit 0; fi
SUDO=""
if [ "$(id -u)" -ne 0 ] && ! { mkdir -p "$site" 2>/dev/null && [ -w "$site" ]; }; then
  if command -v sudo >/dev/null; then SUDO="sudo"; else
    echo "python_path: cannot write $pth; use PYTHONPATH=$package_dir" >&2
    exit 0
  fi
fi
$SUDO mkdir -p "$site"
echo "$package_dir" | $SUDO tee "$pth.tmp" >/dev/null
$SUDO mv "$pth.tmp" "$pth"
echo "python_path: $python imports contourmesh from $package_dir ($pth)"
