//! Named hard cases for the interval buffers (issue 6).

mod common;

use common::Iv;
use interval_buffer::{
    AtomicIntervalCounts, BoundedBuffer, CompactInterval8, Error, Insertion, Interval,
    IntervalCounts, Oracle, PixelLists, Rgba,
};

fn red(z: f64) -> Rgba<f64> {
    Rgba::opaque(1.0, 0.0, z.fract())
}

fn iv(ts: f64, te: f64, z: f64) -> Iv {
    Interval::new(ts, te, z, 0.0, red(z))
}

fn bounded(k: usize, opaque: bool) -> BoundedBuffer<f64, Rgba<f64>> {
    BoundedBuffer::new(1, 1, k, Insertion::paper(opaque)).expect("buffer")
}

#[test]
fn equal_ts_intervals_keep_insertion_order() {
    for opaque in [false, true] {
        let mut b = bounded(8, opaque);
        for z in [3.0, 1.0, 2.0] {
            b.insert(0, 0, Interval::new(0.25, 0.5 + z / 10.0, z, 0.0, red(z)))
                .expect("insert");
        }
        let zs: Vec<f64> = b.pixel(0, 0).iter().map(|i| i.z).collect();
        assert_eq!(zs, vec![3.0, 1.0, 2.0], "opaque = {opaque}");
    }
    // Exact: the segmented sort is stable for equal ts.
    let mut c = IntervalCounts::new(1, 1).expect("counts");
    c.count_n(0, 3).expect("count");
    let mut f = c.finish::<f64, Rgba<f64>>().expect("scan");
    for z in [3.0, 1.0, 2.0] {
        f.push(0, iv(0.25, 0.75, z)).expect("push");
    }
    let e = f.finish().expect("finish");
    assert_eq!(
        e.pixel(0, 0).iter().map(|i| i.z).collect::<Vec<_>>(),
        vec![3.0, 1.0, 2.0]
    );
}

#[test]
fn zero_length_intervals_kept_when_transparent_dropped_when_opaque() {
    let mut t = bounded(4, false);
    let mut o = bounded(4, true);
    for b in [&mut t, &mut o] {
        b.insert(0, 0, iv(0.5, 0.5, 1.0)).expect("insert");
        b.insert(0, 0, iv(0.2, 0.6, 2.0)).expect("insert");
    }
    assert_eq!(t.pixel(0, 0).len(), 2);
    assert_eq!(o.pixel(0, 0).len(), 1);
    assert_eq!(o.pixel(0, 0)[0].z, 2.0);
    // Merging two zero-length intervals blends half-half and stays zero length.
    let mut k1 = bounded(1, false);
    k1.insert(0, 0, iv(0.5, 0.5, 1.0)).expect("insert");
    k1.insert(0, 0, iv(0.5, 0.5, 3.0)).expect("insert");
    let m = k1.pixel(0, 0)[0];
    assert_eq!((m.ts, m.te, m.z), (0.5, 0.5, 2.0));
}

#[test]
fn intervals_touching_at_one_time_are_not_clipped() {
    let mut b = bounded(4, true);
    b.insert(0, 0, iv(0.0, 0.5, 1.0)).expect("insert");
    // Behind, but only touching at t = 0.5: nothing to clip.
    let o = b.insert(0, 0, iv(0.5, 1.0, 5.0)).expect("insert");
    assert!(o.stored && !o.clipped);
    let o = b.insert(0, 0, iv(-0.5, 0.0, 5.0)).expect("insert");
    assert!(o.stored && !o.clipped);
    assert_eq!(b.pixel(0, 0).len(), 3);
    assert_eq!(b.pixel(0, 0)[2], iv(0.5, 1.0, 5.0));
}

#[test]
fn identical_depth_resolves_less_equal_later_wins() {
    let mut b = bounded(4, true);
    b.insert(
        0,
        0,
        Interval::new(0.2, 0.6, 2.0, 1.0, Rgba::opaque(1.0, 0.0, 0.0)),
    )
    .expect("insert");
    // Same depth function, inside the first: not occluded (not strictly nearer), kept.
    let o = b
        .insert(
            0,
            0,
            Interval::new(0.3, 0.5, 2.1, 1.0, Rgba::opaque(0.0, 1.0, 0.0)),
        )
        .expect("insert");
    assert!(o.stored && !o.clipped && o.removed == 0);
    // Same depth function over the whole first interval: the later one wins, both older go.
    let o = b
        .insert(
            0,
            0,
            Interval::new(0.1, 0.7, 1.9, 1.0, Rgba::opaque(0.0, 0.0, 1.0)),
        )
        .expect("insert");
    assert_eq!(o.removed, 2);
    assert_eq!(b.pixel(0, 0).len(), 1);
    assert_eq!(b.pixel(0, 0)[0].payload.b, 1.0);
}

