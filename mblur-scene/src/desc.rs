//! The JSON scene format: plain serde types, one per concept, every struct with
//! `deny_unknown_fields` so a misspelt field is an error, never silently ignored.
//!
//! The full schema with an example is in the workspace's `docs/SCENE_FORMAT.md`. These types only describe the
//! file; [`crate::validate`] checks the numbers and [`crate::prepare`] turns a scene into
//! world-space triangles and 2DH vertices.

use serde::{Deserialize, Serialize};

/// A whole scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// The camera (image size, projection, pose and optional motion).
    pub camera: CameraDesc,
    /// The shutter interval and its response curve (box by default).
    #[serde(default)]
    pub shutter: ShutterDesc,
    /// Linear RGB colour where nothing is drawn.
    #[serde(default)]
    pub background: [f64; 3],
    /// Triangle-mesh objects.
    #[serde(default)]
    pub objects: Vec<ObjectDesc>,
    /// Point-sampled (splat) objects.
    #[serde(default)]
    pub splats: Vec<SplatDesc>,
    /// Lights; only materials with a `shading` other than `unlit` see them.
    #[serde(default)]
    pub lights: Vec<LightDesc>,
}

/// A light. Directional and point lights may move over the shutter: `direction_close`,
/// `position_close` (the two keys open and close), or `keys` at several instants (times
/// strictly increasing, first 0, last 1); directions turn the short way at a constant
/// rate between keys, positions move linearly. No shadows: a light reaches every surface
/// that faces it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightDesc {
    /// Light from everywhere: adds `albedo × color`.
    Ambient {
        /// Linear RGB.
        color: [f64; 3],
    },
    /// Parallel light travelling along `direction` (from the light towards the scene).
    Directional {
        /// Travel direction at shutter open (any non-zero length); required unless `keys`
        /// is given.
        #[serde(default)]
        direction: Option<[f64; 3]>,
        /// Travel direction at shutter close (default: `direction`).
        #[serde(default)]
        direction_close: Option<[f64; 3]>,
        /// Travel directions at several instants. Excludes `direction`/`direction_close`.
        #[serde(default)]
        keys: Option<Vec<DirectionKeyDesc>>,
        /// Linear RGB (default white).
        #[serde(default = "white3")]
        color: [f64; 3],
        /// Irradiance scale (default 1).
        #[serde(default = "one")]
        intensity: f64,
    },
    /// A point light with inverse-square falloff: irradiance `color × intensity / d²`.
    Point {
        /// World position at shutter open; required unless `keys` is given.
        #[serde(default)]
        position: Option<[f64; 3]>,
        /// World position at shutter close (default: `position`).
        #[serde(default)]
        position_close: Option<[f64; 3]>,
        /// World positions at several instants. Excludes `position`/`position_close`.
        #[serde(default)]
        keys: Option<Vec<PositionKeyDesc>>,
        /// Linear RGB (default white).
        #[serde(default = "white3")]
        color: [f64; 3],
        /// Irradiance at unit distance (default 1).
        #[serde(default = "one")]
        intensity: f64,
    },
}

/// One key of a directional light: its travel direction at normalised shutter time `t`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirectionKeyDesc {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// Travel direction (any non-zero length).
    pub direction: [f64; 3],
}

/// One key of a point light: its world position at normalised shutter time `t`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositionKeyDesc {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// World position.
    pub position: [f64; 3],
}

fn white3() -> [f64; 3] {
    [1.0; 3]
}

/// Camera: image size, projection and pose at shutter open, optional pose at close.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Perspective or orthographic projection.
    pub projection: ProjectionDesc,
    /// Eye position at shutter open.
    pub eye: [f64; 3],
    /// Look-at point at shutter open.
    pub target: [f64; 3],
    /// Up direction (default +Y).
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Near clipping distance (view-space depth along the viewing direction).
    pub near: f64,
    /// Far clipping distance.
    pub far: f64,
    /// Camera pose at shutter close; fields left out keep their open value.
    #[serde(default)]
    pub motion: Option<CameraMotion>,
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

/// The projection of the camera.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ProjectionDesc {
    /// OpenGL-style perspective projection.
    Perspective {
        /// Vertical field of view in degrees, in (0, 180).
        fov_y_deg: f64,
    },
    /// Orthographic projection.
    Orthographic {
        /// Height of the view volume in world units (width follows the aspect ratio).
        height: f64,
    },
}

