//! Engraving a text (CYCLE60, seed 001 lines 9799-10068): the characters of a
//! single-stroke font ([`crate::font`], the public-domain Hershey Roman simplex),
//! scaled to the text height, laid out along a line or on the top or bottom of a
//! circle, each stroke plunged at the depth feed and cut at the surface feed,
//! with a rapid retract to the safety plane between strokes.
//!
//! # Layout
//! A character's box is its strokes' extent along the text (the tool-centre path;
//! a space is its advance). `gap` is the distance between neighbouring boxes
//! (on a circle an arc length at the reference radius). The text runs from
//! `s = 0` (left edge of the first box) to its length `L`; the reference point is
//! at `s = 0`, `L/2` or `L` (left, centre, right) and at the height 0, H/2 or H
//! above the baseline (bottom, middle, top; H the capitals' height).
//! - On a line the text runs at `sta` degrees through the reference point.
//! - On the top of a circle it reads clockwise, the letters' tops outwards; on the
//!   bottom counterclockwise, the tops towards the centre. The reference point's
//!   distance from the centre is the radius; each character is placed upright
//!   (not bent) with its box centre at its arc position.

use crate::font::{ADVANCE, CAP, GLYPHS, START};
use crate::{CycleAlarm, Move, P3};
use core::f64::consts::PI;

/// Most characters a text may have (line 9805).
pub const TEXT_MAX: usize = 91;

/// Where the text runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    /// Along a straight line.
    Line,
    /// On the top of a circle (reads clockwise).
    Top,
    /// On the bottom of a circle (reads counterclockwise).
    Bottom,
}

/// What `df` gives (`_VARI` hundred-thousands).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Width {
    /// The distance between characters, nm.
    Spacing,
    /// The text's total width, nm (on a line).
    Total,
    /// The angle between the first and the last character's centre lines, degrees
    /// (on a circle; 360 spreads the characters evenly round it).
    Angle,
}

/// An engraving, as the front end read it (plane coordinates, nm).
#[derive(Clone, Copy, Debug)]
pub struct EngraveSpec<'t> {
    /// The characters (printable ASCII).
    pub text: &'t [u8],
    /// Where the text runs.
    pub path: Path,
    /// The reference point (abscissa, ordinate).
    pub reference: (i64, i64),
    /// The circle's centre (on a circle).
    pub centre: (i64, i64),
    /// The line's angle to the abscissa, degrees (on a line).
    pub sta: f64,
    /// Height of the capitals and digits (tool-centre path), nm.
    pub height: i64,
    /// Spacing, total width (nm) or opening angle (degrees), per `width`.
    pub df: f64,
    /// What `df` gives.
    pub width: Width,
    /// Reference point along the text: 0 left, 1 centre, 2 right.
    pub h_align: u8,
    /// Reference point across the text: 0 baseline, 1 middle, 2 top of the capitals.
    pub v_align: u8,
    /// Retract plane, the safety plane (RFP + SDIS) and the depth, along the applicate.
    pub rtp: i64,
    /// The safety plane.
    pub safe: i64,
    /// The engraving depth.
    pub bottom: i64,
    /// Depth feed (plunges) and surface feed (strokes).
    pub feeds: [i64; 2],
}

/// The generator of one engraving.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Engrave {
    text: [u8; TEXT_MAX],
    n: u8,
    path: Path,
    /// Line: the reference point; circle: the centre.
    org: (f64, f64),
    /// Line: the text direction; circle: unused.
    dir: (f64, f64),
    /// Circle: the radius and the reference point's angle (rad).
    r: f64,
    th0: f64,
    /// nm per font grid unit.
    k: f64,
    gap: f64,
    /// Baseline's offset below the reference point, nm.
    v: f64,
    /// Left edge of the current character's box, nm from the reference point.
    s: f64,
    rtp: i64,
    safe: i64,
    bottom: i64,
    feeds: [i64; 2],
    // The cursor: character, next glyph byte, its end, the character's frame.
    ci: u8,
    pi: u16,
    end: u16,
    /// The accent's strokes still to cut (in [`ACCENTS`]) and its anchor on the grid.
    ai: u8,
    aend: u8,
    anchor: (i32, i32),
    xmin: i32,
    o: (f64, f64),
    a: (f64, f64),
    b: (f64, f64),
    stage: u8,
    down: bool,
    started: bool,
    last: P3,
}

