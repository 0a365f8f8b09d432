//! Scene preparation: from a validated [`SceneDesc`] to the renderer's
//! [`PreparedScene`] — world-space triangles at shutter open and close, per-vertex 2DH
//! positions and view depths for both camera poses, materials and textures.
//!
//! Vertices move linearly in 2DH between open and close (Gribel 2010, Eq. 2); camera motion is
//! folded in by projecting the open positions with the open camera and the close positions
//! with the close camera.

use std::path::{Path, PathBuf};

use glam::{DAffine3, DMat3, DVec3};
use rand::{RngExt, SeedableRng};

use mblur::camera::{CameraFrame, Lens, Projection};
use mblur::shutter::Shutter;
use mblur::texture::Texture;
use mblur::{Material, PreparedScene};

use crate::desc::*;
use crate::error::{Error, Result};
use crate::mesh::{self, Mesh};
use crate::segments::MotionOptions;
use crate::splat_motion::{SplatMotion, SplatPoint, SplatSet, add_splat_set};
use crate::vertex_motion::{MeshObject, VertexMotion, add_mesh_object};

/// The renderer's lens (size, projection, clip depths) of a camera description.
pub fn lens(c: &CameraDesc) -> Lens {
    Lens {
        width: c.width,
        height: c.height,
        projection: match c.projection {
            ProjectionDesc::Perspective { fov_y_deg } => Projection::Perspective { fov_y_deg },
            ProjectionDesc::Orthographic { height } => Projection::Orthographic { height },
        },
        near: c.near,
        far: c.far,
    }
}

/// The shutter response of a validated description: box, tent or its piecewise-linear
/// points with the weights scaled so that the largest is 1 (the response only weighs
/// instants against each other, so the scale is free; scaled, weights of 1e308 or 5e-324
/// survive the renderer's f32 arithmetic).
pub fn shutter(d: &ShutterDesc) -> Shutter {
    let points = match &d.response {
        ResponseDesc::Box => vec![(0.0, 1.0), (1.0, 1.0)],
        ResponseDesc::Tent => vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)],
        ResponseDesc::PiecewiseLinear(p) => {
            let peak = p.iter().map(|q| q[1]).fold(0.0, f64::max);
            p.iter().map(|q| (q[0], q[1] / peak)).collect()
        }
    };
    Shutter {
        open: d.open,
        close: d.close,
        points,
    }
}

fn rgba(c: &[f64]) -> [f64; 4] {
    [c[0], c[1], c[2], c.get(3).copied().unwrap_or(1.0)]
}

/// Builds the affine transform scale, then rotate, then translate.
pub fn affine(t: &TransformDesc) -> DAffine3 {
    DAffine3::from_scale_rotation_translation(
        crate::segments::scale(t.scale.as_ref()),
        crate::segments::rotation(t.rotate.as_ref()),
        DVec3::from_array(t.translate),
    )
}

pub(crate) fn normal_matrix(a: &DAffine3) -> DMat3 {
    a.matrix3.inverse().transpose()
}

struct Ctx<'a> {
    file: &'a str,
    base: &'a Path,
    motion: &'a MotionOptions,
}

impl Ctx<'_> {
    fn path(&self, p: &str) -> PathBuf {
        self.base.join(p)
    }

    fn mesh(&self, m: &MeshDesc) -> Result<Mesh> {
        Ok(match m {
            MeshDesc::Triangles(t) => mesh::triangles(t),
            MeshDesc::File(p) => mesh::load_file(&self.path(p))?,
            MeshDesc::Sphere(s) => mesh::sphere(s),
            MeshDesc::Box(b) => mesh::cuboid(b),
            MeshDesc::Quad(q) => mesh::quad(q),
            MeshDesc::Grid(g) => mesh::grid(g),
            MeshDesc::Fence(f) => mesh::fence(f),
            MeshDesc::Cylinder(c) => mesh::cylinder(c),
        })
    }

    /// Open and close transforms (object placement then motion).
    fn placements(
        &self,
        transform: &Option<TransformDesc>,
        motion: &Option<MotionDesc>,
    ) -> (DAffine3, DAffine3) {
        let place = transform.as_ref().map_or(DAffine3::IDENTITY, affine);
        let m = motion.clone().unwrap_or_default();
        let open = m.open.as_ref().map_or(DAffine3::IDENTITY, affine) * place;
        let close = m.close.as_ref().map_or(DAffine3::IDENTITY, affine) * place;
        (open, close)
    }

    fn close_positions(
        &self,
        field: &str,
        motion: &Option<MotionDesc>,
        close: &DAffine3,
        positions: &[DVec3],
    ) -> Result<Vec<DVec3>> {
        match motion.as_ref().and_then(|m| m.positions_close.as_ref()) {
            Some(ps) => {
                if ps.len() != positions.len() {
                    return Err(Error::invalid(
                        self.file,
                        format!("{field}.motion.positions_close"),
                        format!(
                            "has {} positions but the mesh has {} vertices",
                            ps.len(),
                            positions.len()
                        ),
                    ));
                }
                Ok(ps.iter().map(|p| DVec3::from_array(*p)).collect())
            }
            None => Ok(positions
                .iter()
                .map(|p| close.transform_point3(*p))
                .collect()),
        }
    }
}

