//! # tmsnet
//!
//! A time-ordered (0,m,3)-net sampler for stochastic motion-blur rasterisation, after
//! Munkberg, Clarberg, Hasselgren, Toth, Sugihara and Akenine-Möller 2011, "Hierarchical
//! Stochastic Motion Blur Rasterization", §5 and Appendix A. Point j of 2^m has time
//! `t = j / 2^m` and spatial coordinates from the permuted generator matrices C'_1, C'_2
//! (Eq. 12, 17, 19), which reorder the Grünschloß-Keller net (Eq. 13-14) so that it is
//! sorted in time while its spatial projection stays the Larcher-Pillichshammer points.
//! Because the points are sorted in time, the samples of a tile in a time interval
//! `[t0, t1]` are one contiguous index range, found in O(1) and enumerated with one XOR per
//! coordinate per sample. Per-tile random digit scrambling (XOR with hashed bit vectors)
//! keeps the net property and is stable from frame to frame.
//!
//! Entry points:
//! - [`get_xy()`] / [`get_xy_unchecked`]: the paper's GetXY bit-twiddling generator
//!   (branch-free; [`get_xy_paper_loop`] is the verbatim loop).
//! - [`TileLayout`] + [`TileSampler::samples_in`]: a W x H tile at S samples per pixel, the
//!   samples in a time range with pixel, sub-pixel offset and time, in one iterator.
//! - [`time_index_range`]: the index range of the samples in `[t0, t1]`.
//! - [`BitMatrix`], [`DigitalNet`], [`TimeOrderedNet`]: general digital nets from explicit
//!   generator matrices, with both the original and the permuted construction
//!   ([`generators`]) and the rank criterion for the net property.
//! - [`Scramble`]: random digit scrambling from a tile hash.
//! - [`quality`]: exhaustive net-property check, exact 2D star discrepancy, minimum distance.
//!
//! ```
//! use tmsnet::{TileLayout, TileSampler};
//! // 4x4 pixels at 16 spp (m = 8), tile (10, 3), seed 1: samples with t in [0.5, 0.75].
//! let tile = TileSampler::new(TileLayout::new(4, 4, 16)?, 10, 3, 1)?;
//! for s in tile.samples_in(0.5f32, 0.75)? {
//!     let [px, py] = s.pixel; // pixel within the tile
//!     let [ox, oy] = s.offset; // sub-pixel offset in [0, 1)
//!     assert!(px < 4 && py < 4 && ox < 1.0 && oy < 1.0 && (0.5..=0.75).contains(&s.t));
//! }
//! # Ok::<(), tmsnet::Error>(())
//! ```

mod error;
mod get_xy;
mod matrix;
mod net;
mod ordered;
mod scramble;
mod tile;
mod time_range;

pub mod generators;
pub mod quality;

pub use error::Error;
pub use get_xy::{get_xy, get_xy_paper_loop, get_xy_unchecked};
pub use matrix::{BitMatrix, binomial_mod2};
pub use net::DigitalNet;
pub use ordered::{TimeOrderedNet, XyIter};
pub use scramble::{Scramble, mix64, tile_hash};
pub use tile::{SubPixel, TileLayout, TileSample, TileSampler, TileSamples};
pub use time_range::{sample_time, time_index_range};

/// The largest supported net size exponent: 2^31 points with 31-bit coordinates.
pub const MAX_M: u32 = 31;
