//! # interval-buffer
//!
//! Per-pixel lists of time intervals: what a moving triangle leaves in a pixel.
//!
//! Implements Gribel, Doggett and Akenine-Möller 2010 §5 (the interval of Eq. 16, insertion
//! with the opaque `LESS_EQUAL` optimisations of Fig. 7) and §5.2 (oracle compression, Eq.
//! 18-20), and the exact unbounded lists of Rønnow et al. 2021 §4.1-4.2 (count pass,
//! exclusive scan, fill, segmented sort).
//!
//! **Status: partly implemented.** The [`Interval`] type and the [`Payload`] trait that the
//! `resolve` crate consumes are here; the bounded and exact buffers and the oracle are built
//! by issue 6.
//!
//! ```
//! use interval_buffer::{Interval, Rgba};
//! let iv = Interval::new(0.25_f64, 0.75, 2.0, -1.0, Rgba::new(1.0, 0.0, 0.0, 1.0));
//! assert_eq!(iv.depth_at(0.5), 1.75);
//! assert_eq!(iv.end_depth(), 1.5);
//! ```

mod interval;
mod payload;

pub use interval::Interval;
pub use payload::{Payload, Rgba, Textured};
