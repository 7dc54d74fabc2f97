#!/usr/bin/env python3
"""Writes mill-paths/src/font.rs, CYCLE60's stroke font, from the Hershey
"Roman simplex" glyphs (rowmans) for printable ASCII 32..126.

The Hershey fonts were digitised by Dr. A. V. Hershey at the U.S. National
Bureau of Standards and are in the public domain (only NTIS's own distribution
format is not). The glyph coordinates are read from the PyPI package
`Hershey-Fonts` 2.1.0 (`pip download Hershey-Fonts==2.1.0`, MIT-licensed
package; its `rowmans` table is the usual public-domain .jhf data).

Usage: PYTHONPATH=<unpacked wheel> tools/hershey-font.py > mill-paths/src/font.rs
"""
from HersheyFonts import HersheyFonts

f = HersheyFonts()
f.load_default_font("rowmans")
data, start, adv = [], [], []
for c in range(32, 127):
    g = list(f.glyphs_for_text(chr(c)))[0]
    left = g._HersheyGlyph__left_side
    right = g._HersheyGlyph__right_side
    start.append(len(data))
    adv.append(right - left)
    prev = None
    for stroke in g._HersheyGlyph__strokes:
        # A stroke that starts where the last one ended continues it: no lift.
        if stroke[0] == prev:
            stroke = [None] + stroke[1:]
        prev = stroke[-1]
        for i, p in enumerate(stroke):
            if p is None:
                continue
            x, y = p
            xx, yy = x - left, 9 - y + 8  # baseline at 8, capitals 21 high
            assert 0 <= xx < 128 and 0 <= yy < 256, (chr(c), xx, yy)
            data += [xx | (0x80 if i == 0 else 0), yy]
start.append(len(data))

def rows(v, per=24):
    return "\n".join("    " + " ".join(f"{b}," for b in v[i:i + per]) for i in range(0, len(v), per))

print(f"""//! CYCLE60's stroke font: the Hershey "Roman simplex" glyphs (A. V. Hershey,
//! U.S. National Bureau of Standards; public domain) for printable ASCII 32..126,
//! written by `tools/hershey-font.py` — do not edit by hand.
//!
//! A glyph is [`GLYPHS`]`[START[i]..START[i + 1]]` for the character `32 + i`: byte
//! pairs `(x, y + 8)` on the font grid (capitals 21 units high on the baseline
//! y = 0, descenders to −7, brackets to 25); bit 7 of `x` starts a new stroke (the
//! pen lifts before it). [`ADVANCE`] is the glyph's width with its side bearings.

/// Grid units from the baseline to the top of the capitals and digits.
pub const CAP: i32 = 21;

/// Offset of each glyph's first byte in [`GLYPHS`] (and the end).
#[rustfmt::skip]
pub static START: [u16; {len(start)}] = [
{rows(start, 16)}
];

/// Width of each glyph with its side bearings, grid units.
#[rustfmt::skip]
pub static ADVANCE: [u8; {len(adv)}] = [
{rows(adv)}
];

/// The strokes of every glyph.
#[rustfmt::skip]
pub static GLYPHS: [u8; {len(data)}] = [
{rows(data)}
];""")
