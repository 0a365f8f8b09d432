//! Every built-in scene renders (small, few sub-frames) to a finite, non-trivial image, and a
//! seeded render is pinned pixel for pixel.

use mblur::NoProgress;
use mblur::accum::{self, AccumOptions};
use mblur_scene::Scene;

#[test]
fn every_builtin_scene_renders_small() {
    for (name, _, _) in mblur_scene::builtin::SCENES {
        let p = integration_tests::builtin(name, 40, 24);
        let img = integration_tests::accum(&p, 6);
        let bg = p.background.map(|c| c as f32);
        let drawn = img.pixels.iter().filter(|px| **px != bg).count();
        assert!(
            drawn > 40,
            "{name}: only {drawn} pixels differ from the background"
        );
        let effects = mblur::Effects::analyse(&p);
        if name != "static" {
            assert!(effects.moving() > 0, "{name} should move");
            // Motion blur: some pixel is a strict mix (differs from the single instant t = 0.5).
            let still = accum::render_static(&p, 0.5);
            assert!(img.pixels != still.pixels, "{name}: no blur");
        } else {
            assert_eq!(effects.moving(), 0);
            assert_eq!(accum::auto_times(&p), 1);
        }
    }
}

/// The mesh has about 64k triangles (one straight segment per shutter: the automatic
/// segments of its 35° spin multiply the prepared triangles).
#[test]
fn clothball_has_about_64k_triangles() {
    let one = mblur_scene::segments::MotionOptions {
        segments: mblur_scene::segments::Segments::Fixed(1),
        ..Default::default()
    };
    let p = Scene::builtin("clothball")
        .unwrap()
        .prepare_with(&one)
        .unwrap();
    assert!(
        (60_000..70_000).contains(&p.triangles.len()),
        "{}",
        p.triangles.len()
    );
}

#[test]
fn fence_moves_500_pixels_per_frame() {
    let p = Scene::builtin("fence").unwrap().prepare().unwrap();
    let m = accum::max_motion_pixels(&p);
    assert!((m - 500.0).abs() < 0.01, "{m}");
}

