//! What the renderer computes exactly and what it approximates (Heinzle 2010, §4-§5), each
//! measured against temporal supersampling of static EWA splatting by ray-plane
//! intersection (`tests/common`: the front surface determined at every instant, no crate
//! code). Prints one table per topic; the README quotes them.
//!
//! `cargo run --release -p ewa-splat --example accuracy -- [topic ...]` with topics
//! `crossing`, `tolerance`, `axes`, `static-axis`, `tilt`, `normalise` (default: all), and
//! `cost`: render times of three scenes (not run by default).

#[path = "../tests/common/mod.rs"]
mod common;

use common::{max_diff, mean_diff, pixel_ray, premul, static_ewa_pixel, unpremul};
use ewa_splat::{Camera, KernelParams, RenderSettings, Splat, SplatKey, render};
use glam::{DQuat, DVec3};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

const BG: [f32; 4] = [0.1, 0.2, 0.3, 1.0];
const SUBFRAMES: [u32; 6] = [1, 2, 3, 4, 8, 16];

fn camera(eye: DVec3, fov: f64, w: u32, h: u32) -> Camera {
    Camera::look_at_perspective(eye, DVec3::ZERO, DVec3::Y, fov, 0.1, 100.0, w, h)
}

fn settings(subframes: u32, kernel: KernelParams, depth_epsilon: f64) -> RenderSettings {
    RenderSettings {
        subframes,
        kernel,
        depth_epsilon,
        ..RenderSettings::default()
    }
}

/// The mean over `n` instants of static EWA splatting at pixel (px, py) (straight alpha).
fn dense_pixel(c: &Camera, splats: &[Splat], (px, py): (f64, f64), eps: f64, n: usize) -> [f64; 4] {
    let (o, d) = pixel_ray(c, px, py);
    let mut acc = [0.0; 4];
    for k in 0..n {
        let t = (k as f64 + 0.5) / n as f64;
        let p = static_ewa_pixel(splats, t, o, d, 2.0, eps, premul(BG));
        for (a, v) in acc.iter_mut().zip(p) {
            *a += v / n as f64;
        }
    }
    unpremul(acc)
}

fn pixel_err(got: [f32; 4], want: [f64; 4]) -> f64 {
    (0..4)
        .map(|k| (f64::from(got[k]) - want[k]).abs())
        .fold(0.0, f64::max)
}

/// The issue's case: a static red splat at the origin, a green one moving along the view
/// axis from z = -0.7 to +0.3 (in front from t = 0.7), radius 0.1, camera at z = 5.
fn issue_pair() -> [Splat; 2] {
    let disc = |z| SplatKey::disc(DVec3::new(0.0, 0.0, z), DVec3::Z, 0.1);
    [
        Splat::fixed(disc(0.0), [1.0, 0.0, 0.0, 1.0]),
        Splat::linear(disc(-0.7), disc(0.3), [0.0, 1.0, 0.0, 1.0]),
    ]
}

/// Random sheets facing a one-pixel camera, moving along its axis (as `tests/crossings.rs`).
fn random_sheets(rng: &mut Pcg64) -> Vec<Splat> {
    let n = rng.random_range(2..4);
    (0..n)
        .map(|_| {
            let radius = rng.random_range(0.8..1.5);
            let (r, a) = (
                rng.random_range(0.0..0.75) * radius,
                rng.random_range(0.0..6.3),
            );
            let at = |z| {
                SplatKey::disc(
                    DVec3::new(r * f64::cos(a), r * f64::sin(a), z),
                    DVec3::Z,
                    radius,
                )
            };
            let z0 = rng.random_range(-3.0..3.0);
            let z1: f64 = rng.random_range(-3.0..3.0);
            let c = [rng.random(), rng.random(), rng.random(), 1.0];
            Splat::linear(at(z0), at(z1), c)
        })
        .collect()
}

