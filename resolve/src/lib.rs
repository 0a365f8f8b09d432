//! # resolve
//!
//! The temporal pixel resolve: turns one pixel's list of time intervals into its colour.
//!
//! A pixel's intervals (Gribel 2010, Eq. 16: start and end time, linear depth, payload),
//! sorted by start time and possibly overlapping in time and depth, are swept from t = 0 to
//! t = 1 with an active list kept in depth order (Gribel 2010, §5.1; Rønnow 2021, §4.3,
//! Algorithm 1). Events are interval starts and ends, shutter-response knots and, when
//! [`Settings::intersections`] is on, depth crossings between active intervals (any number
//! at one time: the depth order is evaluated exactly for the float depth lines, so it is a
//! strict total order and crossing events land where the order has really flipped; exact
//! ties go to the later interval in the list, the `LESS_EQUAL` rule). Between events each partition's colour — the nearest interval's for
//! [`Blend::Opaque`], a front-to-back premultiplied OVER with early termination for
//! [`Blend::Transparent`], the background where nothing covers — is integrated exactly
//! against a piecewise-linear shutter response w(t) ([`Shutter`], Eq. 17) and the sum is
//! divided by ∫ w. Textured intervals are shaded per partition along the UV segment lerped
//! at the partition's ends (Rønnow 2021, §4.3, Fig. 7-8) by a [`TapFilter`] (N taps) or an
//! [`ExactFilter`] (exact segment integral, e.g. of a [`BilinearTexture`]).
//!
//! Two implementations of the sweep give the same partitions ([`Sweep`]; crossing times
//! up to their few-ulp nudges): Algorithm 1's
//! active list, O(active) per event, and a kinetic sweep — end times in a min-heap, the
//! visible layers in a short depth-sorted view, the hidden active intervals in a kinetic
//! tournament whose certificates are the only crossings that need processing, a treap in
//! rank order without intersection handling — O(log n + visible layers) per event, so a
//! pixel whose n intervals all overlap costs near n log n instead of n². The default
//! ([`Sweep::Auto`]) starts with the active list and hands over to the kinetic sweep once
//! more than [`HANDOVER_ACTIVE`] intervals are active.
//!
//! Entry points: [`resolve_pixel`], [`Resolver`] (reusable memory, partitions for
//! inspection, [`Resolver::with_sweep`]), [`resolve_with`], [`resolve_with_sweep`],
//! [`resolve_frame`] (whole frame in parallel with rayon), and [`reference::brute_force`]
//! (the dense-sampling ground truth).
//!
//! ```
//! use interval_buffer::{Interval, Rgba};
//! use resolve::{Flat, Settings, resolve_pixel};
//! // Rønnow 2021, Fig. 11: red moves from back to front, green from front to back; they
//! // meet at mid-shutter.
//! let red = Interval::new(0.0_f64, 1.0, 2.0, -1.0, Rgba::opaque(1.0, 0.0, 0.0));
//! let green = Interval::new(0.0_f64, 1.0, 1.0, 1.0, Rgba::opaque(0.0, 1.0, 0.0));
//! let with = resolve_pixel(&[red, green], &Flat, &Settings::opaque()).unwrap();
//! assert!((with.r - 0.5).abs() < 1e-12 && (with.g - 0.5).abs() < 1e-12);
//! let without = Settings::opaque().with_intersections(false);
//! assert_eq!(resolve_pixel(&[red, green], &Flat, &without).unwrap().g, 1.0);
//! ```

mod active_list;
mod bilinear;
mod depth_order;
mod error;
mod frame;
mod kinetic;
mod rank_list;
pub mod reference;
mod shader;
mod shutter;
mod sweep;
mod texture;
mod tournament;

pub use bilinear::{BilinearTexture, MAX_EXACT_PIECES};
pub use error::{PixelError, ResolveError};
pub use frame::resolve_frame;
pub use shader::{ExactFilter, Flat, Shader, TapFilter, uniform_colour, uv_at};
pub use shutter::Shutter;
pub use sweep::{
    Blend, DEFAULT_TRANSMITTANCE_THRESHOLD, HANDOVER_ACTIVE, Partition, Resolver, Scratch,
    Settings, Sweep, resolve_pixel, resolve_with, resolve_with_sweep,
};
pub use texture::{SegmentTexture, Texture};
