#!/usr/bin/env python3
"""Fails unless the per-block budgets of issue 13 hold: reads `bench.sh bench_interp`
output on stdin and checks the "text to planned block" counts (Cortex-M4
instructions from the block's text to its planned motion block).

    m4-tests/bench.sh bench_interp | python3 m4-tests/budget.py

Budgets: a short G01 (also under G96) ≤ 4,000 instructions, a G02/G03 with R
≤ 7,000; a machining centre's 3-axis G01 ("mill G01 XYZ", issue 20) ≤ 4,000, as a
lathe G01 (3,822–3,977; docs/PERFORMANCE.md, per-block round 5); a plain
SINUMERIK `G1 X.. Z..` ("SINUMERIK G1", issue 19: the short way for plain lines)
≤ 4,000, as a FANUC G01 (3,622–3,762; docs/PERFORMANCE.md, "SINUMERIK mode").
Prints each measured block with its budget and margin.
"""
import re
import sys

BUDGETS = {
    "G01": 4000,
    "G01 under G96": 4000,
    "G02 R": 7000,
    "G03 R": 7000,
    "mill G01 XYZ": 4000,
    "SINUMERIK G1": 4000,
}


def planned_counts(lines):
    """(label, count) for every measured step of the text-to-planned pass."""
    label = None
    for line in lines:
        m = re.match(r"bench (.+?): (.+)$", line.strip())
        if m:
            label = m.group(2) if m.group(1) == "text to planned block" else None
            continue
        m = re.match(r"instructions: (\d+)$", line.strip())
        if m and label is not None:
            yield label, int(m.group(1))
            label = None


def main():
    over, seen = [], set()
    for label, count in planned_counts(sys.stdin):
        budget = BUDGETS.get(label)
        if budget is None:
            continue
        seen.add(label)
        print(f"budget: {label:14} {count:6,} of {budget:,} ({budget - count:+,})")
        if count > budget and label not in over:
            over.append(label)
    missing = sorted(set(BUDGETS) - seen)
    if missing:
        print(f"budget: no count for {', '.join(missing)}", file=sys.stderr)
        return 1
    if over:
        print(f"budget: over for {', '.join(over)}", file=sys.stderr)
        return 1
    print("budget: every block within its budget")
    return 0


if __name__ == "__main__":
    sys.exit(main())