#[test]
fn capacity_one_merges_everything_into_one_span() {
    let mut b = bounded(1, false);
    let mut r = common::rng(1);
    let ivs = common::random_intervals(&mut r, 50);
    for i in &ivs {
        b.insert(0, 0, *i).expect("insert");
        assert_eq!(b.pixel(0, 0).len(), 1);
    }
    let m = b.pixel(0, 0)[0];
    let min_ts = ivs.iter().map(|i| i.ts).fold(f64::INFINITY, f64::min);
    let max_te = ivs.iter().map(|i| i.te).fold(0.0, f64::max);
    assert_eq!((m.ts, m.te), (min_ts, max_te));
    assert!(m.is_valid());
    assert!(BoundedBuffer::<f64, Rgba<f64>>::new(1, 1, 0, Insertion::paper(true)).is_err());
}

fn deep() -> bool {
    std::env::var("MBLUR_DEEP").is_ok_and(|v| v == "1")
}

#[test]
fn thousand_intervals_in_one_pixel_bounded_never_grows() {
    let mut r = common::rng(2);
    // The deep run pushes 20 000 intervals into the pixel.
    let ivs = common::random_intervals(&mut r, if deep() { 20_000 } else { 1000 });
    for k in [4, 8, 16, 64] {
        let mut b = bounded(k, false);
        let bytes = b.bytes_per_pixel();
        for i in &ivs {
            b.insert(0, 0, *i).expect("insert");
        }
        let px = b.pixel(0, 0);
        assert_eq!(px.len(), k);
        assert_eq!(b.bytes_per_pixel(), bytes);
        assert!(px.windows(2).all(|w| w[0].ts <= w[1].ts));
        // Merges never lose the covered extent.
        let min_ts = ivs.iter().map(|i| i.ts).fold(f64::INFINITY, f64::min);
        let max_te = ivs.iter().map(|i| i.te).fold(0.0, f64::max);
        assert_eq!(px[0].ts, min_ts);
        assert_eq!(px.iter().map(|i| i.te).fold(0.0, f64::max), max_te);
    }
}

#[test]
fn thousand_intervals_in_one_pixel_exact_keeps_all_sorted() {
    let mut r = common::rng(3);
    let n = if deep() { 20_000 } else { 1000 };
    let ivs = common::random_intervals(&mut r, n);
    let atomic = AtomicIntervalCounts::new(3, 1).expect("counts");
    for _ in &ivs {
        atomic.count(1).expect("count");
    }
    let mut f = atomic
        .into_counts()
        .expect("counts")
        .finish::<f64, Rgba<f64>>()
        .expect("scan");
    for i in &ivs {
        f.push(1, *i).expect("push");
    }
    let e = f.finish().expect("finish");
    let px = e.pixel(1, 0);
    assert_eq!(px.len(), n);
    assert!(px.windows(2).all(|w| w[0].ts <= w[1].ts));
    assert_eq!(e.offsets(), &[0, 0, n as u32, n as u32]);
    // Same colour as the unsorted list (brute-force reference).
    let a = common::resolve_opaque(px, [0.0; 3], 2048);
    let b = common::resolve_opaque(&ivs, [0.0; 3], 2048);
    assert!(common::colour_error(a, b) < 1e-12);
}

