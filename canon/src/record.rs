//! A sink that records actions into a fixed-capacity buffer (tests, on-target checks).

use super::{Canon, CanonSink, Full};

/// Records up to `N` actions; reports [`Full`] beyond that.
#[derive(Debug, Default)]
pub struct RecordingSink<const N: usize> {
    /// The actions received, in order.
    pub actions: heapless::Vec<Canon, N>,
}

impl<const N: usize> RecordingSink<N> {
    /// An empty recorder.
    pub const fn new() -> Self {
        RecordingSink { actions: heapless::Vec::new() }
    }
}

impl<const N: usize> CanonSink for RecordingSink<N> {
    fn push(&mut self, action: Canon) -> Result<(), Full> {
        self.actions.push(action).map_err(|_| Full)
    }
}
