#!/usr/bin/env python3
"""Writes a CAM-style finishing contour of N blocks (default 100,000; no sequence numbers, as many CAM posts write it) to stdout:
0.05-0.2 mm G01 chords of a wavy profile 150 mm long (passes one after another) with a G02/G03 R arc every tenth block,
for timing `lathe check` (docs/PERFORMANCE.md, host throughput).

Usage: tools/contour_100k.py [N] > /tmp/contour.nc && time lathe check /tmp/contour.nc
"""
import math
import sys


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    out = sys.stdout
    out.write("O1000 (contour, %d blocks)\nG21 G18 G99 G40\nT0101\nG50 S2500\nG96 S180 M03\n" % n)
    out.write("G00 X40. Z2.\nG01 Z0 F0.12\n")
    written = 7
    z = 0.0
    k = 0
    while written < n - 2:
        k += 1
        z -= 0.05 + 0.15 * ((k * 7919) % 13) / 12.0
        if z < -150.0:
            # The next pass: back to the start of the part.
            out.write("G00 X60.\nZ2.\nG01 X40. Z0\n")
            written += 3
            z = -0.05
        x = 40.0 + 6.0 * math.sin(z / 3.0) + 2.0 * math.sin(z / 0.7)
        if k % 10 == 0:
            code = "G02" if (k // 10) % 2 else "G03"
            out.write("%s X%.3f Z%.3f R25.\n" % (code, x, z))
        else:
            out.write("G01 X%.3f Z%.3f\n" % (x, z))
        written += 1
    out.write("G00 X60.\nM30\n")


if __name__ == "__main__":
    main()