fn crossing() {
    println!("## crossing: splat surfaces passing through each other (visibility, §4.4)\n");
    println!(
        "issue case at pixel (12, 12) of 25 x 25, fov 0.3 rad (splats 1.5-1.8 px), reference 4096 instants"
    );
    println!("| subframes | red | green | max abs error |\n|---|---|---|---|");
    let c = camera(DVec3::new(0.0, 0.0, 5.0), 0.3, 25, 25);
    let want = dense_pixel(&c, &issue_pair(), (12.5, 12.5), 1.0, 4096);
    for n in SUBFRAMES {
        let s = settings(n, KernelParams::default(), 1.0);
        let got = render(&c, &issue_pair(), BG, &s).unwrap().pixels[12 * 25 + 12];
        println!(
            "| {n} | {:.4} | {:.4} | {:.1e} |",
            got[0],
            got[1],
            pixel_err(got, want)
        );
    }
    println!("(reference: {:.4} red, {:.4} green)\n", want[0], want[1]);
    println!(
        "300 random one-pixel cases: 2-3 sheets, linear depth motions, depth tolerance 0-0.8 radii,"
    );
    println!(
        "minimum temporal axis 1e-7 (isolates visibility); reference 4096 instants (quantisation <= 10/4096 = 2.4e-3)"
    );
    println!("| subframes | max abs error | mean abs error |\n|---|---|---|");
    let c = camera(DVec3::new(0.0, 0.0, 5.0), 0.02, 1, 1);
    let mut rng = Pcg64::seed_from_u64(11);
    let cases: Vec<(Vec<Splat>, f64)> = (0..300)
        .map(|_| (random_sheets(&mut rng), rng.random_range(0.0..0.8)))
        .collect();
    let wants: Vec<[f64; 4]> = cases
        .iter()
        .map(|(s, e)| dense_pixel(&c, s, (0.5, 0.5), *e, 4096))
        .collect();
    let kernel = KernelParams {
        min_a3_rel: 1e-7,
        ..KernelParams::default()
    };
    for n in SUBFRAMES {
        let errs: Vec<f64> = cases
            .iter()
            .zip(&wants)
            .map(|((s, e), w)| {
                pixel_err(
                    render(&c, s, BG, &settings(n, kernel, *e)).unwrap().pixels[0],
                    *w,
                )
            })
            .collect();
        let max = errs.iter().copied().fold(0.0, f64::max);
        println!(
            "| {n} | {max:.1e} | {:.1e} |",
            errs.iter().sum::<f64>() / errs.len() as f64
        );
    }
    println!();
}

fn tolerance() {
    println!("## tolerance: depth tolerance from the low-passed axes, fixed per subframe\n");
    println!(
        "issue case at fov 0.8 rad: the splats project to ~0.6 px, the low-pass enlarges each kernel's"
    );
    println!(
        "axes (and its tolerance) by a factor that depends on the moving splat's distance per subframe"
    );
    println!("| subframes | red | max abs error vs reference |\n|---|---|---|");
    let c = camera(DVec3::new(0.0, 0.0, 5.0), 0.8, 25, 25);
    let want = dense_pixel(&c, &issue_pair(), (12.5, 12.5), 1.0, 4096);
    for n in SUBFRAMES {
        let got = render(
            &c,
            &issue_pair(),
            BG,
            &settings(n, KernelParams::default(), 1.0),
        )
        .unwrap()
        .pixels[12 * 25 + 12];
        println!("| {n} | {:.4} | {:.1e} |", got[0], pixel_err(got, want));
    }
    println!();
}

/// Splats on a grid at z = 0 that rotate by `angle` about an in-plane axis and grow by
/// `grow` over the exposure (keys interpolated linearly, as the reference does).
fn turning_grid(angle: f64, grow: f64) -> Vec<Splat> {
    let mut out = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let centre = DVec3::new(-1.2 + 0.8 * i as f64, -1.2 + 0.8 * j as f64, 0.0);
            let axis = DVec3::new(((i + j) as f64).cos(), ((i * j) as f64).sin(), 0.0).normalize();
            let open = SplatKey::disc(centre, DVec3::Z, 0.3);
            let q = DQuat::from_axis_angle(axis, angle);
            let close = SplatKey {
                centre: centre + DVec3::new(0.05, 0.0, 0.1),
                axis_u: q * open.axis_u * grow,
                axis_v: q * open.axis_v * grow,
            };
            let g = 0.2 + 0.05 * ((3 * i + 5 * j) % 13) as f32;
            out.push(Splat::linear(open, close, [g, 1.0 - g, 0.5, 1.0]));
        }
    }
    out
}

