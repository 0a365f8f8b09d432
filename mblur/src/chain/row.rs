//! The row pipeline: rows are independent, so each row's intervals are emitted once (every
//! primitive of the row's band, in primitive order), placed into that row's exact lists
//! ([`PixelLists`]: count, scan, place, sort; Rønnow 2021 §4.1-4.2) or its bounded buffer
//! (K per pixel with the paper's oracle compression, Gribel 2010 §5.2), and resolved at once
//! (the time sweep against the shutter response, Gribel 2010 §5.1, Eq. 17), in parallel
//! over rows, so the interval storage is one row per thread, reused from row to row.

use interval_buffer::{
    BoundedBuffer, Insertion, Interval, IntervalCounts, Oracle, Payload, PixelLists, Rgba,
};
use rayon::prelude::*;
use resolve::{Partition, Scratch, Settings, Shader};
use std::sync::Mutex;

use super::emit::{RowSpan, emit};
use super::payload::MakePayload;
use super::prim::Prim;
use super::{IntervalStats, Real, cf};
use crate::bands::Bins;
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

/// Resolve settings for the scene and pipeline (Gribel 2010 §5.1, Eq. 17): opaque or
/// transparent resolve, intersection handling, the shutter response and the background.
/// `method` names the method in the error for a shutter response the chain's float type
/// cannot represent.
pub(crate) fn settings<F: Real>(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    method: &str,
) -> Result<Settings<F>> {
    let base = if pipeline.transparency {
        Settings::transparent()
    } else {
        Settings::opaque()
    };
    let points: Vec<(F, F)> = scene
        .shutter
        .points
        .iter()
        .map(|&(t, w)| (cf(t), cf(w)))
        .collect();
    let shutter =
        resolve::Shutter::from_points(&points).map_err(|e| Error::MethodNotApplicable {
            method: method.into(),
            reason: format!("shutter response: {e}"),
        })?;
    let [r, g, b] = scene.background.map(cf::<F>);
    Ok(base
        .with_intersections(pipeline.intersection)
        .with_shutter(shutter)
        .with_background(Rgba::opaque(r, g, b)))
}

/// How a row's intervals are buffered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Buffering {
    /// 0 = exact lists, K > 0 = at most K per pixel with the paper's oracle.
    pub intervals: u32,
    /// Opaque insertion (the pipeline has no transparency).
    pub opaque: bool,
    /// Most intervals one row's exact lists may hold (the memory budget shared by the rows
    /// in flight); `u64::MAX` for no limit. Bounded buffers hold K per pixel whatever is
    /// emitted and ignore it.
    pub row_limit: u64,
}

impl Buffering {
    /// Exact lists or K per pixel, with no memory limit.
    pub(crate) fn unlimited(intervals: u32, opaque: bool) -> Self {
        Buffering {
            intervals,
            opaque,
            row_limit: u64::MAX,
        }
    }
}

/// What a buffered row held, per pixel.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Counts {
    /// Largest number of intervals emitted into one pixel.
    pub max: u32,
    /// Pixels that received at least one interval.
    pub covered: u64,
}

impl Counts {
    fn add(&mut self, c: u32) {
        self.max = self.max.max(c);
        self.covered += u64::from(c > 0);
    }
}

/// A row's bounded buffer (K per pixel) and the number of intervals each pixel was sent.
struct Bounded<F, P> {
    buf: BoundedBuffer<F, P>,
    sent: IntervalCounts,
}

/// Per-thread working memory of the row pipeline, reused from row to row: the resolve's
/// scratch, the row's emitted `(x, interval)` pairs and its exact lists, or its bounded
/// buffer. A row is filled with [`RowScratch::begin`], [`RowScratch::push`] for every
/// interval in emission order, and [`RowScratch::finish`].
pub(crate) struct RowScratch<F, P> {
    /// The resolve's working memory.
    pub resolve: Scratch<F>,
    /// The row's intervals as emitted, (column, interval), for the exact lists.
    emitted: Vec<(u32, Interval<F, P>)>,
    lists: PixelLists<F, P>,
    bounded: Option<Bounded<F, P>>,
    how: Buffering,
    width: usize,
    method: &'static str,
    row: u32,
    received: u64,
}

