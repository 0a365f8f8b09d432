//! Triangle objects in preparation: how an object's vertices move ([`VertexMotion`]:
//! keyed transforms, straight open-to-close positions, or positions at keys), the cut times
//! of its shutter, and its prepared triangles, one per span.

use glam::{DAffine3, DMat3, DVec3};
use rayon::prelude::*;

use mblur::motion::MotionPath;
use mblur::{ObjectInfo, PreparedScene, PreparedTriangle, Vertex2dh};

use crate::desc::NormalsDesc;
use crate::error::{Error, Result};
use crate::mesh::{self, Mesh};
use crate::prepare::{bounds, check_finite, normal_matrix};
use crate::segments::MotionOptions;

/// How the vertices of a triangle object move over the shutter.
#[derive(Debug, Clone)]
pub(crate) enum VertexMotion {
    /// Keyed transforms (placement included): the shutter is cut at the keys and turning
    /// key pairs into segments ([`crate::segments`]).
    Path(MotionPath),
    /// World positions at open and close (one straight segment); the normals turn with
    /// the two placements.
    Ends {
        /// Positions at open.
        open: Vec<DVec3>,
        /// Positions at close.
        close: Vec<DVec3>,
        /// Placements at open and close (for the normals).
        placements: (DAffine3, DAffine3),
    },
    /// World positions at key times (non-decreasing from 0 to 1; a time given twice is a
    /// jump: the first entry is the position just before, the second the one from then
    /// on). Vertices move on straight lines between keys; normals are the smooth normals of
    /// the positions at each key (or the faces' with `normals: flat`).
    Keys(Vec<(f64, Vec<DVec3>)>),
}

/// World positions and normal matrix (`None`: the mesh's own normals do not apply) at one
/// cut time.
type Frame = (Vec<DVec3>, Option<DMat3>);

/// A triangle object ready to be added to a prepared scene.
pub(crate) struct MeshObject<'a> {
    /// The object's name.
    pub name: &'a str,
    /// Where it is described, for messages (`objects[2] "ball"`, a glTF node).
    pub field: &'a str,
    /// Its mesh (object space; [`VertexMotion::Path`] places it).
    pub mesh: &'a Mesh,
    /// Index of its material in the scene.
    pub material: u32,
    /// How it moves.
    pub motion: VertexMotion,
    /// Where its shading normals come from.
    pub normals: NormalsDesc,
}

/// The cut times of an object's shutter and the frames at them: span `s` runs from
/// `times[s]` (frame `opens[s]`) to `times[s + 1]` (frame `opens[s] + 1` unless the
/// motion jumps there, then the extra frame `closes[s]`).
struct Cuts {
    times: Vec<f64>,
    frames: Vec<Frame>,
    spans: Vec<(usize, usize)>,
}

/// Cuts the shutter of `object` and computes its world positions at the cuts.
fn cuts(
    file: &str,
    motion_opts: &MotionOptions,
    scene: &PreparedScene,
    object: &MeshObject<'_>,
) -> Result<Cuts> {
    let field = object.field;
    let positions = &object.mesh.positions;
    let path = match &object.motion {
        VertexMotion::Path(p) => Some(p),
        _ => None,
    };
    let mut times = crate::segments::segment_times(scene, path, positions, motion_opts)
        .map_err(|m| Error::invalid(file, format!("{field}.motion"), m))?;
    let mut frames: Vec<Frame> = Vec::new();
    let mut spans: Vec<(usize, usize)> = Vec::new();
    if let VertexMotion::Keys(keys) = &object.motion {
        times.extend(keys.iter().map(|k| k.0));
        times.sort_by(f64::total_cmp);
        times.dedup();
        for (i, &t) in times.iter().enumerate() {
            let (left, right) = (keyed_at(keys, t, false), keyed_at(keys, t, true));
            if i > 0 && left != right {
                frames.push((left, None));
                let close = frames.len() - 1;
                if let Some(span) = spans.last_mut() {
                    *span = (span.0, close);
                }
            }
            frames.push((right, None));
            if i + 1 < times.len() {
                spans.push((frames.len() - 1, frames.len()));
            }
        }
    } else {
        for &t in &times {
            frames.push(continuous_frame(&object.motion, t));
            spans.push((frames.len() - 1, frames.len()));
        }
        spans.pop();
    }
    for (world, _) in &frames {
        for p in world {
            check_finite(file, field, *p)?;
        }
    }
    Ok(Cuts {
        times,
        frames,
        spans,
    })
}

