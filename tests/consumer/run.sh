#!/usr/bin/env bash
# Installs the build tree into a temporary prefix, moves it (the package must be relocatable),
# then builds against it: a CMake project (find_package(aief), aief::aief, and aief::opencv when
# the build tree has the adapter) and a one-file program through `pkg-config --cflags --libs
# aief`. Fails if any step cannot find, compile, link or run.
#   run.sh BUILD_DIR              install BUILD_DIR, then the above
#   run.sh --installed PREFIX     the above against what is already installed in PREFIX (e.g. /usr
#                                 from the Debian packages, scripts/ci_packages)
#   run.sh --build-tree BUILD_DIR the CMake project against the build folder itself, not installed
#                                 (aief_DIR=BUILD_DIR: its aiefConfig.cmake and exported targets)
set -euo pipefail
source_dir=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "install test: $*" >&2; exit 1; }

# What a build folder was configured with says what it built: the OpenCV parts, the adapter.
parts_of_build() {
  with_opencv=ON
  if grep -q '^AIEF_WITH_OPENCV:BOOL=OFF' "$1/CMakeCache.txt"; then with_opencv=OFF; fi
  expect_opencv=OFF
  if [ "$with_opencv" = ON ] && grep -q '^AIEF_BUILD_OPENCV_ADAPTER:BOOL=ON' "$1/CMakeCache.txt"; then expect_opencv=ON; fi
}
# The CMake consumer (tests/consumer/CMakeLists.txt) configured with CMAKE_ARGS..., built and run.
cmake_consumer() {
  local opencv_flags=()
  [ "$with_opencv" = ON ] || opencv_flags=(-DAIEF_EXPECT_IO=OFF -DCMAKE_DISABLE_FIND_PACKAGE_OpenCV=ON)
  cmake -S "$source_dir" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
        -DAIEF_EXPECT_OPENCV=$expect_opencv "${opencv_flags[@]}" "$@" > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "consumer configure failed"; }
  cmake --build "$work/consumer" > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "consumer build failed"; }
  "$work/consumer/consumer" || fail "the find_package consumer failed"
  if [ "$with_opencv" = ON ]; then
    mkdir -p "$work/io_cmake"
    "$work/consumer/io_consumer" "$work/io_cmake" || fail "the aief::io consumer failed"
  fi
  if [ "$expect_opencv" = ON ]; then
    "$work/consumer/consumer_opencv" || fail "the aief::opencv consumer failed"
    "$work/consumer/feature2d_consumer" || fail "the cv::Feature2D consumer failed"
    "$work/consumer/orbslam2_swap" || fail "the ORB-SLAM2 swap of docs/orbslam2.md failed"
    "$work/consumer/orbslam3_swap" || fail "the ORB-SLAM3 swap of docs/orbslam3.md failed"
  fi
}

if [ "${1:-}" = --build-tree ]; then
  build_dir=$(cd "$2" && pwd)
  parts_of_build "$build_dir"
  # find_package(aief) reads aief_DIR's aiefConfig.cmake before any installed one.
  cmake_consumer -Daief_DIR="$build_dir"
  echo "build tree $build_dir, find_package (OpenCV parts: $with_opencv, adapter: $expect_opencv) consumers: OK"
  exit 0
fi

if [ "${1:-}" = --installed ]; then
  prefix=$2
  # What was installed says what was built: the adapter's header, aief::io's headers.
  with_opencv=OFF expect_opencv=OFF
  [ -d "$prefix/include/aief/io" ] && with_opencv=ON
  [ -e "$prefix/include/aief/opencv.hpp" ] && expect_opencv=ON
else
  build_dir=$1
  cmake --install "$build_dir" --prefix "$work/installed" > "$work/install.log" || fail "cmake --install failed"
  mv "$work/installed" "$work/prefix"
  prefix=$work/prefix
  # An OpenCV-free build (AIEF_WITH_OPENCV=OFF) installs the engine alone: no tool, no aief::io,
  # and its package must configure with OpenCV out of reach.
  parts_of_build "$build_dir"