pub(crate) fn bounds(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

pub(crate) fn check_finite(file: &str, field: &str, v: DVec3) -> Result<DVec3> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(
            file,
            field,
            "transformed geometry is not finite (values too large)",
        ))
    }
}

/// Prepares a validated scene with the default [`MotionOptions`] (automatic segments).
/// `file` names the scene in messages; relative paths resolve against `base`.
pub fn prepare(desc: &SceneDesc, file: &str, base: &Path) -> Result<PreparedScene> {
    prepare_with(desc, file, base, &MotionOptions::default())
}

/// Prepares a validated scene, cutting curved motion into segments as `motion` says.
pub fn prepare_with(
    desc: &SceneDesc,
    file: &str,
    base: &Path,
    motion: &MotionOptions,
) -> Result<PreparedScene> {
    motion
        .validate()
        .map_err(|m| Error::invalid(file, "motion options", m))?;
    let ctx = Ctx { file, base, motion };
    let mut scene = empty_scene(desc);
    for (oi, o) in desc.objects.iter().enumerate() {
        add_object(&ctx, &mut scene, oi, o)?;
    }
    for (si, s) in desc.splats.iter().enumerate() {
        add_splat_object(&ctx, &mut scene, si, s)?;
    }
    Ok(scene)
}

/// The prepared scene without geometry: size, background, shutter and both camera poses.
fn empty_scene(desc: &SceneDesc) -> PreparedScene {
    let c = &desc.camera;
    let (eye, target, up) = (
        DVec3::from_array(c.eye),
        DVec3::from_array(c.target),
        DVec3::from_array(c.up),
    );
    let lens = lens(c);
    let camera_keys = crate::segments::camera_keys(c, &lens);
    let m = c.motion.clone().unwrap_or_default();
    let (camera_open, camera_close) = match (camera_keys.first(), camera_keys.last()) {
        (Some(a), Some(b)) => (a.frame, b.frame),
        _ => (
            CameraFrame::new(&lens, eye, target, up),
            CameraFrame::new(
                &lens,
                m.eye.map_or(eye, DVec3::from_array),
                m.target.map_or(target, DVec3::from_array),
                m.up.map_or(up, DVec3::from_array),
            ),
        ),
    };
    PreparedScene {
        width: c.width,
        height: c.height,
        background: desc.background,
        shutter: shutter(&desc.shutter),
        camera_open,
        camera_close,
        camera_keys,
        near: c.near,
        far: c.far,
        objects: Vec::new(),
        triangles: Vec::new(),
        splat_objects: Vec::new(),
        splats: Vec::new(),
        materials: Vec::new(),
        textures: Vec::new(),
        lights: crate::lights::lights(&desc.lights),
    }
}

/// Adds an object's material (and its texture, if any) to the scene; returns the material
/// index.
fn add_material(ctx: &Ctx<'_>, scene: &mut PreparedScene, desc: &MaterialDesc) -> Result<u32> {
    let texture = match &desc.texture {
        None => None,
        Some(TextureDesc::File(p)) => Some(crate::texture_file::load(&ctx.path(p))?),
        Some(TextureDesc::Checker(ch)) => Some(Texture::checker(
            ch.squares,
            ch.texels_per_square,
            rgba(&ch.a),
            rgba(&ch.b),
        )),
    };
    let tex_index = texture.map(|t| {
        scene.textures.push(t);
        (scene.textures.len() - 1) as u32
    });
    scene.materials.push(crate::lights::with_shading(
        Material::unlit(rgba(&desc.color), tex_index),
        desc,
    ));
    Ok((scene.materials.len() - 1) as u32)
}

