#!/usr/bin/env bash
# The examples people copy (README.md, docs/, scripts/, bench/, python/aief/) spell flags as
# --help does: --n-features for the feature budget and --features-file for match --pairs' and
# colmap's HDF5 file, not their earlier spelling --features (still accepted, with a note). The
# earlier spellings themselves are named in backticks (docs/command_line.md), which this allows.
set -euo pipefail
root=${1:?usage: examples_use_current_flags.sh REPO_ROOT}
cd "$root"
if grep -rnE -- '(^|[^-a-z`])--features[ =]' README.md docs scripts bench python/aief; then
  echo "the lines above use --features: write --n-features N (or --features-file FILE)"
  exit 1
fi
