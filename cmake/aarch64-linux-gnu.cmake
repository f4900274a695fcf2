# Cross-compiling for 64-bit ARM Linux on Debian/Ubuntu (x86-64 host):
#   cmake -S . -B build-aarch64 --toolchain cmake/aarch64-linux-gnu.cmake -DAIEF_WITH_OPENCV=OFF
# Needs g++-aarch64-linux-gnu, and TBB / GoogleTest / Google Benchmark as arm64 multiarch
# packages (scripts/ci_aarch64_packages installs them). CTest runs the tests through
# qemu-aarch64 (CMAKE_CROSSCOMPILING_EMULATOR), so binfmt_misc is not needed.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Debian multiarch: arm64 libraries live in /usr/lib/aarch64-linux-gnu beside the amd64 ones,
# headers in /usr/include are shared. find_package searches <prefix>/lib/<this>/cmake first.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
# Programs are never taken from the target; libraries and packages only for the target arch.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
# "-L /": the arm64 loader and libraries are installed at their multiarch paths under /.
# (-L /usr/aarch64-linux-gnu pairs the cross toolchain's loader with the multiarch libc, and
# hangs in pthread_create.)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /)
