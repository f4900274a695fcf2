#!/usr/bin/env bash
# core/'s folders by floor, the ground first (docs/architecture.md, "core/ by job"). A file of a
# folder may include its own folder's headers and those of folders on lower floors only: no
# arrow runs up or sideways, so no two folders can ever include each other.
set -euo pipefail
core=${1:?usage: core_folders_include_downward.sh CORE_DIR}
floors=(
  "options kernels distribution"  # the option rows; the kernel list and scalar references; the spread
  "level match"                   # a level's geometry and data; pair matching and RANSAC
  "entropy description"           # block entropies and F; orientation and the descriptor per level
  "detection"                     # FAST per block at F
  "frame"                         # one image's stages in order
  "sweep"                         # the adaptive sweep over thresholds, and F carried over a video
)
floor_of() {
  local i
  for i in "${!floors[@]}"; do
    for folder in ${floors[$i]}; do [ "$folder" = "$1" ] && { echo "$i"; return; }; done
  done
  echo "none"
}
status=0
for dir in "$core"/*/; do
  folder=$(basename "$dir")
  [ "$folder" = generated ] && continue
  floor=$(floor_of "$folder")
  if [ "$floor" = none ]; then echo "core/$folder/ is on no floor of $0: add it"; status=1; continue; fi
  while IFS=: read -r file line include; do
    target=$(sed -E 's|.*"core/([a-z_0-9]+)/.*|\1|' <<<"$include")
    [ "$target" = "$folder" ] && continue
    target_floor=$(floor_of "$target")
    if [ "$target_floor" = none ] || [ "$target_floor" -ge "$floor" ]; then
      echo "${file#"$core"/../}:$line includes core/$target/ (floor $target_floor) from core/$folder/ (floor $floor)"
      status=1
    fi
  done < <(grep -nE '^#include "core/[a-z_0-9]+/' -r "$dir" --include=*.cpp --include=*.hpp || true)
done
exit $status
