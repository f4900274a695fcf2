#!/usr/bin/env python3
"""Instructions each kernel executes under qemu-aarch64, neon64 against scalar: the one speed
figure for ARM this project can measure without ARM hardware (bench/RESULTS.md, "ARM").

Debian's qemu-user ships no TCG plugins (no libinsn.so) and valgrind is x86-only, so this counts
from qemu's own logs: `-d in_asm` gives each translated block's instructions, `-d exec,nochain`
logs every block executed, and each block is credited to the function whose symbol range holds
it (aarch64-linux-gnu-nm; aief_bench_kernel_sets is linked without PIE so the addresses agree).
A kernel's count is the instructions in the functions named after it (the scalar reference,
the neon64 template and their lambdas; libm's cos/sin in rBRIEF are not counted, on either
side), for one benchmark iteration (--benchmark_min_time=0), minus the same count for a run
that registers the inputs but runs no benchmark (the inputs are made with the scalar kernels).

usage: bench/kernel_instructions.py [--build build-aarch64] [--kernels K,K...]
"""
import argparse
import bisect
import json
import re
import subprocess
import sys
from collections import Counter

KERNELS = ["resize_bilinear_rows", "gaussian7_rows", "accumulate_histogram", "fast9_scores_row",
           "fast9_local_maxima_row", "ic_moments", "rbrief_describe", "hamming_256_many"]
SETS = ["scalar", "neon64"]


def kernel_functions(binary):
    """(start, end, kernel) of every function symbol named after a kernel, sorted by start."""
    out = subprocess.run(["aarch64-linux-gnu-nm", "-C", "-S", "--defined-only", binary], check=True,
                         capture_output=True, text=True).stdout
    ranges = []
    for line in out.splitlines():
        parts = line.split(" ", 3)
        if len(parts) < 4 or parts[2] not in "TtWw":
            continue
        for kernel in KERNELS:
            if re.search(r"\b" + kernel + r"(_scalar\b|<)", parts[3]):
                start = int(parts[0], 16)
                ranges.append((start, start + int(parts[1], 16), kernel))
    return sorted(ranges)


def instructions_per_kernel(binary, ranges, benchmark_filter):
    """Instructions executed in each kernel's functions, and the benchmark iterations run."""
    command = ["qemu-aarch64", "-L", "/", "-d", "in_asm,exec,nochain", binary, f"--benchmark_filter={benchmark_filter}",
               "--benchmark_min_time=0", "--benchmark_format=json"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    block_size, executed = {}, Counter()
    block_start = None
    for line in process.stderr:
        if line.startswith("Trace "):
            executed[int(line.split("[", 1)[1].split("/")[1], 16)] += 1
        elif line.startswith("IN:"):
            block_start = None
        elif line.startswith("0x") and ":" in line:
            address = int(line.split(":", 1)[0], 16)
            if block_start is None:
                block_start, block_size[address] = address, 0
            block_size[block_start] += 1
    report = json.loads(process.stdout.read() or "{\"benchmarks\": []}")
    if process.wait() != 0:
        sys.exit(f"kernel_instructions: {' '.join(command)} failed")
    starts = [r[0] for r in ranges]
    counts = Counter()
    for address, times in executed.items():
        i = bisect.bisect_right(starts, address) - 1
        if i >= 0 and address < ranges[i][1]:
            counts[ranges[i][2]] += times * block_size.get(address, 0)
    iterations = {b["name"]: b["iterations"] for b in report["benchmarks"]}
    return counts, iterations


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build-aarch64")
    parser.add_argument("--kernels", default=",".join(KERNELS))
    args = parser.parse_args()
    binary = f"{args.build}/bench/aief_bench_kernel_sets"
    ranges = kernel_functions(binary)
    setup, _ = instructions_per_kernel(binary, ranges, "^$")  # inputs only, no benchmark
    print("| kernel (graf 320x240 crop, one pass) | scalar instructions | neon64 instructions | scalar / neon64 |")
    print("|---|---:|---:|---:|")
    for kernel in args.kernels.split(","):
        per_set = {}
        for kernel_set in SETS:
            name = f"{kernel}/{kernel_set}/graf_320x240"
            counts, iterations = instructions_per_kernel(binary, ranges, f"^{re.escape(name)}$")
            if iterations.get(name) != 1:
                sys.exit(f"kernel_instructions: {name} ran {iterations.get(name)} iterations, expected 1")
            per_set[kernel_set] = counts[kernel] - setup[kernel]
        print(f"| {kernel} | {per_set['scalar']:,} | {per_set['neon64']:,} | {per_set['scalar'] / per_set['neon64']:.2f} |",
              flush=True)


if __name__ == "__main__":
    main()