impl<F: Real, P: Payload<F> + Copy + Default + Send + Sync> RowScratch<F, P> {
    /// Empty working memory.
    pub(crate) fn new() -> Self {
        RowScratch {
            resolve: Scratch::new(),
            emitted: Vec::new(),
            lists: PixelLists::new(),
            bounded: None,
            how: Buffering::unlimited(0, false),
            width: 0,
            method: "",
            row: 0,
            received: 0,
        }
    }

    /// Bytes the exact lists hold per interval of a row: the emitted record, its sort key
    /// and its sorted copy.
    pub(crate) const BYTES_PER_INTERVAL: usize =
        std::mem::size_of::<(u32, Interval<F, P>)>() + PixelLists::<F, P>::BYTES_PER_INTERVAL;

    /// Starts row `row` of `width` pixels, buffered as `how` says; `method` names the
    /// method in errors. Exact lists keep their memory from the previous row; a bounded
    /// buffer (K per pixel) is fed in emission order as intervals arrive, so a row never
    /// holds more than K intervals per pixel.
    pub(crate) fn begin(
        &mut self,
        width: usize,
        row: u32,
        how: Buffering,
        method: &'static str,
    ) -> Result<()> {
        self.emitted.clear();
        self.bounded = None;
        self.received = 0;
        (self.width, self.row, self.how, self.method) = (width, row, how, method);
        if how.intervals > 0 {
            let err = |e| buffer_error(method, e);
            let insertion = Insertion {
                oracle: Oracle::paper_for(how.opaque),
                opaque: how.opaque,
            };
            self.bounded = Some(Bounded {
                buf: BoundedBuffer::new(width, 1, how.intervals as usize, insertion)
                    .map_err(err)?,
                sent: IntervalCounts::new(width, 1).map_err(err)?,
            });
        }
        Ok(())
    }

    /// Sends interval `iv` to pixel `x` of the row. Errors: exact lists past the row's
    /// share of the memory budget ([`Error::MemoryBudget`]).
    pub(crate) fn push(&mut self, x: u32, iv: Interval<F, P>) -> Result<()> {
        let method = self.method;
        let err = |e| buffer_error(method, e);
        self.received += 1;
        match &mut self.bounded {
            Some(b) => {
                b.sent.count(x as usize).map_err(err)?;
                b.buf.insert(x as usize, 0, iv).map_err(err)?;
            }
            None => {
                if self.emitted.len() as u64 >= self.how.row_limit {
                    return Err(Error::MemoryBudget {
                        method: method.into(),
                        row: self.row,
                        bytes_per_interval: Self::BYTES_PER_INTERVAL as u64,
                        row_limit: self.how.row_limit,
                    });
                }
                self.emitted.push((x, iv));
            }
        }
        Ok(())
    }

    /// Sorts the row's exact lists (count, scan, place, per-pixel sort by ts) if it has
    /// them and calls `f(x, list, scratch)` for every pixel's list, left to right.
    pub(crate) fn finish(
        &mut self,
        mut f: impl FnMut(usize, &[Interval<F, P>], &mut Scratch<F>) -> Result<()>,
    ) -> Result<Counts> {
        let method = self.method;
        let mut counts = Counts::default();
        match &self.bounded {
            Some(b) => {
                for &c in b.sent.counts() {
                    counts.add(c);
                }
                for x in 0..self.width {
                    f(x, b.buf.pixel_index(x), &mut self.resolve)?;
                }
            }
            None => {
                self.lists
                    .rebuild(self.width, &self.emitted)
                    .map_err(|e| buffer_error(method, e))?;
                for x in 0..self.width {
                    counts.add(self.lists.count(x));
                }
                for x in 0..self.width {
                    f(x, self.lists.pixel(x), &mut self.resolve)?;
                }
            }
        }
        Ok(counts)
    }

    /// Intervals the row received so far.
    pub(crate) fn received(&self) -> u64 {
        self.received
    }
}