#[test]
fn fence_pattern_paper_oracle_fails_below_the_period_count() {
    // Gribel 2010, Fig. 11: a square wave of foreground (white) and background (brown).
    let bg = Rgba::opaque(0.4, 0.3, 0.2);
    let fence = common::fence(20, bg);
    let truth = common::resolve_opaque(&fence, [0.0; 3], 8000);
    // Half white, half background.
    assert!(common::colour_error(truth, [0.7, 0.65, 0.6]) < 1e-3);
    let run = |k: usize, oracle: Oracle<f64>| {
        let mut b = BoundedBuffer::new(
            1,
            1,
            k,
            Insertion {
                oracle,
                opaque: true,
            },
        )
        .expect("buffer");
        for i in &fence {
            b.insert(0, 0, *i).expect("insert");
        }
        common::colour_error(common::resolve_blend(b.pixel(0, 0), [0.0; 3], 8000), truth)
    };
    // Enough slots: exact.
    assert!(run(32, Oracle::paper()) < 1e-9);
    // 16 slots: the paper's oracle merges foreground across the gaps and loses the mix.
    assert!(run(16, Oracle::paper()) > 0.05);
    // The coverage-preserving merge keeps the mix even at K = 4.
    assert!(run(4, Oracle::paper().with_keep_coverage(true)) < 1e-3);
}

#[test]
fn exact_offsets_past_u32_max_are_a_clear_error() {
    let mut c = IntervalCounts::new(3, 1).expect("counts");
    c.count_n(0, u32::MAX - 1).expect("count");
    c.count_n(1, 2).expect("count");
    let err = c.finish::<f32, Rgba<f32>>().err();
    assert_eq!(
        err,
        Some(Error::TooManyIntervals {
            total: u64::from(u32::MAX) + 1
        })
    );
    assert!(err.is_some_and(|e| e.to_string().contains("u32")));
}

#[test]
fn exact_fill_mismatch_is_reported() {
    let mut c = IntervalCounts::new(2, 1).expect("counts");
    c.count(0).expect("count");
    let mut f = c.finish::<f64, Rgba<f64>>().expect("scan");
    assert!(matches!(
        f.push(1, iv(0.0, 1.0, 1.0)),
        Err(Error::PushOverCount {
            pixel: 1,
            counted: 0
        })
    ));
    assert!(matches!(
        f.push(2, iv(0.0, 1.0, 1.0)),
        Err(Error::PixelOutOfRange { .. })
    ));
    assert_eq!(
        f.finish().err(),
        Some(Error::CountMismatch {
            pixel: 0,
            counted: 1,
            pushed: 0
        })
    );
}

#[test]
fn non_finite_input_is_an_error_everywhere() {
    let bad = Interval::new(0.1, f64::NAN, 1.0, 0.0, red(1.0));
    let rev = iv(0.6, 0.5, 1.0);
    let mut b = bounded(2, true);
    assert_eq!(b.insert(0, 0, bad), Err(Error::InvalidInterval));
    assert_eq!(b.insert(0, 0, rev), Err(Error::InvalidInterval));
    assert!(b.pixel(0, 0).is_empty());
    let mut c = IntervalCounts::new(1, 1).expect("counts");
    c.count(0).expect("count");
    let mut f = c.finish::<f64, Rgba<f64>>().expect("scan");
    assert_eq!(f.push(0, bad), Err(Error::InvalidInterval));
    assert_eq!(
        CompactInterval8::from_interval(&bad),
        Err(Error::InvalidInterval)
    );
}

#[test]
fn extreme_magnitudes_merge_stays_finite() {
    let mut b = BoundedBuffer::new(1, 1, 1, Insertion::paper(false)).expect("buffer");
    let big = f32::MAX / 2.0;
    b.insert(
        0,
        0,
        Interval::new(0.0_f32, 0.5, big, big, Rgba::opaque(1.0, 0.0, 0.0)),
    )
    .expect("insert");
    b.insert(
        0,
        0,
        Interval::new(0.5_f32, 1.0, -big, -big, Rgba::opaque(0.0, 1.0, 0.0)),
    )
    .expect("insert");
    b.insert(
        0,
        0,
        Interval::new(0.9_f32, 1.0, big, -big, Rgba::opaque(0.0, 1.0, 0.0)),
    )
    .expect("insert");
    let m = b.pixel(0, 0)[0];
    assert!(m.is_valid() && m.payload.r.is_finite());
    assert_eq!((m.ts, m.te), (0.0, 1.0));
}

