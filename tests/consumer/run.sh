#!/usr/bin/env bash
# Installs the build tree into a temporary prefix, then builds two consumers against it: a CMake
# project (find_package(aief), aief::aief) and a one-file program through pkg-config. Fails if
# either cannot find, compile, link or run.
set -euo pipefail
build_dir=$1
source_dir=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/include/aief/extractor.hpp"
test -f "$work/prefix/include/aief/version.hpp"
test -x "$work/prefix/bin/aief"
cmake -S "$source_dir" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
"$work/consumer/consumer"
pc_dir=$(dirname "$(find "$work/prefix" -name aief.pc | head -n 1)")
export PKG_CONFIG_PATH="$pc_dir"
c++ -std=c++17 "$source_dir/main.cpp" -o "$work/pkgconfig_consumer" $(pkg-config --cflags --libs --static aief)
"$work/pkgconfig_consumer"
echo "install, find_package and pkg-config consumers: OK"