/// An interval buffer error: a row too large for the buffer is a limit of the method;
/// anything else (an interval or pixel the buffer rejects) is a bug in emission.
fn buffer_error(method: &str, e: interval_buffer::Error) -> Error {
    match e {
        interval_buffer::Error::TooManyIntervals { .. } | interval_buffer::Error::TooLarge => {
            Error::MethodNotApplicable {
                method: method.into(),
                reason: format!("interval buffer: {e}"),
            }
        }
        e => Error::internal("the interval buffer", e.to_string()),
    }
}

/// The resolve of one pixel's sorted list with a render's shader and settings.
pub(crate) struct Resolver<'a, F, S> {
    /// The shader of the payloads.
    pub shader: &'a S,
    /// The resolve settings ([`settings`]).
    pub settings: &'a Settings<F>,
    /// The method, for errors.
    pub method: &'static str,
}

impl<F: Real, S> Resolver<'_, F, S> {
    /// The colour of pixel `(x, y)` from its sorted `list`; `sink` sees every partition of
    /// the sweep.
    pub(crate) fn pixel<P>(
        &self,
        scratch: &mut Scratch<F>,
        list: &[Interval<F, P>],
        (x, y): (u32, u32),
        sink: impl FnMut(&Partition<F>),
    ) -> Result<Rgba<F>>
    where
        S: Shader<F, P>,
    {
        resolve::resolve_with(scratch, list, self.shader, self.settings, sink).map_err(|e| {
            Error::Resolve {
                method: self.method.into(),
                x,
                y,
                message: e.to_string(),
            }
        })
    }
}

/// One render of the chain: the primitives binned by bands of rows, the payloads, the
/// resolve and the buffering, shared by every row.
pub(crate) struct Rows<'a, F: Real, M, S> {
    /// The scene.
    pub scene: &'a PreparedScene,
    /// Every primitive.
    pub prims: &'a [Prim<F>],
    /// The primitives of each band of rows.
    pub bins: &'a Bins,
    /// The payload maker.
    pub mk: &'a M,
    /// The resolve.
    pub resolver: Resolver<'a, F, S>,
    /// The buffering.
    pub buffering: Buffering,
}

/// Working memory kept per thread of the current rayon pool across jobs. (`map_init` would
/// build one per job, and with one row per job every row would grow its buffers from
/// empty.)
struct PerThread<T> {
    slots: Vec<Mutex<T>>,
    make: fn() -> T,
}

impl<T> PerThread<T> {
    /// One `make()` per thread of the current pool.
    fn new(make: fn() -> T) -> Self {
        let slots = (0..rayon::current_num_threads().max(1))
            .map(|_| Mutex::new(make()))
            .collect();
        PerThread { slots, make }
    }

    /// `f` on the calling thread's slot; on a fresh `make()` when the thread is not one of
    /// the pool's or its slot is in use further up the same thread's stack (a job that
    /// waits on rayon may run another) or was poisoned by a panic.
    fn with<R>(&self, f: impl FnOnce(&mut T) -> R) -> R {
        let slot = rayon::current_thread_index().and_then(|i| self.slots.get(i));
        match slot.and_then(|m| m.try_lock().ok()) {
            Some(mut guard) => f(&mut guard),
            None => f(&mut (self.make)()),
        }
    }
}

/// One row's output: linear RGB per pixel and what its buffers held.
struct RowOut {
    pixels: Vec<[f32; 3]>,
    stats: IntervalStats,
}

