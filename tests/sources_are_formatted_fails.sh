#!/usr/bin/env bash
# tests/sources_are_formatted.sh refuses what it should: a copy of .clang-format with one file in
# the house format passes; the same file laid out otherwise, or with a line over 100 columns, fails.
#   sources_are_formatted_fails.sh CLANG_FORMAT REPOSITORY
set -euo pipefail
clang_format=${1:?usage: sources_are_formatted_fails.sh CLANG_FORMAT REPOSITORY}
repository=${2:?usage: sources_are_formatted_fails.sh CLANG_FORMAT REPOSITORY}
check=$repository/tests/sources_are_formatted.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$repository/.clang-format" "$work/"
printf 'int sum(int a, int b) { return a + b; }\n' > "$work/good.cpp"
"$check" "$clang_format" "$work" > /dev/null || { echo "a formatted file was refused"; exit 1; }
printf 'int sum(int a,int b)\n{\n    return a+b;\n}\n' > "$work/good.cpp"
if "$check" "$clang_format" "$work" > "$work/out"; then echo "a file formatted otherwise passed"; exit 1; fi
grep -q good.cpp "$work/out" || { echo "the refusal does not name the file"; exit 1; }
printf '// %0101d\nint one() { return 1; }\n' 0 > "$work/good.cpp"
if "$check" "$clang_format" "$work" > "$work/out"; then echo "a line over 100 columns passed"; exit 1; fi
grep -q 'good.cpp:1' "$work/out" || { echo "the long line is not named"; exit 1; }
echo "the format check refuses a file laid out otherwise and a line over 100 columns"