#[test]
fn textured_payload_is_clipped_with_interpolated_uv() {
    use interval_buffer::Textured;
    let t = |uv0: [f64; 2], uv1: [f64; 2], alpha: f64| Textured {
        uv_start: uv0,
        uv_end: uv1,
        material: 1,
        alpha,
    };
    let mut b = BoundedBuffer::new(1, 1, 4, Insertion::paper(true)).expect("buffer");
    b.insert(
        0,
        0,
        Interval::new(0.0, 0.5, 1.0, 0.0, t([0.0; 2], [1.0; 2], 1.0)),
    )
    .expect("insert");
    // Behind the first over [0.25, 0.5]: clipped to [0.5, 1.0], uv re-interpolated.
    let o = b
        .insert(
            0,
            0,
            Interval::new(0.25, 1.0, 2.0, 0.0, t([0.0, 0.0], [3.0, 6.0], 1.0)),
        )
        .expect("insert");
    assert!(o.clipped);
    let c = b.pixel(0, 0)[1];
    assert_eq!((c.ts, c.te), (0.5, 1.0));
    assert!(
        (c.payload.uv_start[0] - 1.0).abs() < 1e-12 && (c.payload.uv_start[1] - 2.0).abs() < 1e-12
    );
    assert_eq!(c.payload.uv_end, [3.0, 6.0]);
    // A transparent interval never occludes: an interval behind it is kept whole.
    let mut b = BoundedBuffer::new(1, 1, 4, Insertion::paper(true)).expect("buffer");
    b.insert(
        0,
        0,
        Interval::new(0.0, 1.0, 1.0, 0.0, t([0.0; 2], [1.0; 2], 0.5)),
    )
    .expect("insert");
    let o = b
        .insert(
            0,
            0,
            Interval::new(0.2, 0.4, 2.0, 0.0, t([0.0; 2], [1.0; 2], 1.0)),
        )
        .expect("insert");
    assert!(o.stored && !o.clipped);
    assert_eq!(b.pixel(0, 0).len(), 2);
}

#[test]
fn value_stability_seeded_meshes_k4() {
    let mut r = common::rng(42);
    let ivs = common::moving_meshes(&mut r);
    let mut b = bounded(4, true);
    for i in &ivs {
        b.insert(0, 0, *i).expect("insert");
    }
    let got: Vec<[f64; 4]> = b
        .pixel(0, 0)
        .iter()
        .map(|i| [i.ts, i.te, i.z, i.k])
        .collect();
    assert_eq!(ivs.len(), 98);
    let pinned = [
        [
            0.16737468322301968,
            0.6477913885663902,
            6.21936146984519,
            2.8228579064454937,
        ],
        [
            0.22960512490714238,
            0.32130956225448576,
            5.267205472047863,
            -2.9426808583518405,
        ],
        [
            0.30829444536306183,
            0.6005266566970977,
            5.4722261574149265,
            -1.9813380624223695,
        ],
        [
            0.6005266566970977,
            0.8780700705313514,
            5.043592977521804,
            -1.7688898177434225,
        ],
    ];
    assert_eq!(got.len(), pinned.len());
    for (g, p) in got.iter().zip(&pinned) {
        for (a, b) in g.iter().zip(p) {
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{g:?} vs {p:?}");
        }
    }
}

/// f32 times in one pixel of the exact lists (which sort f32 times on one-word keys):
/// negative times, -0 and +0, and ties come out in the stable order by time, equal times
/// (both zeros included) in batch order, as a stable sort of the batch gives them.
#[test]
fn f32_exact_lists_order_negative_times_signed_zeros_and_ties() {
    let t = [0.5_f32, -0.25, 0.0, 0.5, -0.0, -0.25, 1.0, 0.0, 0.5];
    let batch: Vec<(u32, Interval<f32, f32>)> = t
        .iter()
        .enumerate()
        .map(|(i, &ts)| (0, Interval::new(ts, 1.0, 1.0, 0.0, i as f32)))
        .collect();
    let mut lists = PixelLists::new();
    lists.rebuild(1, &batch).expect("rebuild");
    let mut want: Vec<_> = batch.iter().map(|(_, iv)| *iv).collect();
    want.sort_by(|a, b| a.ts.partial_cmp(&b.ts).expect("finite"));
    let tags = |v: &[Interval<f32, f32>]| v.iter().map(|iv| iv.payload).collect::<Vec<_>>();
    assert_eq!(tags(lists.pixel(0)), tags(&want));
    assert_eq!(
        tags(lists.pixel(0)),
        [1.0, 5.0, 2.0, 4.0, 7.0, 0.0, 3.0, 8.0, 6.0]
    );
}