impl<F: Real, M: MakePayload<F>, S: Shader<F, M::P> + Sync> Rows<'_, F, M, S> {
    /// Every row, in parallel: the image and what the buffers held (one progress step per
    /// row).
    pub(crate) fn render(&self, progress: &dyn Progress) -> Result<(Image, IntervalStats)> {
        let scene = self.scene;
        let scratch = PerThread::new(RowScratch::new);
        // Every pixel without intervals resolves to the same colour (the background over
        // the shutter): resolved once here instead of once per empty pixel. An error is
        // left to the pixels, which report it with their coordinates.
        let empty = self
            .resolver
            .pixel(&mut Scratch::new(), &[], (0, 0), |_| {})
            .ok()
            .map(rgb);
        let rows: Vec<RowOut> = (0..scene.height)
            .into_par_iter()
            // One row per job: rows cost very different amounts (a lit ball in a few
            // bands), and a thread that runs out of work can only steal whole jobs.
            .with_max_len(1)
            .map(|y| {
                let row = scratch.with(|scratch| self.row(y, scratch, empty));
                progress.advance(1);
                row
            })
            .collect::<Result<_>>()?;
        let mut stats = IntervalStats::default();
        let mut pixels = Vec::with_capacity(scene.width as usize * scene.height as usize);
        for row in rows {
            pixels.extend(row.pixels);
            let s = row.stats;
            stats.total += s.total;
            stats.max = stats.max.max(s.max);
            stats.covered += s.covered;
            stats.pixels += s.pixels;
        }
        let image = Image {
            width: scene.width,
            height: scene.height,
            pixels,
        };
        Ok((image, stats))
    }

    /// Emits, buffers and resolves row `y`: every primitive of the row's band emits its
    /// intervals once, in primitive order; they are buffered and each pixel is resolved
    /// from its sorted list, a pixel without intervals taking `empty` when it is known (the
    /// colour an empty list resolves to).
    fn row(
        &self,
        y: u32,
        scratch: &mut RowScratch<F, M::P>,
        empty: Option<[f32; 3]>,
    ) -> Result<RowOut> {
        let scene = self.scene;
        let w = scene.width as usize;
        let method = self.resolver.method;
        scratch.begin(w, y, self.buffering, method)?;
        for &i in self.bins.band(y) {
            let prim = self.prims.get(i as usize).ok_or_else(|| {
                Error::internal("the row pipeline", format!("primitive {i} out of range"))
            })?;
            emit(
                scene,
                prim,
                RowSpan::row(y, scene.width),
                self.mk,
                |x, iv| scratch.push(x as u32, iv),
            )?;
        }
        let total = scratch.received();
        let mut pixels = Vec::with_capacity(w);
        let counts = scratch.finish(|x, list, resolve| {
            let c = match empty {
                Some(c) if list.is_empty() => c,
                _ => rgb(self.resolver.pixel(resolve, list, (x as u32, y), |_| {})?),
            };
            pixels.push(c);
            Ok(())
        })?;
        let stats = IntervalStats {
            total,
            max: counts.max,
            covered: counts.covered,
            pixels: w as u64,
            culled: 0,
            clipped: 0,
        };
        Ok(RowOut { pixels, stats })
    }
}

/// A resolved colour as the image stores it: linear RGB in f32, non-finite channels 0.
fn rgb<F: Real>(c: Rgba<F>) -> [f32; 3] {
    [c.r, c.g, c.b].map(|v| v.to_f32().filter(|v| v.is_finite()).unwrap_or(0.0))
}

#[cfg(test)]
mod tests {
    use super::PerThread;

    /// Each pool thread gets its own slot, kept from job to job; a thread outside the pool
    /// and a nested use on the same thread get fresh values instead of blocking.
    #[test]
    fn per_thread_slots_are_reused_and_never_block() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| {
            let slots = PerThread::new(Vec::<u32>::new);
            assert_eq!(slots.slots.len(), 2);
            for job in 0..8 {
                slots.with(|v| v.push(job));
            }
            let kept: usize = slots.slots.iter().map(|m| m.lock().unwrap().len()).sum();
            assert_eq!(kept, 8, "every job's value stays in a slot");
            let nested = slots.with(|outer| {
                outer.push(100);
                slots.with(|inner| inner.len())
            });
            assert_eq!(nested, 0, "the nested use got a fresh value");
        });
        let outside = PerThread::new(|| vec![7u32]);
        outside.slots.iter().for_each(|m| m.lock().unwrap().clear());
        assert_eq!(
            outside.with(|v| v.len()),
            1,
            "not a pool thread: a fresh make()"
        );
    }
}