/// Code page 1252's accented letters 0xC0-0xFF as an ASCII letter and an accent
/// ([`ACCENT_AT`]'s 1-7); `.` is a letter the font cannot make (61179), × is x.
const LATIN_BASE: &[u8; 64] = b"AAAAAA.CEEEEIIII.NOOOOOx.UUUUY..aaaaaa.ceeeeiiii.nooooo..uuuuy.y";
const LATIN_ACCENT: &[u8; 64] = b"1234560712351235041234500123520012345607123512350412345001235205";

/// The accents' strokes, as the glyphs' (`x` + 8, `y` + 8 about the accent's anchor:
/// the middle of the letter's box, 2 units above its capitals or its x-height 14, the
/// baseline for the cedilla): grave, acute, circumflex, tilde, diaeresis, ring,
/// cedilla, caron (drawn here, not Hershey's).
#[rustfmt::skip]
static ACCENTS: [u8; 52] = [
    0x86, 11, 9, 8,
    0x87, 8, 10, 11,
    0x85, 8, 8, 11, 11, 8,
    0x85, 9, 7, 11, 9, 9, 11, 11,
    0x86, 8, 6, 9, 0x8a, 8, 10, 9,
    0x88, 8, 6, 10, 8, 12, 10, 10, 8, 8,
    0x88, 8, 9, 6, 7, 4,
    0x85, 11, 8, 8, 11, 11,
];

/// Where each accent's strokes start in [`ACCENTS`] (accent `i` is `[i - 1]..[i]`).
const ACCENT_AT: [u8; 9] = [0, 4, 8, 14, 22, 30, 40, 46, 52];

/// The letter and the accent (0: none) character `c` is made of (`c` printable
/// ASCII, or code page 1252 0xC0-0xFF), or 61179.
fn parts(c: u8) -> Result<(u8, u8), CycleAlarm> {
    let (b, a) = match c {
        32..=126 => (c, b'0'),
        0xc0.. => (LATIN_BASE[usize::from(c - 0xc0)], LATIN_ACCENT[usize::from(c - 0xc0)]),
        0x8a => (b'S', b'8'),
        0x9a => (b's', b'8'),
        0x8e => (b'Z', b'8'),
        0x9e => (b'z', b'8'),
        0x9f => (b'Y', b'5'),
        _ => (b'.', b'0'),
    };
    if b == b'.' && c != b'.' {
        return Err(CycleAlarm::CharacterMissing);
    }
    Ok((b, a - b'0'))
}

/// The glyph of ASCII `c` (its range in [`GLYPHS`]), or 61179 when the font lacks it.
fn glyph(c: u8) -> Result<(usize, usize), CycleAlarm> {
    let i = usize::from(c.wrapping_sub(32));
    match (START.get(i), START.get(i + 1)) {
        (Some(&a), Some(&b)) => Ok((usize::from(a), usize::from(b))),
        _ => Err(CycleAlarm::CharacterMissing),
    }
}

/// The box of `c` (its letter's): its left edge on the grid and its width in grid units.
fn extent(c: u8) -> (i32, i32) {
    let c = parts(c).map_or(b' ', |p| p.0);
    let Ok((a, b)) = glyph(c) else { return (0, 0) };
    let (mut lo, mut hi) = (i32::MAX, i32::MIN);
    for x in GLYPHS.get(a..b).unwrap_or(&[]).iter().step_by(2) {
        let x = i32::from(x & 0x7f);
        (lo, hi) = (lo.min(x), hi.max(x));
    }
    if lo > hi {
        // No strokes (a space): its advance.
        return (0, i32::from(ADVANCE.get(usize::from(c.wrapping_sub(32))).copied().unwrap_or(0)));
    }
    (lo, hi - lo)
}

