//! A glTF frame as the renderer's [`PreparedScene`]: the camera at the window's sampled
//! instants, and every mesh instance as a triangle object whose motion is sampled from the
//! animation.
//!
//! Rigid instances (no skin, no animated morph weights) become transform keys
//! ([`VertexMotion::Path`]) at the sampled instants, so a rotation between two samples
//! turns along its arc and is cut into segments like JSON keys. Deformed instances
//! (skins, animated morph weights) and rigid ones that cannot be keyed as transforms
//! (a STEP jump inside the window, a sheared world matrix) become world positions at the
//! sampled instants ([`VertexMotion::Keys`]), straight between samples.

use glam::{DAffine3, DMat4, DVec3};

use ::gltf::khr_lights_punctual::Kind;
use mblur::camera::{CameraFrame, Lens, Projection};
use mblur::motion::{CameraKey, MotionKey, MotionPath, Turn};
use mblur::shutter::Shutter;
use mblur::texture::Texture;
use mblur::{Light, Material, PreparedScene, ShadingModel};

use super::anim::{Rig, Target};
use super::mesh::{Primitive, material, primitive};
use super::{GltfFrame, GltfOptions, GltfScene};
use crate::desc::NormalsDesc;
use crate::error::{Error, Result};
use crate::segments::MotionOptions;
use crate::vertex_motion::{MeshObject, VertexMotion, add_mesh_object};

/// Depth of the far plane of a perspective camera without `zfar`, as a multiple of its
/// `znear`.
pub const INFINITE_FAR: f64 = 1e6;

/// Default image height when neither width nor height is given.
const DEFAULT_HEIGHT: u32 = 480;

/// The normalised shutter time of instant `t` in `window`.
fn norm(window: [f64; 2], t: f64) -> f64 {
    if t >= window[1] {
        1.0
    } else {
        ((t - window[0]) / (window[1] - window[0])).clamp(0.0, 1.0)
    }
}

/// Prepares `g` with animation `rig` over `opts.window`.
pub(super) fn prepare(
    g: &GltfScene,
    rig: &Rig,
    opts: &GltfOptions,
    motion: &MotionOptions,
) -> Result<GltfFrame> {
    let [t0, t1] = opts.window;
    if !(t0.is_finite() && t1.is_finite() && t0 < t1) {
        return Err(Error::invalid(
            &g.label,
            "shutter window",
            format!("must be two finite times, open < close; got [{t0}, {t1}]"),
        ));
    }
    let mut warnings = Vec::new();
    let mut scene = camera_scene(g, rig, opts)?;
    let nodes: Vec<::gltf::Node<'_>> = g.doc.nodes().collect();
    let mut materials: Vec<Option<u32>> = vec![None; g.doc.materials().count() + 1];
    let mut ignored = Vec::new();
    // Per material of the scene, in order: whether lights may light it (not unlit).
    let mut lit_materials: Vec<bool> = Vec::new();
    for &ni in &g.nodes {
        let Some(node) = nodes.get(ni) else { continue };
        let Some(m) = node.mesh() else { continue };
        let name = node
            .name()
            .map_or_else(|| format!("node {ni}"), str::to_string);
        let count = m.primitives().count();
        for (pi, p) in m.primitives().enumerate() {
            let at = format!("nodes[{ni}] \"{name}\" mesh {} primitive {pi}", m.index());
            let prim = primitive(&g.buffers, &p, &at).map_err(|e| Error::format(&g.path, e))?;
            let slot = prim.material.map_or(0, |i| i + 1);
            let mat = match materials.get(slot).copied().flatten() {
                Some(i) => i,
                None => {
                    let i = add_material(g, &mut scene, &p.material(), &mut ignored)?;
                    lit_materials.push(!p.material().unlit());
                    if let Some(s) = materials.get_mut(slot) {
                        *s = Some(i);
                    }
                    i
                }
            };
            let label = if count > 1 {
                format!("{name}#{pi}")
            } else {
                name.clone()
            };
            let vm = instance_motion(g, rig, node, &prim, opts.window, &at)?;
            let object = MeshObject {
                name: &label,
                field: &at,
                mesh: &prim.mesh,
                material: mat,
                motion: vm,
                normals: NormalsDesc::Auto,
            };
            add_mesh_object(&g.label, motion, &mut scene, object)?;
        }
    }
    scene.lights = punctual_lights(g, rig, &nodes, opts.window, &mut warnings);
    if !scene.lights.is_empty() {
        // Lit by the file's lights: every material but KHR_materials_unlit ones is Lambert.
        for (m, gm) in scene.materials.iter_mut().zip(&lit_materials) {
            if *gm {
                m.shading = ShadingModel::Lambert;
            }
        }
    }
    if !ignored.is_empty() {
        warnings.push(format!(
            "{}: lighting textures ignored (base colour only): {}",
            g.label,
            ignored.join(", ")
        ));
    }
    let optional: Vec<&str> = g
        .doc
        .extensions_used()
        .filter(|e| !super::SUPPORTED_REQUIRED.contains(e))
        .collect();
    if !optional.is_empty() {
        warnings.push(format!(
            "{}: optional extensions ignored: {}",
            g.label,
            optional.join(", ")
        ));
    }
    Ok(GltfFrame { scene, warnings })
}

