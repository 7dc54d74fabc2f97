#!/usr/bin/env python3
"""Sums `bench.sh bench_dense` per chain: instructions per block and the CPU load of
the whole chain at 168 MHz (issue 22's dense programs at full feed), and fails
unless the target holds: 0.02 mm blocks at F6000 run at the programmed feed, at
least 5,000 blocks/s, within 50 % of the CPU.

    m4-tests/bench.sh bench_dense | python3 m4-tests/dense.py

Per measured period bench_dense prints three counts — the control task's fill
(text to planned block for every block of the period), the period interrupt
(Engine::period) and all the period's step interrupts (Player::run) — and then
the blocks filled and crossed, the edges queued, the step interrupts and the path
speed. Each interrupt costs 12 + 12 cycles of entry and exit on top of its body
(counted here); instructions are read as cycles (a lower bound: no flash wait
states).
"""
import re
import sys

CLOCK = 168e6
PERIOD_S = 1e-3
ENTRY_EXIT = 24


def main():
    runs = {}
    seg = None
    counts = []
    for line in sys.stdin:
        line = line.strip()
        m = re.match(r"bench dense (\d+) um: period \d+", line)
        if m:
            seg, counts = int(m.group(1)), []
            continue
        m = re.match(r"instructions: (\d+)$", line)
        if m and seg is not None:
            counts.append(int(m.group(1)))
            continue
        m = re.match(r"fill (\d+) blocks, period crossed (\d+) blocks, (\d+) edges, (\d+) step interrupts, (\d+) mm/min", line)
        if m and seg is not None and len(counts) == 3:
            fill, crossed, edges, steps, speed = map(int, m.groups())
            runs.setdefault(seg, []).append((counts[0], counts[1], counts[2], fill, crossed, edges, steps, speed))
    if not runs:
        print("dense: no bench_dense output on stdin", file=sys.stderr)
        return 1
    failed = []
    print(f"{'segment':>8} {'feed':>9} {'blocks/s':>9} {'fill/block':>11} {'period':>8} {'steps':>7} {'CPU':>6}")
    print(f"{'mm':>8} {'mm/min':>9} {'':>9} {'(text->plan)':>11} {'irq':>8} {'irqs':>7} {'168MHz':>6}")
    for seg, rows in sorted(runs.items()):
        n = len(rows)
        fill = sum(r[0] for r in rows)
        filled = sum(r[3] for r in rows)
        period = sum(r[1] for r in rows) / n
        steps = sum(r[2] for r in rows) / n
        irqs = sum(r[6] for r in rows) / n
        crossed = sum(r[4] for r in rows) / n
        speed = sum(r[7] for r in rows) / n
        per_period = fill / n + period + steps + (1 + irqs) * ENTRY_EXIT
        cpu = per_period / (CLOCK * PERIOD_S)
        print(
            f"{seg / 1000:>8.2f} {speed:>9.0f} {crossed / PERIOD_S:>9.0f} {fill / max(filled, 1):>11.0f}"
            f" {period:>8.0f} {steps:>7.0f} {100 * cpu:>5.1f}%"
        )
        if seg == 20 and (speed < 6000 or crossed / PERIOD_S < 5000 or cpu > 0.5):
            failed.append(f"0.02 mm: {speed:.0f} mm/min, {crossed / PERIOD_S:.0f} blocks/s, {100 * cpu:.1f} % CPU")
    if 20 not in runs:
        failed.append("no 0.02 mm chain")
    if failed:
        print(f"dense: target missed: {'; '.join(failed)}", file=sys.stderr)
        return 1
    print("dense: 0.02 mm at F6000 within the target (programmed feed, >= 5,000 blocks/s, <= 50 % CPU)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
