//! The temporal pixel resolve: a sweep over one pixel's intervals (Gribel 2010, §5.1;
//! Rønnow 2021, Algorithm 1).

use interval_buffer::{Interval, Rgba};
use num_traits::Float;

use crate::bilinear::unpremultiply;
use crate::depth_order::Line;
use crate::{ResolveError, Shader, Shutter};

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

/// Reusable per-thread working memory of the sweep (the active list).
#[derive(Clone, Debug, Default)]
pub struct Scratch<F> {
    active: Vec<Line<F>>,
}

impl<F> Scratch<F> {
    /// Empty working memory; it grows to the largest active list seen.
    pub fn new() -> Self {
        Self { active: Vec::new() }
    }
}

/// A resolver that owns its settings and working memory: the convenient single-thread
/// entry point.
#[derive(Clone, Debug)]
pub struct Resolver<F> {
    settings: Settings<F>,
    scratch: Scratch<F>,
}

impl<F: Float> Resolver<F> {
    /// A resolver with these settings.
    pub fn new(settings: Settings<F>) -> Self {
        Self {
            settings,
            scratch: Scratch::new(),
        }
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
        resolve_with(&mut self.scratch, intervals, shader, &self.settings, |_| {})
    }

    /// Resolves one pixel and reports every partition to `sink` (see [`resolve_with`]).
    pub fn resolve_partitions<P, S: Shader<F, P>>(
        &mut self,
        intervals: &[Interval<F, P>],
        shader: &S,
        sink: impl FnMut(&Partition<F>),
    ) -> Result<Rgba<F>, ResolveError> {
        resolve_with(&mut self.scratch, intervals, shader, &self.settings, sink)
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
/// and — with [`Settings::intersections`] — depth crossings. At each event the active list
/// is brought into depth order for the span that follows (see `depth_order.rs`): fully
/// re-sorted (insertion sort, linear when nearly sorted) for transparent blending, so any
/// number of simultaneous crossings reorder correctly; only the nearest found for opaque
/// blending. Without intersection handling each interval is inserted at its depth rank when
/// it starts and keeps it. The next crossing is the earliest one that changes what is
/// visible: between depth-adjacent intervals down to the deepest layer early termination
/// can reach (from [`Shader::min_alpha`]) or into that layer (transparent), or between the
/// nearest interval and any other (opaque).
///
/// Errors: [`ResolveError::InvalidInterval`], [`ResolveError::Unsorted`],
/// [`ResolveError::InvalidSettings`], [`ResolveError::NonFiniteColour`].
pub fn resolve_with<F: Float, P, S: Shader<F, P>>(
    scratch: &mut Scratch<F>,
    intervals: &[Interval<F, P>],
    shader: &S,
    settings: &Settings<F>,
    mut sink: impl FnMut(&Partition<F>),
) -> Result<Rgba<F>, ResolveError> {
    settings.validate()?;
    validate(intervals)?;
    let (zero, one) = (F::zero(), F::one());
    let half = one / (one + one);
    let clamp01 = |t: F| t.max(zero).min(one);
    let shutter = &settings.shutter;
    let background = settings.background.premultiplied();
    let (opaque, threshold) = match settings.blend {
        Blend::Opaque => (true, zero),
        Blend::Transparent { threshold } => (false, threshold),
    };
    let active = &mut scratch.active;
    active.clear();
    let mut next = 0;
    let mut cursor = 0;
    let mut total = [zero; 4];
    let mut r = zero;
    while r < one {
        active.retain(|l| l.te > r);
        while let Some(iv) = intervals.get(next) {
            if clamp01(iv.ts) > r {
                break;
            }
            let te = clamp01(iv.te);
            if te > r {
                let line = Line {
                    c: iv.z - iv.k * iv.ts,
                    k: iv.k,
                    te,
                    index: next,
                };
                if settings.intersections {
                    active.push(line);
                } else {
                    let at = active.partition_point(|e| !line.nearer_after(e, r));
                    active.insert(at, line);
                }
            }
            next += 1;
        }
        shutter.advance(&mut cursor, r);

        // The partition ends at the next start, end, shutter knot or crossing.
        let mut re = one;
        if let Some(iv) = intervals.get(next) {
            re = re.min(clamp01(iv.ts));
        }
        if let Some(knot) = shutter.next_knot(cursor) {
            re = re.min(knot);
        }
        for l in active.iter() {
            re = re.min(l.te);
        }
        if settings.intersections && !active.is_empty() {
            re = if opaque {
                nearest_to_front(active, r);
                first_crossing_with_front(active, r, re)
            } else {
                sort_by_depth_after(active, r);
                let last = last_visible_layer(active, intervals, shader, threshold);
                first_crossing_in_view(active, r, re, last)
            };
        }

        // Eq. 17 on this partition: w is linear on it, so the trapezoid rule is exact.
        let w0 = shutter.right_value(cursor, r);
        let w1 = shutter.right_value(cursor, re);
        let weight = (re - r) * (w0 + w1) * half;
        let mut colour = [zero; 4];
        let mut layers = 0;
        if weight > zero {
            if active.is_empty() {
                colour = background;
            } else if opaque {
                let front = active.first().and_then(|l| intervals.get(l.index));
                if let Some(iv) = front {
                    colour = at_full_opacity(shader.shade(iv, r, re, w0, w1));
                    layers = 1;
                }
            } else {
                let mut transmittance = one;
                for l in active.iter() {
                    let Some(iv) = intervals.get(l.index) else {
                        continue;
                    };
                    let c = shader.shade(iv, r, re, w0, w1);
                    for (acc, c) in colour.iter_mut().zip(c) {
                        *acc = *acc + transmittance * c;
                    }
                    transmittance = transmittance * (one - c[3].max(zero).min(one));
                    layers += 1;
                    if transmittance <= threshold {
                        break;
                    }
                }
                if transmittance > threshold {
                    for (acc, b) in colour.iter_mut().zip(background) {
                        *acc = *acc + transmittance * b;
                    }
                }
            }
            for (acc, c) in total.iter_mut().zip(colour) {
                *acc = *acc + weight * c;
            }
        }
        sink(&Partition {
            t0: r,
            t1: re,
            weight,
            colour,
            front: active.first().map(|l| l.index),
            layers,
        });
        r = re;
    }
    let norm = shutter.total();
    let out = unpremultiply([
        total[0] / norm,
        total[1] / norm,
        total[2] / norm,
        total[3] / norm,
    ]);
    if out.r.is_finite() && out.g.is_finite() && out.b.is_finite() && out.a.is_finite() {
        Ok(out)
    } else {
        Err(ResolveError::NonFiniteColour)
    }
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

/// Premultiplied colour shown at full opacity: divided by its alpha (black for alpha 0).
fn at_full_opacity<F: Float>(c: [F; 4]) -> [F; 4] {
    if c[3] > F::zero() {
        [c[0] / c[3], c[1] / c[3], c[2] / c[3], F::one()]
    } else {
        [F::zero(), F::zero(), F::zero(), F::one()]
    }
}

/// Moves the interval nearest just after `t` to the front (opaque resolve: nothing behind
/// it needs an order).
fn nearest_to_front<F: Float>(active: &mut [Line<F>], t: F) {
    let mut best = 0;
    for (i, l) in active.iter().enumerate().skip(1) {
        if let Some(b) = active.get(best)
            && l.nearer_after(b, t)
        {
            best = i;
        }
    }
    active.swap(0, best);
}

/// Earliest time in (t, end) at which another interval becomes nearer than the front one.
fn first_crossing_with_front<F: Float>(active: &[Line<F>], t: F, end: F) -> F {
    let mut next = NextCrossing::new(t, end);
    if let Some((front, rest)) = active.split_first() {
        for l in rest {
            next.consider(front, l);
        }
    }
    next.time()
}

/// The earliest crossing among candidate pairs: raw estimates are compared, and only the
/// winner is nudged to where its exact order has flipped (the exact check is the slow part).
struct NextCrossing<F, L> {
    t: F,
    end: F,
    best: Option<(F, L, L)>,
}

impl<F: Float> NextCrossing<F, Line<F>> {
    fn new(t: F, end: F) -> Self {
        Self { t, end, best: None }
    }

    /// `a` nearer than `b` just after `t`.
    fn consider(&mut self, a: &Line<F>, b: &Line<F>) {
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
    fn time(&self) -> F {
        match self.best {
            Some((tau, a, b)) => a.nudge_past_crossing(&b, tau).min(self.end),
            None => self.end,
        }
    }
}

/// Insertion sort of the active list into depth order just after `t`: linear for a list
/// that was sorted at the previous event, plus one swap per crossing since.
fn sort_by_depth_after<F: Float>(active: &mut [Line<F>], t: F) {
    for i in 1..active.len() {
        let mut j = i;
        while j > 0 && active[j].nearer_after(&active[j - 1], t) {
            active.swap(j, j - 1);
            j -= 1;
        }
    }
}

/// Index of the deepest layer that transparent blending can reach: with the shader's alpha
/// lower bounds, transmittance is certainly `<= threshold` after it (the last layer if
/// never).
fn last_visible_layer<F: Float, P, S: Shader<F, P>>(
    active: &[Line<F>],
    intervals: &[Interval<F, P>],
    shader: &S,
    threshold: F,
) -> usize {
    let mut transmittance = F::one();
    for (i, l) in active.iter().enumerate() {
        if let Some(iv) = intervals.get(l.index) {
            let alpha = shader.min_alpha(iv).max(F::zero()).min(F::one());
            transmittance = transmittance * (F::one() - alpha);
            if transmittance <= threshold {
                return i;
            }
        }
    }
    active.len().saturating_sub(1)
}

/// Earliest time in (t, end) at which the depth-sorted layers `0..=last` change: a crossing
/// between two of them, which is first between neighbours (Rønnow 2021, Algorithm 1,
/// FindNearestIntervalIntersection), or a deeper interval crossing layer `last` to enter.
/// Crossings among the layers behind are not events; the next re-sort fixes their order.
fn first_crossing_in_view<F: Float>(active: &[Line<F>], t: F, end: F, last: usize) -> F {
    let mut next = NextCrossing::new(t, end);
    for pair in active.get(..=last).unwrap_or(active).windows(2) {
        if let [a, b] = pair {
            next.consider(a, b);
        }
    }
    if let Some(deepest) = active.get(last) {
        for behind in active.get(last + 1..).unwrap_or(&[]) {
            next.consider(deepest, behind);
        }
    }
    next.time()
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
