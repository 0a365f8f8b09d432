//! Surface intervals (triangles) in the A-buffer against a dense time-sampling reference:
//! per pixel, at N times t, the surfaces active at t (surface intervals by their depth at t,
//! the splat surface by the exact ray-plane depth of the moving splat plane at t, computed
//! here without the crate) are sorted by depth and composited front to back over the
//! background; the mean over t is the box-shutter integral. The midpoint rule is off by at
//! most one sample per discontinuity (interval ends and depth swaps), so the tolerance is
//! `(discontinuities + 2) / N` per channel.

use ewa_splat::{
    Camera, RenderError, RenderSettings, Splat, SplatKey, SurfaceInterval, SurfaceLists,
    Visibility, render, render_with_surfaces,
};
use glam::DVec3;
use proptest::prelude::*;

/// One pixel looking down -z from (0, 0, 5); its ray starts at z = 4.9 (near 0.1) and runs
/// along -z, so a plane z = c is at depth 4.9 - c.
fn one_pixel() -> Camera {
    Camera::look_at_perspective(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::ZERO,
        DVec3::Y,
        0.2,
        0.1,
        100.0,
        1,
        1,
    )
}

const RAY_Z: f64 = 4.9;

/// A splat facing the camera, radius 1 (the ray stays inside its cylinder), moving along z
/// from `z0` to `z1`.
fn sheet(z0: f64, z1: f64, colour: [f32; 4]) -> Splat {
    let open = SplatKey::disc(DVec3::new(0.0, 0.0, z0), DVec3::Z, 1.0);
    let close = SplatKey::disc(DVec3::new(0.0, 0.0, z1), DVec3::Z, 1.0);
    Splat::linear(open, close, colour)
}

fn premul(c: [f32; 4]) -> [f64; 4] {
    let a = f64::from(c[3]);
    [
        f64::from(c[0]) * a,
        f64::from(c[1]) * a,
        f64::from(c[2]) * a,
        a,
    ]
}

/// The dense reference: straight-alpha RGBA (alpha 1 over an opaque background).
fn dense(
    sheets: &[(f64, f64)],
    sheet_colour: [f64; 4],
    surfaces: &[SurfaceInterval],
    bg: [f64; 4],
    n: usize,
) -> [f64; 4] {
    let mut acc = [0.0; 4];
    for i in 0..n {
        let t = (i as f64 + 0.5) / n as f64;
        // (depth, colour, is surface interval)
        let mut layers: Vec<(f64, [f64; 4], bool)> = surfaces
            .iter()
            .filter(|s| s.t0 <= t && t < s.t1)
            .map(|s| (s.depth_at(t), s.colour, true))
            .collect();
        let splat_depth = sheets
            .iter()
            .map(|(z0, z1)| RAY_Z - (z0 + (z1 - z0) * t))
            .fold(f64::INFINITY, f64::min);
        if splat_depth.is_finite() {
            layers.push((splat_depth, sheet_colour, false));
        }
        layers.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.2.cmp(&a.2)));
        let mut tr = 1.0;
        let mut c = [0.0; 4];
        for (_, col, _) in &layers {
            for k in 0..4 {
                c[k] += tr * col[k];
            }
            tr *= 1.0 - col[3];
        }
        for k in 0..4 {
            acc[k] += (c[k] + tr * bg[k]) / n as f64;
        }
    }
    let a = acc[3];
    [acc[0] / a, acc[1] / a, acc[2] / a, a]
}

fn render_pixel(
    sheets: &[(f64, f64)],
    colour: [f32; 4],
    surfaces: &[SurfaceInterval],
    bg: [f32; 4],
) -> [f32; 4] {
    let splats: Vec<Splat> = sheets.iter().map(|(a, b)| sheet(*a, *b, colour)).collect();
    let entries: Vec<(u32, u32, SurfaceInterval)> = surfaces.iter().map(|s| (0, 0, *s)).collect();
    let lists = SurfaceLists::new(1, 1, &entries).unwrap();
    let frame = render_with_surfaces(
        &one_pixel(),
        &splats,
        bg,
        &RenderSettings::default(),
        &lists,
    )
    .unwrap();
    frame.pixels[0]
}

fn surface() -> impl Strategy<Value = SurfaceInterval> {
    (
        0.0f64..1.0,
        0.0f64..1.0,
        1.0f64..9.0,
        -6.0f64..6.0,
        prop::array::uniform3(0.0f64..1.0),
        prop_oneof![Just(1.0f64), 0.1f64..1.0],
    )
        .prop_map(|(a, len, depth, slope, rgb, alpha)| SurfaceInterval {
            t0: a,
            t1: (a + len).min(1.0),
            depth,
            depth_slope: slope,
            colour: [rgb[0] * alpha, rgb[1] * alpha, rgb[2] * alpha, alpha],
        })
}

/// A motion along z of at least 0.05 (the kernel's minimum temporal axis is 1e-3 of the
/// radius, so the fragment depth is the plane's exactly) with both ends in [-3, 3].
fn motion() -> impl Strategy<Value = (f64, f64)> {
    (-3.0f64..3.0, 0.05f64..3.0, any::<bool>()).prop_map(|(z0, m, up)| {
        let z1 = if up { z0 + m } else { z0 - m };
        if (-3.0..=3.0).contains(&z1) {
            (z0, z1)
        } else {
            (z0, if up { z0 - m } else { z0 + m })
        }
    })
}

