//! The screen-space bound (§4.3): no pixel whose ray enters a kernel's bounding cylinder
//! (contribution above the cut-off) lies outside the octagon, checked densely.

mod common;

use common::{deep, pixel_ray};
use ewa_splat::{
    Bounding, Camera, Kernel, KernelParams, RenderSettings, Splat, ellipse_aabb, octagon,
    polygon_contains, render,
};
use glam::{DMat4, DVec2, DVec3, DVec4};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn screen_matrix(cam: &Camera) -> DMat4 {
    let (w, h) = (cam.width as f64, cam.height as f64);
    DMat4::from_cols(
        DVec4::new(w / 2.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, -h / 2.0, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 1.0, 0.0),
        DVec4::new(w / 2.0, h / 2.0, 0.0, 1.0),
    ) * cam.view_proj
}

fn rvec(rng: &mut Pcg64, r: f64) -> DVec3 {
    DVec3::new(
        rng.random_range(-r..r),
        rng.random_range(-r..r),
        rng.random_range(-r..r),
    )
}

#[test]
fn no_contributing_sample_outside_the_octagon() {
    let kernels = if deep() { 400 } else { 80 };
    let sub = 4; // 4x4 samples per pixel
    let cam = Camera::look_at_perspective(
        DVec3::new(0.5, 0.4, 6.0),
        DVec3::ZERO,
        DVec3::Y,
        0.9,
        0.1,
        100.0,
        48,
        40,
    );
    let screen = screen_matrix(&cam);
    let mut rng = Pcg64::seed_from_u64(3);
    let params = KernelParams::default();
    let (mut checked, mut inside_cyl, mut bounded) = (0u64, 0u64, 0u64);
    let samples: Vec<(f64, f64, DVec3, DVec3)> = (0..cam.height * sub)
        .flat_map(|j| (0..cam.width * sub).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (px, py) = ((i as f64 + 0.5) / sub as f64, (j as f64 + 0.5) / sub as f64);
            let (o, d) = pixel_ray(&cam, px, py);
            (px, py, o, d)
        })
        .collect();
    for _ in 0..kernels {
        let c = rvec(&mut rng, 2.0);
        let a1 = rvec(&mut rng, 0.6);
        let a2 = rvec(&mut rng, 0.6);
        let m = rvec(&mut rng, 2.5);
        let Some(k) = Kernel::new(c, a1, a2, 0.5 * m, 0.5, 0.5, &params) else {
            continue;
        };
        let a3 = k.axes[2];
        let (Some(e0), Some(e1)) = (
            ellipse_aabb(&screen, c - a3, a1, a2),
            ellipse_aabb(&screen, c + a3, a1, a2),
        ) else {
            continue;
        };
        bounded += 1;
        let oct = octagon(&e0, &e1);
        for &(px, py, o, d) in &samples {
            checked += 1;
            let Some(line) = k.ray_line(o, d) else {
                continue;
            };
            if Kernel::cylinder_span(&line).is_some() {
                inside_cyl += 1;
                assert!(
                    polygon_contains(&oct, DVec2::new(px, py)),
                    "sample ({px}, {py}) outside {oct:?}"
                );
            }
        }
    }
    assert!(
        bounded > kernels / 2 && inside_cyl > 1000 && checked > inside_cyl,
        "{bounded} {inside_cyl} {checked}"
    );
}

#[test]
fn octagon_and_box_bounds_render_the_same_image_with_fewer_tests() {
    let cam = Camera::look_at_perspective(
        DVec3::new(0.0, 0.0, 6.0),
        DVec3::ZERO,
        DVec3::Y,
        0.9,
        0.1,
        100.0,
        48,
        40,
    );
    let mut rng = Pcg64::seed_from_u64(5);
    let splats: Vec<Splat> = (0..30)
        .map(|_| {
            let c = rvec(&mut rng, 1.5);
            // diagonal motion: where the octagon is much tighter than the box
            let m = DVec3::new(1.5, 1.2, 0.0) * rng.random_range(-1.0..1.0);
            Splat::moving_disc(
                c,
                m,
                DVec3::new(0.2, 0.1, 1.0),
                0.2,
                [rng.random(), 0.5, 0.5, 1.0],
            )
        })
        .collect();
    let oct = render(
        &cam,
        &splats,
        [0.0, 0.0, 0.0, 1.0],
        &RenderSettings::default(),
    )
    .unwrap();
    let bx = render(
        &cam,
        &splats,
        [0.0, 0.0, 0.0, 1.0],
        &RenderSettings {
            bounding: Bounding::Box,
            ..RenderSettings::default()
        },
    )
    .unwrap();
    assert_eq!(oct.pixels, bx.pixels);
    assert_eq!(oct.stats.fragments, bx.stats.fragments);
    assert!(
        oct.stats.pixels_tested < bx.stats.pixels_tested,
        "{:?} {:?}",
        oct.stats,
        bx.stats
    );
}
