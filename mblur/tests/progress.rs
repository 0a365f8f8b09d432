//! Every method reports its progress in real units: it announces a total and a unit once,
//! then advances by exactly that total (counted against what the method does: the image's
//! rows for the interval chain, the sub-frames for accum, the 16-row bands for ewa).

use std::sync::Mutex;

use integration_tests::builtin;
use mblur::{AccumOptions, Method, MethodOptions, NoProgress, Progress, StochasticOptions};

/// Records the announced total and unit and the steps advanced.
#[derive(Default)]
struct Recorder(Mutex<(Vec<(u64, &'static str)>, u64)>);

impl Progress for Recorder {
    fn start(&self, total: u64, unit: &'static str) {
        self.0.lock().unwrap().0.push((total, unit));
    }
    fn advance(&self, steps: u64) {
        self.0.lock().unwrap().1 += steps;
    }
    fn finish(&self) {}
}

fn progress_of(scene: &str, w: u32, h: u32, options: MethodOptions) -> ((u64, &'static str), u64) {
    let p = builtin(scene, w, h);
    let r = Recorder::default();
    mblur::render(&p, &options, &r).unwrap();
    let (starts, advanced) = r.0.into_inner().unwrap();
    assert_eq!(starts.len(), 1, "{scene}: one announced total");
    (starts[0], advanced)
}

#[test]
fn each_method_counts_its_own_unit_and_finishes_at_its_total() {
    let (w, h) = (40, 24);
    let rows = progress_of("billiards", w, h, MethodOptions::defaults(Method::Analytic));
    assert_eq!(rows, ((u64::from(h), "rows"), u64::from(h)));
    let prism = progress_of("billiards", w, h, MethodOptions::defaults(Method::Prism));
    assert_eq!(prism, ((u64::from(h), "rows"), u64::from(h)));
    let accum = progress_of(
        "billiards",
        w,
        h,
        MethodOptions::Accum(AccumOptions {
            times: Some(7),
            jitter: None,
            ..Default::default()
        }),
    );
    assert_eq!(accum, ((7, "sub-frames"), 7));
    let ewa = progress_of("splat-ball", w, h, MethodOptions::defaults(Method::Ewa));
    assert_eq!(
        ewa,
        (
            (u64::from(h.div_ceil(16)), "bands of 16 rows"),
            u64::from(h.div_ceil(16))
        )
    );
    let (start, advanced) = progress_of(
        "billiards",
        w,
        h,
        MethodOptions::Stochastic(StochasticOptions {
            spp: Some(4),
            ..Default::default()
        }),
    );
    assert_eq!(start.1, "raster stages");
    assert_eq!(advanced, start.0);
    let still = progress_of("static", w, h, MethodOptions::defaults(Method::Analytic));
    assert_eq!(still, ((1, "static frames"), 1));
    // The default render: one step per sample position.
    let n = u64::from(mblur::aa::AUTO_SAMPLES);
    let default = progress_of("static", w, h, MethodOptions::default());
    assert_eq!(default, ((n, "sample positions"), n));
    // Rendering without a progress receiver is the same render.
    let p = builtin("billiards", w, h);
    let a = mblur::render(&p, &MethodOptions::defaults(Method::Analytic), &NoProgress).unwrap();
    let b = mblur::render(
        &p,
        &MethodOptions::defaults(Method::Analytic),
        &Recorder::default(),
    )
    .unwrap();
    assert_eq!(a.image, b.image);
}