/// World positions and normal matrix at `t` of a path or a straight motion.
fn continuous_frame(motion: &VertexMotion, t: f64) -> Frame {
    match motion {
        VertexMotion::Path(p) => {
            let a = p.affine(t);
            (Vec::new(), Some(normal_matrix(&a)))
        }
        VertexMotion::Ends {
            open,
            close,
            placements,
        } => {
            let w = open.iter().zip(close).map(|(a, b)| *a * (1.0 - t) + *b * t);
            let n = if t < 1.0 {
                &placements.0
            } else {
                &placements.1
            };
            (w.collect(), Some(normal_matrix(n)))
        }
        VertexMotion::Keys(keys) => (keyed_at(keys, t, true), None),
    }
}

/// Positions of keyed motion at `t`: the limit from the left (`right` false) or from the
/// right; they differ only at a jump.
fn keyed_at(keys: &[(f64, Vec<DVec3>)], t: f64, right: bool) -> Vec<DVec3> {
    // The key pair (i, i + 1) holding t: t_i <= t < t_(i+1) from the right,
    // t_i < t <= t_(i+1) from the left.
    let i = if right {
        keys.iter().rposition(|k| k.0 <= t)
    } else {
        keys.iter()
            .position(|k| k.0 >= t)
            .and_then(|j| j.checked_sub(1))
    };
    let pair = i.and_then(|i| keys.get(i).zip(keys.get(i + 1)));
    match pair {
        Some((a, b)) if b.0 > a.0 => {
            let u = ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0);
            let lerp = |(p, q): (&DVec3, &DVec3)| *p * (1.0 - u) + *q * u;
            a.1.iter().zip(&b.1).map(lerp).collect()
        }
        _ => {
            let end = if keys.last().is_some_and(|k| t >= k.0) {
                keys.last()
            } else {
                keys.first()
            };
            end.map(|k| k.1.clone()).unwrap_or_default()
        }
    }
}

