//! Splat sets in preparation: how a set's splats move (keyed transforms as for objects, or
//! straight open-to-close positions), the cut times of its shutter ([`crate::segments`],
//! the same segmentation and tolerance as triangle objects, on the splat centres) and its
//! prepared splats, one per splat and segment.

use glam::{DAffine3, DVec3};

use mblur::motion::MotionPath;
use mblur::{ObjectInfo, PreparedScene, PreparedSplat, SplatLocal};

use crate::error::{Error, Result};
use crate::prepare::{bounds, check_finite, normal_matrix};
use crate::segments::MotionOptions;

/// A splat in object space: position, normal, radius and colour.
pub(crate) type SplatPoint = (DVec3, DVec3, f64, [f64; 4]);

/// How the splats of a set move over the shutter.
pub(crate) enum SplatMotion {
    /// Keyed transforms (placement included), as for triangle objects.
    Path(MotionPath),
    /// World positions at close (`positions_close`) and the placements at open and close:
    /// one straight segment.
    Ends {
        /// Placement at open (the centres at open, the normals and radii before close).
        open: DAffine3,
        /// Placement at close (the normals and radii at close).
        close: DAffine3,
        /// World centres at close, one per splat.
        positions: Vec<DVec3>,
    },
}

/// A transform's placement of splats: the affine map, its normal matrix and the radius
/// factor (the cube root of the volume scale: exact for a uniform scale).
struct Placement {
    affine: DAffine3,
    normals: glam::DMat3,
    radius: f64,
}

impl Placement {
    fn new(affine: DAffine3) -> Self {
        Placement {
            normals: normal_matrix(&affine),
            radius: affine.matrix3.determinant().abs().cbrt(),
            affine,
        }
    }
}

/// One splat of a set ready to be added: the set's index, name and field, its object-space
/// splats and motion.
pub(crate) struct SplatSet<'a> {
    /// Index of the set in the scene's `splat_objects`.
    pub index: u32,
    /// Its name.
    pub name: &'a str,
    /// Where it is described, for messages (`splats[0] "dust"`).
    pub field: &'a str,
    /// Its splats in object space.
    pub points: &'a [SplatPoint],
    /// How they move.
    pub motion: SplatMotion,
    /// Index of its material (`u32::MAX` when unlit).
    pub material: u32,
}

/// Adds a splat set: its splats (one per splat and span of its shutter, cut as a triangle
/// object's is) and its entry.
pub(crate) fn add_splat_set(
    file: &str,
    opts: &MotionOptions,
    scene: &mut PreparedScene,
    set: SplatSet<'_>,
) -> Result<()> {
    let path = match &set.motion {
        SplatMotion::Path(p) => Some(p),
        SplatMotion::Ends { .. } => None,
    };
    let centres: Vec<DVec3> = set.points.iter().map(|p| p.0).collect();
    let times = crate::segments::segment_times(scene, path, &centres, opts)
        .map_err(|m| Error::invalid(file, format!("{}.motion", set.field), m))?;
    let curved = path.filter(|p| p.is_curved());
    // The placements at the cut times (for straight motion: open before close, close at
    // shutter close, as a triangle object's normals take them).
    let placements: Vec<Placement> = times
        .iter()
        .map(|&t| match &set.motion {
            SplatMotion::Path(p) => Placement::new(p.affine(t)),
            SplatMotion::Ends { open, close, .. } => {
                Placement::new(if t < 1.0 { *open } else { *close })
            }
        })
        .collect();
    let centre_at = |i: usize, k: usize, p: DVec3| -> DVec3 {
        match &set.motion {
            SplatMotion::Ends {
                open, positions, ..
            } => {
                let (a, b) = (open.transform_point3(p), positions[i]);
                let t = times[k];
                a * (1.0 - t) + b * t
            }
            SplatMotion::Path(_) => placements[k].affine.transform_point3(p),
        }
    };
    let start = scene.splats.len();
    let mut all = Vec::with_capacity(2 * set.points.len());
    let mut rmax: f64 = 0.0;
    for (i, &(p, n, r, color)) in set.points.iter().enumerate() {
        for (k, w) in times.windows(2).enumerate() {
            let (a, b) = (&placements[k], &placements[k + 1]);
            let centre_open = check_finite(file, set.field, centre_at(i, k, p))?;
            let centre_close = check_finite(file, set.field, centre_at(i, k + 1, p))?;
            all.push(centre_open);
            all.push(centre_close);
            let splat = PreparedSplat {
                object: set.index,
                centre_open,
                centre_close,
                normal_open: (a.normals * n).normalize_or(DVec3::Z),
                normal_close: (b.normals * n).normalize_or(DVec3::Z),
                radius_open: r * a.radius,
                radius_close: r * b.radius,
                color,
                open: scene.project_at(w[0], centre_open),
                close: scene.project_at(w[1], centre_close),
                span: [w[0], w[1]],
                local: curved.map(|_| SplatLocal {
                    centre: p,
                    normal: n,
                    radius: r,
                }),
            };
            rmax = rmax.max(splat.radius_open).max(splat.radius_close);
            scene.splats.push(splat);
        }
    }
    let (lo, hi) = bounds(all.into_iter());
    scene.splat_objects.push(ObjectInfo {
        name: set.name.to_string(),
        range: start..scene.splats.len(),
        material: set.material,
        swept_bounds: (lo - DVec3::splat(rmax), hi + DVec3::splat(rmax)),
        path: curved.cloned(),
        segments: (times.len() - 1) as u32,
    });
    Ok(())
}