/// Pinned output of a seeded render: changes here mean the renderer's output changed.
#[test]
fn seeded_billiards_render_is_stable() {
    let p = integration_tests::builtin("billiards-unlit", 32, 18);
    let img = accum::render(
        &p,
        &AccumOptions {
            times: Some(8),
            jitter: Some(42),
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap();
    let probe = |x: u32, y: u32| img.get(x, y).unwrap();
    let pinned: [((u32, u32), [f32; 3]); 4] = PINNED;
    for ((x, y), expect) in pinned {
        let got = probe(x, y);
        for k in 0..3 {
            assert!(
                (got[k] - expect[k]).abs() <= 1e-6 * expect[k].abs().max(1.0),
                "({x}, {y}): {got:?} vs {expect:?}"
            );
        }
    }
}

/// The first two probes lie on spinning balls: accum places each sub-frame on the balls'
/// true rotation arc (motion keys interpolate rotations), not on the chord.
const PINNED: [((u32, u32), [f32; 3]); 4] = [
    ((13, 5), [0.1597598, 0.2503367, 0.072794475]),
    ((17, 7), [0.35128066, 0.16070504, 0.062423024]),
    ((8, 10), [0.3625, 0.5125, 0.38125]),
    ((23, 10), [0.05, 0.15, 0.8]),
];

/// accum draws static triangles once into a base layer and, per sub-frame, only the moving
/// ones over it, resolving and restoring only the columns they change in each row, with
/// each lit triangle's surface set up once per sub-frame. The reference composes the same
/// sub-frames the plain way, without the static path's fragment buffer: per sub-frame and
/// pixel, every triangle placed at the sub-frame's time with `corners_at`, set up and
/// rasterised in index order, each fragment shaded on its own (`shade_surface`, `shade`),
/// the nearest opaque one kept (LESS_EQUAL, the later triangle winning an exact tie), the
/// transparent ones in front of it sorted nearest first and blended front to back with
/// premultiplied OVER; the colours summed in f64 with the sub-frame weights. Bit-identical
/// on every built-in scene, lit and unlit, with one and with several sub-frames, evenly
/// spaced and jittered.
#[test]
fn accum_over_a_base_layer_equals_whole_frames_composed_from_scratch() {
    let (w, h) = (48, 27);
    let mut names: Vec<String> = Vec::new();
    for (name, _, _) in mblur_scene::builtin::SCENES {
        names.push(name.to_string());
        let unlit = format!("{name}-unlit");
        if Scene::builtin(&unlit).is_ok() {
            names.push(unlit);
        }
    }
    assert!(names.iter().any(|n| n.ends_with("-unlit")));
    for name in &names {
        let p = integration_tests::builtin(name, w, h);
        for (times, jitter) in [(1, None), (5, None), (5, Some(7))] {
            let opts = AccumOptions {
                times: Some(times),
                jitter,
                ..Default::default()
            };
            let img = accum::render(&p, &opts, &NoProgress).unwrap();
            let want = composed_from_scratch(&p, times, jitter);
            for (i, (got, want)) in img.pixels.iter().zip(&want).enumerate() {
                assert!(
                    got.map(f32::to_bits) == want.map(f32::to_bits),
                    "{name}, {times} sub-frames, jitter {jitter:?}, pixel {i}: {got:?} vs {want:?}"
                );
            }
        }
    }
}

/// One pixel of a sub-frame: the nearest opaque fragment (depth, triangle, colour) and
/// every transparent one (depth, triangle, premultiplied RGBA).
#[derive(Default, Clone)]
struct Pixel {
    opaque: Option<(f64, u32, [f64; 3])>,
    transparent: Vec<(f64, u32, [f64; 4])>,
}

/// accum's image composed sub-frame by sub-frame from every triangle (see
/// `accum_over_a_base_layer_equals_whole_frames_composed_from_scratch`).
fn composed_from_scratch(
    p: &mblur::PreparedScene,
    times: u32,
    jitter: Option<u64>,
) -> Vec<[f32; 3]> {
    use mblur::static_path::{Target, setup_corners, splats_as_discs};
    let s = splats_as_discs(p);
    let target = Target::of(&s);
    let (w, h) = (s.width as usize, s.height as usize);
    let mut sum = vec![[0.0f64; 3]; w * h];
    for (t, weight) in accum::sample_times(&s, times, jitter) {
        let mut frame = vec![Pixel::default(); w * h];
        for (i, tri) in s.triangles.iter().enumerate() {
            if !tri.exists_at(t) {
                continue;
            }
            let mut screen = Vec::new();
            let opaque = s.is_opaque(tri.material);
            setup_corners(
                tri,
                s.corners_at(tri, t),
                i as u32,
                opaque,
                &target,
                &mut screen,
            );
            for st in &screen {
                st.rasterise(0, s.height, |x, y, f| {
                    if f.depth > s.far {
                        return;
                    }
                    let c = if s.is_lit(tri.material) {
                        s.shade_surface(tri, f.bary, t)
                    } else {
                        s.shade(tri.material, f.uv)
                    };
                    let px = &mut frame[y as usize * w + x as usize];
                    if c[3] >= 1.0 {
                        if px
                            .opaque
                            .is_none_or(|(d, o, _)| f.depth < d || (f.depth == d && st.order >= o))
                        {
                            px.opaque = Some((f.depth, st.order, [c[0], c[1], c[2]]));
                        }
                    } else if c[3] > 0.0 {
                        px.transparent.push((f.depth, st.order, c));
                    }
                });
            }
        }
        for (px, out) in frame.iter_mut().zip(sum.iter_mut()) {
            let (od, oo, base) = px.opaque.unwrap_or((f64::INFINITY, 0, s.background));
            let front = |&(d, o, _): &(f64, u32, [f64; 4])| d < od || (d == od && o > oo);
            px.transparent.retain(front);
            px.transparent
                .sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
            let mut acc = [0.0f64; 4];
            for (_, _, c) in &px.transparent {
                let k = 1.0 - acc[3];
                for j in 0..4 {
                    acc[j] += k * c[j];
                }
            }
            let k = 1.0 - acc[3];
            for j in 0..3 {
                out[j] += weight * (acc[j] + k * base[j]);
            }
        }
    }
    sum.iter()
        .map(|c| c.map(|v| if v.is_finite() { v as f32 } else { 0.0 }))
        .collect()
}