impl Engrave {
    /// The engraving of `s`, or its alarm: 61179 a character the font lacks (or
    /// more than [`TEXT_MAX`]), 61176 characters that do not fit the total width,
    /// the opening angle or the circle.
    pub fn new(s: &EngraveSpec<'_>) -> Result<Self, CycleAlarm> {
        // The program's text: UTF-8 (U+00C0-U+00FF and Š š Ž ž Ÿ as two bytes) or
        // code page 1252.
        let mut text = [0u8; TEXT_MAX];
        let (mut i, mut n) = (0, 0);
        while let Some(&b) = s.text.get(i) {
            let c = match (b, s.text.get(i + 1)) {
                (0xc2 | 0xc3, Some(&t)) if t & 0xc0 == 0x80 => {
                    i += 1;
                    (b & 3) << 6 | (t & 0x3f)
                }
                (0xc5, Some(&t)) if matches!(t, 0xa0 | 0xa1 | 0xb8 | 0xbd | 0xbe) => {
                    i += 1;
                    match t {
                        0xa0 => 0x8a,
                        0xa1 => 0x9a,
                        0xb8 => 0x9f,
                        0xbd => 0x8e,
                        _ => 0x9e,
                    }
                }
                // A quote written in single quotes ('"', '''; lines 9990-10000).
                (b'\'', Some(&q @ (b'"' | b'\''))) if s.text.get(i + 2) == Some(&b'\'') => {
                    i += 2;
                    q
                }
                _ => b,
            };
            i += 1;
            parts(c)?;
            *text.get_mut(n).ok_or(CycleAlarm::CharacterMissing)? = c;
            n += 1;
        }
        let k = s.height as f64 / f64::from(CAP);
        let mut sum = 0.0;
        for &c in &text[..n] {
            sum += f64::from(extent(c).1) * k;
        }
        let (first, last) = match (text[..n].first(), text[..n].last()) {
            (Some(&f), Some(&l)) => (f64::from(extent(f).1) * k, f64::from(extent(l).1) * k),
            _ => (0.0, 0.0),
        };
        let (ra, ro) = (s.reference.0 as f64, s.reference.1 as f64);
        let (ca, co) = (s.centre.0 as f64, s.centre.1 as f64);
        let r = libm::hypot(ra - ca, ro - co);
        let gaps = n.saturating_sub(1).max(1) as f64;
        let gap = match s.width {
            Width::Spacing => s.df,
            Width::Total => (s.df - sum) / gaps,
            // The full circle: as many gaps as characters.
            Width::Angle if s.df >= 360.0 => (2.0 * PI * r - sum) / n.max(1) as f64,
            Width::Angle => (s.df * PI / 180.0 * r - sum + (first + last) / 2.0) / gaps,
        };
        let len = sum + gap * n.saturating_sub(1) as f64;
        if gap.is_nan() || gap < 0.0 || (s.path != Path::Line && len > 2.0 * PI * r) {
            return Err(CycleAlarm::TextLengthTooSmall);
        }
        let h = s.height as f64;
        let (sn, cs) = libm::sincos(s.sta * PI / 180.0);
        let line = s.path == Path::Line;
        let mut e = Engrave {
            text,
            n: n as u8,
            path: s.path,
            org: if line { (ra, ro) } else { (ca, co) },
            dir: (cs, sn),
            r,
            th0: libm::atan2(ro - co, ra - ca),
            k,
            gap,
            v: h * f64::from(s.v_align.min(2)) / 2.0,
            s: -len * f64::from(s.h_align.min(2)) / 2.0,
            rtp: s.rtp,
            safe: s.safe,
            bottom: s.bottom,
            feeds: s.feeds,
            ci: 0,
            pi: 0,
            end: 0,
            ai: 0,
            aend: 0,
            anchor: (0, 0),
            xmin: 0,
            o: (0.0, 0.0),
            a: (0.0, 0.0),
            b: (0.0, 0.0),
            stage: 0,
            down: false,
            started: false,
            last: P3::default(),
        };
        e.frame();
        Ok(e)
    }

