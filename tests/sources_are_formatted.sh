#!/usr/bin/env bash
# The tree is written in the house format (.clang-format, CONTRIBUTING.md "Style"): every C++
# file git tracks is what `clang-format -i` leaves, and no line passes 100 columns outside a raw
# string (COLMAP's schema in io/colmap_database.cpp is SQL that the database keeps as written).
#   sources_are_formatted.sh CLANG_FORMAT ROOT
# Every C++ file below ROOT is checked but those of build folders (a CMakeCache.txt in them) and
# hidden ones: no git needed (CI's fresh root has none).
set -euo pipefail
clang_format=${1:?usage: sources_are_formatted.sh CLANG_FORMAT ROOT}
root=${2:?usage: sources_are_formatted.sh CLANG_FORMAT ROOT}
cd "$root"
mapfile -t files < <(find . \( -name '.?*' -o -exec test -e '{}/CMakeCache.txt' \; \) -prune -o \
  -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' \) -print | sort)
((${#files[@]})) || { echo "no C++ files under $root"; exit 1; }
status=0
unformatted=$("$clang_format" --style=file --dry-run "${files[@]}" 2>&1 | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: warning: code should be clang-formatted.*/\1/p' | sort -u)
if [ -n "$unformatted" ]; then
  echo "not in the house format (run: clang-format -i FILE):"
  sed 's/^/  /' <<<"$unformatted"
  status=1
fi
long=$(awk 'FNR == 1 { raw = 0 } /R"[A-Za-z_]*\(/ { raw = 1 } length > 100 && !raw { print FILENAME ":" FNR } /\)[A-Za-z_]*"/ { raw = 0 }' "${files[@]}")
if [ -n "$long" ]; then
  echo "lines over 100 columns:"
  sed 's/^/  /' <<<"$long"
  status=1
fi
exit $status