/// Camera pose at shutter close, or camera keys.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraMotion {
    /// Eye position at shutter close.
    #[serde(default)]
    pub eye: Option<[f64; 3]>,
    /// Look-at point at shutter close.
    #[serde(default)]
    pub target: Option<[f64; 3]>,
    /// Up direction at shutter close.
    #[serde(default)]
    pub up: Option<[f64; 3]>,
    /// Poses at several instants (times strictly increasing, first 0, last 1); fields left
    /// out keep the camera's own `eye`, `target`, `up`. Excludes `eye`/`target`/`up` here.
    #[serde(default)]
    pub keys: Option<Vec<CameraKeyDesc>>,
}

/// One camera key: the pose at normalised shutter time `t`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraKeyDesc {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// Eye position.
    #[serde(default)]
    pub eye: Option<[f64; 3]>,
    /// Look-at point.
    #[serde(default)]
    pub target: Option<[f64; 3]>,
    /// Up direction.
    #[serde(default)]
    pub up: Option<[f64; 3]>,
}

/// Shutter interval and response.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShutterDesc {
    /// Shutter open time in seconds (motion is given at this instant).
    #[serde(default)]
    pub open: f64,
    /// Shutter close time in seconds (> open).
    #[serde(default = "one")]
    pub close: f64,
    /// Response curve w(t) over the normalised shutter t in [0, 1].
    #[serde(default)]
    pub response: ResponseDesc,
}

fn one() -> f64 {
    1.0
}

impl Default for ShutterDesc {
    fn default() -> Self {
        ShutterDesc {
            open: 0.0,
            close: 1.0,
            response: ResponseDesc::Box,
        }
    }
}

/// Shutter response curve over normalised time.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ResponseDesc {
    /// w(t) = 1.
    #[default]
    Box,
    /// w(t) = 1 - |2t - 1| (peak at mid-shutter).
    Tent,
    /// Explicit `[t, w]` points, t strictly increasing from 0 to 1, w >= 0, not all zero.
    PiecewiseLinear(Vec<[f64; 2]>),
}

/// A triangle-mesh object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDesc {
    /// Name used in messages and in the effects report.
    pub name: String,
    /// The geometry.
    pub mesh: MeshDesc,
    /// Colour or texture (default opaque white).
    #[serde(default)]
    pub material: MaterialDesc,
    /// Placement applied to the mesh before any motion (default identity).
    #[serde(default)]
    pub transform: Option<TransformDesc>,
    /// Motion over the shutter (default: static).
    #[serde(default)]
    pub motion: Option<MotionDesc>,
    /// Where the shading normals come from (default `auto`).
    #[serde(default)]
    pub normals: NormalsDesc,
}

/// The shading normals of a mesh object.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalsDesc {
    /// The mesh's own normals (file normals, analytic normals of built-in shapes); corners
    /// without one take the smooth normal.
    #[default]
    Auto,
    /// Area-weighted vertex normals (the sum of the faces' cross products at each shared
    /// position), recomputed at every key of the motion.
    Smooth,
    /// The face normal at every corner.
    Flat,
}

/// Mesh geometry: inline triangles, a file, or a built-in shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum MeshDesc {
    /// Inline triangles, each three `[x, y, z]` points. UVs are (0,0), (1,0), (0,1).
    Triangles(Vec<[[f64; 3]; 3]>),
    /// A `.obj` or `.ply` file, relative to the scene file.
    File(String),
    /// UV sphere centred at the origin.
    Sphere(SphereDesc),
    /// Axis-aligned box centred at the origin.
    Box(BoxDesc),
    /// Quad in the XY plane centred at the origin, facing +Z.
    Quad(QuadDesc),
    /// Subdivided sheet in the XY plane (cloth), optionally wavy.
    Grid(GridDesc),
    /// A row of vertical slats along X in the XY plane.
    Fence(FenceDesc),
    /// Cylinder along Y centred at the origin.
    Cylinder(CylinderDesc),
}

/// Parameters of [`MeshDesc::Sphere`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereDesc {
    /// Radius.
    #[serde(default = "one")]
    pub radius: f64,
    /// Number of latitude rings (longitude segments are twice this); about 4 n^2 triangles.
    #[serde(default = "sixteen")]
    pub subdivisions: u32,
    /// Radial wrinkle amplitude as a fraction of the radius (0 = smooth).
    #[serde(default)]
    pub wrinkle: f64,
    /// Wrinkle frequency (waves around the equator).
    #[serde(default = "eight")]
    pub wrinkle_frequency: f64,
}

fn sixteen() -> u32 {
    16
}
fn eight() -> f64 {
    8.0
}

/// Parameters of [`MeshDesc::Box`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxDesc {
    /// Edge lengths along X, Y, Z.
    #[serde(default = "unit3")]
    pub size: [f64; 3],
}

fn unit3() -> [f64; 3] {
    [1.0; 3]
}
fn unit2() -> [f64; 2] {
    [1.0; 2]
}

