//! The temporal pixel visualiser (`mblur inspect`, Gribel 2010 §5.2.1):
//! - its lists, resolved, give exactly the analytic render's pixel (exact and K = 4);
//! - its exact list agrees with an independent brute force: dense time sampling of which
//!   triangles cover the pixel centre at t (edge functions on the projected vertices at t),
//!   compared as coverage time per triangle;
//! - the SVG is well-formed XML with one line per interval in each panel;
//! - errors (pixel outside the image, splat scenes, K = 0) through the library (the same
//!   errors through the command, leaving no output file, are in `mblur-cli/tests/inspect.rs`).

use std::collections::HashMap;

use integration_tests::{builtin, render};
use mblur::inspect::{PixelIntervals, pixel_intervals};
use mblur::{AnalyticOptions, Image, MethodOptions, PreparedScene, PreparedTriangle};

/// The analytic render with `intervals` per pixel (0 = exact lists).
fn analytic(p: &PreparedScene, intervals: u32) -> Image {
    render(
        p,
        &MethodOptions::Analytic(AnalyticOptions {
            intervals,
            ..Default::default()
        }),
    )
    .image
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter()
        .zip(&b)
        .all(|(x, y)| (x - y).abs() <= 1e-5 * x.abs().max(y.abs()).max(1.0))
}

/// Every `step`-th pixel (both ways): the visualiser's resolved colours equal the analytic
/// renders with exact lists and with K = 4.
fn resolves_like_render(name: &str, w: u32, h: u32, step: u32) {
    let p = builtin(name, w, h);
    let (exact, k4) = (analytic(&p, 0), analytic(&p, 4));
    let (mut pixels, mut busy) = (0, 0);
    for y in (0..h).step_by(step as usize) {
        for x in (0..w).step_by(step as usize) {
            let v = pixel_intervals(&p, x, y, 4).unwrap();
            assert!(
                close(v.exact.colour, exact.get(x, y).unwrap()),
                "{name} ({x}, {y}) exact: {:?} vs render {:?}",
                v.exact.colour,
                exact.get(x, y)
            );
            assert!(
                close(v.compressed.colour, k4.get(x, y).unwrap()),
                "{name} ({x}, {y}) K=4: {:?} vs render {:?}",
                v.compressed.colour,
                k4.get(x, y)
            );
            assert!(v.compressed.intervals.len() <= 4);
            pixels += 1;
            busy += usize::from(v.exact.intervals.len() > 4);
        }
    }
    eprintln!("{name}: {pixels} pixels, {busy} with more than 4 exact intervals");
}

#[test]
fn billiards_resolves_like_the_render() {
    resolves_like_render("billiards", 48, 27, 3);
}

#[test]
fn fence_resolves_like_the_render() {
    resolves_like_render("fence", 48, 27, 3);
}

#[test]
fn transparent_cubes_resolve_like_the_render() {
    resolves_like_render("transparent-cubes", 48, 27, 3);
}

#[test]
fn crossing_quads_resolve_like_the_render() {
    resolves_like_render("crossing-quads", 48, 36, 4);
}

#[test]
fn textured_quad_resolves_like_the_render() {
    resolves_like_render("textured-quad", 32, 32, 3);
}

#[test]
fn pills_resolve_like_the_render() {
    resolves_like_render("pills", 48, 27, 4);
}

#[test]
fn static_scene_resolves_like_the_static_path() {
    // A static opaque scene renders through the static path (no interval storage); its
    // intervals are full-shutter lines of constant depth.
    resolves_like_render("static", 48, 27, 3);
    let p = builtin("static", 48, 27);
    let v = pixel_intervals(&p, 24, 13, 4).unwrap();
    assert!(!v.exact.intervals.is_empty());
    for iv in &v.exact.intervals {
        assert_eq!((iv.t0, iv.t1), (0.0, 1.0));
        assert_eq!(iv.z0, iv.z1);
    }
}

/// Coverage of the pixel centre (px, py) by `tri` at time u local to its span, from the
/// projected corners at u: `Some(true)` inside, `Some(false)` outside, `None` within 1e-7 px of an edge.
fn covers(tri: &PreparedTriangle, u: f64, (px, py): (f64, f64)) -> Option<bool> {
    let v = tri.at(u);
    let s = v.map(|c| {
        assert!(c.w > 0.0);
        c.screen()
    });
    let cross = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let area = cross(s[0], s[1], s[2]);
    if area == 0.0 {
        return Some(false);
    }
    let mut on_edge = false;
    for k in 0..3 {
        let (a, b) = (s[k], s[(k + 1) % 3]);
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let e = cross(a, b, (px, py)) * area.signum();
        if e < -1e-7 * len {
            return Some(false);
        }
        on_edge |= e <= 1e-7 * len;
    }
    if on_edge { None } else { Some(true) }
}

