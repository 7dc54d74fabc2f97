//! The tool paths of the milling cycles, in the working plane: what a pocket, a
//! slot, a spigot, a face or a contour is cut with, pass by pass, as a sequence of
//! [`Move`]s. Pure geometry — no language, no machine state: a front end (the
//! SINUMERIK cycles in `interp-siemens`) reads and checks the cycle's parameters
//! and builds a generator ([`MillGen`]); the shared engine (`interp-core`'s
//! `cycles::mill`) maps each move onto the plane's axes and emits it, through the
//! same emitter, dry run, soft limits and motion core as every other cycle.
//!
//! # Coordinates
//! A point is a [`P3`]: abscissa `a`, ordinate `o` of the active plane and the
//! applicate `d` (the infeed axis: G17 X/Y/Z, G18 Z/X/Y, G19 Y/Z/X; seed 001
//! lines 526-543, 3486-3494), work coordinates in nm. Arcs are in the plane and
//! may move the applicate (a helix). Angles are degrees, counterclockwise seen
//! from the applicate's plus side.
//!
//! # Generators
//! A generator is a small state machine that yields one move at a time
//! ([`MillGen::next`]): a pocket of many levels and rings is never materialised
//! (the interpreter's outbox holds 16 actions and the board has 128 KB of RAM).
//! Generators are pure functions of their inputs — the engine runs each one twice,
//! a dry run that raises every alarm (soft limits of every pass) before the first
//! move, then the real run — so `next` must yield the same moves both times. A
//! generator's state is copied into the interpreter's expansion and its dry run:
//! keep it small ([`MillGen`]'s size is bounded by a test).
//!
//! # Size
//! This crate is built at opt-level "z" for the board (firmware/.cargo/config.toml,
//! m4-tests/Cargo.toml): the milling cycles run once per cycle call, not per block.
//! Use f64 (libm) for per-pass geometry, i64 nm for every point handed out.
#![no_std]

pub mod contour;
#[cfg(feature = "contour")]
pub mod contour_mill;
#[cfg(feature = "engrave")]
pub mod engrave;
#[cfg(feature = "face")]
pub mod face;
#[cfg(feature = "engrave")]
pub mod font;
pub mod infeed;
#[cfg(feature = "island")]
pub mod island;
pub mod plan;
pub mod pocket;
pub mod rot;
#[cfg(feature = "slot")]
pub mod slot;
#[cfg(feature = "face")]
pub mod spigot;
pub mod thread;
#[cfg(any(feature = "contour", feature = "island"))]
mod v2;

pub use canon::alarm::CycleAlarm;
pub use contour::{Contour, Elem, NoContour};

/// A point: abscissa, ordinate (the plane) and applicate (the infeed axis), work
/// coordinates in nm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct P3 {
    /// Abscissa (1st axis of the plane: X in G17).
    pub a: i64,
    /// Ordinate (2nd axis of the plane: Y in G17).
    pub o: i64,
    /// Applicate (the infeed axis: Z in G17).
    pub d: i64,
}

impl P3 {
    /// A point.
    pub const fn new(a: i64, o: i64, d: i64) -> Self {
        P3 { a, o, d }
    }

    /// The same point in the plane at applicate `d`.
    pub const fn at(self, d: i64) -> Self {
        P3 { d, ..self }
    }
}

/// One move of a milling cycle (the engine maps it onto the plane's axes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Move {
    /// Rapid (G0) to a point.
    Rapid(P3),
    /// Straight cutting move (G1) to a point at `feed` (nm/min, or nm/rev under
    /// G95: the cycle's feed words are in the feed mode in force).
    Line {
        /// End point.
        to: P3,
        /// Feed.
        feed: i64,
    },
    /// Arc in the plane (G2 clockwise / G3 counterclockwise seen from the
    /// applicate's plus side) to `to` about `centre`; a change of applicate makes
    /// it a helix. A full circle (end = start in the plane) is one turn.
    Arc {
        /// End point.
        to: P3,
        /// Centre in the plane (abscissa, ordinate).
        centre: (i64, i64),
        /// G2.
        cw: bool,
        /// Feed.
        feed: i64,
    },
    /// Dwell, ms.
    Dwell(u32),
    /// Spindle speed from here on, rev/min (the finishing speed SSF).
    Speed(u32),
}