/// Adds a triangle object: its triangles (one per span of its shutter) and its entry.
pub(crate) fn add_mesh_object(
    file: &str,
    motion_opts: &MotionOptions,
    scene: &mut PreparedScene,
    object: MeshObject<'_>,
) -> Result<()> {
    let mut cuts = cuts(file, motion_opts, scene, &object)?;
    let keyed = matches!(object.motion, VertexMotion::Keys(_));
    let mesh = object.mesh;
    // Paths keep object-space positions: place them at every cut.
    if let VertexMotion::Path(p) = &object.motion {
        for (t, f) in cuts.times.iter().zip(cuts.frames.iter_mut()) {
            let a = p.affine(*t);
            f.0 = mesh
                .positions
                .par_iter()
                .map(|q| a.transform_point3(*q))
                .collect();
            for w in &f.0 {
                check_finite(file, object.field, *w)?;
            }
        }
    }
    let curved = match object.motion {
        VertexMotion::Path(p) => Some(p).filter(MotionPath::is_curved),
        _ => None,
    };
    // Smooth vertex normals at every cut, when some corner takes them (positions at keys
    // leave the mesh's own normals behind).
    let smooth = match object.normals {
        NormalsDesc::Smooth => true,
        NormalsDesc::Auto => {
            keyed
                || mesh
                    .triangles
                    .iter()
                    .flatten()
                    .any(|c| c.normal == DVec3::ZERO)
        }
        NormalsDesc::Flat => false,
    };
    let smooth: Vec<Vec<DVec3>> = cuts
        .frames
        .par_iter()
        .map(|f| {
            if smooth {
                crate::lights::smooth_normals(&f.0, &mesh.triangles)
            } else {
                Vec::new()
            }
        })
        .collect();
    let projected = project_frames(scene, &cuts);
    // The spans that have both frames, in order: triangle k's span j is the object's
    // triangle k * spans.len() + j.
    let spans: Vec<Span<'_>> = cuts
        .times
        .windows(2)
        .zip(&cuts.spans)
        .filter_map(|(w, &(o, c))| {
            Some(Span {
                times: [w[0], w[1]],
                frames: [o, c],
                open: cuts.frames.get(o)?,
                close: cuts.frames.get(c)?,
            })
        })
        .collect();
    let oi = scene.objects.len() as u32;
    let start = scene.triangles.len();
    // Built in parallel, in place, in the order of the serial loop over triangles then
    // spans (the scene's other fields are read meanwhile, so the list is taken out).
    let mut triangles = std::mem::take(&mut scene.triangles);
    {
        let scene = &*scene;
        let (smooth, projected, spans) = (&smooth, &projected, &spans);
        let per = spans.len().max(1);
        triangles.par_extend(
            (0..mesh.triangles.len() * spans.len())
                .into_par_iter()
                .map(|j| {
                    let t = &mesh.triangles[j / per];
                    let span = &spans[j % per];
                    let idx = t.map(|c| c.position as usize);
                    let local = curved
                        .as_ref()
                        .map(|_| idx.map(|i| mesh.position(i as u32)));
                    let corner = |f: &Frame, k: usize| {
                        let sm = smooth.get(k).map_or(&[][..], Vec::as_slice);
                        corner_frame(f, sm, object.normals, t, &idx)
                    };
                    let [o, c] = span.frames;
                    let ((world_open, normal_open), (world_close, normal_close)) =
                        (corner(span.open, o), corner(span.close, c));
                    // A corner past the frame's vertices sits at the origin, as in
                    // `corner_frame`.
                    let project = |frame: usize, t: f64| {
                        let cut = projected.get(frame).and_then(Option::as_ref);
                        idx.map(|i| {
                            cut.and_then(|v| v.get(i))
                                .copied()
                                .unwrap_or_else(|| scene.project_at(t, DVec3::ZERO))
                        })
                    };
                    PreparedTriangle {
                        object: oi,
                        material: object.material,
                        open: project(o, span.times[0]),
                        close: project(c, span.times[1]),
                        world_open,
                        world_close,
                        uv: t.map(|c| c.uv),
                        normal_open,
                        normal_close,
                        span: span.times,
                        local,
                    }
                }),
        );
    }
    scene.triangles = triangles;
    scene.objects.push(ObjectInfo {
        name: object.name.to_string(),
        range: start..scene.triangles.len(),
        material: object.material,
        swept_bounds: bounds(
            scene.triangles[start..]
                .iter()
                .flat_map(|t| t.world_open.into_iter().chain(t.world_close)),
        ),
        path: curved,
        segments: (cuts.times.len() - 1) as u32,
    });
    Ok(())
}

/// One span of an object's shutter: its times, the indices of its open and close frames
/// and those frames.
struct Span<'a> {
    times: [f64; 2],
    frames: [usize; 2],
    open: &'a Frame,
    close: &'a Frame,
}

/// Every frame's vertices projected once, at the cut the frame belongs to (a frame is the
/// close of one segment and the open of the next at the same time), so the triangles
/// sharing a vertex share its projection; `None` for a frame no span uses.
fn project_frames(scene: &PreparedScene, cuts: &Cuts) -> Vec<Option<Vec<Vertex2dh>>> {
    let mut projected: Vec<Option<Vec<Vertex2dh>>> = vec![None; cuts.frames.len()];
    for (w, &(o, c)) in cuts.times.windows(2).zip(&cuts.spans) {
        for (k, t) in [(o, w[0]), (c, w[1])] {
            if let (Some(slot @ None), Some(f)) = (projected.get_mut(k), cuts.frames.get(k)) {
                *slot = Some(f.0.par_iter().map(|p| scene.project_at(t, *p)).collect());
            }
        }
    }
    projected
}

/// World corners and unit normals of mesh triangle `t` (position indices `idx`) in one
/// frame (world positions and normal matrix, `None` where the mesh's own normals do not
/// apply), chosen per `mode` ([`crate::lights::corner_normal`]) with the frame's `smooth`
/// vertex normals.
fn corner_frame(
    (world, normals): &Frame,
    smooth: &[DVec3],
    mode: NormalsDesc,
    t: &[mesh::Corner; 3],
    idx: &[usize; 3],
) -> ([DVec3; 3], [DVec3; 3]) {
    let w = idx.map(|i| world.get(i).copied().unwrap_or(DVec3::ZERO));
    let face = (w[1] - w[0]).cross(w[2] - w[0]).normalize_or_zero();
    let n = t.map(|c| crate::lights::corner_normal(mode, &c, normals.as_ref(), smooth, face));
    (w, n)
}
