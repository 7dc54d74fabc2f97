//! A contour the cycle was called with (CYCLE72's contour, CYCLE73's pocket edge
//! and islands): its elements in the plane, read from the interpreter's shape
//! store through [`Contour`] (the engine keeps it once; generators only index it).

/// One element of a contour in the plane (abscissa, ordinate), nm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Elem {
    /// Start point.
    pub from: (i64, i64),
    /// End point.
    pub to: (i64, i64),
    /// An arc: its centre and whether it runs clockwise (G2); `None` for a line.
    pub arc: Option<((i64, i64), bool)>,
}

/// The contour store as a generator reads it.
pub trait Contour {
    /// Number of elements.
    fn len(&self) -> usize;
    /// Element `i` (`i < len()`).
    fn elem(&self, i: usize) -> Elem;
    /// No elements.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The contour of a cycle that has none.
pub struct NoContour;

impl Contour for NoContour {
    fn len(&self) -> usize {
        0
    }
    fn elem(&self, _: usize) -> Elem {
        Elem { from: (0, 0), to: (0, 0), arc: None }
    }
}

impl Contour for [Elem] {
    fn len(&self) -> usize {
        <[Elem]>::len(self)
    }
    fn elem(&self, i: usize) -> Elem {
        self[i]
    }
}
