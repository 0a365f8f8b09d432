//! The temporal pixel resolve: a sweep over one pixel's intervals (Gribel 2010, §5.1;
//! Rønnow 2021, Algorithm 1).

use interval_buffer::{Interval, Rgba};
use num_traits::Float;

use crate::bilinear::unpremultiply;
use crate::depth_order::Line;
use crate::kinetic::KineticScratch;
use crate::{ResolveError, Shader, Shutter, active_list, kinetic};

/// Default transmittance below which transparent blending stops (Rønnow 2021, Algorithm 1:
/// "If transmittance threshold is reached, stop early"). Skipped layers change a colour
/// channel in [0, 1] by at most this much.
pub const DEFAULT_TRANSMITTANCE_THRESHOLD: f64 = 1e-4;

/// How the active intervals of a partition combine into its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Blend<F> {
    /// The nearest interval's colour at full opacity (Gribel 2010, §5.1: "simply the color
    /// of the nearest (in depth) interval"); payload alpha is ignored (premultiplied colour
    /// divided by its alpha, black where alpha is 0). Nothing behind the nearest interval is
    /// shaded, and with intersection handling only crossings with the nearest interval are
    /// events.
    Opaque,
    /// Front-to-back Porter-Duff OVER of every active interval, premultiplied, then the
    /// background behind what transmittance remains (Gribel 2010, Fig. 8; Rønnow 2021,
    /// Algorithm 1). Blending stops once the transmittance is `<= threshold`; the rest
    /// (deeper layers and background) is dropped, an error of at most `threshold` per
    /// channel for colours in [0, 1].
    Transparent {
        /// Transmittance at which blending stops early, in [0, 1].
        threshold: F,
    },
}

/// Everything that decides how a pixel resolves, besides its intervals and shader.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings<F> {
    /// Opaque or transparent compositing of the active intervals.
    pub blend: Blend<F>,
    /// Whether depth crossings between active intervals are sweep events (Rønnow 2021,
    /// Algorithm 1, red lines; ~10% of the resolve time there). Without them an interval
    /// keeps the depth rank it got when it became active, for its whole life (Rønnow 2021,
    /// Fig. 11, left).
    pub intersections: bool,
    /// Colour seen where no interval covers the pixel and behind what transparent layers
    /// let through (straight alpha).
    pub background: Rgba<F>,
    /// The shutter response w(t) of Eq. 17.
    pub shutter: Shutter<F>,
}

impl<F: Float> Settings<F> {
    /// Transparent blending with the default threshold, intersection handling on, opaque
    /// black background, box shutter.
    pub fn transparent() -> Self {
        Self {
            blend: Blend::Transparent {
                threshold: F::from(DEFAULT_TRANSMITTANCE_THRESHOLD).unwrap_or_else(F::zero),
            },
            intersections: true,
            background: Rgba::opaque(F::zero(), F::zero(), F::zero()),
            shutter: Shutter::box_filter(),
        }
    }

    /// Opaque resolve, intersection handling on, opaque black background, box shutter.
    pub fn opaque() -> Self {
        Self {
            blend: Blend::Opaque,
            ..Self::transparent()
        }
    }

    /// The same settings with intersection handling switched on or off.
    pub fn with_intersections(mut self, on: bool) -> Self {
        self.intersections = on;
        self
    }

    /// The same settings with another background colour.
    pub fn with_background(mut self, background: Rgba<F>) -> Self {
        self.background = background;
        self
    }

    /// The same settings with another shutter response.
    pub fn with_shutter(mut self, shutter: Shutter<F>) -> Self {
        self.shutter = shutter;
        self
    }

    /// The same settings with transparent blending at transmittance threshold `threshold`.
    pub fn with_threshold(mut self, threshold: F) -> Self {
        self.blend = Blend::Transparent { threshold };
        self
    }