const N: usize = 4096;

proptest! {
    #[test]
    fn piecewise_resolve_matches_dense_time_sampling(
        sheets in proptest::collection::vec(motion(), 0..3),
        surfaces in proptest::collection::vec(surface(), 0..5),
        rgb in prop::array::uniform3(0.0f32..1.0),
        alpha in prop_oneof![Just(1.0f32), 0.2f32..1.0],
        bg in prop::array::uniform3(0.0f32..1.0),
    ) {
        let colour = [rgb[0], rgb[1], rgb[2], alpha];
        let bg = [bg[0], bg[1], bg[2], 1.0];
        let got = render_pixel(&sheets, colour, &surfaces, bg);
        let want = dense(&sheets, premul(colour), &surfaces, premul(bg), N);
        // Ends of every interval, one swap per pair of linear depths.
        let n = surfaces.len();
        let cuts = 2 + 2 * n + n * (sheets.len() + n) + sheets.len() * sheets.len();
        let tol = cuts as f64 / N as f64 + 1e-5;
        for k in 0..4 {
            prop_assert!(
                (f64::from(got[k]) - want[k]).abs() <= tol,
                "channel {k}: got {got:?}, dense {want:?}, tol {tol}"
            );
        }
    }
}

/// An opaque green triangle at a fixed ray depth over the whole shutter.
fn static_green(depth: f64) -> SurfaceInterval {
    SurfaceInterval {
        t0: 0.0,
        t1: 1.0,
        depth,
        depth_slope: 0.0,
        colour: [0.0, 1.0, 0.0, 1.0],
    }
}

/// A splat sheet crossing a static opaque triangle at t = 0.25 exactly (depth 2 + 4t
/// against 3): the piecewise result is exact, the dense one converges to it as 1/N.
#[test]
fn crossing_is_cut_exactly_and_dense_sampling_converges_to_it() {
    let tri = static_green(3.0);
    // Depth 2 + 4t: z from 2.9 to -1.1.
    let sheets = [(RAY_Z - 2.0, RAY_Z - 6.0)];
    let red = [1.0, 0.0, 0.0, 1.0];
    let got = render_pixel(&sheets, red, &[tri], [0.0, 0.0, 0.0, 1.0]);
    assert!((f64::from(got[0]) - 0.25).abs() < 1e-6, "{got:?}");
    assert!((f64::from(got[1]) - 0.75).abs() < 1e-6, "{got:?}");
    let mut last = f64::INFINITY;
    for n in [64, 256, 1024] {
        let want = dense(&sheets, premul(red), &[tri], [0.0, 0.0, 0.0, 1.0], n);
        let e = (f64::from(got[0]) - want[0]).abs();
        assert!(e <= 1.0 / n as f64 + 1e-6 && e <= last, "N {n}: {e}");
        last = e;
    }
}

/// What the piece-midpoint rule would cost without the cut at the depth swap: a single
/// piece [0, 1] decided at t = 0.5 would give all red (the sheet is in front at the
/// middle) instead of 0.25 red, an error of the whole swapped fraction. The renderer cuts,
/// so the result matches the swap time for a sweep of swap times.
#[test]
fn swap_times_are_honoured_across_the_exposure() {
    for i in 1..20 {
        let ts = i as f64 / 20.0;
        // Sheet depth 2 + 4t crosses a triangle at depth 2 + 4 ts.
        let tri = static_green(2.0 + 4.0 * ts);
        let got = render_pixel(
            &[(RAY_Z - 2.0, RAY_Z - 6.0)],
            [1.0, 0.0, 0.0, 1.0],
            &[tri],
            [0.0, 0.0, 0.0, 1.0],
        );
        assert!((f64::from(got[0]) - ts).abs() < 1e-6, "swap {ts}: {got:?}");
    }
}

#[test]
fn surfaces_need_the_a_buffer_and_the_viewport_size() {
    let tri = static_green(3.0);
    let cam = one_pixel();
    let lists = SurfaceLists::new(1, 1, &[(0, 0, tri)]).unwrap();
    let approx = RenderSettings {
        visibility: Visibility::Approximate,
        ..RenderSettings::default()
    };
    let bg = [0.0, 0.0, 0.0, 1.0];
    assert_eq!(
        render_with_surfaces(&cam, &[], bg, &approx, &lists),
        Err(RenderError::Surfaces)
    );
    let wrong = SurfaceLists::empty(2, 1);
    assert_eq!(
        render_with_surfaces(&cam, &[], bg, &RenderSettings::default(), &wrong),
        Err(RenderError::Surfaces)
    );
    // Empty lists with approximate visibility are plain `render`.
    let s = [sheet(0.0, 0.5, [1.0, 0.0, 0.0, 1.0])];
    assert_eq!(
        render_with_surfaces(&cam, &s, bg, &approx, &SurfaceLists::empty(1, 1)),
        render(&cam, &s, bg, &approx)
    );
    assert!(RenderError::Surfaces.to_string().contains("A-buffer"));
}