/// Adds glTF material `m` (and its texture) to the scene; returns its index.
fn add_material(
    g: &GltfScene,
    scene: &mut PreparedScene,
    m: &::gltf::Material<'_>,
    ignored: &mut Vec<String>,
) -> Result<u32> {
    let at = format!(
        "{}: materials[{}]",
        g.label,
        m.index().map_or("default".into(), |i| i.to_string())
    );
    let mut decode = |i: usize| decode_image(g, i);
    let (mut mat, texture): (Material, Option<Texture>) = material(m, &at, &mut decode, ignored)?;
    if let Some(t) = texture {
        scene.textures.push(t);
        mat.texture = Some((scene.textures.len() - 1) as u32);
    }
    scene.materials.push(mat);
    Ok((scene.materials.len() - 1) as u32)
}

/// The `KHR_lights_punctual` lights of the scene's nodes, each placed by its node's world
/// matrix at the window's open and close (two light keys: positions linear, directions
/// turning the short way in between). Directional lights shine
/// along the node's -Z with irradiance `color × intensity` (lux); point and spot lights
/// fall off as `intensity / d²` (candela). Spot cones and ranges are not modelled: a
/// warning names how many were ignored.
fn punctual_lights(
    g: &GltfScene,
    rig: &Rig,
    nodes: &[::gltf::Node<'_>],
    [t0, t1]: [f64; 2],
    warnings: &mut Vec<String>,
) -> Vec<Light> {
    let (mut cones, mut ranges) = (0, 0);
    let mut out = Vec::new();
    for &ni in &g.nodes {
        let Some(light) = nodes.get(ni).and_then(|n| n.light()) else {
            continue;
        };
        let (a, b) = (rig.world(ni, t0, false), rig.world(ni, t1, true));
        let colour = light.color().map(f64::from);
        let intensity = f64::from(light.intensity());
        ranges += usize::from(light.range().is_some());
        out.push(match light.kind() {
            Kind::Directional => {
                let dir = |m: &DMat4| m.transform_vector3(-DVec3::Z).normalize_or(-DVec3::Z);
                Light::directional(dir(&a), dir(&b), colour, intensity)
            }
            kind => {
                cones += usize::from(matches!(kind, Kind::Spot { .. }));
                Light::point(
                    a.transform_point3(DVec3::ZERO),
                    b.transform_point3(DVec3::ZERO),
                    colour,
                    intensity,
                )
            }
        });
    }
    if cones + ranges > 0 {
        warnings.push(format!(
            "{}: {cones} spot cone(s) and {ranges} light range(s) ignored: spot lights shine \
             in every direction, every light falls off as 1/d² without a cut-off",
            g.label
        ));
    }
    out
}

/// The size and sRGB RGBA8 texels of image `i`: from a buffer view, a `data:` URI or a
/// file relative to the glTF file.
fn decode_image(g: &GltfScene, i: usize) -> Result<(u32, u32, Vec<u8>)> {
    let img = g
        .doc
        .images()
        .nth(i)
        .ok_or_else(|| Error::format(&g.path, format!("images[{i}] does not exist")))?;
    let label = g.path.join(format!("images[{i}]"));
    let bytes: Vec<u8> = match img.source() {
        ::gltf::image::Source::View { view, .. } => g
            .buffers
            .view(&view)
            .map_err(|m| Error::format(&g.path, format!("images[{i}]: {m}")))?
            .to_vec(),
        ::gltf::image::Source::Uri { uri, .. } => match super::data::data_uri(uri) {
            Some(r) => r.map_err(|m| Error::format(&g.path, format!("images[{i}]: {m}")))?,
            None => {
                let path = super::data::relative_file(&g.base, uri)
                    .map_err(|m| Error::format(&g.path, format!("images[{i}]: {m}")))?;
                let bytes = crate::input::read_bounded(
                    &path,
                    crate::input::MAX_TEXTURE_BYTES,
                    "texture file",
                )?;
                return crate::texture_file::decode_rgba8(&path, &bytes);
            }
        },
    };
    if bytes.starts_with(&[0xFF, 0xD8]) {
        return Err(Error::format(
            label,
            "JPEG textures are not supported (PNG only)",
        ));
    }
    crate::texture_file::decode_rgba8(&label, &bytes)
}

/// The camera node chosen by `opts.camera` (or the first camera node of the scene).
fn camera_node<'a>(g: &'a GltfScene, opts: &GltfOptions) -> Result<::gltf::Node<'a>> {
    let nodes: Vec<::gltf::Node<'a>> = g.doc.nodes().collect();
    let cams: Vec<::gltf::Node<'a>> = g
        .nodes
        .iter()
        .filter_map(|&i| nodes.get(i).cloned())
        .filter(|n| n.camera().is_some())
        .collect();
    let name_of = |n: &::gltf::Node<'_>| {
        n.name()
            .or_else(|| n.camera().and_then(|c| c.name()))
            .map_or_else(|| format!("nodes[{}]", n.index()), str::to_string)
    };
    match &opts.camera {
        None => cams.into_iter().next().ok_or_else(|| {
            Error::format(
                &g.path,
                "has no camera in its scene: mblur needs one to render (add a camera node)",
            )
        }),
        Some(want) => cams
            .iter()
            .find(|n| n.name() == Some(want) || n.camera().and_then(|c| c.name()) == Some(want))
            .cloned()
            .ok_or_else(|| {
                let names: Vec<String> = cams.iter().map(name_of).collect();
                Error::format(
                    &g.path,
                    format!(
                        "has no camera `{want}` (cameras: {})",
                        if names.is_empty() {
                            "none".into()
                        } else {
                            names.join(", ")
                        }
                    ),
                )
            }),
    }
}