    fn validate(&self) -> Result<(), ResolveError> {
        let b = &self.background;
        let background_ok =
            b.r.is_finite() && b.g.is_finite() && b.b.is_finite() && b.a.is_finite();
        let blend_ok = match self.blend {
            Blend::Opaque => true,
            Blend::Transparent { threshold } => threshold >= F::zero() && threshold <= F::one(),
        };
        if background_ok && blend_ok {
            Ok(())
        } else {
            Err(ResolveError::InvalidSettings)
        }
    }
}

impl<F: Float> Default for Settings<F> {
    fn default() -> Self {
        Self::transparent()
    }
}

/// One resolved interval Δ_k of the sweep: a span of time over which the set and the
/// depth order of the active intervals do not change (Gribel 2010, §5.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Partition<F> {
    /// Start of the span.
    pub t0: F,
    /// End of the span (`> t0`).
    pub t1: F,
    /// ∫_{t0}^{t1} w(t) dt, the span's weight in Eq. 17 (before dividing by ∫₀¹ w).
    pub weight: F,
    /// The span's premultiplied colour c_k, background included; all zero when `weight`
    /// is zero (zero-weight spans are not shaded).
    pub colour: [F; 4],
    /// List position of the nearest active interval, `None` where only background shows.
    pub front: Option<usize>,
    /// Number of intervals shaded for this span (0 for background or zero weight).
    pub layers: usize,
}

/// Reusable per-thread working memory of the sweep (active list, end-time heap, kinetic
/// tournament, rank list).
#[derive(Clone, Debug)]
pub struct Scratch<F> {
    active: Vec<Line<F>>,
    kinetic: KineticScratch<F>,
}

impl<F> Scratch<F> {
    /// Empty working memory; it grows to the largest pixel seen.
    pub fn new() -> Self {
        Self {
            active: Vec::new(),
            kinetic: KineticScratch::new(),
        }
    }
}

impl<F> Default for Scratch<F> {
    fn default() -> Self {
        Self::new()
    }
}

/// Which implementation of the sweep resolves a pixel. All produce the same partitions
/// (Δ_k; crossing times up to their few-ulp nudges) and colours with intersection handling (without it, see [`Settings::intersections`]:
/// each places a starting interval by its own binary search of the stale rank order);
/// they differ in cost when many intervals overlap in time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sweep {
    /// The default: [`Sweep::ActiveList`] while few intervals are active (at most
    /// [`HANDOVER_ACTIVE`] with intersection handling, half that without: cheapest for the
    /// few overlapping intervals of most pixels), then [`Sweep::Kinetic`] from the first
    /// time more are active to the end of the shutter.
    #[default]
    Auto,
    /// Kinetic sweep (from the first interval start on): end times in a min-heap; with intersection handling the visible
    /// layers in a short depth-sorted view and the hidden active intervals in a kinetic
    /// tournament (only the nearest hidden interval can enter the view next, and the
    /// tournament's certificates say when that changes); without it, the active list as a
    /// balanced tree in rank order. Per event O(log n + visible layers) instead of
    /// O(active), so a pixel with n intervals costs near n log n even when all n overlap
    /// (see `kinetic.rs`). Transparent blending that never reaches its transmittance
    /// threshold keeps every active interval visible: then each partition costs O(active),
    /// as its colour needs every layer, and every crossing is a visible event.
    Kinetic,
    /// Rønnow 2021, Algorithm 1 as written: one active list, scanned at every event
    /// (ends, nearest, crossings), re-sorted by insertion sort: O(active) per event, so
    /// O(n²) when all n intervals overlap.
    ActiveList,
}

/// [`Sweep::Auto`] hands a pixel over from the active list to the kinetic sweep once more
/// than this many intervals are active at once with intersection handling (half this
/// without). Measured crossover (BENCHMARKS.md): below it the kinetic structures' constant
/// factors cost more than the O(active) scans they replace.
pub const HANDOVER_ACTIVE: usize = 32;