    /// Sets the cursor on character `ci` (its strokes and its frame).
    fn frame(&mut self) {
        let c = self.text.get(usize::from(self.ci)).copied().unwrap_or(b' ');
        let (letter, accent) = parts(c).unwrap_or((b' ', 0));
        let (a, b) = glyph(letter).unwrap_or((0, 0));
        (self.pi, self.end) = (a as u16, b as u16);
        let i = usize::from(accent);
        (self.ai, self.aend) = match (ACCENT_AT.get(i.wrapping_sub(1)), ACCENT_AT.get(i)) {
            (Some(&a), Some(&b)) if accent > 0 => (a, b),
            _ => (0, 0),
        };
        let (xmin, w) = extent(c);
        let top = if accent == 7 {
            0
        } else if letter.is_ascii_uppercase() {
            23
        } else {
            16
        };
        self.anchor = (xmin + w / 2, top);
        self.xmin = xmin;
        let w = f64::from(w) * self.k;
        let (oa, oo) = self.org;
        (self.o, self.a) = match self.path {
            Path::Line => ((oa + self.s * self.dir.0, oo + self.s * self.dir.1), self.dir),
            Path::Top | Path::Bottom => {
                let top = self.path == Path::Top;
                let arc = (self.s + w / 2.0) / self.r;
                let phi = if top { self.th0 - arc } else { self.th0 + arc };
                let (sn, cs) = libm::sincos(phi);
                let a = if top { (sn, -cs) } else { (-sn, cs) };
                ((oa + self.r * cs - w / 2.0 * a.0, oo + self.r * sn - w / 2.0 * a.1), a)
            }
        };
        // Up: the text direction turned a quarter counterclockwise.
        self.b = (-self.a.1, self.a.0);
    }

    /// The current character's next stroke point on the grid and whether it
    /// starts a stroke: its letter's, then its accent's.
    fn peek(&self) -> Option<(i32, i32, bool)> {
        let (data, i, d): (&[u8], usize, (i32, i32)) = if self.pi < self.end {
            (&GLYPHS, usize::from(self.pi), (0, 0))
        } else if self.ai < self.aend {
            (&ACCENTS, usize::from(self.ai), (self.anchor.0 - 8, self.anchor.1))
        } else {
            return None;
        };
        let (x, y) = (data.get(i).copied().unwrap_or(0), data.get(i + 1).copied().unwrap_or(8));
        Some((i32::from(x & 0x7f) + d.0, i32::from(y) - 8 + d.1, x & 0x80 != 0))
    }

    /// Grid point (`x`, `y`) of the current character, in the plane.
    fn point(&self, x: i32, y: i32) -> P3 {
        let du = f64::from(x - self.xmin) * self.k;
        let w = f64::from(y) * self.k - self.v;
        let a = self.o.0 + du * self.a.0 + w * self.b.0;
        let o = self.o.1 + du * self.a.1 + w * self.b.1;
        P3::new(libm::round(a) as i64, libm::round(o) as i64, self.bottom)
    }
}

impl Iterator for Engrave {
    type Item = Move;