/// The lens of glTF camera `c` at the image size asked for (or derived from its aspect
/// ratio).
fn lens(g: &GltfScene, c: &::gltf::Camera<'_>, opts: &GltfOptions) -> Result<Lens> {
    let bad = |m: String| Error::format(&g.path, format!("camera {}: {m}", c.index()));
    let (projection, aspect, near, far) = match c.projection() {
        ::gltf::camera::Projection::Perspective(p) => {
            let fov = f64::from(p.yfov()).to_degrees();
            if !(fov > 0.0 && fov < 180.0) {
                return Err(bad(format!("yfov must be in (0, pi), got {}", p.yfov())));
            }
            let near = f64::from(p.znear());
            let far = p.zfar().map_or(near * INFINITE_FAR, f64::from);
            let aspect = p.aspect_ratio().map(f64::from);
            (
                Projection::Perspective { fov_y_deg: fov },
                aspect,
                near,
                far,
            )
        }
        ::gltf::camera::Projection::Orthographic(o) => {
            let (x, y) = (f64::from(o.xmag()), f64::from(o.ymag()));
            if !(y > 0.0 && x > 0.0 && y.is_finite() && x.is_finite()) {
                return Err(bad(format!("xmag and ymag must be > 0, got {x} and {y}")));
            }
            let p = Projection::Orthographic { height: 2.0 * y };
            (p, Some(x / y), f64::from(o.znear()), f64::from(o.zfar()))
        }
    };
    let ortho = matches!(projection, Projection::Orthographic { .. });
    if !(near.is_finite() && far.is_finite() && near < far && (ortho || near > 0.0)) {
        return Err(bad(format!(
            "znear {near} and zfar {far} must be finite with znear < zfar (and znear > 0 for a \
             perspective camera)"
        )));
    }
    let aspect = aspect
        .filter(|a| a.is_finite() && *a > 0.0)
        .unwrap_or(4.0 / 3.0);
    let side = |x: f64| x.round().clamp(1.0, f64::from(crate::validate::MAX_SIDE)) as u32;
    let (width, height) = match (opts.width, opts.height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, side(f64::from(w) / aspect)),
        (None, Some(h)) => (side(f64::from(h) * aspect), h),
        (None, None) => (side(f64::from(DEFAULT_HEIGHT) * aspect), DEFAULT_HEIGHT),
    };
    let max = crate::validate::MAX_SIDE;
    let pixels = u64::from(width) * u64::from(height);
    if width == 0
        || height == 0
        || width > max
        || height > max
        || pixels > crate::validate::MAX_PIXELS
    {
        return Err(Error::invalid(
            &g.label,
            "image size",
            format!(
                "{width} x {height}: each side must be 1..={max} and at most {} pixels",
                crate::validate::MAX_PIXELS
            ),
        ));
    }
    Ok(Lens {
        width,
        height,
        projection,
        near,
        far,
    })
}