/// A resolver that owns its settings and working memory: the convenient single-thread
/// entry point.
#[derive(Clone, Debug)]
pub struct Resolver<F> {
    settings: Settings<F>,
    scratch: Scratch<F>,
    sweep: Sweep,
}

impl<F: Float> Resolver<F> {
    /// A resolver with these settings (and the default [`Sweep::Kinetic`]).
    pub fn new(settings: Settings<F>) -> Self {
        Self {
            settings,
            scratch: Scratch::new(),
            sweep: Sweep::default(),
        }
    }

    /// The same resolver with another sweep implementation.
    pub fn with_sweep(mut self, sweep: Sweep) -> Self {
        self.sweep = sweep;
        self
    }

    /// The settings in use.
    pub fn settings(&self) -> &Settings<F> {
        &self.settings
    }

    /// Resolves one pixel (see [`resolve_pixel`]).
    pub fn resolve<P, S: Shader<F, P>>(
        &mut self,
        intervals: &[Interval<F, P>],
        shader: &S,
    ) -> Result<Rgba<F>, ResolveError> {
        resolve_with_sweep(
            self.sweep,
            &mut self.scratch,
            intervals,
            shader,
            &self.settings,
            |_| {},
        )
    }

    /// Resolves one pixel and reports every partition to `sink` (see [`resolve_with`]).
    pub fn resolve_partitions<P, S: Shader<F, P>>(
        &mut self,
        intervals: &[Interval<F, P>],
        shader: &S,
        sink: impl FnMut(&Partition<F>),
    ) -> Result<Rgba<F>, ResolveError> {
        resolve_with_sweep(
            self.sweep,
            &mut self.scratch,
            intervals,
            shader,
            &self.settings,
            sink,
        )
    }
}

/// Resolves one pixel's intervals into its colour (Gribel 2010, Eq. 17).
///
/// `intervals` must be sorted by `ts` (as the interval buffer keeps them); they may overlap
/// in time and in depth. Times outside [0, 1] are clamped to the shutter; zero-length
/// intervals cover nothing. The result is ∑_k ∫ w c_k / ∫₀¹ w with straight alpha (alpha 1
/// whenever the background is opaque).
///
/// ```
/// use interval_buffer::{Interval, Rgba};
/// use resolve::{Flat, Settings, resolve_pixel};
/// // Red covers the first half of the shutter over a white background.
/// let red = Interval::new(0.0_f64, 0.5, 1.0, 0.0, Rgba::opaque(1.0, 0.0, 0.0));
/// let settings = Settings::opaque().with_background(Rgba::opaque(1.0, 1.0, 1.0));
/// let c = resolve_pixel(&[red], &Flat, &settings).unwrap();
/// assert_eq!((c.r, c.g, c.b), (1.0, 0.5, 0.5));
/// ```
pub fn resolve_pixel<F: Float, P, S: Shader<F, P>>(
    intervals: &[Interval<F, P>],
    shader: &S,
    settings: &Settings<F>,
) -> Result<Rgba<F>, ResolveError> {
    resolve_with(&mut Scratch::new(), intervals, shader, settings, |_| {})
}

