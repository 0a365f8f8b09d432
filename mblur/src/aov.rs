//! Arbitrary output variables (AOVs): the per-pixel data a compositing or dataset pipeline
//! wants next to the motion-blurred image, each defined at the pixel centre like the image:
//!
//! - **depth**: the view depth of the nearest surface, averaged over the part of the shutter
//!   during which some surface covers the pixel (weighted by the shutter response); the far
//!   plane where nothing ever covers it;
//! - **motion**: the screen-space displacement, in pixels (+x right, +y down), from shutter
//!   open to shutter close of the surface point visible at the sharp instant; 0 where no
//!   surface is visible then. The point keeps its perspective-correct barycentric weights as
//!   the corners move in 2DH (Gribel 2010, Eq. 2), so a translating surface's vector is its
//!   exact displacement;
//! - **sharp**: the image at one instant of the shutter (a static render);
//! - **id**: 1 + the object index of the surface visible at the sharp instant, 0 where none
//!   is;
//! - **coverage**: the fraction of the shutter (weighted by its response) during which some
//!   surface covers the pixel.
//!
//! "Surface" means any triangle whatever its material's opacity: a transparent pane in front
//! of a wall gives the pane's depth, motion and id, and counts as coverage. Splats are
//! rendered as the discs of the static path. Depth and coverage are sampled at the
//! sub-frame times of `accum` ([`crate::accum::sample_times`]): exact for a static scene,
//! converging with the number of times for a moving one; motion, id and sharp are exact at
//! their instant.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::Progress;
use crate::static_path::{BAND_ROWS, FrameTriangles, splats_as_discs};

/// Which AOVs to compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AovSet {
    /// Shutter-averaged depth of the nearest surface.
    pub depth: bool,
    /// Screen-space motion vectors of the surface visible at the sharp instant.
    pub motion: bool,
    /// The image at the sharp instant.
    pub sharp: bool,
    /// Object id of the surface visible at the sharp instant.
    pub id: bool,
    /// Fraction of the shutter the pixel is covered.
    pub coverage: bool,
}

impl AovSet {
    /// Every AOV.
    pub const ALL: AovSet = AovSet {
        depth: true,
        motion: true,
        sharp: true,
        id: true,
        coverage: true,
    };

    /// True when no AOV is asked for.
    pub fn is_empty(&self) -> bool {
        *self == AovSet::default()
    }
}

/// How the AOVs are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AovOptions {
    /// The sharp instant, in [0, 1] (fraction of the shutter), for `sharp`, `id` and
    /// `motion`.
    pub sharp_at: f64,
    /// Sub-frame times for `depth` and `coverage` (default: `accum`'s automatic count,
    /// [`crate::accum::auto_times`]).
    pub times: Option<u32>,
}

impl Default for AovOptions {
    fn default() -> Self {
        AovOptions {
            sharp_at: 0.5,
            times: None,
        }
    }
}

impl AovOptions {
    /// Checks the options: `sharp_at` in [0, 1], `times` in 1..=4096.
    pub fn validate(&self) -> Result<()> {
        if !(0.0..=1.0).contains(&self.sharp_at) {
            return Err(Error::Setting {
                method: "aov",
                setting: "sharp_at",
                message: format!("must be in [0, 1], got {}", self.sharp_at),
            });
        }
        if let Some(n) = self.times
            && !(1..=4096).contains(&n)
        {
            return Err(Error::Setting {
                method: "aov",
                setting: "times",
                message: format!("must be between 1 and 4096, got {n}"),
            });
        }
        Ok(())
    }
}