/// The motion of JSON object `o` (its `transform` and `motion`) with mesh `mesh`.
fn vertex_motion(ctx: &Ctx<'_>, field: &str, o: &ObjectDesc, mesh: &Mesh) -> Result<VertexMotion> {
    let keyed = o.motion.as_ref().and_then(|m| m.keys.as_ref());
    if let Some(keys) = keyed.filter(|k| k.iter().any(|k| k.positions.is_some())) {
        let place = o.transform.as_ref().map_or(DAffine3::IDENTITY, affine);
        let mut out = Vec::with_capacity(keys.len());
        for (i, k) in keys.iter().enumerate() {
            let ps = k.positions.as_deref().unwrap_or_default();
            if ps.len() != mesh.positions.len() {
                return Err(Error::invalid(
                    ctx.file,
                    format!("{field}.motion.keys[{i}].positions"),
                    format!(
                        "has {} positions but the mesh has {} vertices",
                        ps.len(),
                        mesh.positions.len()
                    ),
                ));
            }
            let world = ps
                .iter()
                .map(|p| place.transform_point3(DVec3::from_array(*p)));
            out.push((k.t, world.collect()));
        }
        return Ok(VertexMotion::Keys(out));
    }
    if let Some(path) = crate::segments::motion_path(&o.transform, &o.motion) {
        return Ok(VertexMotion::Path(path));
    }
    let (open_aff, close_aff) = ctx.placements(&o.transform, &o.motion);
    let open = mesh
        .positions
        .iter()
        .map(|p| open_aff.transform_point3(*p))
        .collect();
    let close = ctx.close_positions(field, &o.motion, &close_aff, &mesh.positions)?;
    Ok(VertexMotion::Ends {
        open,
        close,
        placements: (open_aff, close_aff),
    })
}

/// Adds triangle object `oi`: its material, its triangles (one per segment of the
/// shutter, [`crate::segments`]) and its object entry.
fn add_object(ctx: &Ctx<'_>, scene: &mut PreparedScene, oi: usize, o: &ObjectDesc) -> Result<()> {
    let field = format!("objects[{oi}] \"{}\"", o.name);
    let mesh = ctx.mesh(&o.mesh)?;
    let material = add_material(ctx, scene, &o.material)?;
    let motion = vertex_motion(ctx, &field, o, &mesh)?;
    let object = MeshObject {
        name: &o.name,
        field: &field,
        mesh: &mesh,
        material,
        motion,
        normals: o.normals,
    };
    add_mesh_object(ctx.file, ctx.motion, scene, object)
}

/// The object-space splats of a PLY file (per-vertex normals, radii and colours).
fn ply_points(ctx: &Ctx<'_>, s: &SplatDesc, field: &str, p: &str) -> Result<Vec<SplatPoint>> {
    let color = rgba(&s.color);
    let mut points = Vec::new();
    let path = ctx.path(p);
    let ply = crate::ply::read(&path)?;
    let normals = ply
        .normals
        .as_ref()
        .ok_or_else(|| Error::format(&path, "splat PLY needs per-vertex normals (nx, ny, nz)"))?;
    if s.radius.is_none() && ply.radii.is_none() {
        return Err(Error::invalid(
            ctx.file,
            format!("{field}.radius"),
            "is required: the PLY has no `radius` property",
        ));
    }
    for (i, pos) in ply.positions.iter().enumerate() {
        let r = s
            .radius
            .or_else(|| ply.radii.as_ref().and_then(|r| r.get(i).copied()))
            .unwrap_or(0.0);
        if !(r > 0.0 && r.is_finite()) {
            return Err(Error::format(
                &path,
                format!("vertex {i}: radius must be > 0, got {r}"),
            ));
        }
        let c = ply
            .colors
            .as_ref()
            .and_then(|c| c.get(i))
            .map_or(color, |c| [c[0], c[1], c[2], color[3]]);
        let n = normals
            .get(i)
            .copied()
            .unwrap_or(DVec3::Z)
            .normalize_or(DVec3::Z);
        points.push((*pos, n, r, c));
    }
    Ok(points)
}