/// [`resolve_pixel`] with caller-owned working memory, reporting each resolved partition
/// Δ_k to `sink` in time order (a "temporal pixel visualizer", Gribel 2010, §5.2.1).
///
/// The sweep (Rønnow 2021, Algorithm 1): events are interval starts and ends, shutter knots
/// and — with [`Settings::intersections`] — depth crossings that change what is visible:
/// between depth-adjacent intervals down to the deepest layer early termination can reach
/// (from [`Shader::min_alpha`]; the nearest only, for opaque blending), or a hidden interval
/// crossing into that layer. At each event the visible layers are brought into exact depth
/// order for the span that follows (see `depth_order.rs`), so any number of simultaneous
/// crossings reorder correctly. Without intersection handling each interval is inserted at
/// its depth rank when it starts and keeps it. Uses [`Sweep::Kinetic`]; see
/// [`resolve_with_sweep`] to choose.
///
/// Errors: [`ResolveError::InvalidInterval`], [`ResolveError::Unsorted`],
/// [`ResolveError::InvalidSettings`], [`ResolveError::NonFiniteColour`].
pub fn resolve_with<F: Float, P, S: Shader<F, P>>(
    scratch: &mut Scratch<F>,
    intervals: &[Interval<F, P>],
    shader: &S,
    settings: &Settings<F>,
    sink: impl FnMut(&Partition<F>),
) -> Result<Rgba<F>, ResolveError> {
    resolve_with_sweep(Sweep::default(), scratch, intervals, shader, settings, sink)
}

/// [`resolve_with`] by a chosen [`Sweep`] implementation (same result, different cost).
pub fn resolve_with_sweep<F: Float, P, S: Shader<F, P>>(
    sweep: Sweep,
    scratch: &mut Scratch<F>,
    intervals: &[Interval<F, P>],
    shader: &S,
    settings: &Settings<F>,
    mut sink: impl FnMut(&Partition<F>),
) -> Result<Rgba<F>, ResolveError> {
    settings.validate()?;
    validate(intervals)?;
    let mut compositor = Compositor::new(intervals, shader, settings);
    let handover = match sweep {
        // The kinetic structures index intervals with u32.
        _ if intervals.len() >= u32::MAX as usize => usize::MAX,
        Sweep::Auto if settings.intersections => HANDOVER_ACTIVE,
        Sweep::Auto => HANDOVER_ACTIVE / 2,
        Sweep::Kinetic => 0,
        Sweep::ActiveList => usize::MAX,
    };
    let active = &mut scratch.active;
    let stopped = active_list::sweep(active, &mut compositor, settings, &mut sink, handover);
    if let Some((r, next, cursor)) = stopped {
        let start = kinetic::Start {
            r,
            next,
            cursor,
            active,
        };
        kinetic::sweep(
            &mut scratch.kinetic,
            &mut compositor,
            settings,
            &mut sink,
            start,
        );
    }
    compositor.finish()
}

fn validate<F: Float, P>(intervals: &[Interval<F, P>]) -> Result<(), ResolveError> {
    let mut previous = F::neg_infinity();
    for (index, iv) in intervals.iter().enumerate() {
        if !iv.is_valid() || !(iv.z - iv.k * iv.ts).is_finite() {
            return Err(ResolveError::InvalidInterval { index });
        }
        if iv.ts < previous {
            return Err(ResolveError::Unsorted { index });
        }
        previous = iv.ts;
    }
    Ok(())
}

/// Shades and accumulates partitions (Eq. 17), whichever sweep produced them.
pub(crate) struct Compositor<'a, F, P, S> {
    pub intervals: &'a [Interval<F, P>],
    pub shader: &'a S,
    pub shutter: &'a Shutter<F>,
    background: [F; 4],
    /// `Blend::Opaque`.
    pub opaque: bool,
    /// Transmittance threshold (0 for opaque).
    pub threshold: F,
    total: [F; 4],
}

impl<'a, F: Float, P, S: Shader<F, P>> Compositor<'a, F, P, S> {
    fn new(intervals: &'a [Interval<F, P>], shader: &'a S, settings: &'a Settings<F>) -> Self {
        let (opaque, threshold) = match settings.blend {
            Blend::Opaque => (true, F::zero()),
            Blend::Transparent { threshold } => (false, threshold),
        };
        Self {
            intervals,
            shader,
            shutter: &settings.shutter,
            background: settings.background.premultiplied(),
            opaque,
            threshold,
            total: [F::zero(); 4],
        }
    }