/// Parameters of [`MeshDesc::Quad`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuadDesc {
    /// Width (X) and height (Y).
    #[serde(default = "unit2")]
    pub size: [f64; 2],
    /// How many times the texture repeats across the quad.
    #[serde(default = "unit2")]
    pub uv_repeat: [f64; 2],
}

/// Parameters of [`MeshDesc::Grid`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridDesc {
    /// Width (X) and height (Y).
    #[serde(default = "unit2")]
    pub size: [f64; 2],
    /// Cells along X and Y (2 triangles per cell).
    pub divisions: [u32; 2],
    /// Amplitude of the Z ripple (cloth folds), 0 = flat.
    #[serde(default)]
    pub wave_amplitude: f64,
    /// Ripples across the sheet.
    #[serde(default = "one")]
    pub wave_frequency: f64,
}

/// Parameters of [`MeshDesc::Fence`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FenceDesc {
    /// Number of slats.
    pub slats: u32,
    /// Width of one slat.
    pub slat_width: f64,
    /// Gap between slats.
    pub gap: f64,
    /// Slat height.
    pub height: f64,
}

/// Parameters of [`MeshDesc::Cylinder`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderDesc {
    /// Radius.
    #[serde(default = "one")]
    pub radius: f64,
    /// Length along Y.
    #[serde(default = "one")]
    pub height: f64,
    /// Segments around the axis (>= 3).
    #[serde(default = "sixteen")]
    pub segments: u32,
    /// `flat` discs, `round` hemispheres (a pill / capsule) or `none`.
    #[serde(default)]
    pub caps: Caps,
}

/// End caps of a cylinder.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Caps {
    /// Flat discs.
    #[default]
    Flat,
    /// Hemispheres of the cylinder radius (a capsule, adds length 2 r).
    Round,
    /// Open tube.
    None,
}

/// Surface colour: `color` (straight RGBA, linear) times an optional texture.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// Linear RGBA, straight alpha; alpha < 1 makes the object transparent. RGB is accepted
    /// (alpha 1).
    #[serde(default = "white")]
    pub color: Vec<f64>,
    /// Optional texture, multiplied with `color`.
    #[serde(default)]
    pub texture: Option<TextureDesc>,
    /// How the surface responds to the scene's lights (default `unlit`: colour × texture).
    #[serde(default)]
    pub shading: ShadingDesc,
    /// Specular colour of the `blinn_phong` lobe (linear RGB, default 0.5 grey).
    #[serde(default = "half_grey")]
    pub specular: [f64; 3],
    /// Blinn-Phong exponent, 0 to 10000 (default 32).
    #[serde(default = "thirty_two")]
    pub shininess: f64,
    /// Emitted radiance of a lit material (linear RGB, default black).
    #[serde(default)]
    pub emissive: [f64; 3],
}

/// How a material responds to light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadingDesc {
    /// Colour × texture, whatever the lights.
    #[default]
    Unlit,
    /// Ambient plus diffuse.
    Lambert,
    /// Ambient, diffuse and a Blinn-Phong specular lobe.
    BlinnPhong,
}

fn half_grey() -> [f64; 3] {
    [0.5; 3]
}

fn thirty_two() -> f64 {
    32.0
}

fn white() -> Vec<f64> {
    vec![1.0; 4]
}

impl Default for MaterialDesc {
    fn default() -> Self {
        MaterialDesc {
            color: white(),
            texture: None,
            shading: ShadingDesc::Unlit,
            specular: half_grey(),
            shininess: thirty_two(),
            emissive: [0.0; 3],
        }
    }
}

/// A texture: a PNG file or a procedural checkerboard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TextureDesc {
    /// A PNG file relative to the scene file (sRGB, decoded to linear).
    File(String),
    /// A procedural checkerboard of `squares` x `squares` cells in \[0,1\]^2, texel-exact.
    Checker(CheckerDesc),
}

/// Parameters of [`TextureDesc::Checker`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckerDesc {
    /// Cells per side.
    #[serde(default = "eight_u")]
    pub squares: u32,
    /// Texels per cell (the texture is `squares * texels_per_square` texels wide).
    #[serde(default = "eight_u")]
    pub texels_per_square: u32,
    /// Linear RGBA of the even cells.
    #[serde(default = "white")]
    pub a: Vec<f64>,
    /// Linear RGBA of the odd cells.
    #[serde(default = "black4")]
    pub b: Vec<f64>,
}

fn eight_u() -> u32 {
    8
}
fn black4() -> Vec<f64> {
    vec![0.0, 0.0, 0.0, 1.0]
}