fi
for file in include/aief/aief.hpp include/aief/extractor.hpp include/aief/version.hpp; do
  test -e "$prefix/$file" || fail "missing $file in the install tree"
done
if [ "$with_opencv" = ON ]; then
  "$prefix/bin/aief" --version > /dev/null || fail "the installed aief tool does not run"
else
  test ! -e "$prefix/include/aief/opencv.hpp" || fail "an OpenCV-free install has include/aief/opencv.hpp"
fi
config=$(find "$prefix"/lib* -maxdepth 4 -name aiefConfig.cmake | head -n 1)
test -n "$config" || fail "no aiefConfig.cmake installed"
pc_file=$(find "$prefix"/lib* -maxdepth 4 -name aief.pc | head -n 1)
test -n "$pc_file" || fail "no aief.pc installed"

cmake_consumer -DCMAKE_PREFIX_PATH="$prefix"

export PKG_CONFIG_PATH=$(dirname "$pc_file")
libdir=$(dirname "$PKG_CONFIG_PATH")
# pkg_consumer NAME SOURCE PACKAGE...: SOURCE compiled and linked with `pkg-config --cflags --libs
# PACKAGE...` alone, then run (with a folder of its own as argument).
pkg_consumer() {
  local name=$1 source=$2 flags
  shift 2
  flags=$(pkg-config --cflags --libs "$@") || fail "pkg-config does not know $*"
  # shellcheck disable=SC2086  # the flags are a word list
  c++ -std=c++17 "$source_dir/$source" -o "$work/$name" $flags || fail "the pkg-config consumer $name did not build with: $flags"
  mkdir -p "$work/$name.out"
  LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$work/$name" "$work/$name.out" || fail "the pkg-config consumer $name failed"  # a shared build has no rpath here
}
pkg_consumer pkgconfig_consumer main.cpp aief
pkg_checked="aief"
if [ "$with_opencv" = ON ]; then
  pkg_consumer pkgconfig_io_consumer io_main.cpp aief-io
  pkg_checked+=", aief-io"
  # docs/install.md's static link of the archives, whatever the package's own libraries are:
  # libaief_io.a needs OpenCV, HDF5 and SQLite, libaief.a TBB and pthreads.
  if [ -e "$libdir/libaief_io.a" ]; then
    static_libs=(opencv4)
    grep -q AIEF_HAVE_HDF5 "$PKG_CONFIG_PATH/aief-io.pc" && static_libs+=(hdf5)
    grep -q AIEF_HAVE_COLMAP_EXPORT "$PKG_CONFIG_PATH/aief-io.pc" && static_libs+=(sqlite3)
    # shellcheck disable=SC2046  # the flags are word lists
    c++ -std=c++17 "$source_dir/io_main.cpp" -o "$work/static_io_consumer" $(pkg-config --cflags aief-io) \
        "$libdir/libaief_io.a" "$libdir/libaief.a" $(pkg-config --libs "${static_libs[@]}") -ltbb -lpthread \
      || fail "the static link of docs/install.md (libaief_io.a libaief.a, pkg-config --libs ${static_libs[*]}, -ltbb -lpthread) failed"
    mkdir -p "$work/static_io.out"
    "$work/static_io_consumer" "$work/static_io.out" || fail "the statically linked aief::io consumer failed"
    ldd "$work/static_io_consumer" | grep -q 'libaief' && fail "the static consumer loads a shared libaief"
    pkg_checked+=", the static archives"
  fi
fi
if [ "$expect_opencv" = ON ]; then
  pkg_consumer pkgconfig_opencv_consumer opencv_main.cpp aief-opencv
  pkg_consumer pkgconfig_feature2d_consumer feature2d_main.cpp aief-opencv
  pkg_checked+=", aief-opencv"
fi
where="install (relocated)"
[ -n "${build_dir:-}" ] || where="install in $prefix"
echo "$where, find_package (OpenCV parts: $with_opencv, adapter: $expect_opencv) and pkg-config ($pkg_checked) consumers: OK"
