//! # interval-buffer
//!
//! Per-pixel lists of time intervals: what moving triangles leave in a pixel during the
//! shutter interval, stored either bounded (at most K intervals per pixel, compressed on
//! overflow) or exact (unbounded lists in one flat array).
//!
//! Implements Gribel, Doggett and Akenine-Möller 2010 §5 (the interval of Eq. 16; insertion
//! sorted by ts with the opaque `LESS_EQUAL` optimisations of Fig. 7) and §5.2 (the oracle
//! of Eq. 18-19 with the constants of §6, the merge of Eq. 20, the temporal pixel
//! visualiser), and the exact lists of Rønnow et al. 2021 §4.1-4.2 (count pass, exclusive
//! scan to `u32` offsets, fill, segmented sort by ts). Entry points: [`BoundedBuffer`]
//! (configured by [`Insertion`] and [`Oracle`]; rows in parallel via
//! [`BoundedBuffer::par_rows_mut`]); [`IntervalCounts`] (or [`AtomicIntervalCounts`]) →
//! [`ExactFill`] → [`ExactBuffer`], or [`PixelLists`] (the same lists from one batch of
//! pairs, memory reused from batch to batch); [`CompactInterval`] (Gribel's 12-byte
//! storage form); [`CompressionTrace`] (one pixel's list before and after every insertion). Both buffers
//! hand out per-pixel `&[Interval]` slices sorted by ts for the `resolve` crate.
//!
//! Decisions: Eq. 20's blend weight is read as `len_j / (len_i + len_j)` (the printed
//! numerator `t_j^e - t_i^s` makes it exceed 1; see [`merge_alpha`]). Neither buffer stores
//! Gribel's far-plane background interval (it would take one of the K slots): time not
//! covered by any opaque interval shows the background colour in the resolve. Our extension
//! beyond the paper is the opt-in coverage-preserving merge ([`Oracle::keep_coverage`]): it
//! fixes the paper's fence failure (Fig. 11) and ties on random content but is 1.3-1.8x
//! worse on moving meshes, so the default stays the paper's oracle (figures in the crate's
//! docs/BENCHMARKS.md).
//!
//! ```
//! use interval_buffer::{BoundedBuffer, Insertion, Interval, Rgba};
//! let mut buf = BoundedBuffer::new(4, 4, 2, Insertion::paper(true))?;
//! let red = Rgba::opaque(1.0_f32, 0.0, 0.0);
//! buf.insert(1, 2, Interval::new(0.0, 0.5, 2.0, 0.0, red))?;
//! buf.insert(1, 2, Interval::new(0.6, 0.7, 2.0, 0.0, red))?;
//! buf.insert(1, 2, Interval::new(0.8, 1.0, 2.0, 0.0, red))?; // overflow: two merge
//! assert_eq!(buf.pixel(1, 2).len(), 2);
//! # Ok::<(), interval_buffer::Error>(())
//! ```

mod bounded;
mod compact;
mod error;
mod exact;
mod interval;
mod lists;
mod oracle;
mod payload;
mod pixel;
mod trace;

pub use bounded::{BoundedBuffer, RowMut};
pub use compact::{CompactInterval, CompactInterval8, CompactInterval16, QuantisedTime};
pub use error::Error;
pub use exact::{
    AtomicIntervalCounts, CountRowMut, ExactBuffer, ExactFill, FillRowMut, IntervalCounts,
};
pub use interval::Interval;
pub use lists::PixelLists;
pub use oracle::{Oracle, merge_alpha, merge_eq20};
pub use payload::{Payload, Rgba, Textured};
pub use pixel::{Insertion, PixelMut};
pub use trace::{CompressionTrace, InsertOutcome, MergeStep, TraceEvent};