/// Max and mean absolute error of an image against `reference` for each subframe count.
fn image_table(c: &Camera, splats: &[Splat], kernel: KernelParams, reference: &[[f64; 4]]) {
    println!("| subframes | max abs error | mean abs error |\n|---|---|---|");
    for n in SUBFRAMES {
        let f = render(c, splats, BG, &settings(n, kernel, 1.0)).unwrap();
        println!(
            "| {n} | {:.1e} | {:.1e} |",
            max_diff(&f.pixels, reference),
            mean_diff(&f.pixels, reference)
        );
    }
    println!();
}

fn axes() {
    println!("## axes: kernel axes fixed per subframe (the mean of the subframe's end keys)\n");
    println!(
        "16 splats (radius 0.3) rotating 60 deg about an in-plane axis and growing 1.5x, 32 x 32,"
    );
    println!("reference 1024 instants of static EWA with the interpolated keys");
    let c = camera(DVec3::new(0.0, 0.0, 4.0), 0.8, 32, 32);
    let splats = turning_grid(60f64.to_radians(), 1.5);
    let reference = common::supersample_culled(&c, &splats, BG, 2.0, 1.0, 1024);
    image_table(&c, &splats, KernelParams::default(), &reference);
}

fn static_axis() {
    println!(
        "## static-axis: minimum temporal axis of static splats (min_a3_rel x radius along the normal)\n"
    );
    println!(
        "(a) 25 overlapping static splats (radius 0.45, spacing 0.3, random colours) tilted 60 deg"
    );
    println!("about x, seen obliquely, 32 x 32, vs static EWA");
    println!("| min_a3_rel | max abs error | mean abs error |\n|---|---|---|");
    let c = camera(DVec3::new(0.0, 2.0, 3.5), 0.8, 32, 32);
    let normal = DVec3::new(0.0, (60f64).to_radians().sin(), (60f64).to_radians().cos());
    let (u, v) = normal.any_orthonormal_pair();
    let mut rng = Pcg64::seed_from_u64(3);
    let mut splats = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            let centre = (i as f64 - 2.0) * 0.3 * u + (j as f64 - 2.0) * 0.3 * v;
            let col = [rng.random(), rng.random(), rng.random(), 1.0];
            splats.push(Splat::fixed(SplatKey::disc(centre, normal, 0.45), col));
        }
    }
    let reference = common::supersample(&c, &splats, BG, 2.0, 1.0, 1);
    for rel in [1e-3, 1e-5, 1e-7] {
        let kernel = KernelParams {
            min_a3_rel: rel,
            ..KernelParams::default()
        };
        let f = render(&c, &splats, BG, &settings(1, kernel, 1.0)).unwrap();
        println!(
            "| {rel:.0e} | {:.1e} | {:.1e} |",
            max_diff(&f.pixels, &reference),
            mean_diff(&f.pixels, &reference)
        );
    }
    println!(
        "\n(b) crossing time: a static sheet crossed by one moving at relative depth speed v (no depth"
    );
    println!(
        "tolerance, one pixel, radius 1): the static kernel's depth sweeps +-min_a3_rel per subframe"
    );
    println!("| v | subframes | error, min_a3_rel 1e-3 | error, 1e-7 |\n|---|---|---|---|");
    let c = camera(DVec3::new(0.0, 0.0, 5.0), 0.02, 1, 1);
    for v in [1.0, 0.1, 0.01] {
        let disc = |z| SplatKey::disc(DVec3::new(0.0, 0.0, z), DVec3::Z, 1.0);
        let splats = [
            Splat::fixed(disc(0.0), [1.0, 0.0, 0.0, 1.0]),
            Splat::linear(disc(-0.4 * v), disc(0.6 * v), [0.0, 1.0, 0.0, 1.0]),
        ];
        let want = dense_pixel(&c, &splats, (0.5, 0.5), 0.0, 4096);
        for n in [1, 4] {
            let err = |rel| {
                let kernel = KernelParams {
                    min_a3_rel: rel,
                    ..KernelParams::default()
                };
                pixel_err(
                    render(&c, &splats, BG, &settings(n, kernel, 0.0))
                        .unwrap()
                        .pixels[0],
                    want,
                )
            };
            println!("| {v} | {n} | {:.1e} | {:.1e} |", err(1e-3), err(1e-7));
        }
    }
    println!();
}

