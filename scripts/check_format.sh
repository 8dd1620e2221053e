#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Lists C++ source lines longer than the 120 columns of .clang-format, as FILE:LINE: N columns, and
# exits 1 when there are any. The code base is not run through clang-format wholesale (it would touch
# every file at once); new and edited code should be, and this check keeps the column limit meanwhile.
# Usage: scripts/check_format.sh [PATH...]   (default: every tracked .h/.cpp/.c file)
set -euo pipefail
cd "$(dirname "$0")/.."
limit=120
if [ $# -gt 0 ]; then
  mapfile -t files < <(git ls-files -- "$@" | grep -E '\.(h|hpp|c|cpp)$' || true)
else
  mapfile -t files < <(git ls-files -- '*.h' '*.hpp' '*.c' '*.cpp')
fi
[ ${#files[@]} -eq 0 ] && exit 0
# Columns are characters, not bytes: comments hold UTF-8 (mm^2, Greek letters).
found=$(LC_ALL=C.UTF-8 grep -nHP "^.{$((limit + 1)),}" -- "${files[@]}" || true)
[ -z "$found" ] && exit 0
while IFS= read -r hit; do
  file=${hit%%:*}; rest=${hit#*:}; line=${rest%%:*}; text=${rest#*:}
  printf '%s:%s: %d columns\n' "$file" "$line" "$(LC_ALL=C.UTF-8; echo ${#text})"
done <<<"$found"
echo "$(wc -l <<<"$found") line(s) over $limit columns" >&2
exit 1
