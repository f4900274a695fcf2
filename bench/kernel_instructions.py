#!/usr/bin/env python3
"""Instructions each kernel executes under qemu-aarch64, neon64 against scalar: the one speed
figure for ARM this project can measure without ARM hardware (docs/arm.md).

Debian's qemu-user ships no TCG plugins (no libinsn.so) and valgrind is x86-only, so this counts
from qemu's own logs: `-d in_asm` gives each translated block's instructions and `-d
exec,nochain` logs every block executed, both restricted (-dfilter) to the program's own code:
the executable's text segment, which holds libaief (aief_bench_kernel_sets is linked without
PIE, so the addresses are the file's). Each kernel's benchmark runs twice, with 1 and with 2
iterations (--aief_iterations); the difference is one pass of the kernel over the graf crop's
pyramid, whatever the set-up costs. It includes the kernel's callees in libaief and the
benchmark's loop around it, and excludes shared libraries on both sides (libc's memset, libm's
cos/sin in rBRIEF, Google Benchmark itself).

usage: bench/kernel_instructions.py [--build build-aarch64] [--kernels K,K...]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import threading
from collections import Counter

def listed_kernels(build):
    """The kernel list, as configure wrote it to <build>/kernel_list.txt (cmake/kernel_list.cmake),
    then the pipeline."""
    with open(os.path.join(build, "kernel_list.txt")) as f:
        return f.read().split() + ["extract"]


SETS = ["scalar", "neon64"]


def text_segment(binary):
    """(start, size) of the executable's one loadable, executable segment."""
    out = subprocess.run(["readelf", "-lW", binary], check=True, capture_output=True, text=True).stdout
    segments = [(int(f[2], 16), int(f[5], 16)) for f in (line.split() for line in out.splitlines())
                if f and f[0] == "LOAD" and "E" in f[6:-1]]
    if len(segments) != 1:
        sys.exit(f"kernel_instructions: expected one executable segment in {binary}, found {len(segments)}")
    return segments[0]


def count_log(path, result):
    """Executed instructions in a qemu in_asm + exec log, read as it is written."""
    block_size, executed = {}, Counter()
    block_start = None
    with open(path, "r", errors="replace") as log:
        for line in log:
            if line.startswith("Trace "):
                executed[line.split("[", 1)[1].split("/", 2)[1]] += 1
            elif line.startswith("IN:"):
                block_start = None
            elif line.startswith("0x"):
                address = line.split(":", 1)[0][2:].rjust(16, "0")
                if block_start is None:
                    block_start, block_size[address] = address, 0
                block_size[block_start] += 1
    result.append(sum(times * block_size.get(address, 0) for address, times in executed.items()))


def instructions(binary, segment, benchmark_name, iterations):
    """Instructions executed in the program's own code by one run of one benchmark."""
    with tempfile.TemporaryDirectory() as work:
        fifo = os.path.join(work, "qemu.log")
        os.mkfifo(fifo)
        result = []
        reader = threading.Thread(target=count_log, args=(fifo, result))
        reader.start()
        command = ["qemu-aarch64", "-L", "/", "-d", "in_asm,exec,nochain", "-dfilter", f"{segment[0]:#x}+{segment[1]:#x}",
                   "-D", fifo, binary, f"--benchmark_filter=^{re.escape(benchmark_name)}/iterations:{iterations}$", f"--aief_iterations={iterations}"]
        run = subprocess.run(command, capture_output=True, text=True)
        reader.join()
        if run.returncode != 0 or benchmark_name not in run.stdout:
            sys.exit(f"kernel_instructions: {' '.join(command)} failed:\n{run.stderr}")
        return result[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build-aarch64")
    parser.add_argument("--kernels", help="comma-separated (default: the kernel list, then extract)")
    args = parser.parse_args()
    kernels = args.kernels.split(",") if args.kernels else listed_kernels(args.build)
    binary = f"{args.build}/bench/aief_bench_kernel_sets"
    segment = text_segment(binary)
    print("| kernel, one pass over the graf 320x240 crop | scalar | neon64 | scalar / neon64 |")
    print("|---|---:|---:|---:|", flush=True)
    for kernel in kernels:
        per_set = {}
        for kernel_set in SETS:
            name = f"{kernel}/{kernel_set}/graf_320x240"
            per_set[kernel_set] = instructions(binary, segment, name, 2) - instructions(binary, segment, name, 1)
        print(f"| {kernel} | {per_set['scalar']:,} | {per_set['neon64']:,} | {per_set['scalar'] / per_set['neon64']:.2f} |",
              flush=True)


if __name__ == "__main__":
    main()