fn tilt() {
    println!("## tilt: minimum angle between a3 and the splat plane (tangential motion)\n");
    println!(
        "a splat (radius 0.35) sliding 1.6 along its plane, seen 40 deg off its normal, 32 x 32,"
    );
    println!("reference 2048 instants");
    let c = camera(DVec3::new(3.2, 0.0, 3.8), 0.8, 32, 32);
    let splats = [Splat::moving_disc(
        DVec3::new(-0.8, 0.0, 0.0),
        DVec3::new(1.6, 0.0, 0.0),
        DVec3::Z,
        0.35,
        [1.0, 0.8, 0.2, 1.0],
    )];
    let reference = common::supersample(&c, &splats, BG, 2.0, 1.0, 2048);
    println!("| min_angle | subframes | max abs error | mean abs error |\n|---|---|---|---|");
    for deg in [1.0, 0.1, 0.01] {
        let kernel = KernelParams {
            min_angle: f64::to_radians(deg),
            ..KernelParams::default()
        };
        for n in [1, 4, 16] {
            let f = render(&c, &splats, BG, &settings(n, kernel, 1.0)).unwrap();
            println!(
                "| {deg} deg | {n} | {:.1e} | {:.1e} |",
                max_diff(&f.pixels, &reference),
                mean_diff(&f.pixels, &reference)
            );
        }
    }
    println!();
}

fn normalise() {
    println!(
        "## normalise: one surface's colour normalised per piece (ratio of weight integrals, §5.4)\n"
    );
    println!(
        "a sheet of 36 overlapping splats (radius 0.3, spacing 0.25, random colours) sliding 0.6"
    );
    println!(
        "along its plane, seen along its normal, 32 x 32, reference 1024 instants; min_angle 0.1 deg only"
    );
    println!("moves the kernels in depth here (the view is along the normal)");
    let c = camera(DVec3::new(0.0, 0.0, 4.0), 0.8, 32, 32);
    let mut rng = Pcg64::seed_from_u64(5);
    let mut splats = Vec::new();
    for i in 0..6 {
        for j in 0..6 {
            let centre = DVec3::new(-0.9 + 0.25 * i as f64, -0.6 + 0.25 * j as f64, 0.0);
            let col = [rng.random(), rng.random(), rng.random(), 1.0];
            splats.push(Splat::moving_disc(
                centre,
                DVec3::new(0.6, 0.0, 0.0),
                DVec3::Z,
                0.3,
                col,
            ));
        }
    }
    let reference = common::supersample_culled(&c, &splats, BG, 2.0, 1.0, 1024);
    image_table(&c, &splats, KernelParams::default(), &reference);
}

/// A ball of `n` tangent splats of radius `r` (Fibonacci sphere, radius `scale`) at
/// `centre`, translating by `motion`.
fn ball(
    n: usize,
    r: f64,
    scale: f64,
    centre: DVec3,
    motion: DVec3,
    colour: [f32; 4],
) -> Vec<Splat> {
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let ring = (1.0 - y * y).sqrt();
            let phi = i as f64 * 2.399_963;
            let normal = DVec3::new(ring * phi.cos(), y, ring * phi.sin());
            Splat::moving_disc(centre + normal * scale, motion, normal, r, colour)
        })
        .collect()
}

