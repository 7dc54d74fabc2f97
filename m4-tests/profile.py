#!/usr/bin/env python3
"""Folds an icount profile ("ADDRESS COUNT" lines) into instructions per function.

Usage: m4-tests/profile.sh BIN   (builds, runs BIN under QEMU with the profiling
plugin, prints the top functions of all measured regions together)
       profile.py ELF PROFILE [TOP]
"""
import bisect
import subprocess
import sys


def symbols(elf):
    out = subprocess.run(["arm-none-eabi-nm", "-n", "-C", elf], capture_output=True, text=True, check=True).stdout
    syms = []
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if len(parts) == 3 and parts[1] in "tTwW":
            syms.append((int(parts[0], 16) & ~1, parts[2]))
    return syms


def main():
    elf, prof = sys.argv[1], sys.argv[2]
    top = int(sys.argv[3]) if len(sys.argv) > 3 else 25
    syms = symbols(elf)
    starts = [a for a, _ in syms]
    per_fn = {}
    total = 0
    with open(prof) as f:
        for line in f:
            addr, count = line.split()
            addr, count = int(addr, 16), int(count)
            i = bisect.bisect_right(starts, addr) - 1
            name = syms[i][1] if i >= 0 else "?"
            per_fn[name] = per_fn.get(name, 0) + count
            total += count
    print(f"{total} instructions in measured regions")
    for name, count in sorted(per_fn.items(), key=lambda kv: -kv[1])[:top]:
        print(f"{count:10} {100.0 * count / total:5.1f}%  {name[:110]}")


if __name__ == "__main__":
    main()
