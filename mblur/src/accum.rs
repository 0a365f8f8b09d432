//! The `accum` method: N static renders at evenly spaced (or jittered) times, averaged with
//! the shutter response — the ground truth the analytic, prism, stochastic and EWA methods
//! are compared against.
//!
//! The shutter [0, 1] is cut into N equal strata; stratum k is rendered at its midpoint (or
//! at a seeded uniform time inside it with jitter) and weighted by the exact integral of
//! w(t) over the stratum divided by the integral over [0, 1]. Each sub-frame is an ordinary
//! static render (see [`crate::raster`]): near-plane clipping, LESS_EQUAL depth, transparent
//! fragments sorted and blended front to back. Splats are drawn as oriented 16-sided discs
//! of their radius (the EWA method filters them with Gaussians instead).

use std::collections::HashMap;

use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::{Material, PreparedScene, PreparedTriangle};
use crate::progress::Progress;
use crate::raster::{FragmentBuffer, ScreenTriangle, Target, setup};

/// Rows per parallel band.
const BAND_ROWS: u32 = 8;
/// Largest accepted `--times`.
pub const MAX_TIMES: u32 = 1 << 16;
/// Sides of the polygon a splat is drawn as.
pub const SPLAT_DISC_SIDES: u32 = 16;

/// Options of the accumulation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AccumOptions {
    /// Number of sub-frames; `None` picks [`auto_times`].
    pub times: Option<u32>,
    /// Seed for jittered times within each stratum; `None` uses stratum midpoints.
    pub jitter: Option<u64>,
}

/// The largest screen-space displacement (pixels) of any vertex or splat centre over the
/// shutter (vertices behind the eye are ignored).
pub fn max_motion_pixels(scene: &PreparedScene) -> f64 {
    let disp = |a: crate::camera::Vertex2dh, b: crate::camera::Vertex2dh| {
        if a.w > 0.0 && b.w > 0.0 {
            let ((ax, ay), (bx, by)) = (a.screen(), b.screen());
            let d = ((bx - ax).powi(2) + (by - ay).powi(2)).sqrt();
            if d.is_finite() { d } else { 0.0 }
        } else {
            0.0
        }
    };
    let tri = scene
        .triangles
        .par_iter()
        .filter(|t| t.is_moving())
        .map(|t| {
            (0..3)
                .map(|k| disp(t.open[k], t.close[k]))
                .fold(0.0, f64::max)
        })
        .reduce(|| 0.0, f64::max);
    let spl = scene
        .splats
        .iter()
        .map(|s| disp(s.open, s.close))
        .fold(0.0, f64::max);
    tri.max(spl)
}

/// Automatic sub-frame count: one frame for a static scene, otherwise enough that no vertex
/// moves more than half a pixel between sub-frames (at least 16, at most 4096).
pub fn auto_times(scene: &PreparedScene) -> u32 {
    let moving = scene.triangles.iter().any(PreparedTriangle::is_moving)
        || scene.splats.iter().any(|s| scene.splat_moves(s));
    if !moving {
        return 1;
    }
    let m = max_motion_pixels(scene);
    ((2.0 * m).ceil() as u32).clamp(16, 4096)
}

/// The sub-frame times and weights (weights sum to 1).
pub fn sample_times(scene: &PreparedScene, n: u32, jitter: Option<u64>) -> Vec<(f64, f64)> {
    let total = scene.shutter.integral(0.0, 1.0);
    let mut rng = jitter.map(rand_pcg::Pcg32::seed_from_u64);
    let nf = f64::from(n);
    (0..n)
        .map(|k| {
            let (a, b) = (f64::from(k) / nf, f64::from(k + 1) / nf);
            let u = rng.as_mut().map_or(0.5, |r| r.random::<f64>());
            (a + (b - a) * u, scene.shutter.integral(a, b) / total)
        })
        .filter(|&(_, w)| w > 0.0)
        .collect()
}

fn basis(n: DVec3) -> (DVec3, DVec3) {
    n.any_orthonormal_pair()
}

/// The scene with every splat replaced by an oriented disc of triangles (one material per
/// distinct splat colour), for static rasterisation.
pub fn splats_as_discs(scene: &PreparedScene) -> PreparedScene {
    let mut out = scene.clone();
    if scene.splats.is_empty() {
        return out;
    }
    let mut mats: HashMap<[u64; 4], u32> = HashMap::new();
    let sides = SPLAT_DISC_SIDES;
    let object_base = out.objects.len() as u32;
    for s in &scene.splats {
        let key = s.color.map(f64::to_bits);
        let material = *mats.entry(key).or_insert_with(|| {
            out.materials.push(Material {
                color: s.color,
                texture: None,
            });
            (out.materials.len() - 1) as u32
        });
        let (uo, vo) = basis(s.normal_open);
        let (uc, vc) = basis(s.normal_close);
        let ring = |c: DVec3, u: DVec3, v: DVec3, r: f64, k: u32| {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(sides);
            c + (u * a.cos() + v * a.sin()) * r
        };
        for k in 0..sides {
            let k1 = (k + 1) % sides;
            let world_open = [
                s.centre_open,
                ring(s.centre_open, uo, vo, s.radius_open, k),
                ring(s.centre_open, uo, vo, s.radius_open, k1),
            ];
            let world_close = [
                s.centre_close,
                ring(s.centre_close, uc, vc, s.radius_close, k),
                ring(s.centre_close, uc, vc, s.radius_close, k1),
            ];
            out.triangles.push(PreparedTriangle {
                object: object_base + s.object,
                material,
                open: world_open.map(|p| scene.camera_open.project(p)),
                close: world_close.map(|p| scene.camera_close.project(p)),
                world_open,
                world_close,
                uv: [DVec2::ZERO; 3],
                normal_open: [s.normal_open; 3],
                normal_close: [s.normal_close; 3],
            });
        }
    }
    out
}

