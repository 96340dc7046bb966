#!/usr/bin/env bash
# Fails when a C++ source is not formatted as .clang-format says (Debian 12's clang-format 14;
# another version may format differently). Fix with:
#   find lib meshgen apps tests fuzz python \( -name '*.cpp' -o -name '*.hpp' \) -print0 | xargs -0 clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check_format: clang-format not found (scripts/install_deps.sh installs it)" >&2; exit 1; }
mapfile -d '' files < <(find lib meshgen apps tests fuzz python \( -name '*.cpp' -o -name '*.hpp' \) -print0 | sort -z)
if ! clang-format --dry-run --Werror "${files[@]}"; then
  echo "check_format: the files above differ from .clang-format; run clang-format -i on them" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files follow .clang-format"
