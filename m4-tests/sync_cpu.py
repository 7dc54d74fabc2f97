#!/usr/bin/env python3
"""CPU share of the encoder-count interrupt per spindle revolution (issue 22): reads
`bench.sh bench_isr` output on stdin and, for each pass measured per revolution,
prints the share of the locked revolutions (the steady one, and their range: the
ramp zone before the deceleration and the revolutions with the ramps' ends differ),
the worst revolution's and the average over the revolutions printed; fails if any revolution of a 1.5 mm pass goes over the
limit (10 % of the CPU at 3000 rpm × 4096 counts/rev).

    m4-tests/bench.sh bench_isr | tee bench_isr.out
    python3 m4-tests/sync_cpu.py < bench_isr.out

Share = (instructions + 54 cycles an interrupt: entry and exit 24, about ten
timer/NVIC register accesses ~30 on APB1) × revolutions a second / 168 MHz,
instructions read as cycles (no flash wait states): docs/PERFORMANCE.md.
"""
import re
import sys

CLOCK_HZ = 168_000_000
PER_INTERRUPT = 54
LIMIT_PCT = 10.0


def passes(lines):
    """(lead_um, rpm, [(revolution, phase, instructions, interrupts)], rest) per pass
    measured per revolution (`rest`: the part after the last whole revolution)."""
    current, pending = None, None
    for line in lines:
        line = line.strip()
        m = re.match(r"bench count interrupts per spindle revolution, G32 (\d+) um lead at (\d+) rpm", line)
        if m:
            if current:
                yield current
            current = [int(m.group(1)), int(m.group(2)), [], None]
            continue
        if current is None:
            continue
        m = re.match(r"revolution (\d+) \(Some\((\w+)", line)
        if m:
            pending = (int(m.group(1)), m.group(2))
            continue
        if line.startswith("the rest of the pass"):
            pending = ("rest", "")
            continue
        m = re.match(r"instructions: (\d+) in (\d+) regions", line)
        if m and pending:
            sums = (int(m.group(1)), int(m.group(2)))
            if pending[0] == "rest":
                current[3] = sums
                yield current
                current = None
            else:
                current[2].append((pending[0], pending[1], *sums))
            pending = None


def share(instructions, interrupts, rpm, revolutions=1.0):
    cycles = instructions + PER_INTERRUPT * interrupts
    return 100.0 * cycles * rpm / 60.0 / revolutions / CLOCK_HZ


def main():
    over, seen = [], 0
    for lead, rpm, revs, _rest in passes(sys.stdin):
        seen += 1
        if not revs:
            continue
        pcts = [share(i, n, rpm) for _, _, i, n in revs]
        locked = [round(p, 2) for (_, ph, _, _), p in zip(revs, pcts) if ph == "Locked"]
        steady = max(set(locked), key=locked.count) if locked else 0.0
        k = max(range(len(revs)), key=lambda j: pcts[j])
        worst, worst_pct = revs[k], pcts[k]
        print(
            f"sync cpu: {lead / 1000:g} mm lead at {rpm} rpm: locked {steady:.2f} % "
            f"({min(locked, default=0):.2f}–{max(locked, default=0):.2f}), "
            f"worst revolution {worst[0]} ({worst[1]}, {worst[3]} interrupts, {worst[2]:,} instructions) "
            f"{worst_pct:.2f} %, average over the {len(revs)} revolutions printed {sum(pcts) / len(pcts):.2f} %"
        )
        if lead == 1500 and worst_pct > LIMIT_PCT:
            over.append(f"{rpm} rpm revolution {worst[0]}: {worst_pct:.2f} %")
    if not seen:
        print("sync_cpu.py: no per-revolution passes in the input", file=sys.stderr)
        sys.exit(1)
    if over:
        print(f"sync_cpu.py: over {LIMIT_PCT} %: " + "; ".join(over), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