/// True when `tri` at time u local to its span shows the winding `hidden` (the sign of
/// its screen area, which with every w > 0 is the sign of the 2DH determinant).
fn turned_away(tri: &PreparedTriangle, u: f64, hidden: mblur::cull::Facing) -> bool {
    let s = tri.at(u).map(|c| c.screen());
    let area = (s[1].0 - s[0].0) * (s[2].1 - s[0].1) - (s[1].1 - s[0].1) * (s[2].0 - s[0].0);
    match hidden {
        mblur::cull::Facing::Front => area > 0.0,
        mblur::cull::Facing::Back => area < 0.0,
        mblur::cull::Facing::Mixed => false,
    }
}

/// The exact list's coverage time per triangle against dense sampling at `n` times.
/// Only scenes whose triangles stay in front of the near plane and inside the far plane.
fn coverage_matches_brute_force(name: &str, w: u32, h: u32, pixels: &[(u32, u32)]) {
    let p = builtin(name, w, h);
    let n = 2048usize;
    let mut checked = 0;
    // Back faces of opaque closed meshes are culled by the renderer: triangles facing away
    // over the whole shutter leave no interval, and the others may lose the times they
    // face away (a conservative clip keeps some of that time next to each root).
    let culled = mblur::cull::backface_mask(&p);
    let culling = mblur::cull::Culling::of(&p);
    for &(x, y) in pixels {
        let v = pixel_intervals(&p, x, y, 4).unwrap();
        let mut analytic: HashMap<u32, f64> = HashMap::new();
        for iv in &v.exact.intervals {
            *analytic.entry(iv.triangle).or_default() += f64::from(iv.t1 - iv.t0);
        }
        let c = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        for (i, tri) in p.triangles.iter().enumerate() {
            let all = tri.open.iter().chain(&tri.close);
            assert!(
                all.clone()
                    .all(|v| v.w > 0.0 && v.depth >= p.near && v.depth <= p.far),
                "{name}: triangle {i} leaves the near/far range (choose another scene)"
            );
            // Conservative screen bounds over the shutter (w > 0 throughout).
            let (lo, hi) = all.fold(
                (
                    (f64::INFINITY, f64::INFINITY),
                    (f64::NEG_INFINITY, f64::NEG_INFINITY),
                ),
                |(lo, hi), v| {
                    let (sx, sy) = v.screen();
                    ((lo.0.min(sx), lo.1.min(sy)), (hi.0.max(sx), hi.1.max(sy)))
                },
            );
            let a = analytic.get(&(i as u32)).copied().unwrap_or(0.0);
            if culled.get(i).copied().unwrap_or(false) {
                assert_eq!(a, 0.0, "{name}: culled triangle {i} left intervals");
                continue;
            }
            if c.0 < lo.0 || c.0 > hi.0 || c.1 < lo.1 || c.1 > hi.1 {
                assert_eq!(a, 0.0, "{name} ({x}, {y}) triangle {i} outside its bounds");
                continue;
            }
            let (mut inside, mut edge, mut switches, mut prev) = (0usize, 0usize, 0usize, None);
            for j in 0..n {
                let t = (j as f64 + 0.5) / n as f64;
                // A segment of curved motion exists only over its span, in local time there.
                let s = if !tri.exists_at(t) {
                    Some(false)
                } else if turned_away(tri, tri.local_time(t), culling.hidden(i)) {
                    // Covered or not, the renderer may drop it: counted as ambiguous.
                    covers(tri, tri.local_time(t), c).and(None)
                } else {
                    covers(tri, tri.local_time(t), c)
                };
                match s {
                    Some(true) => inside += 1,
                    None => edge += 1,
                    Some(false) => {}
                }
                if s.is_some() && prev.is_some() && s != prev {
                    switches += 1;
                }
                if s.is_some() {
                    prev = s;
                }
            }
            let brute = (inside as f64 + 0.5 * edge as f64) / n as f64;
            // Each switch of coverage between samples is resolved to within one sample
            // spacing; on-edge samples are ambiguous; f32 edge-eqn roots are ~1e-5 off.
            let tol = (switches as f64 + 1.0) / n as f64 + 0.5 * edge as f64 / n as f64 + 1e-4;
            assert!(
                (a - brute).abs() <= tol,
                "{name} ({x}, {y}) triangle {i}: analytic {a:.5}, brute force {brute:.5} (tol {tol:.5})"
            );
            checked += usize::from(a > 0.0 || brute > 0.0);
        }
    }
    assert!(
        checked > 0,
        "{name}: no covering triangle in the chosen pixels"
    );
    eprintln!("{name}: {checked} (pixel, triangle) coverage times checked");
}