/// The camera pose of world matrix `m`: eye at its origin, looking down its -Z, up its +Y.
fn pose(lens: &Lens, m: &DMat4) -> CameraFrame {
    let eye = m.transform_point3(DVec3::ZERO);
    let fw = m.transform_vector3(-DVec3::Z).normalize_or(-DVec3::Z);
    let up = m.transform_vector3(DVec3::Y).normalize_or(DVec3::Y);
    CameraFrame::new(lens, eye, eye + fw, up)
}

/// The prepared scene without geometry: size, shutter (a box over the window, in seconds)
/// and the camera, keyed at the window's sampled instants when it moves.
fn camera_scene(g: &GltfScene, rig: &Rig, opts: &GltfOptions) -> Result<PreparedScene> {
    let node = camera_node(g, opts)?;
    let Some(cam) = node.camera() else {
        return Err(Error::format(&g.path, "camera node without a camera"));
    };
    let lens = lens(g, &cam, opts)?;
    let [t0, t1] = opts.window;
    let chain = rig.chain(node.index());
    let moving = rig.channels_of(&chain).any(|c| c.target != Target::Weights);
    if rig.channels_of(&chain).any(|c| c.jumps_within(t0, t1)) {
        return Err(Error::format(
            &g.path,
            format!(
                "camera node {}: a STEP key jumps inside the shutter window [{t0}, {t1}] s; \
                 a camera cannot jump during an exposure",
                node.index()
            ),
        ));
    }
    let animated = chain
        .iter()
        .filter(|&&n| rig.channels_of(&[n]).next().is_some())
        .count();
    let camera_keys: Vec<CameraKey> = if moving {
        rig.sample_times(&chain, t0, t1, animated > 1)
            .into_iter()
            .map(|(t, left)| CameraKey {
                t: norm(opts.window, t),
                frame: pose(&lens, &rig.world(node.index(), t, left)),
            })
            .collect()
    } else {
        Vec::new()
    };
    let still = pose(&lens, &rig.world(node.index(), t0, false));
    let (open, close) = match (camera_keys.first(), camera_keys.last()) {
        (Some(a), Some(b)) => (a.frame, b.frame),
        _ => (still, still),
    };
    Ok(PreparedScene {
        width: lens.width,
        height: lens.height,
        background: [0.0; 3],
        shutter: Shutter {
            open: t0,
            close: t1,
            points: vec![(0.0, 1.0), (1.0, 1.0)],
        },
        camera_open: open,
        camera_close: close,
        camera_keys,
        near: lens.near,
        far: lens.far,
        objects: Vec::new(),
        triangles: Vec::new(),
        splat_objects: Vec::new(),
        splats: Vec::new(),
        materials: Vec::new(),
        textures: Vec::new(),
        lights: Vec::new(),
    })
}

