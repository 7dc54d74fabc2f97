//! A fixed handful of moves, yielded in order: the simplest generator (a short
//! positioning or a cycle of a few moves).

use crate::Move;

/// Most moves a [`Plan`] holds.
pub const PLAN_MAX: usize = 8;

/// Moves yielded in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    moves: [Move; PLAN_MAX],
    len: u8,
    next: u8,
}

impl Plan {
    /// A plan of `moves`; `None` if more than [`PLAN_MAX`].
    pub fn new(moves: &[Move]) -> Option<Self> {
        let mut p = Plan { moves: [Move::Dwell(0); PLAN_MAX], len: 0, next: 0 };
        p.moves.get_mut(..moves.len())?.copy_from_slice(moves);
        p.len = moves.len() as u8;
        Some(p)
    }
}

impl Iterator for Plan {
    type Item = Move;

    /// The next move.
    fn next(&mut self) -> Option<Move> {
        if self.next >= self.len {
            return None;
        }
        let m = self.moves.get(usize::from(self.next)).copied();
        self.next += 1;
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::P3;

    #[test]
    fn a_plan_yields_its_moves_in_order() {
        let a = Move::Rapid(P3::new(1, 2, 3));
        let b = Move::Dwell(500);
        let mut p = Plan::new(&[a, b]).unwrap();
        assert_eq!((p.next(), p.next(), p.next()), (Some(a), Some(b), None));
        assert!(Plan::new(&[b; PLAN_MAX + 1]).is_none());
    }
}