/// The static path as the methods take it for a scene where nothing moves: one static
/// render ([`render`] with one time, no jitter), reported as one progress step.
pub(crate) fn static_path(scene: &PreparedScene, progress: &dyn Progress) -> Result<Image> {
    render(
        scene,
        &AccumOptions {
            times: Some(1),
            jitter: None,
        },
        progress,
    )
}

/// One static render at time `t` (the static path), as linear RGB.
pub fn render_static(scene: &PreparedScene, t: f64) -> Image {
    let scene = splats_as_discs(scene);
    let all: Vec<u32> = (0..scene.triangles.len() as u32).collect();
    let mut acc = vec![[0.0f64; 3]; scene.width as usize * scene.height as usize];
    let mut bands = make_bands(&scene);
    draw(&scene, &all, t, &mut bands, None);
    add(&scene, &bands, 1.0, &mut acc);
    to_image(&scene, &acc)
}

/// Renders with N sub-frames (the ground truth). Reports one progress step per sub-frame.
///
/// Static triangles (no 2DH motion) are rasterised once into a base layer that every
/// sub-frame starts from; only moving triangles are rasterised per sub-frame.
pub fn render(
    scene: &PreparedScene,
    opts: &AccumOptions,
    progress: &dyn Progress,
) -> Result<Image> {
    let n = opts.times.unwrap_or_else(|| auto_times(scene));
    if n == 0 || n > MAX_TIMES {
        return Err(Error::Option {
            option: "--times".into(),
            message: format!("must be between 1 and {MAX_TIMES}, got {n}"),
        });
    }
    let scene = splats_as_discs(scene);
    let times = sample_times(&scene, n, opts.jitter);
    let (moving, fixed): (Vec<u32>, Vec<u32>) =
        (0..scene.triangles.len() as u32).partition(|&i| scene.triangles[i as usize].is_moving());
    let mut acc = vec![[0.0f64; 3]; scene.width as usize * scene.height as usize];
    let mut bands = make_bands(&scene);
    progress.start(times.len() as u64);
    let base = if fixed.is_empty() || times.len() == 1 {
        None
    } else {
        let mut base = make_bands(&scene);
        draw(&scene, &fixed, 0.0, &mut base, None);
        Some(base)
    };
    let per_frame = if base.is_some() {
        moving
    } else {
        (0..scene.triangles.len() as u32).collect()
    };
    for &(t, w) in &times {
        draw(&scene, &per_frame, t, &mut bands, base.as_deref());
        add(&scene, &bands, w, &mut acc);
        progress.advance(1);
    }
    progress.finish();
    Ok(to_image(&scene, &acc))
}

fn make_bands(scene: &PreparedScene) -> Vec<FragmentBuffer> {
    (0..scene.height.div_ceil(BAND_ROWS))
        .map(|b| {
            let row0 = b * BAND_ROWS;
            FragmentBuffer::new(scene.width, row0, BAND_ROWS.min(scene.height - row0))
        })
        .collect()
}

fn to_image(scene: &PreparedScene, acc: &[[f64; 3]]) -> Image {
    Image {
        width: scene.width,
        height: scene.height,
        pixels: acc
            .iter()
            .map(|p| p.map(|c| if c.is_finite() { c as f32 } else { 0.0 }))
            .collect(),
    }
}

/// Resets every band (to `base` or empty) and rasterises triangles `which` at time `t`.
fn draw(
    scene: &PreparedScene,
    which: &[u32],
    t: f64,
    bands: &mut [FragmentBuffer],
    base: Option<&[FragmentBuffer]>,
) {
    let target = Target {
        width: scene.width,
        height: scene.height,
        near: scene.near,
    };
    let tris: Vec<ScreenTriangle> = which
        .par_iter()
        .fold(Vec::new, |mut v, &i| {
            if let Some(tri) = scene.triangles.get(i as usize) {
                setup(tri, t, i, scene.is_opaque(tri.material), &target, &mut v);
            }
            v
        })
        .reduce(Vec::new, |mut a, mut b| {
            a.append(&mut b);
            a
        });
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); bands.len()];
    for (i, st) in tris.iter().enumerate() {
        for b in st.y0 / BAND_ROWS..=st.y1 / BAND_ROWS {
            if let Some(bin) = bins.get_mut(b as usize) {
                bin.push(i as u32);
            }
        }
    }
    bands
        .par_iter_mut()
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(k, (band, bin))| {
            match base.and_then(|b| b.get(k)) {
                Some(b) => band.reset_from(b),
                None => band.clear(),
            }
            for &i in bin {
                band.draw(scene, &tris[i as usize]);
            }
        });
}

/// Resolves every band and adds `weight` times the colours to `acc`.
fn add(scene: &PreparedScene, bands: &[FragmentBuffer], weight: f64, acc: &mut [[f64; 3]]) {
    let band_pixels = (scene.width * BAND_ROWS) as usize;
    bands
        .par_iter()
        .zip(acc.par_chunks_mut(band_pixels))
        .for_each(|(band, out)| {
            band.resolve(scene.background, |i, c| {
                if let Some(o) = out.get_mut(i) {
                    for k in 0..3 {
                        o[k] += weight * c[k];
                    }
                }
            });
        });
}
