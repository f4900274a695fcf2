#!/bin/sh
# The licence travels with every way aief is shipped (README.md, "Licence"): LICENSE is the Apache
# License 2.0, NOTICE names the third-party data carried, and the wheel's metadata
# (pyproject.toml), the Debian packages' copyright files (cmake/packaging.cmake, checked by
# installing each component into a folder of its own), the pkg-config files and the README say so.
# Usage: licence_is_carried.sh SOURCE_DIR BUILD_DIR
set -eu
src=$1 build=$2
fail() { echo "licence_is_carried: $*" >&2; exit 1; }

grep -q "Apache License" "$src/LICENSE" && grep -q "Version 2.0, January 2004" "$src/LICENSE" \
  || fail "LICENSE is not the Apache License 2.0"
for carried in data/orb_pattern_31.txt "modules/features2d/src/orb.cpp" \
               data/box_descriptor/teblid_256.txt opencv_contrib; do
  grep -q "$carried" "$src/NOTICE" || fail "NOTICE does not name $carried"
done
# TEBLID's source file carries no copyright line: the copyright is not credited to the paper's
# authors (data/box_descriptor/README.md names the source as it is).
! grep -q "Copyright.*Iago Suarez" "$src/NOTICE" "$src/cmake/debian_copyright" \
  || fail "NOTICE or cmake/debian_copyright credits TEBLID's table to the paper's authors"
grep -q "no copyright" "$src/NOTICE" || fail "NOTICE does not say TEBLID's file has no copyright line"
# The sample images are the Oxford group's research images, not the project's Apache-2.0 files.
grep -q "^Files: data/samples/\*" "$src/cmake/debian_copyright" \
  || fail "cmake/debian_copyright: data/samples has no stanza of its own (Files: * says Apache-2.0)"
grep -q '^license = { text = "Apache-2.0" }' "$src/pyproject.toml" || fail "pyproject.toml: no license"
grep -q 'license-files = \["LICENSE", "NOTICE"\]' "$src/pyproject.toml" \
  || fail "pyproject.toml: LICENSE and NOTICE not in the wheel"
grep -q "Apache Software License" "$src/pyproject.toml" || fail "pyproject.toml: no licence classifier"
grep -q '^## Licence' "$src/README.md" && grep -q '(LICENSE)' "$src/README.md" \
  || fail "README.md: no Licence section"
found=0
for pc in "$build"/aief*.pc; do
  grep -q '^License: Apache-2.0$' "$pc" || fail "$pc: no License line"
  found=1
done
[ "$found" = 1 ] || fail "no aief*.pc in $build"

# Every component installs its Debian copyright file with LICENSE and NOTICE beside it.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
components=$(sed -n 's/^set(CPACK_COMPONENTS_ALL \(.*\))$/\1/p' "$build/CPackConfig.cmake" | tr -d '"' | tr ';' ' ')
[ -n "$components" ] || fail "no components in $build/CPackConfig.cmake"
for component in $components; do
  cmake --install "$build" --component "$component" --prefix "$work/$component" > /dev/null
  copyright=$(find "$work/$component/share/doc" -name copyright 2>/dev/null | head -1)
  [ -n "$copyright" ] || fail "component $component installs no share/doc/<package>/copyright"
  grep -q "^License: Apache-2.0" "$copyright" || fail "$copyright: no Apache-2.0"
  grep -q "^Files: data/orb_pattern_31.txt" "$copyright" || fail "$copyright: the ORB pattern is not named"
  grep -q "^Files: data/box_descriptor/teblid_256.txt" "$copyright" || fail "$copyright: TEBLID is not named"
  dir=$(dirname "$copyright")
  [ -f "$dir/LICENSE" ] && [ -f "$dir/NOTICE" ] || fail "component $component: no LICENSE and NOTICE in $dir"
done
echo "licence_is_carried: LICENSE, NOTICE, pyproject.toml, README.md, $(ls "$build"/aief*.pc | wc -l) pkg-config files and the copyright of components: $components"