/// Render times (best of 5) of three scenes at 160 x 120: the render bench's two sheets
/// (no surface crossings), `splat_image`'s ring over a wall (none), and two balls of 1500
/// splats passing through each other (many).
fn cost() {
    println!("## cost: render time, best of 5, 160 x 120 (A-buffer, erf Full)\n");
    let c = camera(DVec3::new(0.0, 0.0, 4.0), 0.9, 160, 120);
    let mut sheets = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let (u, v) = (i as f64 * 0.2 - 0.9, j as f64 * 0.2 - 0.9);
            let g = 0.3 + 0.05 * ((3 * i + 7 * j) % 10) as f32;
            sheets.push(Splat::fixed(
                SplatKey::disc(DVec3::new(u, v, 0.0), DVec3::Z, 0.16),
                [g, g, g, 1.0],
            ));
            let open = DVec3::new(0.5 * u - 0.8, 0.5 * v - 0.3, 1.0);
            sheets.push(Splat::moving_disc(
                open,
                DVec3::new(1.2, 0.5, 0.2),
                DVec3::new(0.1, 0.0, 1.0),
                0.08,
                [0.9, 0.5, 0.1, 1.0],
            ));
        }
    }
    let mut ring = Vec::new();
    for i in 0..90 {
        let a0 = std::f64::consts::TAU * i as f64 / 90.0;
        let keys = (0..5)
            .map(|k| {
                let a = a0 + 0.6 * k as f64 / 4.0;
                SplatKey::disc(DVec3::new(a.cos(), a.sin(), 0.5), DVec3::Z, 0.09)
            })
            .collect();
        ring.push(Splat {
            keys,
            colour: [0.5, 0.4, 0.3, 1.0],
            span: [0.0, 1.0],
        });
    }
    for i in 0..12 {
        for j in 0..12 {
            let centre = DVec3::new(-1.65 + 0.3 * i as f64, -1.65 + 0.3 * j as f64, -0.5);
            ring.push(Splat::fixed(
                SplatKey::disc(centre, DVec3::Z, 0.22),
                [0.5, 0.5, 0.5, 1.0],
            ));
        }
    }
    let mut balls = ball(
        1500,
        0.1,
        1.0,
        DVec3::new(-0.4, 0.0, 0.0),
        DVec3::new(0.8, 0.1, 0.3),
        [0.5, 0.5, 0.5, 1.0],
    );
    balls.extend(ball(
        1500,
        0.08,
        0.7,
        DVec3::new(0.6, 0.2, -1.0),
        DVec3::new(-0.6, 0.0, 2.0),
        [0.9, 0.1, 0.1, 1.0],
    ));
    println!(
        "| scene | subframes | time | fragments | max per pixel | line integrals |\n|---|---|---|---|---|---|"
    );
    for (name, splats) in [("sheets", &sheets), ("ring", &ring), ("balls", &balls)] {
        for n in [1, 4, 16] {
            let s = settings(n, KernelParams::default(), 1.0);
            let mut best = f64::INFINITY;
            let mut stats = None;
            for _ in 0..5 {
                let t = std::time::Instant::now();
                let f = render(&c, splats, BG, &s).unwrap();
                best = best.min(t.elapsed().as_secs_f64());
                stats = Some(f.stats);
            }
            let st = stats.unwrap_or_default();
            println!(
                "| {name} | {n} | {:.1} ms | {} | {} | {} |",
                best * 1e3,
                st.fragments,
                st.max_fragments_per_pixel,
                st.line_integrals
            );
        }
    }
    println!();
}

fn main() {
    let topics: Vec<String> = std::env::args().skip(1).collect();
    let all = topics.is_empty();
    let run = |name: &str, f: fn()| {
        if all || topics.iter().any(|t| t == name) {
            f();
        }
    };
    run("crossing", crossing);
    run("tolerance", tolerance);
    run("axes", axes);
    run("static-axis", static_axis);
    run("tilt", tilt);
    run("normalise", normalise);
    if topics.iter().any(|t| t == "cost") {
        cost();
    }
}