/// The object-space splats sampled uniformly by area over a mesh surface.
fn sampled_points(
    ctx: &Ctx<'_>,
    s: &SplatDesc,
    field: &str,
    sd: &SampleDesc,
) -> Result<Vec<SplatPoint>> {
    let color = rgba(&s.color);
    let mut points = Vec::new();
    let m = ctx.mesh(&sd.mesh)?;
    let areas: Vec<f64> = m.triangles.iter().map(|t| m.triangle_area(t)).collect();
    let total: f64 = areas.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return Err(Error::invalid(
            ctx.file,
            format!("{field}.source.sample.mesh"),
            "has zero surface area",
        ));
    }
    let mut cdf = Vec::with_capacity(areas.len());
    let mut acc = 0.0;
    for a in &areas {
        acc += a;
        cdf.push(acc);
    }
    let mut rng = rand_pcg::Pcg32::seed_from_u64(sd.seed);
    let radius = s.radius.unwrap_or(0.0);
    for _ in 0..sd.count {
        let x: f64 = rng.random::<f64>() * total;
        let ti = cdf.partition_point(|&c| c < x).min(m.triangles.len() - 1);
        let t = &m.triangles[ti];
        let (u, v): (f64, f64) = (rng.random(), rng.random());
        let su = u.sqrt();
        let (b0, b1, b2) = (1.0 - su, su * (1.0 - v), su * v);
        let [a, b, c] = t.map(|c| m.position(c.position));
        let p = a * b0 + b * b1 + c * b2;
        let face = (b - a).cross(c - a).normalize_or(DVec3::Z);
        let n = (t[0].normal * b0 + t[1].normal * b1 + t[2].normal * b2).normalize_or(face);
        points.push((p, n, radius, color));
    }
    Ok(points)
}

/// Refuses a splat larger than the whole point set (radius above the diagonal of the points'
/// bounding box, for sets of two or more distinct points): every such splat covers every
/// pixel the object does, and the EWA A-buffer's exact resolve costs the square of the
/// splats overlapping a pixel (a radius mutated to 2^32 took minutes on a 16 x 12 image).
fn check_radii(ctx: &Ctx<'_>, s: &SplatDesc, field: &str, points: &[SplatPoint]) -> Result<()> {
    let (lo, hi) = bounds(points.iter().map(|p| p.0));
    let extent = (hi - lo).length();
    if !(extent > 0.0 && extent.is_finite()) {
        return Ok(());
    }
    let Some((i, r)) = points
        .iter()
        .map(|p| p.2)
        .enumerate()
        .find(|&(_, r)| r > extent)
    else {
        return Ok(());
    };
    let what = format!(
        "is larger than the whole point set ({extent:.4} across): every splat would cover \
         the whole object; use a radius near the spacing of the points"
    );
    match (&s.source, s.radius) {
        (SplatSource::Ply(p), None) => Err(Error::format(
            ctx.path(p),
            format!("vertex {i}: radius {r} {what}"),
        )),
        _ => Err(Error::invalid(
            ctx.file,
            format!("{field}.radius"),
            format!("{r} {what}"),
        )),
    }
}

/// Adds splat object `si`: its splats (one per splat and segment of its shutter) and its
/// object entry ([`crate::splat_motion`]).
fn add_splat_object(
    ctx: &Ctx<'_>,
    scene: &mut PreparedScene,
    si: usize,
    s: &SplatDesc,
) -> Result<()> {
    let field = format!("splats[{si}] \"{}\"", s.name);
    let points = match &s.source {
        SplatSource::Ply(p) => ply_points(ctx, s, &field, p)?,
        SplatSource::Sample(sd) => sampled_points(ctx, s, &field, sd)?,
    };
    check_radii(ctx, s, &field, &points)?;
    let motion = match crate::segments::motion_path(&s.transform, &s.motion) {
        Some(path) => SplatMotion::Path(path),
        None => {
            let (open, close) = ctx.placements(&s.transform, &s.motion);
            let centres: Vec<DVec3> = points.iter().map(|p| p.0).collect();
            let positions = ctx.close_positions(&field, &s.motion, &close, &centres)?;
            SplatMotion::Ends {
                open,
                close,
                positions,
            }
        }
    };
    let material = match crate::lights::splat_material(s) {
        Some(m) => {
            scene.materials.push(m);
            (scene.materials.len() - 1) as u32
        }
        None => u32::MAX,
    };
    let set = SplatSet {
        index: si as u32,
        name: &s.name,
        field: &field,
        points: &points,
        motion,
        material,
    };
    add_splat_set(ctx.file, ctx.motion, scene, set)
}