    /// The partition [r, re] (inside one linear piece of the shutter, `cursor` as after
    /// [`Shutter::advance`] to `r`) with the active intervals `layers` front to back (at
    /// least down to where early termination stops): its weight ∫ w (trapezoid rule, exact
    /// for linear w) and colour, added to the pixel's sum.
    pub fn partition(
        &mut self,
        cursor: usize,
        r: F,
        re: F,
        layers: impl Iterator<Item = usize>,
    ) -> Partition<F> {
        let (zero, one) = (F::zero(), F::one());
        let half = one / (one + one);
        let w0 = self.shutter.right_value(cursor, r);
        let w1 = self.shutter.right_value(cursor, re);
        let weight = (re - r) * (w0 + w1) * half;
        let mut layers = layers.peekable();
        let front = layers.peek().copied();
        let mut colour = [zero; 4];
        let mut shaded = 0;
        if weight > zero {
            if front.is_none() {
                colour = self.background;
            } else if self.opaque {
                if let Some(iv) = front.and_then(|i| self.intervals.get(i)) {
                    colour = at_full_opacity(self.shader.shade(iv, r, re, w0, w1));
                    shaded = 1;
                }
            } else {
                let mut transmittance = one;
                for i in layers {
                    let Some(iv) = self.intervals.get(i) else {
                        continue;
                    };
                    let c = self.shader.shade(iv, r, re, w0, w1);
                    for (acc, c) in colour.iter_mut().zip(c) {
                        *acc = *acc + transmittance * c;
                    }
                    transmittance = transmittance * (one - c[3].max(zero).min(one));
                    shaded += 1;
                    if transmittance <= self.threshold {
                        break;
                    }
                }
                if transmittance > self.threshold {
                    for (acc, b) in colour.iter_mut().zip(self.background) {
                        *acc = *acc + transmittance * b;
                    }
                }
            }
            for (acc, c) in self.total.iter_mut().zip(colour) {
                *acc = *acc + weight * c;
            }
        }
        Partition {
            t0: r,
            t1: re,
            weight,
            colour,
            front,
            layers: shaded,
        }
    }

    /// Σ_k ∫ w c_k / ∫₀¹ w, straight alpha.
    fn finish(self) -> Result<Rgba<F>, ResolveError> {
        let norm = self.shutter.total();
        let t = self.total;
        let out = unpremultiply([t[0] / norm, t[1] / norm, t[2] / norm, t[3] / norm]);
        if out.r.is_finite() && out.g.is_finite() && out.b.is_finite() && out.a.is_finite() {
            Ok(out)
        } else {
            Err(ResolveError::NonFiniteColour)
        }
    }
}

/// Premultiplied colour shown at full opacity: divided by its alpha (black for alpha 0).
fn at_full_opacity<F: Float>(c: [F; 4]) -> [F; 4] {
    // Already opaque (the common case): the divisions would be by one, exact.
    if c[3] == F::one() {
        return c;
    }
    if c[3] > F::zero() {
        [c[0] / c[3], c[1] / c[3], c[2] / c[3], F::one()]
    } else {
        [F::zero(), F::zero(), F::zero(), F::one()]
    }
}

/// The earliest crossing among candidate pairs: raw estimates are compared, and only the
/// winner is nudged to where its exact order has flipped (the exact check is the slow part).
pub(crate) struct NextCrossing<F, L> {
    t: F,
    end: F,
    best: Option<(F, L, L)>,
}

impl<F: Float> NextCrossing<F, Line<F>> {
    /// No crossing yet in (t, end).
    pub fn new(t: F, end: F) -> Self {
        Self { t, end, best: None }
    }

    /// `a` nearer than `b` just after `t`.
    pub fn consider(&mut self, a: &Line<F>, b: &Line<F>) {
        if let Some(mut tau) = a.crossing_estimate(b) {
            if tau <= self.t {
                // Rounded to before now although b is still behind: nudge now.
                tau = a.nudge_past_crossing(b, tau);
            }
            let best = self.best.map_or(self.end, |x| x.0);
            if tau > self.t && tau < best {
                self.best = Some((tau, *a, *b));
            }
        }
    }