/// Scale, then rotate, then translate.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformDesc {
    /// Translation.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Rotation about an axis through the origin.
    #[serde(default)]
    pub rotate: Option<RotateDesc>,
    /// Uniform (a number) or per-axis (`[x, y, z]`) scale.
    #[serde(default)]
    pub scale: Option<ScaleDesc>,
}

/// Rotation about `axis` by `degrees` (right-handed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotateDesc {
    /// Axis (need not be unit length, must not be zero).
    pub axis: [f64; 3],
    /// Angle in degrees.
    pub degrees: f64,
}

/// Uniform or per-axis scale.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ScaleDesc {
    /// Same factor on every axis.
    Uniform(f64),
    /// One factor per axis.
    PerAxis([f64; 3]),
}

/// Motion over the shutter: transforms at open and close (each default identity), or at
/// several keys, applied after the object's `transform` and interpolated as transforms
/// (translation and scale linear, rotation turning at a constant rate: an arc, not a
/// chord); or explicit world-space vertex positions at close (one straight segment).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionDesc {
    /// Transform at shutter open.
    #[serde(default)]
    pub open: Option<TransformDesc>,
    /// Transform at shutter close.
    #[serde(default)]
    pub close: Option<TransformDesc>,
    /// World-space vertex positions at close, one per mesh vertex in mesh order (inline
    /// triangles: 3 per triangle; OBJ: `v` lines; PLY: vertex elements; shapes: generation
    /// order). Excludes `open`/`close` and `keys`. The vertices move on straight lines (the
    /// data has no curve).
    #[serde(default)]
    pub positions_close: Option<Vec<[f64; 3]>>,
    /// Transforms (or, for triangle objects, vertex positions) at several instants (times
    /// strictly increasing, first 0, last 1). Excludes `open`/`close` and
    /// `positions_close`.
    #[serde(default)]
    pub keys: Option<Vec<MotionKeyDesc>>,
}

/// One motion key: a transform (scale, then rotate, then translate) at normalised shutter
/// time `t`. A scale may be zero here (the object shrinks to a point at that instant).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionKeyDesc {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// Translation.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Rotation about an axis through the origin.
    #[serde(default)]
    pub rotate: Option<RotateDesc>,
    /// Uniform or per-axis scale.
    #[serde(default)]
    pub scale: Option<ScaleDesc>,
    /// Vertex positions at this key, one per mesh vertex in mesh order, in the object's
    /// space (placed by its `transform`). Either every key of an object gives positions
    /// (and no transform) or none does; between two keys the vertices move on straight
    /// lines.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub positions: Option<Vec<[f64; 3]>>,
}

impl MotionKeyDesc {
    /// The key's transform.
    pub fn transform(&self) -> TransformDesc {
        TransformDesc {
            translate: self.translate,
            rotate: self.rotate.clone(),
            scale: self.scale.clone(),
        }
    }
}

/// A point-sampled object rendered by splatting.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SplatDesc {
    /// Name used in messages and in the effects report.
    pub name: String,
    /// Where the points come from.
    pub source: SplatSource,
    /// Splat radius in world units (required unless the PLY has a `radius` property).
    #[serde(default)]
    pub radius: Option<f64>,
    /// Linear RGBA (straight alpha), used where the PLY has no colour.
    #[serde(default = "white")]
    pub color: Vec<f64>,
    /// Placement before motion.
    #[serde(default)]
    pub transform: Option<TransformDesc>,
    /// Motion as for objects: transforms at open and close or at keys (a turning path is
    /// cut into segments as an object's is), or `positions_close` (one per point); keys
    /// give no per-point positions.
    #[serde(default)]
    pub motion: Option<MotionDesc>,
    /// How the splats respond to the scene's lights, as [`MaterialDesc::shading`] (default
    /// `unlit`); each splat's colour is its albedo and its normal the shading normal.
    #[serde(default)]
    pub shading: ShadingDesc,
    /// Specular colour of `blinn_phong` (default 0.5 grey).
    #[serde(default = "half_grey")]
    pub specular: [f64; 3],
    /// Blinn-Phong exponent, 0 to 10000 (default 32).
    #[serde(default = "thirty_two")]
    pub shininess: f64,
    /// Emitted radiance of lit splats (default black).
    #[serde(default)]
    pub emissive: [f64; 3],
}

/// Source of splat points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SplatSource {
    /// A PLY file with `x y z nx ny nz` (optional `red green blue`, `radius`).
    Ply(String),
    /// Area-uniform samples on a mesh.
    Sample(SampleDesc),
}

/// Parameters of [`SplatSource::Sample`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SampleDesc {
    /// Mesh to sample (shapes or files, as for objects).
    pub mesh: MeshDesc,
    /// Number of points.
    pub count: u32,
    /// Seed of the PCG32 sampler (default 0).
    #[serde(default)]
    pub seed: u64,
}