fn grid(w: u32, h: u32, step: u32) -> Vec<(u32, u32)> {
    (0..h)
        .step_by(step as usize)
        .flat_map(|y| (0..w).step_by(step as usize).map(move |x| (x, y)))
        .collect()
}

#[test]
fn billiards_coverage_times_match_dense_sampling() {
    coverage_matches_brute_force("billiards", 48, 27, &grid(48, 27, 5));
}

#[test]
fn fence_coverage_times_match_dense_sampling() {
    coverage_matches_brute_force("fence", 48, 27, &grid(48, 27, 6));
}

#[test]
fn crossing_quads_coverage_times_match_dense_sampling() {
    coverage_matches_brute_force("crossing-quads", 48, 36, &grid(48, 36, 5));
}

#[test]
fn transparent_cubes_coverage_times_match_dense_sampling() {
    coverage_matches_brute_force("transparent-cubes", 48, 27, &grid(48, 27, 5));
}

/// Counts the `line` elements of class `interval` in each `g` of class `panel`.
fn check_svg(v: &PixelIntervals, scene: &str) {
    let svg = mblur_lab::inspect::to_svg(v, scene);
    assert_eq!(
        integration_tests::svg_panel_intervals(&svg),
        vec![v.exact.intervals.len(), v.compressed.intervals.len()]
    );
    assert!(svg.contains(&format!("pixel ({}, {})", v.x, v.y)));
}

#[test]
fn svg_is_xml_with_one_line_per_interval() {
    let p = builtin("fence", 64, 36);
    let mut most = 0;
    for (x, y) in grid(64, 36, 7) {
        let v = pixel_intervals(&p, x, y, 4).unwrap();
        most = most.max(v.exact.intervals.len());
        check_svg(&v, "fence <&\"escaped\">");
    }
    assert!(most > 4, "some fence pixel needs compression");
    // Transparent and textured scenes, and a background-only pixel.
    for (name, w, h) in [("transparent-cubes", 48, 27), ("textured-quad", 32, 32)] {
        let p = builtin(name, w, h);
        for (x, y) in grid(w, h, 8) {
            check_svg(&pixel_intervals(&p, x, y, 2).unwrap(), name);
        }
    }
}

#[test]
fn background_only_pixel_has_no_intervals() {
    let p = builtin("crossing-quads", 48, 36);
    let bg = p.background.map(|c| c as f32);
    let v = pixel_intervals(&p, 0, 0, 4).unwrap();
    assert!(v.exact.intervals.is_empty() && v.compressed.intervals.is_empty());
    assert!(close(v.exact.colour, bg));
    assert_eq!(
        integration_tests::svg_panel_intervals(&mblur_lab::inspect::to_svg(&v, "crossing-quads")),
        vec![0, 0]
    );
}

#[test]
fn compression_merges_fence_intervals_down_to_k() {
    // The fence (Gribel 2010, Fig. 11) leaves many short intervals per pixel; K = 2 keeps
    // two, at least one of them a merge.
    let p = builtin("fence", 64, 36);
    let v = pixel_intervals(&p, 32, 18, 2).unwrap();
    assert!(v.exact.intervals.len() > 2, "{}", v.exact.intervals.len());
    assert_eq!(v.compressed.intervals.len(), 2);
    assert!(v.compressed.intervals.iter().any(|i| i.merged));
    assert!(v.exact.intervals.iter().all(|i| !i.merged));
    // Partitions tile the shutter.
    for list in [&v.exact, &v.compressed] {
        assert_eq!(list.spans.first().map(|s| s.t0), Some(0.0));
        assert_eq!(list.spans.last().map(|s| s.t1), Some(1.0));
        assert!(list.spans.windows(2).all(|w| w[0].t1 == w[1].t0));
    }
}

#[test]
fn errors_name_the_problem() {
    let p = builtin("billiards", 32, 18);
    let e = pixel_intervals(&p, 32, 0, 4).unwrap_err().to_string();
    assert!(e.contains("`pixel`") && e.contains("32 x 18"), "{e}");
    let e = pixel_intervals(&p, 0, 18, 4).unwrap_err().to_string();
    assert!(e.contains("`pixel`"), "{e}");
    let e = pixel_intervals(&p, 0, 0, 0).unwrap_err().to_string();
    assert!(e.contains("`intervals`"), "{e}");
    let splats = builtin("splat-ball", 32, 18);
    let e = pixel_intervals(&splats, 1, 1, 4).unwrap_err().to_string();
    assert!(e.contains("only splats"), "{e}");
    assert_eq!(mblur_lab::inspect::parse_pixel(" 3, 4"), Ok((3, 4)));
    assert!(mblur_lab::inspect::parse_pixel("3;4").is_err());
    assert!(mblur_lab::inspect::parse_pixel("-1,4").is_err());
}