    /// The next move.
    fn next(&mut self) -> Option<Move> {
        loop {
            match self.stage {
                1 => {
                    self.stage = 2;
                    return Some(Move::Rapid(self.last.at(self.safe)));
                }
                2 => {
                    (self.stage, self.down) = (0, true);
                    return Some(Move::Line { to: self.last, feed: self.feeds[0] });
                }
                3 => return None,
                _ => {}
            }
            let Some((x, y, new)) = self.peek() else {
                if self.ci >= self.n {
                    if self.down {
                        self.down = false;
                        return Some(Move::Rapid(self.last.at(self.safe)));
                    }
                    self.stage = 3;
                    return self.started.then_some(Move::Rapid(self.last.at(self.rtp)));
                }
                let c = self.text.get(usize::from(self.ci)).copied().unwrap_or(b' ');
                self.s += f64::from(extent(c).1) * self.k + self.gap;
                self.ci += 1;
                if self.ci < self.n {
                    self.frame();
                }
                continue;
            };
            if new && self.down {
                // The pen lifts: back to the safety plane.
                self.down = false;
                return Some(Move::Rapid(self.last.at(self.safe)));
            }
            if self.pi < self.end {
                self.pi += 2;
            } else {
                self.ai += 2;
            }
            let p = self.point(x, y);
            self.last = p;
            if !new {
                return Some(Move::Line { to: p, feed: self.feeds[1] });
            }
            if !self.started {
                self.started = true;
                self.stage = 1;
                return Some(Move::Rapid(p.at(self.rtp)));
            }
            self.stage = 2;
            return Some(Move::Rapid(p.at(self.safe)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn spec(text: &[u8]) -> EngraveSpec<'_> {
        EngraveSpec {
            text,
            path: Path::Line,
            reference: (10_000_000, 25_000_000),
            centre: (0, 0),
            sta: 0.0,
            height: 21_000_000,
            df: 5_000_000.0,
            width: Width::Spacing,
            h_align: 0,
            v_align: 0,
            rtp: 100_000_000,
            safe: 1_000_000,
            bottom: -1_500_000,
            feeds: [2500, 2000],
        }
    }

    fn all(s: &EngraveSpec<'_>) -> Vec<Move> {
        let mut e = Engrave::new(s).unwrap();
        core::iter::from_fn(|| e.next()).collect()
    }

    /// "L" (two strokes joined: the stem down, the foot right) at 1 mm per unit:
    /// the Hershey L is (4,21)-(4,0)-(16,0) on the grid; its box starts at x 4.
    #[test]
    fn the_letter_l_is_its_grid_scaled() {
        let m = all(&spec(b"L"));
        let (x, y) = (10_000_000, 25_000_000);
        assert_eq!(
            m,
            [
                Move::Rapid(P3::new(x, y + 21_000_000, 100_000_000)),
                Move::Rapid(P3::new(x, y + 21_000_000, 1_000_000)),
                Move::Line { to: P3::new(x, y + 21_000_000, -1_500_000), feed: 2500 },
                Move::Line { to: P3::new(x, y, -1_500_000), feed: 2000 },
                Move::Line { to: P3::new(x + 12_000_000, y, -1_500_000), feed: 2000 },
                Move::Rapid(P3::new(x + 12_000_000, y, 1_000_000)),
                Move::Rapid(P3::new(x + 12_000_000, y, 100_000_000)),
            ]
        );
        assert!(all(&spec(b"")).is_empty());
    }

    /// "É" (UTF-8, or code page 1252's 0xC9) is "E" and an acute: (-1,0)-(2,3)
    /// about the middle of E's box (x 4..17: 10) 2 above the capitals (23).
    #[test]
    fn an_accented_letter_is_its_letter_and_the_accent() {
        let e = all(&spec(b"E"));
        let ea = all(&spec(b"\xc3\x89"));
        assert_eq!(ea, all(&spec(b"\xc9")));
        // A quote in single quotes is the quote.
        assert_eq!(all(&spec(b"'\"'")), all(&spec(b"\"")));
        assert_eq!(all(&spec(b"'''")), all(&spec(b"'")));
        // Š in UTF-8 is code page 1252's 0x8A: S and a caron.
        assert_eq!(all(&spec("\u{160}".as_bytes())), all(&spec(b"\x8a")));
        assert!(all(&spec(b"\x8a")).len() > all(&spec(b"S")).len());
        // E's moves up to its last retract, then the accent's stroke.
        assert_eq!(ea[..e.len() - 1], e[..e.len() - 1]);
        let at = |x: i64, y: i64, d: i64| P3::new(10_000_000 + (x - 4) * 1_000_000, 25_000_000 + y * 1_000_000, d);
        assert_eq!(
            ea[e.len() - 1..],
            [
                Move::Rapid(at(9, 23, 1_000_000)),
                Move::Line { to: at(9, 23, -1_500_000), feed: 2500 },
                Move::Line { to: at(12, 26, -1_500_000), feed: 2000 },
                Move::Rapid(at(12, 26, 1_000_000)),
                Move::Rapid(at(12, 26, 100_000_000)),
            ]
        );
    }

    #[test]
    fn alarms() {
        for t in [&b"A\xe6"[..], b"\xc3\xa6", b"\x7f", b"\x1f", b"\xb0"] {
            assert_eq!(Engrave::new(&spec(t)).err(), Some(CycleAlarm::CharacterMissing), "{t:?}");
        }
        assert_eq!(Engrave::new(&spec(&[b'A'; 92])).err(), Some(CycleAlarm::CharacterMissing));
        let mut s = spec(b"LL");
        (s.width, s.df) = (Width::Total, 23_000_000.0);
        assert_eq!(Engrave::new(&s).err(), Some(CycleAlarm::TextLengthTooSmall));
        s.df = 24_000_000.0;
        assert!(Engrave::new(&s).is_ok());
    }
}
