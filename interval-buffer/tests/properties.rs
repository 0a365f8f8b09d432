//! Property tests of the bounded and exact strategies, the merge and the compact form.
//! Case count from `PROPTEST_CASES`.

mod common;

use common::Iv;
use interval_buffer::{
    BoundedBuffer, CompactInterval8, CompactInterval16, Insertion, Interval, IntervalCounts,
    Oracle, PixelLists, Rgba, merge_alpha, merge_eq20,
};
use proptest::prelude::*;

prop_compose! {
    fn interval()(ts in 0.0..1.0_f64, len in prop_oneof![Just(0.0), 0.0..0.5_f64],
                  z in 0.1..10.0_f64, k in -5.0..5.0_f64,
                  r in 0.0..1.0_f64, g in 0.0..1.0_f64, b in 0.0..1.0_f64) -> Iv {
        Interval::new(ts, (ts + len).min(1.0), z, k, Rgba::opaque(r, g, b))
    }
}

fn list(max: usize) -> impl Strategy<Value = Vec<Iv>> {
    proptest::collection::vec(interval(), 0..max)
}

/// Independent reference of bounded insertion without opaque optimisations: a Vec, an
/// upper-bound insert, then one merge of the oracle's best pair when over capacity.
fn reference_insert(v: &mut Vec<Iv>, iv: Iv, k: usize, oracle: &Oracle<f64>) {
    let p = v.iter().take_while(|e| e.ts <= iv.ts).count();
    v.insert(p, iv);
    if v.len() > k {
        let mut best = (0, 0, f64::INFINITY);
        for i in 0..v.len() {
            for j in i + 1..v.len().min(i + oracle.window + 1) {
                let o = oracle.cost(&v[i], &v[j]);
                if o < best.2 {
                    best = (i, j, o);
                }
            }
        }
        let m = oracle.merge_in_list(v.len(), |q| &v[q], best.0, best.1);
        v[best.0] = m;
        v.remove(best.1);
    }
}

fn nearest(list: &[Iv], t: f64) -> Option<(f64, f64, Rgba<f64>)> {
    // (nearest depth, second-nearest depth, colour); later entries win exact ties.
    let mut best: Option<(f64, f64, Rgba<f64>)> = None;
    for iv in list.iter().filter(|iv| iv.contains_time(t)) {
        let d = iv.depth_at(t);
        best = Some(match best {
            None => (d, f64::INFINITY, iv.payload),
            Some((bd, _, _)) if d <= bd => (d, bd, iv.payload),
            Some((bd, second, c)) => (bd, second.min(d), c),
        });
    }
    best
}