/// The generator of one milling cycle call. One variant per path family; each
/// lives in its own module and yields its moves through [`MillGen::next`]. Every
/// generator is `Copy`: the engine copies it into the dry run, and a copy is one
/// `memcpy` where a derived `Clone` is code per variant.
// The variants differ in size (a plan holds its moves); a box would cost `Copy`,
// and `generator_size_is_bounded` keeps the whole small.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MillGen {
    /// A fixed handful of moves ([`plan::Plan`]).
    Plan(plan::Plan),
    /// A rectangular or circular pocket ([`pocket::Pocket`]: POCKET1 to POCKET4).
    Pocket(pocket::Pocket),
    /// A thread milled on a helix ([`thread::Thread`]: CYCLE90).
    Thread(thread::Thread),
    /// A face ([`face::Face`]: CYCLE71).
    #[cfg(feature = "face")]
    Face(face::Face),
    /// A rectangular or circular spigot ([`spigot::Spigot`]: CYCLE76, CYCLE77).
    #[cfg(feature = "face")]
    Spigot(spigot::Spigot),
    /// Slots on a circle ([`slot::Slots`]: LONGHOLE, SLOT1, SLOT2).
    #[cfg(feature = "slot")]
    Slots(slot::Slots),
    /// A text engraved stroke by stroke ([`engrave::Engrave`]: CYCLE60).
    #[cfg(feature = "engrave")]
    Engrave(engrave::Engrave),
    /// Along a programmed contour ([`contour_mill::ContourMill`]: CYCLE72).
    #[cfg(feature = "contour")]
    Contour(contour_mill::ContourMill),
}

impl MillGen {
    /// The next move, `None` when the cycle is done. `contour` is the contour the
    /// cycle was called with (CYCLE72, CYCLE73's pocket and islands), read from
    /// the interpreter's shape store; [`NoContour`] for the others. An alarm here
    /// (a geometry only found while the passes are laid out) is raised in the dry
    /// run, before anything moves.
    #[inline(never)]
    pub fn next(&mut self, contour: &dyn Contour) -> Result<Option<Move>, CycleAlarm> {
        let _ = contour;
        match self {
            MillGen::Plan(p) => Ok(p.next()),
            MillGen::Pocket(p) => Ok(p.next()),
            MillGen::Thread(t) => Ok(t.next()),
            #[cfg(feature = "face")]
            MillGen::Face(p) => Ok(p.next()),
            #[cfg(feature = "face")]
            MillGen::Spigot(p) => Ok(p.next()),
            #[cfg(feature = "slot")]
            MillGen::Slots(p) => Ok(p.next()),
            #[cfg(feature = "engrave")]
            MillGen::Engrave(p) => Ok(p.next()),
            #[cfg(feature = "contour")]
            MillGen::Contour(p) => p.next(contour),
        }
    }
}

/// Where a move ends (`None`: it does not move).
pub(crate) fn end_of(m: &Move) -> Option<P3> {
    match m {
        Move::Rapid(p) | Move::Line { to: p, .. } | Move::Arc { to: p, .. } => Some(*p),
        _ => None,
    }
}

/// `m`, unless it ends where the path already is (`last`, then moved on to its
/// end): the generators leave moves of zero length out.
#[cfg(any(feature = "face", feature = "slot"))]
pub(crate) fn moved(last: &mut P3, m: Move) -> Option<Move> {
    match end_of(&m) {
        Some(to) if to == *last => None,
        Some(to) => {
            *last = to;
            Some(m)
        }
        None => Some(m),
    }
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
mod tests {
    use super::*;

    /// A generator is copied into the interpreter's expansion and its dry run, on a
    /// board with 96 KB of static RAM: keep it small.
    #[test]
    fn generator_size_is_bounded() {
        let n = core::mem::size_of::<MillGen>();
        assert!(n <= 512, "MillGen is {n} bytes");
    }
}
