#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Lists the project's source files that lack the SPDX licence line, and exits 1 when there are any.
# With --fix, writes the line into them instead.
#   C++ (.h .hpp .c .cpp .cxx and their .in templates):     // SPDX-License-Identifier: BSD-3-Clause
#   CMake, shell, Python, Snakefiles (after a #! line):    # SPDX-License-Identifier: BSD-3-Clause
#   XML templates (.xml.in, after the <?xml ?> line):      <!-- SPDX-License-Identifier: BSD-3-Clause -->
# Data, JSON, YAML, Markdown, the LICENSE and third-party files (Slicer's schema) are not checked.
# Usage: scripts/check_spdx.sh [--fix]   (every tracked or new, not ignored, file)
set -euo pipefail
cd "$(dirname "$0")/.."
id="SPDX-License-Identifier: BSD-3-Clause"
fix=0
[ "${1:-}" = "--fix" ] && fix=1

# The comment that carries the line in `file`, or nothing when the file is not checked.
comment_for() {
  case "$1" in
    pipelines/slicer/schema/*) ;;  # Slicer's Execution Model schema, under its own licence
    *.h | *.hpp | *.c | *.cpp | *.cxx | *.h.in | *.hpp.in | *.cpp.in) echo "// $id" ;;
    CMakeLists.txt | */CMakeLists.txt | *.cmake | *.cmake.in) echo "# $id" ;;
    *.sh | *.py | Snakefile | */Snakefile | .ci/run) echo "# $id" ;;
    *.xml.in) echo "<!-- $id -->" ;;
  esac
}

# Lines that may precede the licence line: a #! line, an XML declaration.
preamble_lines() {
  local first
  first=$(head -n 1 -- "$1")
  case "$first" in
    '#!'* | '<?xml'*) echo 1 ;;
    *) echo 0 ;;
  esac
}

missing=0
while IFS= read -r file; do
  [ -f "$file" ] || continue
  line=$(comment_for "$file")
  [ -n "$line" ] || continue
  skip=$(preamble_lines "$file")
  if [ "$(sed -n "$((skip + 1))p" -- "$file")" = "$line" ]; then continue; fi
  if [ $fix -eq 1 ]; then
    if [ "$skip" -eq 0 ]; then
      sed -i "1i $line" -- "$file"
    else
      sed -i "${skip}a $line" -- "$file"
    fi
    echo "fixed: $file"
  else
    echo "$file: no '$line' on line $((skip + 1))"
    missing=$((missing + 1))
  fi
done < <(git ls-files --cached --others --exclude-standard)
if [ $missing -gt 0 ]; then
  echo "$missing file(s) without the SPDX line; scripts/check_spdx.sh --fix adds it" >&2
  exit 1
fi