/// The AOVs asked for, each row-major from the top row (`None` for those not asked for).
#[derive(Debug, Clone, PartialEq)]
pub struct Aovs {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Shutter-averaged view depth of the nearest surface (the far plane where never
    /// covered).
    pub depth: Option<Vec<f32>>,
    /// Screen-space motion (x, y) in pixels from open to close.
    pub motion: Option<Vec<[f32; 2]>>,
    /// The image at the sharp instant.
    pub sharp: Option<Image>,
    /// 1 + object index at the sharp instant, 0 for none.
    pub id: Option<Vec<u32>>,
    /// Fraction of the shutter covered, in [0, 1].
    pub coverage: Option<Vec<f32>>,
}

/// The nearest surface at a pixel centre at one instant.
#[derive(Debug, Clone, Copy)]
struct Nearest {
    depth: f64,
    triangle: u32,
    bary: [f64; 3],
}

/// The nearest surface at every pixel centre at time `t` (the later triangle wins an exact
/// depth tie, as in the static path).
fn nearest_at(scene: &PreparedScene, all: &[u32], t: f64) -> Vec<Option<Nearest>> {
    let frame = FrameTriangles::of(scene, all, t);
    let w = scene.width as usize;
    let mut out = vec![None; w * scene.height as usize];
    out.par_chunks_mut(w * BAND_ROWS as usize)
        .zip(frame.bins().all().par_iter())
        .enumerate()
        .for_each(|(band, (chunk, bin))| {
            let row0 = band as u32 * BAND_ROWS;
            let row1 = (row0 + BAND_ROWS).min(scene.height);
            for &i in bin {
                let Some(st) = frame.get(i) else {
                    continue;
                };
                st.rasterise(row0, row1, |x, y, f| {
                    let slot = chunk.get_mut((y - row0) as usize * w + x as usize);
                    if let Some(slot) = slot
                        && slot.is_none_or(|n: Nearest| f.depth <= n.depth)
                    {
                        *slot = Some(Nearest {
                            depth: f.depth,
                            triangle: st.order,
                            bary: f.bary,
                        });
                    }
                });
            }
        });
    out
}

/// Screen displacement (close - open) of the point with barycentric weights `bary` on
/// triangle `t`, its corners placed on their true path at shutter open and close; zero
/// where either end is behind the camera or not finite.
fn motion_of(scene: &PreparedScene, n: &Nearest) -> [f32; 2] {
    let Some(tri) = scene.triangles.get(n.triangle as usize) else {
        return [0.0; 2];
    };
    let at = |v: &[crate::camera::Vertex2dh; 3]| {
        let (mut x, mut y, mut w) = (0.0, 0.0, 0.0);
        for (b, p) in n.bary.iter().zip(v) {
            (x, y, w) = (x + b * p.x, y + b * p.y, w + b * p.w);
        }
        (w > 0.0).then(|| (x / w, y / w))
    };
    // On the true path at shutter open and close (for a segment of a curved path, not at
    // its span's ends).
    match (
        at(&scene.corners_at(tri, 0.0)),
        at(&scene.corners_at(tri, 1.0)),
    ) {
        (Some(a), Some(b)) => {
            let d = [(b.0 - a.0) as f32, (b.1 - a.1) as f32];
            if d.iter().all(|v| v.is_finite()) {
                d
            } else {
                [0.0; 2]
            }
        }
        _ => [0.0; 2],
    }
}

/// Computes the AOVs of `which` for `scene`; one progress step per sub-frame time, one for
/// the sharp instant.
pub fn render_aovs(
    scene: &PreparedScene,
    which: AovSet,
    options: &AovOptions,
    progress: &dyn Progress,
) -> Result<Aovs> {
    options.validate()?;
    let discs;
    let scene = if scene.splats.is_empty() {
        scene
    } else {
        discs = splats_as_discs(scene);
        &discs
    };
    let all: Vec<u32> = (0..scene.triangles.len() as u32).collect();
    let pixels = scene.width as usize * scene.height as usize;
    let sampled = which.depth || which.coverage;
    let times = if sampled {
        let n = options
            .times
            .unwrap_or_else(|| crate::accum::auto_times(scene));
        crate::accum::sample_times(scene, n, None)
    } else {
        Vec::new()
    };
    progress.start(times.len() as u64 + 1, "sub-frames");
    let mut covered = vec![0.0f64; if sampled { pixels } else { 0 }];
    let mut depth_sum = vec![0.0f64; if sampled { pixels } else { 0 }];
    for &(t, weight) in &times {
        let nearest = nearest_at(scene, &all, t);
        covered
            .par_iter_mut()
            .zip(depth_sum.par_iter_mut())
            .zip(nearest.par_iter())
            .for_each(|((c, d), n)| {
                if let Some(n) = n {
                    *c += weight;
                    *d += weight * n.depth;
                }
            });
        progress.advance(1);
    }
    let sharp_nearest =
        (which.motion || which.id).then(|| nearest_at(scene, &all, options.sharp_at));
    let aovs = Aovs {
        width: scene.width,
        height: scene.height,
        depth: which.depth.then(|| {
            covered
                .iter()
                .zip(&depth_sum)
                .map(|(&c, &d)| {
                    if c > 0.0 {
                        (d / c) as f32
                    } else {
                        scene.far as f32
                    }
                })
                .collect()
        }),
        coverage: which
            .coverage
            .then(|| covered.iter().map(|&c| c.clamp(0.0, 1.0) as f32).collect()),
        motion: which.motion.then(|| {
            sharp_nearest
                .iter()
                .flatten()
                .map(|n| n.as_ref().map_or([0.0; 2], |n| motion_of(scene, n)))
                .collect()
        }),
        id: which.id.then(|| {
            sharp_nearest
                .iter()
                .flatten()
                .map(|n| {
                    n.and_then(|n| scene.triangles.get(n.triangle as usize))
                        .map_or(0, |t| t.object + 1)
                })
                .collect()
        }),
        sharp: which
            .sharp
            .then(|| crate::static_path::render_at(scene, options.sharp_at)),
    };
    progress.advance(1);
    progress.finish();
    Ok(aovs)
}
