//! Value stability: the counters and the sample buffer of a fixed seeded scene are pinned,
//! so any change of the sample pattern, the coverage rule or the traversal shows up here.

use raster_hier::{EdgeTest, RasterConfig, SampleBuffer, Traversal, benchmark_scene, rasterise};

fn fnv(ids: &[u32]) -> u64 {
    ids.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &v| {
        (h ^ u64::from(v)).wrapping_mul(0x100_0000_01b3)
    })
}

#[test]
fn pinned_scene_counters_and_buffer_hash() {
    let tris = benchmark_scene::<f32>(60, 12.0, 1.0, 64, 48, 99);
    let mut buf = SampleBuffer::<f32>::new(64, 48, 4, 4, 16, 4, 5).expect("valid");
    let c = rasterise(
        &mut buf,
        &tris,
        &RasterConfig::new(Traversal::Our(EdgeTest::LinearisedSetup)),
    )
    .expect("valid");
    let got = (
        c.samples_written,
        c.sample_tests,
        c.tile_tests,
        fnv(buf.ids()),
    );
    eprintln!("{got:?}");
    assert_eq!(got, PINNED);
}

const PINNED: (u64, u64, u64, u64) = (8106, 34456, 1886, 3_418_645_750_207_619_074);

#[test]
fn result_does_not_depend_on_thread_count() {
    let tris = benchmark_scene::<f32>(120, 10.0, 2.0, 96, 64, 4);
    let render = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| {
            let mut buf = SampleBuffer::<f32>::new(96, 64, 8, 4, 16, 4, 2).expect("valid");
            let c = rasterise(
                &mut buf,
                &tris,
                &RasterConfig::new(Traversal::Our(EdgeTest::Exact)),
            )
            .expect("valid");
            (
                buf.ids().to_vec(),
                buf.depths().iter().map(|d| d.to_bits()).collect::<Vec<_>>(),
                c,
            )
        })
    };
    let (a, b) = (render(1), render(3));
    assert_eq!(a, b);
    assert!(a.2.samples_written > 1000);
}

/// The same scene with [`RasterConfig::fine`] (levels down to single pixels): the buffer is
/// the pinned one bit for bit (levels never change the image), and the counters of the
/// finer traversal are pinned too.
#[test]
fn pinned_scene_with_pixel_levels_same_buffer() {
    let tris = benchmark_scene::<f32>(60, 12.0, 1.0, 64, 48, 99);
    let mut buf = SampleBuffer::<f32>::new(64, 48, 4, 4, 16, 4, 5).expect("valid");
    let c = rasterise(&mut buf, &tris, &RasterConfig::fine()).expect("valid");
    let got = (c.sample_tests, c.tile_tests);
    eprintln!("{got:?}");
    assert_eq!((c.samples_written, fnv(buf.ids())), (PINNED.0, PINNED.3));
    assert_eq!(got, PINNED_FINE);
    // Fewer sample tests than the paper's levels with the same edge test, more tile tests.
    let mut coarse = SampleBuffer::<f32>::new(64, 48, 4, 4, 16, 4, 5).expect("valid");
    let k = rasterise(
        &mut coarse,
        &tris,
        &RasterConfig::new(Traversal::Our(EdgeTest::LinearisedPerLevel)),
    )
    .expect("valid");
    assert!(c.sample_tests < k.sample_tests && c.tile_tests > k.tile_tests);
}

const PINNED_FINE: (u64, u64) = (14731, 17745);
