//! # raster-hier
//!
//! Hierarchical stochastic motion-blur rasterisation with tile temporal bounds, after
//! Munkberg, Clarberg, Hasselgren, Toth, Sugihara and Akenine-Möller 2011, "Hierarchical
//! Stochastic Motion Blur Rasterization", §3-§4 and §7. A frame of linearly moving 2DH
//! triangles (edge-eqn's [`MovingTriangle`]) is culled per triangle — temporal view-frustum
//! culling from the vertex lines vs the frustum planes ([`frustum_interval`]) and
//! conservative motion back-face culling from the Bernstein form of the orientation cubic
//! ([`facing`]; [`facing_windows`] gives the times a triangle may face the camera, for
//! clipping instead of whole-shutter culling) — bounded on screen ([`screen_bound`]: six projected vertices, or the whole
//! screen when w crosses 0), and traversed 16 → 8 → 4 pixel tiles. Each tile test
//! ([`TileTester`]) is the moving 2DH AABB against the tile frustum planes with the n-vertex
//! (Eq. 1-2) intersected with the moving-edge test, linearised (Eq. 4-9, γ at setup, per
//! coarse tile, or re-derived per tile at every level around the parent tile's time interval)
//! or exact (quadratic per tile corner, at every level or at the finest only) — [`EdgeTest`];
//! the result is trivial
//! reject or a conservative time interval, and only the tmsnet samples in that interval are
//! tested with edge-eqn's combined inside-and-depth call ([`covered_depth`]) and a
//! LESS_EQUAL depth test into a multisampled
//! [`SampleBuffer`] with a time-dependent z-max per tile. Traversal levels may go below the
//! 4x4 sample-pattern tile (e.g. 16 → 8 → 4 → 2 → 1, [`RasterConfig::fine`]): each 2x2
//! quad or pixel then gets its own interval from the pattern tile's linearisation
//! ([`EdgeWindow`]) and only its own pixels' samples in it are tested — beyond the paper's
//! traversal; the sample pattern and the image do not change. The baselines BBOX, CONVEX,
//! INTERLEAVE and OUR with the §7 fallback ([`Traversal`]) use the same samples and inside
//! test and produce bit-identical buffers; [`Counters`] report their cost.
//!
//! Entry points: [`SampleBuffer::new`], [`rasterise`] (parallel over coarse tiles with
//! rayon) with a [`RasterConfig`] (`new(traversal)`: the paper's 16 → 8 → 4; `fine()`),
//! [`SampleBuffer::resolve`] (box filter), the building blocks above, and
//! [`benchmark_scene`] (the deterministic synthetic scenes of the benchmarks).
//!
//! ```
//! use edge_eqn::MovingTriangle;
//! use raster_hier::{EdgeTest, RasterConfig, RasterTriangle, SampleBuffer, Traversal, rasterise};
//! let q = [[2.0, 2.0, 1.0], [12.0, 2.0, 1.0], [2.0, 12.0, 1.0]];
//! let r = q.map(|[x, y, w]| [x + 16.0, y, w]);
//! let tris = [RasterTriangle::whole(MovingTriangle::<f32>::new(q, r), 0)];
//! let mut buf = SampleBuffer::<f32>::new(32, 16, 16, 4, 16, 4, 7)?;
//! let stats = rasterise(&mut buf, &tris, &RasterConfig::new(Traversal::Our(EdgeTest::Exact)))?;
//! let img = buf.resolve(|_| [1.0; 4], [0.0; 4]);
//! assert!(stats.samples_written > 0 && img.iter().any(|p| p[0] > 0.0));
//! # Ok::<(), raster_hier::Error>(())
//! ```

pub mod bound;
pub mod buffer;
pub mod convex;
pub mod counters;
pub mod cull;
pub mod error;
pub mod interval;
mod pixel_index;
pub mod raster;
pub mod scene;
pub mod tile_test;
pub mod windows;

pub use bound::{Rect, ScreenBound, screen_bound};
pub use buffer::{Footprint, NO_HIT, SampleBuffer};
pub use convex::{ConvexHull, HullRows, ROW_SLACK, SweptHull};
pub use counters::Counters;
pub use cull::{Facing, facing, frustum_interval, is_backfacing};
pub use edge_eqn::MovingTriangle;
pub use error::Error;
pub use interval::TimeInterval;
pub use raster::{RasterConfig, RasterTriangle, Traversal, covered, covered_depth, rasterise};
pub use scene::benchmark_scene;
pub use tile_test::{EdgeTest, EdgeWindow, Linearised, TileTester};
pub use windows::{FacingWindows, facing_windows};
