#!/usr/bin/env python3
"""Stack frames of a firmware ELF, from its disassembly (arm-none-eabi-objdump -d):
each function's frame is what its prologue pushes and subtracts from sp. Prints the
largest frames and, for every embassy task, the deepest path of direct calls under
it (calls through `dyn` and function pointers are not followed, so a real stack can
be deeper: qemu-test.py reads the real high-water mark).

Usage: firmware/stack-frames.py ELF [N]     (N largest frames, default 15)
"""
import re
import subprocess
import sys

PROLOGUE = 14  # instructions of a prologue searched for push/sub sp


def disassemble(elf):
    out = subprocess.run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", "-C", elf],
                         check=True, stdout=subprocess.PIPE, text=True).stdout
    return out.splitlines()


def analyse(lines):
    names, frame, calls = {}, {}, {}
    cur, n = None, 0
    for i, line in enumerate(lines):
        m = re.match(r"^([0-9a-f]+) <(.*)>:$", line)
        if m:
            cur, n = int(m.group(1), 16), 0
            names[cur], frame[cur], calls[cur] = m.group(2), 0, set()
            continue
        if cur is None:
            continue
        n += 1
        if n <= PROLOGUE:
            frame[cur] += prologue_bytes(lines, i, line)
        m = re.search(r"\t(?:bl|b\.w|b|blx)(?:\.w)?\s+([0-9a-f]+) <", line)
        if m and int(m.group(1), 16) != cur:
            calls[cur].add(int(m.group(1), 16))
    return names, frame, calls


def prologue_bytes(lines, i, line):
    m = re.search(r"\tpush(?:\.w)?\s+\{(.*)\}", line)
    if m:
        return 4 * len(m.group(1).split(","))
    m = re.search(r"\tvpush\s+\{(.*)\}", line)
    if m:
        count = 0
        for r in m.group(1).split(","):
            r = r.strip()
            if "-" in r:
                a, b = r.split("-")
                count += int(b.strip()[1:]) - int(a[1:]) + 1
            else:
                count += 1
        return 8 * count
    m = re.search(r"\tsub(?:\.w|w)?\s+sp, (?:sp, )?#(\d+)", line)
    if m:
        return int(m.group(1))
    m = re.search(r"\tsub(?:\.w)?\s+sp, (?:sp, )?(r\d+)$", line)
    if m:
        for j in range(i - 1, max(i - 6, 0), -1):
            mm = re.search(r"\tmov(?:w|\.w)?\s+%s, #(\d+)" % m.group(1), lines[j])
            if mm:
                return int(mm.group(1))
    return 0


def deepest(a, names, frame, calls, memo, path):
    if a in memo:
        return memo[a]
    if a in path:
        return 0, []
    path.add(a)
    best = (0, [])
    for c in calls.get(a, ()):
        if c in names:
            d = deepest(c, names, frame, calls, memo, path)
            if d[0] > best[0]:
                best = d
    path.discard(a)
    memo[a] = (frame[a] + best[0], [a] + best[1])
    return memo[a]


def main():
    elf = sys.argv[1]
    top = int(sys.argv[2]) if len(sys.argv) > 2 else 15
    names, frame, calls = analyse(disassemble(elf))
    print("largest frames (bytes):")
    for a in sorted(frame, key=frame.get)[-top:][::-1]:
        print(f"  {frame[a]:6d}  {names[a][:110]}")
    memo = {}
    for a in sorted(a for a in names if "TaskStorage" in names[a] and names[a].endswith("::poll")):
        depth, path = deepest(a, names, frame, calls, memo, set())
        print(f"task at {a:#010x}: deepest direct path {depth} bytes")
        for x in path:
            if frame[x] >= 256:
                print(f"  {frame[x]:6d}  {names[x][:110]}")


if __name__ == "__main__":
    main()