/// Scale, rotation and translation of `m`, or `None` when `m` is not one (shear, a
/// projective part, a zero scale).
fn decompose(m: &DMat4) -> Option<MotionKey> {
    let a = DAffine3::from_mat4(*m);
    let (scale, rotation, translate) = a.to_scale_rotation_translation();
    let back = DMat4::from_scale_rotation_translation(scale, rotation, translate);
    let size = m.to_cols_array().iter().fold(1.0f64, |s, x| s.max(x.abs()));
    let err = (back - *m)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |s, x| s.max(x.abs()));
    let ok = scale.is_finite() && rotation.is_finite() && err <= 1e-9 * size;
    ok.then_some(MotionKey {
        t: 0.0,
        translate,
        rotation,
        scale,
    })
}

/// The motion of mesh instance `node` (primitive `prim`) over `window`.
fn instance_motion(
    g: &GltfScene,
    rig: &Rig,
    node: &::gltf::Node<'_>,
    prim: &Primitive,
    window: [f64; 2],
    at: &str,
) -> Result<VertexMotion> {
    let [t0, t1] = window;
    let n = node.index();
    let chain = rig.chain(n);
    let skin = node.skin().filter(|_| prim.skin.is_some());
    let morphing =
        !prim.targets.is_empty() && rig.channels_of(&[n]).any(|c| c.target == Target::Weights);
    let trs_animated = chain
        .iter()
        .filter(|&&k| rig.channels_of(&[k]).any(|c| c.target != Target::Weights))
        .count();
    if skin.is_none() && !morphing {
        let jumps = rig.channels_of(&chain).any(|c| c.jumps_within(t0, t1));
        let times = rig.sample_times(&chain, t0, t1, trs_animated > 1);
        let keys: Option<Vec<MotionKey>> = times
            .iter()
            .map(|&(t, left)| {
                decompose(&rig.world(n, t, left)).map(|k| MotionKey {
                    t: norm(window, t),
                    ..k
                })
            })
            .collect();
        if let (false, Some(keys)) = (jumps, keys) {
            let turns = keys
                .windows(2)
                .map(|w| Turn::slerp(w[0].rotation, w[1].rotation))
                .collect();
            return Ok(VertexMotion::Path(MotionPath::new(
                keys,
                turns,
                DAffine3::IDENTITY,
            )));
        }
    }
    // Deformed, or rigid motion that transform keys cannot hold: positions at samples.
    let mut nodes = chain.clone();
    if let Some(s) = &skin {
        for j in s.joints() {
            nodes.extend(rig.chain(j.index()));
        }
    }
    let times = rig.sample_times(&nodes, t0, t1, skin.is_some() || trs_animated > 0);
    let ibm = match &skin {
        Some(s) => inverse_binds(g, s)?,
        None => Vec::new(),
    };
    let mut keys = Vec::with_capacity(times.len());
    for (t, left) in times {
        let local = prim.morphed(&rig.weights_at(n, t, left));
        let world = match &skin {
            Some(s) => {
                let joints: Vec<DMat4> = s
                    .joints()
                    .enumerate()
                    .map(|(k, j)| {
                        rig.world(j.index(), t, left)
                            * ibm.get(k).copied().unwrap_or(DMat4::IDENTITY)
                    })
                    .collect();
                prim.skinned(&local, &joints)
                    .map_err(|m| Error::format(&g.path, format!("{at}: {m}")))?
            }
            None => {
                let m = rig.world(n, t, left);
                local.iter().map(|p| m.transform_point3(*p)).collect()
            }
        };
        keys.push((norm(window, t), world));
    }
    Ok(VertexMotion::Keys(keys))
}

/// The inverse bind matrices of skin `s` (identity when absent).
fn inverse_binds(g: &GltfScene, s: &::gltf::Skin<'_>) -> Result<Vec<DMat4>> {
    let joints = s.joints().count();
    let Some(a) = s.inverse_bind_matrices() else {
        return Ok(vec![DMat4::IDENTITY; joints]);
    };
    let what = format!("skins[{}] inverseBindMatrices", s.index());
    let (v, _) = super::data::read(&g.buffers, &a, &[::gltf::accessor::Dimensions::Mat4], &what)
        .map_err(|m| Error::format(&g.path, m))?;
    if v.len() / 16 < joints {
        return Err(Error::format(
            &g.path,
            format!("{what}: {} matrices for {joints} joints", v.len() / 16),
        ));
    }
    Ok(v.chunks_exact(16)
        .map(|c| {
            let mut a = [0.0; 16];
            a.copy_from_slice(c);
            DMat4::from_cols_array(&a)
        })
        .collect())
}