proptest! {
    #[test]
    fn insertion_keeps_sorted_and_at_most_k(ivs in list(60), k in 1usize..12, opaque in any::<bool>()) {
        let mut buf = BoundedBuffer::new(1, 1, k, Insertion::paper(opaque)).unwrap();
        for (n, iv) in ivs.iter().enumerate() {
            buf.insert(0, 0, *iv).unwrap();
            let px = buf.pixel(0, 0);
            prop_assert!(px.len() <= k);
            if !opaque {
                prop_assert_eq!(px.len(), (n + 1).min(k));
            }
            prop_assert!(px.windows(2).all(|w| w[0].ts <= w[1].ts));
            prop_assert!(px.iter().all(Interval::is_valid));
        }
    }

    #[test]
    fn insertion_f32_keeps_sorted_and_extent(ivs in list(60), k in 1usize..12, opaque in any::<bool>()) {
        let f = |i: &Iv| Interval::new(i.ts as f32, i.te as f32, i.z as f32, i.k as f32,
            Rgba::opaque(i.payload.r as f32, i.payload.g as f32, i.payload.b as f32));
        let mut buf = BoundedBuffer::<f32, Rgba<f32>>::new(1, 1, k, Insertion::paper(opaque)).unwrap();
        for iv in &ivs {
            buf.insert(0, 0, f(iv)).unwrap();
        }
        let px = buf.pixel(0, 0);
        prop_assert!(px.len() <= k && px.windows(2).all(|w| w[0].ts <= w[1].ts));
        prop_assert!(px.iter().all(|i| i.is_valid() && i.payload.r.is_finite()));
        if !opaque && !ivs.is_empty() {
            // Merges keep the first start and the last end exactly.
            let min_ts = ivs.iter().map(|i| i.ts as f32).fold(f32::INFINITY, f32::min);
            let max_te = ivs.iter().map(|i| i.te as f32).fold(0.0, f32::max);
            prop_assert_eq!(px[0].ts, min_ts);
            prop_assert_eq!(px.iter().map(|i| i.te).fold(0.0, f32::max), max_te);
        }
    }

    #[test]
    fn bounded_matches_vec_reference(ivs in list(40), k in 1usize..10, window in 1usize..5,
                                     cover in any::<bool>()) {
        let oracle = Oracle::paper().with_window(window).with_keep_coverage(cover);
        let how = Insertion { oracle, opaque: false };
        let mut buf = BoundedBuffer::new(2, 1, k, how).unwrap();
        let mut v = Vec::new();
        for iv in &ivs {
            buf.insert(1, 0, *iv).unwrap();
            reference_insert(&mut v, *iv, k, &oracle);
            prop_assert_eq!(buf.pixel(1, 0), &v[..]);
        }
        prop_assert!(buf.pixel(0, 0).is_empty());
    }

    #[test]
    fn merge_keeps_ts_and_max_te(a in interval(), b in interval()) {
        let (a, b) = if a.ts <= b.ts { (a, b) } else { (b, a) };
        let m = merge_eq20(&a, &b);
        prop_assert_eq!(m.ts, a.ts);
        prop_assert_eq!(m.te, a.te.max(b.te));
        let alpha = merge_alpha(&a, &b);
        prop_assert!((0.0..=1.0).contains(&alpha));
        // alpha is the duration weight of b.
        if a.duration() + b.duration() > 0.0 {
            let w = b.duration() / (a.duration() + b.duration());
            prop_assert!((alpha - w).abs() <= 1e-15);
        }
        // Merged slope lies between the inputs; depth at a.ts between the two depths there.
        prop_assert!(m.k >= a.k.min(b.k) - 1e-12 && m.k <= a.k.max(b.k) + 1e-12);
        let (za, zb) = (a.z, b.depth_at(a.ts));
        prop_assert!(m.z >= za.min(zb) - 1e-9 && m.z <= za.max(zb) + 1e-9);
        // Equal lengths blend half-half.
        let b2 = Interval { te: b.ts + a.duration(), ..b };
        if b2.duration() == a.duration() {
            prop_assert_eq!(merge_alpha(&a, &b2), 0.5);
        }
    }

    #[test]
    fn merge_f32_tracks_f64(a in interval(), b in interval()) {
        let (a, b) = if a.ts <= b.ts { (a, b) } else { (b, a) };
        let m = merge_eq20(&a, &b);
        let f = |i: &Iv| Interval::new(i.ts as f32, i.te as f32, i.z as f32, i.k as f32,
            Rgba::opaque(i.payload.r as f32, i.payload.g as f32, i.payload.b as f32));
        let m32 = merge_eq20(&f(&a), &f(&b));
        let tol = |x: f64| 1e-5 * (1.0 + x.abs()) + 1e-5 * (a.z.abs() + b.z.abs() + a.k.abs() + b.k.abs());
        prop_assert_eq!(m32.ts, a.ts as f32);
        prop_assert!((f64::from(m32.z) - m.z).abs() <= tol(m.z));
        prop_assert!((f64::from(m32.k) - m.k).abs() <= tol(m.k));
    }

    #[test]
    fn exact_returns_the_inserted_multiset(
        items in proptest::collection::vec((0usize..12, interval()), 0..80),
        parallel in any::<bool>()
    ) {
        let (w, h) = (4, 3);
        let mut counts = IntervalCounts::new(w, h).unwrap();
        for (p, _) in &items {
            counts.count(*p).unwrap();
        }
        let mut fill = counts.finish::<f64, Rgba<f64>>().unwrap();
        if parallel {
            use rayon::prelude::*;
            fill.par_rows_mut().for_each(|mut row| {
                let y = row.y();
                for (p, iv) in items.iter().filter(|(p, _)| p / w == y) {
                    row.push(p % w, *iv).unwrap();
                }
            });
        } else {
            for (p, iv) in &items {
                fill.push(*p, *iv).unwrap();
            }
        }
        let buf = fill.finish().unwrap();
        let key = |i: &Iv| [i.ts, i.te, i.z, i.k, i.payload.r, i.payload.g, i.payload.b].map(f64::to_bits);
        for p in 0..w * h {
            let got = buf.pixel_index(p);
            prop_assert!(got.windows(2).all(|x| x[0].ts <= x[1].ts));
            let mut a: Vec<_> = got.iter().map(key).collect();
            let mut b: Vec<_> = items.iter().filter(|(q, _)| *q == p).map(|(_, i)| key(i)).collect();
            a.sort();
            b.sort();
            prop_assert_eq!(a, b);
        }
        prop_assert_eq!(buf.intervals().len(), items.len());
    }

    #[test]
    fn exact_sort_is_stable_on_long_segments(
        items in proptest::collection::vec((0u8..8, interval()), 0..200)
    ) {
        // Few distinct ts values: many ties, and segments past the key-sort threshold.
        let ivs: Vec<Iv> = items.iter().map(|(t, iv)| Interval { ts: f64::from(*t) / 8.0, te: 1.0, ..*iv }).collect();
        let mut counts = IntervalCounts::new(2, 1).unwrap();
        counts.count_n(1, ivs.len() as u32).unwrap();
        let mut fill = counts.finish::<f64, Rgba<f64>>().unwrap();
        for iv in &ivs {
            fill.push(1, *iv).unwrap();
        }
        let buf = fill.finish().unwrap();
        let mut expect = ivs.clone();
        expect.sort_by(|a, b| a.ts.total_cmp(&b.ts));
        prop_assert_eq!(buf.pixel(1, 0), &expect[..]);
    }

    #[test]
    fn pixel_lists_equal_the_exact_buffer_in_f64_and_f32(
        batches in proptest::collection::vec(
            proptest::collection::vec((0u32..6, 0u8..6, interval()), 0..120), 1..4)
    ) {
        // Several batches through one reused PixelLists; times on a coarse grid for many
        // ties (stable order), each batch against count -> fill -> finish (the reference
        // path of Rønnow 2021 §4.1-4.2) and against a stable sort of the pixel's
        // insertions.
        let mut lists = PixelLists::new();
        let mut lists32 = PixelLists::new();
        for batch in &batches {
            let pairs: Vec<(u32, Iv)> = batch
                .iter()
                .map(|(p, t, iv)| {
                    let ts = f64::from(*t) / 8.0;
                    (*p, Interval { ts, te: iv.te.max(ts), ..*iv })
                })
                .collect();
            let pixels = 6;
            let mut counts = IntervalCounts::new(pixels, 1).unwrap();
            for (p, _) in &pairs {
                counts.count(*p as usize).unwrap();
            }
            let mut fill = counts.finish::<f64, Rgba<f64>>().unwrap();
            for (p, iv) in &pairs {
                fill.push(*p as usize, *iv).unwrap();
            }
            let exact = fill.finish().unwrap();
            lists.rebuild(pixels, &pairs).unwrap();
            let to32 = |iv: &Iv| Interval::new(iv.ts as f32, iv.te as f32, iv.z as f32, iv.k as f32, iv.payload.r as f32);
            let pairs32: Vec<(u32, Interval<f32, f32>)> = pairs.iter().map(|(p, iv)| (*p, to32(iv))).collect();
            lists32.rebuild(pixels, &pairs32).unwrap();
            prop_assert_eq!(lists.len(), pairs.len());
            for p in 0..pixels {
                prop_assert_eq!(lists.pixel(p), exact.pixel_index(p));
                let mut expect32: Vec<_> = pairs32.iter().filter(|(q, _)| *q as usize == p).map(|(_, iv)| *iv).collect();
                expect32.sort_by(|a, b| a.ts.total_cmp(&b.ts));
                prop_assert_eq!(lists32.pixel(p), &expect32[..]);
            }
        }
    }

    #[test]
    fn opaque_optimisations_keep_the_visible_colour(ivs in list(24), ts in proptest::collection::vec(0.0..1.0_f64, 32)) {
        // K large enough that nothing is compressed: only the Fig. 7 optimisations act.
        let mut buf = BoundedBuffer::new(1, 1, 32, Insertion::paper(true)).unwrap();
        for iv in &ivs {
            buf.insert(0, 0, *iv).unwrap();
        }
        let opt = buf.pixel(0, 0);
        for &t in &ts {
            let full = nearest(&ivs, t);
            let got = nearest(opt, t);
            match full {
                None => prop_assert!(got.is_none()),
                Some((d, second, c)) => {
                    // Skip near-ties, where rounding of a clipped interval's depth may flip the order.
                    if second - d > 1e-9 * (1.0 + d.abs()) {
                        let g = got.map(|g| g.2);
                        prop_assert_eq!(g, Some(c), "t = {}", t);
                    }
                }
            }
        }
    }

    #[test]
    fn trace_events_chain(ivs in list(30), k in 1usize..6) {
        let mut buf = BoundedBuffer::new(3, 2, k, Insertion::paper(false)).unwrap();
        buf.trace_pixel_index(4);
        for iv in &ivs {
            buf.insert(1, 1, *iv).unwrap();
            buf.insert(0, 0, *iv).unwrap();
        }
        let trace = buf.take_trace().unwrap();
        prop_assert_eq!(trace.events.len(), ivs.len());
        for w in trace.events.windows(2) {
            prop_assert_eq!(&w[0].after, &w[1].before);
        }
        if let Some(last) = trace.events.last() {
            prop_assert_eq!(&last.after[..], buf.pixel(1, 1));
        }
        prop_assert_eq!(trace.compression_steps().count(), ivs.len().saturating_sub(k));
    }

    #[test]
    fn compact_round_trip_error_is_bounded(iv in interval(), t in 0.0..1.0_f64) {
        let c16 = CompactInterval16::from_interval(&iv).unwrap();
        let c8 = CompactInterval8::from_interval(&iv).unwrap();
        let b16: Iv = c16.to_interval();
        let b8: Iv = c8.to_interval();
        prop_assert!((b16.ts - iv.ts).abs() <= 0.5 / 65535.0 + 1e-12);
        prop_assert!((b8.te - iv.te).abs() <= 0.5 / 255.0 + 1e-12);
        prop_assert!(b8.ts <= b8.te);
        // f16 slope: relative error 2^-11; f32 depth: relative 2^-24; over |t - ts| <= 1.
        let bound = iv.k.abs() * 2f64.powi(-11) + 1e-6 * (1.0 + iv.z.abs() + iv.k.abs());
        prop_assert!((b16.depth_at(t) - iv.depth_at(t)).abs() <= bound);
        prop_assert!((b16.payload.r - iv.payload.r).abs() <= 0.5 / 255.0 + 1e-12);
    }
}
