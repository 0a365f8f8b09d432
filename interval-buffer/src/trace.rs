//! Temporal pixel visualiser data: one pixel's interval list before and after each insertion
//! and compression step (Gribel 2010 §5.2.1, "temporal pixel visualizer").

use crate::Interval;

/// What one insertion did to a pixel's list.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InsertOutcome<F> {
    /// Whether the new interval (possibly clipped, possibly merged) entered the list.
    /// `false` when the opaque optimisations dropped it as fully occluded or empty.
    pub stored: bool,
    /// Whether the new interval was clipped in time because an opaque interval occluded
    /// one end of it (Gribel 2010, Fig. 7, second from bottom).
    pub clipped: bool,
    /// How many existing intervals the new opaque interval fully occluded and removed.
    pub removed: usize,
    /// The compression step taken on overflow, if any.
    pub merged: Option<MergeStep<F>>,
}

/// One compression step: the pair merged and its oracle value (Gribel 2010, Eq. 19-20).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MergeStep<F> {
    /// Index of the first interval of the merged pair, in the list of capacity + 1
    /// intervals (the full list with the new interval inserted in ts order).
    pub i: usize,
    /// Index of the second interval (`i < j <= i + window`) in the same list.
    pub j: usize,
    /// The oracle value `O(Δi, Δj)` of the pair (with the tandem term when enabled).
    pub cost: F,
}

/// One recorded insertion into the traced pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceEvent<F, P> {
    /// The interval as the caller inserted it.
    pub inserted: Interval<F, P>,
    /// The pixel's list before the insertion, sorted by ts.
    pub before: Vec<Interval<F, P>>,
    /// The pixel's list after the insertion (and compression), sorted by ts.
    pub after: Vec<Interval<F, P>>,
    /// What the insertion did.
    pub outcome: InsertOutcome<F>,
}

/// The history of one pixel: every insertion, with the list before and after.
///
/// Requested from a buffer for one pixel index; the renderer can draw each event as a
/// time/depth plot (Gribel 2010 built such a visualiser to design the oracle).
#[derive(Clone, Debug, PartialEq)]
pub struct CompressionTrace<F, P> {
    /// The traced pixel's index, `y * width + x`.
    pub pixel: usize,
    /// Every insertion into the pixel, in order.
    pub events: Vec<TraceEvent<F, P>>,
}

impl<F, P> CompressionTrace<F, P> {
    /// An empty trace for pixel index `pixel`.
    pub fn new(pixel: usize) -> Self {
        CompressionTrace {
            pixel,
            events: Vec::new(),
        }
    }

    /// The events that compressed the list (a merge on overflow).
    pub fn compression_steps(&self) -> impl Iterator<Item = &TraceEvent<F, P>> {
        self.events.iter().filter(|e| e.outcome.merged.is_some())
    }
}