    /// The event time: the winner nudged past its exact crossing, capped by `end`.
    pub fn time(&self) -> F {
        match self.best {
            Some((tau, a, b)) => a.nudge_past_crossing(&b, tau).min(self.end),
            None => self.end,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Flat;

    fn flat(ts: f64, te: f64, z: f64, k: f64, c: [f64; 4]) -> Interval<f64, Rgba<f64>> {
        Interval::new(ts, te, z, k, Rgba::new(c[0], c[1], c[2], c[3]))
    }

    #[test]
    fn empty_pixel_is_background() {
        let bg = Rgba::opaque(0.25, 0.5, 0.75);
        let s = Settings::transparent().with_background(bg);
        let c = resolve_pixel::<f64, Rgba<f64>, _>(&[], &Flat, &s).unwrap();
        assert_eq!(c, bg);
    }

    #[test]
    fn nearer_interval_wins_where_both_are_active() {
        let ivs = [
            flat(0.0, 1.0, 2.0, 0.0, [1.0, 0.0, 0.0, 1.0]),
            flat(0.25, 0.75, 1.0, 0.0, [0.0, 0.0, 1.0, 1.0]),
        ];
        for s in [Settings::opaque(), Settings::transparent()] {
            let c = resolve_pixel(&ivs, &Flat, &s).unwrap();
            assert!(
                (c.r - 0.5).abs() < 1e-15 && (c.b - 0.5).abs() < 1e-15,
                "{c:?}"
            );
        }
    }

    #[test]
    fn partitions_tile_the_shutter() {
        let ivs = [
            flat(0.1, 0.9, 1.0, 1.0, [1.0, 0.0, 0.0, 0.5]),
            flat(0.2, 0.6, 1.6, -1.0, [0.0, 1.0, 0.0, 0.5]),
        ];
        let mut parts = Vec::new();
        let mut r = Resolver::new(Settings::transparent());
        r.resolve_partitions(&ivs, &Flat, |p| parts.push(*p))
            .unwrap();
        assert_eq!(parts.first().map(|p| p.t0), Some(0.0));
        assert_eq!(parts.last().map(|p| p.t1), Some(1.0));
        assert!(
            parts
                .windows(2)
                .all(|w| w[0].t1 == w[1].t0 && w[0].t0 < w[0].t1)
        );
        // Crossing at t = 0.5 (1 + 1 * 0.4 = 1.6 - 0.3... lines: 0.9 + t and 1.8 - t).
        assert!(parts.iter().any(|p| (p.t0 - 0.45).abs() < 1e-12));
    }

    #[test]
    fn invalid_input_is_an_error() {
        let good = flat(0.0, 1.0, 1.0, 0.0, [1.0; 4]);
        let s = Settings::transparent();
        let reversed = flat(0.6, 0.5, 1.0, 0.0, [1.0; 4]);
        assert_eq!(
            resolve_pixel(&[good, reversed], &Flat, &s),
            Err(ResolveError::InvalidInterval { index: 1 })
        );
        let early = flat(-0.5, 0.5, 1.0, 0.0, [1.0; 4]);
        assert_eq!(
            resolve_pixel(&[good, early], &Flat, &s),
            Err(ResolveError::Unsorted { index: 1 })
        );
        let nan = flat(0.0, 1.0, 1.0, 0.0, [f64::NAN, 0.0, 0.0, 1.0]);
        assert_eq!(
            resolve_pixel(&[nan], &Flat, &s),
            Err(ResolveError::NonFiniteColour)
        );
        let bad = Settings::transparent().with_threshold(2.0);
        assert_eq!(
            resolve_pixel(&[good], &Flat, &bad),
            Err(ResolveError::InvalidSettings)
        );
    }
}
