//! Checks every number of a parsed scene and names the object and field of the first bad one.
//!
//! JSON cannot hold NaN or infinity and serde_json rejects out-of-range literals such as
//! `1e999` while parsing, but scenes built in code can hold anything, so every number is
//! checked here again.

use crate::desc::*;
use crate::error::{Error, Result};

/// Largest accepted image, in pixels (width x height): 8192 x 8192.
pub const MAX_PIXELS: u64 = 1 << 26;
/// Largest accepted image side, in pixels.
pub const MAX_SIDE: u32 = 1 << 15;
/// Largest accepted sphere `subdivisions`.
pub const MAX_SUBDIVISIONS: u32 = 2048;
/// Largest accepted cell count of a grid, slat count of a fence, or cylinder segment count.
pub const MAX_CELLS: u64 = 1 << 24;
/// Largest accepted number of sampled splats per object.
pub const MAX_SPLATS: u32 = 10_000_000;
/// Largest accepted procedural texture side, in texels.
pub const MAX_TEXTURE_SIDE: u32 = 8192;
/// Largest accepted colour channel (material, splat, checker and background colours): the
/// renderer blends in f32, and a channel above this leaves no headroom for sums of many
/// layers or weights (f32's largest value is about 3.4e38).
pub const MAX_COLOR: f64 = 1e6;
/// Largest accepted Blinn-Phong exponent.
pub const MAX_SHININESS: f64 = 10_000.0;
/// Largest accepted light intensity.
pub const MAX_INTENSITY: f64 = 1e12;
/// Most lights a scene may have (every lit sample loops over them).
pub const MAX_LIGHTS: usize = 64;
/// Most points a piecewise-linear shutter response may have.
pub const MAX_SHUTTER_POINTS: usize = 4096;
/// Smallest accepted integral of a piecewise-linear shutter response over the shutter,
/// relative to its largest weight: the response must be open for at least this fraction of
/// the shutter at its peak. A narrower spike vanishes when its times are rounded to f32.
pub const MIN_SHUTTER_OPEN: f64 = 1e-6;

struct V<'a> {
    file: &'a str,
}

impl V<'_> {
    fn err(&self, field: &str, msg: impl Into<String>) -> Error {
        Error::invalid(self.file, field, msg)
    }

    fn finite(&self, field: &str, v: f64) -> Result<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be a finite number, got {v}")))
        }
    }

    fn positive(&self, field: &str, v: f64) -> Result<f64> {
        self.finite(field, v)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be > 0, got {v}")))
        }
    }

    fn non_negative(&self, field: &str, v: f64) -> Result<f64> {
        self.finite(field, v)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be >= 0, got {v}")))
        }
    }

    fn vec3(&self, field: &str, v: &[f64; 3]) -> Result<()> {
        for (k, x) in v.iter().enumerate() {
            self.finite(&format!("{field}[{k}]"), *x)?;
        }
        Ok(())
    }

    fn count(&self, field: &str, v: u64, lo: u64, hi: u64) -> Result<()> {
        if v < lo || v > hi {
            Err(self.err(field, format!("must be between {lo} and {hi}, got {v}")))
        } else {
            Ok(())
        }
    }

    fn color(&self, field: &str, c: &[f64]) -> Result<()> {
        if c.len() != 3 && c.len() != 4 {
            return Err(self.err(
                field,
                format!("must have 3 (RGB) or 4 (RGBA) numbers, got {}", c.len()),
            ));
        }
        for (k, x) in c.iter().enumerate() {
            let f = format!("{field}[{k}]");
            self.channel(&f, *x)?;
            if k == 3 && *x > 1.0 {
                return Err(self.err(&f, format!("alpha must be in [0, 1], got {x}")));
            }
        }
        Ok(())
    }

    /// One colour channel: finite, in `[0, MAX_COLOR]`.
    fn channel(&self, field: &str, x: f64) -> Result<()> {
        self.non_negative(field, x)?;
        if x > MAX_COLOR {
            return Err(self.err(
                field,
                format!("must be at most {MAX_COLOR:e} (colours are linear RGB), got {x}"),
            ));
        }
        Ok(())
    }

    /// A piecewise-linear shutter response: 2 to [`MAX_SHUTTER_POINTS`] points, times
    /// strictly increasing from 0 to 1, weights finite and >= 0, open for at least
    /// [`MIN_SHUTTER_OPEN`] of the shutter at its peak weight.
    fn response(&self, pts: &[[f64; 2]]) -> Result<()> {
        let f = "shutter.response.piecewise_linear";
        if pts.len() < 2 || pts.len() > MAX_SHUTTER_POINTS {
            return Err(self.err(
                f,
                format!(
                    "needs 2 to {MAX_SHUTTER_POINTS} [t, w] points, got {}",
                    pts.len()
                ),
            ));
        }
        for (i, p) in pts.iter().enumerate() {
            self.finite(&format!("{f}[{i}][0]"), p[0])?;
            self.non_negative(&format!("{f}[{i}][1]"), p[1])?;
            if i > 0 && p[0] <= pts[i - 1][0] {
                return Err(self.err(&format!("{f}[{i}][0]"), "times must be strictly increasing"));
            }
        }
        if pts[0][0] != 0.0 || pts[pts.len() - 1][0] != 1.0 {
            return Err(self.err(f, "must start at t = 0 and end at t = 1"));
        }
        let peak = pts.iter().map(|p| p[1]).fold(0.0, f64::max);
        if peak == 0.0 {
            return Err(self.err(f, "weights must not all be zero"));
        }
        // The trapezoid integral of w / peak: every term is at most the interval's length.
        let open: f64 = pts
            .windows(2)
            .map(|q| 0.5 * (q[0][1] / peak + q[1][1] / peak) * (q[1][0] - q[0][0]))
            .sum();
        if open < MIN_SHUTTER_OPEN {
            return Err(self.err(
                f,
                format!(
                    "is open for {open:e} of the shutter at its peak weight; at least {MIN_SHUTTER_OPEN:e} is needed (a narrower spike vanishes in f32 time)"
                ),
            ));
        }
        Ok(())
    }

    fn transform(&self, field: &str, t: &TransformDesc) -> Result<()> {
        self.transform_with(field, t, false)
    }

    /// Checks a transform; `zero_scale` allows a scale of zero (motion keys).
    fn transform_with(&self, field: &str, t: &TransformDesc, zero_scale: bool) -> Result<()> {
        self.vec3(&format!("{field}.translate"), &t.translate)?;
        if let Some(r) = &t.rotate {
            let f = format!("{field}.rotate.axis");
            self.vec3(&f, &r.axis)?;
            let len2: f64 = r.axis.iter().map(|x| x * x).sum();
            if !(len2 > 0.0 && len2.is_finite()) {
                return Err(self.err(&f, "must be a non-zero vector"));
            }
            self.finite(&format!("{field}.rotate.degrees"), r.degrees)?;
        }
        match &t.scale {
            None => {}
            Some(ScaleDesc::Uniform(s)) => {
                let f = format!("{field}.scale");
                self.finite(&f, *s)?;
                if *s == 0.0 && !zero_scale {
                    return Err(self.err(&f, "must not be zero"));
                }
            }
            Some(ScaleDesc::PerAxis(s)) => {
                for (k, x) in s.iter().enumerate() {
                    let f = format!("{field}.scale[{k}]");
                    self.finite(&f, *x)?;
                    if *x == 0.0 && !zero_scale {
                        return Err(self.err(&f, "must not be zero"));
                    }
                }
            }
        }
        Ok(())
    }

    fn motion(&self, field: &str, m: &MotionDesc) -> Result<()> {
        if m.positions_close.is_some() && (m.open.is_some() || m.close.is_some()) {
            return Err(self.err(
                field,
                "give either `open`/`close` transforms or `positions_close`, not both",
            ));
        }
        if let Some(t) = &m.open {
            self.transform(&format!("{field}.open"), t)?;
        }
        if let Some(t) = &m.close {
            self.transform(&format!("{field}.close"), t)?;
        }
        if let Some(ps) = &m.positions_close {
            for (i, p) in ps.iter().enumerate() {
                self.vec3(&format!("{field}.positions_close[{i}]"), p)?;
            }
        }
        if let Some(keys) = &m.keys {
            if m.open.is_some() || m.close.is_some() || m.positions_close.is_some() {
                return Err(self.err(
                    field,
                    "give `keys`, or `open`/`close` transforms, or `positions_close`: one of them",
                ));
            }
            self.key_times(&format!("{field}.keys"), keys.iter().map(|k| k.t))?;
            let keyed = keys.iter().any(|k| k.positions.is_some());
            for (i, k) in keys.iter().enumerate() {
                let f = format!("{field}.keys[{i}]");
                self.transform_with(&f, &k.transform(), true)?;
                if keyed {
                    self.key_positions(&f, k)?;
                }
            }
        }
        Ok(())
    }

    /// Checks a key of an object whose keys give vertex positions: positions present and
    /// finite, no transform.
    fn key_positions(&self, field: &str, k: &MotionKeyDesc) -> Result<()> {
        let Some(ps) = &k.positions else {
            return Err(self.err(
                &format!("{field}.positions"),
                "is missing: when one key gives vertex positions, every key must",
            ));
        };
        if k.translate != [0.0; 3] || k.rotate.is_some() || k.scale.is_some() {
            return Err(self.err(
                field,
                "a key with `positions` takes no `translate`, `rotate` or `scale` (place the \
                 object with its `transform`)",
            ));
        }
        for (i, p) in ps.iter().enumerate() {
            self.vec3(&format!("{field}.positions[{i}]"), p)?;
        }
        Ok(())
    }

    /// Checks key times: at least two, finite, strictly increasing, first 0 and last 1. The
    /// error names the offending key.
    fn key_times(&self, field: &str, times: impl Iterator<Item = f64>) -> Result<()> {
        let times: Vec<f64> = times.collect();
        if times.len() < 2 {
            return Err(self.err(field, "needs at least two keys (t = 0 and t = 1)"));
        }
        for (i, &t) in times.iter().enumerate() {
            let f = format!("{field}[{i}].t");
            self.finite(&f, t)?;
            if !(0.0..=1.0).contains(&t) {
                return Err(self.err(&f, format!("must be in [0, 1], got {t}")));
            }
            if let Some(&prev) = i.checked_sub(1).and_then(|j| times.get(j))
                && t <= prev
            {
                return Err(self.err(
                    &f,
                    format!("key times must strictly increase: {t} follows {prev}"),
                ));
            }
        }
        if times.first() != Some(&0.0) {
            return Err(self.err(&format!("{field}[0].t"), "the first key must be at t = 0"));
        }
        if times.last() != Some(&1.0) {
            let n = times.len() - 1;
            return Err(self.err(&format!("{field}[{n}].t"), "the last key must be at t = 1"));
        }
        Ok(())
    }

    fn mesh(&self, field: &str, m: &MeshDesc) -> Result<()> {
        match m {
            MeshDesc::Triangles(ts) => {
                if ts.is_empty() {
                    return Err(
                        self.err(&format!("{field}.triangles"), "needs at least one triangle")
                    );
                }
                for (i, t) in ts.iter().enumerate() {
                    for (k, p) in t.iter().enumerate() {
                        self.vec3(&format!("{field}.triangles[{i}][{k}]"), p)?;
                    }
                }
            }
            MeshDesc::File(p) => {
                if p.is_empty() {
                    return Err(self.err(&format!("{field}.file"), "empty path"));
                }
            }
            MeshDesc::Sphere(s) => {
                self.positive(&format!("{field}.sphere.radius"), s.radius)?;
                self.count(
                    &format!("{field}.sphere.subdivisions"),
                    s.subdivisions.into(),
                    2,
                    MAX_SUBDIVISIONS.into(),
                )?;
                let f = format!("{field}.sphere.wrinkle");
                self.non_negative(&f, s.wrinkle)?;
                if s.wrinkle >= 1.0 {
                    return Err(self.err(&f, format!("must be < 1, got {}", s.wrinkle)));
                }
                self.finite(
                    &format!("{field}.sphere.wrinkle_frequency"),
                    s.wrinkle_frequency,
                )?;
            }
            MeshDesc::Box(b) => {
                for (k, x) in b.size.iter().enumerate() {
                    self.positive(&format!("{field}.box.size[{k}]"), *x)?;
                }
            }
            MeshDesc::Quad(q) => {
                for (k, x) in q.size.iter().enumerate() {
                    self.positive(&format!("{field}.quad.size[{k}]"), *x)?;
                }
                for (k, x) in q.uv_repeat.iter().enumerate() {
                    self.finite(&format!("{field}.quad.uv_repeat[{k}]"), *x)?;
                }
            }
            MeshDesc::Grid(g) => {
                for (k, x) in g.size.iter().enumerate() {
                    self.positive(&format!("{field}.grid.size[{k}]"), *x)?;
                }
                let f = format!("{field}.grid.divisions");
                self.count(&format!("{f}[0]"), g.divisions[0].into(), 1, MAX_CELLS)?;
                self.count(&format!("{f}[1]"), g.divisions[1].into(), 1, MAX_CELLS)?;
                let cells = u64::from(g.divisions[0]) * u64::from(g.divisions[1]);
                if cells > MAX_CELLS {
                    return Err(self.err(
                        &f,
                        format!("{cells} cells is more than the limit {MAX_CELLS}"),
                    ));
                }
                self.finite(&format!("{field}.grid.wave_amplitude"), g.wave_amplitude)?;
                self.finite(&format!("{field}.grid.wave_frequency"), g.wave_frequency)?;
            }
            MeshDesc::Fence(fe) => {
                self.count(
                    &format!("{field}.fence.slats"),
                    fe.slats.into(),
                    1,
                    MAX_CELLS,
                )?;
                self.positive(&format!("{field}.fence.slat_width"), fe.slat_width)?;
                self.non_negative(&format!("{field}.fence.gap"), fe.gap)?;
                self.positive(&format!("{field}.fence.height"), fe.height)?;
            }
            MeshDesc::Cylinder(c) => {
                self.positive(&format!("{field}.cylinder.radius"), c.radius)?;
                self.positive(&format!("{field}.cylinder.height"), c.height)?;
                self.count(
                    &format!("{field}.cylinder.segments"),
                    c.segments.into(),
                    3,
                    1 << 16,
                )?;
            }
        }
        Ok(())
    }

    /// The specular colour, emissive colour and shininess of a lit surface.
    fn shading(
        &self,
        field: &str,
        specular: &[f64; 3],
        emissive: &[f64; 3],
        shininess: f64,
    ) -> Result<()> {
        self.color(&format!("{field}.specular"), specular)?;
        self.color(&format!("{field}.emissive"), emissive)?;
        let f = format!("{field}.shininess");
        self.non_negative(&f, shininess)?;
        if shininess > MAX_SHININESS {
            return Err(self.err(
                &f,
                format!("must be at most {MAX_SHININESS}, got {shininess}"),
            ));
        }
        Ok(())
    }

    fn material(&self, field: &str, m: &MaterialDesc) -> Result<()> {
        self.color(&format!("{field}.color"), &m.color)?;
        self.shading(field, &m.specular, &m.emissive, m.shininess)?;
        match &m.texture {
            None => {}
            Some(TextureDesc::File(p)) if p.is_empty() => {
                return Err(self.err(&format!("{field}.texture.file"), "empty path"));
            }
            Some(TextureDesc::File(_)) => {}
            Some(TextureDesc::Checker(c)) => {
                let f = format!("{field}.texture.checker");
                self.count(
                    &format!("{f}.squares"),
                    c.squares.into(),
                    1,
                    MAX_TEXTURE_SIDE.into(),
                )?;
                self.count(
                    &format!("{f}.texels_per_square"),
                    c.texels_per_square.into(),
                    1,
                    MAX_TEXTURE_SIDE.into(),
                )?;
                let side = u64::from(c.squares) * u64::from(c.texels_per_square);
                if side > MAX_TEXTURE_SIDE.into() {
                    return Err(self.err(
                        &f,
                        format!("texture side {side} exceeds {MAX_TEXTURE_SIDE}"),
                    ));
                }
                self.color(&format!("{f}.a"), &c.a)?;
                self.color(&format!("{f}.b"), &c.b)?;
            }
        }
        Ok(())
    }
}

/// Validates a parsed scene; `file` names it in messages.
pub fn validate(scene: &SceneDesc, file: &str) -> Result<()> {
    let v = V { file };
    v.camera(&scene.camera)?;
    v.shutter(&scene.shutter)?;
    for (k, x) in scene.background.iter().enumerate() {
        v.channel(&format!("background[{k}]"), *x)?;
    }
    for (i, o) in scene.objects.iter().enumerate() {
        let f = format!("objects[{i}] \"{}\"", o.name);
        v.mesh(&format!("{f}.mesh"), &o.mesh)?;
        v.material(&format!("{f}.material"), &o.material)?;
        if let Some(t) = &o.transform {
            v.transform(&format!("{f}.transform"), t)?;
        }
        if let Some(m) = &o.motion {
            v.motion(&format!("{f}.motion"), m)?;
        }
    }
    for (i, s) in scene.splats.iter().enumerate() {
        v.splat(i, s)?;
    }
    if scene.lights.len() > MAX_LIGHTS {
        return Err(v.err(
            "lights",
            format!("at most {MAX_LIGHTS} lights, got {}", scene.lights.len()),
        ));
    }
    for (i, l) in scene.lights.iter().enumerate() {
        v.light(&format!("lights[{i}]"), l)?;
    }
    Ok(())
}

impl V<'_> {
    /// Checks a light: colour channels, intensity in `[0, MAX_INTENSITY]`, finite positions
    /// and non-zero directions, and its motion: the open value (and optional close value),
    /// or keys with times as for motion keys ([`V::key_times`]).
    fn light(&self, field: &str, l: &LightDesc) -> Result<()> {
        let (color, intensity) = match l {
            LightDesc::Ambient { color } => (color, None),
            LightDesc::Directional {
                direction,
                direction_close,
                keys,
                color,
                intensity,
            } => {
                let keyed = keys.as_ref().map(|k| k.iter().map(|k| (k.t, k.direction)));
                let ends = [
                    ("direction", direction),
                    ("direction_close", direction_close),
                ];
                self.light_motion(field, ends, keyed, true)?;
                (color, Some(*intensity))
            }
            LightDesc::Point {
                position,
                position_close,
                keys,
                color,
                intensity,
            } => {
                let keyed = keys.as_ref().map(|k| k.iter().map(|k| (k.t, k.position)));
                let ends = [("position", position), ("position_close", position_close)];
                self.light_motion(field, ends, keyed, false)?;
                (color, Some(*intensity))
            }
        };
        self.color(&format!("{field}.color"), color)?;
        if let Some(i) = intensity {
            let f = format!("{field}.intensity");
            self.non_negative(&f, i)?;
            if i > MAX_INTENSITY {
                return Err(self.err(&f, format!("must be at most {MAX_INTENSITY:e}, got {i}")));
            }
        }
        Ok(())
    }

    /// The motion of a directional (`direction`) or point light: its open and close values
    /// `ends` (the open one required) or `keys`, not both; every value finite, and non-zero
    /// for a `direction`.
    fn light_motion(
        &self,
        field: &str,
        ends: [(&str, &Option<[f64; 3]>); 2],
        keys: Option<impl Iterator<Item = (f64, [f64; 3])>>,
        direction: bool,
    ) -> Result<()> {
        let value = |f: &str, v: &[f64; 3]| -> Result<()> {
            self.vec3(f, v)?;
            let len2 = v.iter().map(|x| x * x).sum::<f64>();
            if direction && !(len2 > 0.0 && len2.is_finite()) {
                return Err(self.err(f, "must be a non-zero finite direction"));
            }
            Ok(())
        };
        let [(open_name, open), (close_name, close)] = ends;
        let Some(keys) = keys else {
            let Some(open) = open else {
                return Err(self.err(
                    &format!("{field}.{open_name}"),
                    "is required (or give `keys`)",
                ));
            };
            value(&format!("{field}.{open_name}"), open)?;
            if let Some(c) = close {
                value(&format!("{field}.{close_name}"), c)?;
            }
            return Ok(());
        };
        if open.is_some() || close.is_some() {
            return Err(self.err(
                field,
                format!("give `keys` or `{open_name}` (and `{close_name}`), not both"),
            ));
        }
        let keys: Vec<(f64, [f64; 3])> = keys.collect();
        let f = format!("{field}.keys");
        self.key_times(&f, keys.iter().map(|k| k.0))?;
        for (i, (_, v)) in keys.iter().enumerate() {
            value(&format!("{f}[{i}].{open_name}"), v)?;
        }
        Ok(())
    }

    /// Checks the camera: image size, projection, clip depths and both poses.
    fn camera(&self, c: &CameraDesc) -> Result<()> {
        self.count("camera.width", c.width.into(), 1, MAX_SIDE.into())?;
        self.count("camera.height", c.height.into(), 1, MAX_SIDE.into())?;
        let pixels = u64::from(c.width) * u64::from(c.height);
        if pixels > MAX_PIXELS {
            return Err(self.err(
                "camera.width x camera.height",
                format!(
                    "{} x {} = {pixels} pixels exceeds the limit of {MAX_PIXELS}",
                    c.width, c.height
                ),
            ));
        }
        match c.projection {
            ProjectionDesc::Perspective { fov_y_deg } => {
                let f = self.finite("camera.projection.perspective.fov_y_deg", fov_y_deg)?;
                if !(f > 0.0 && f < 180.0) {
                    return Err(self.err(
                        "camera.projection.perspective.fov_y_deg",
                        format!("must be in (0, 180), got {f}"),
                    ));
                }
                self.positive("camera.near", c.near)?;
            }
            ProjectionDesc::Orthographic { height } => {
                self.positive("camera.projection.orthographic.height", height)?;
                self.finite("camera.near", c.near)?;
            }
        }
        self.finite("camera.far", c.far)?;
        if c.near >= c.far {
            return Err(self.err(
                "camera.near",
                format!("must be less than camera.far ({} >= {})", c.near, c.far),
            ));
        }
        self.pose("camera.", &c.eye, &c.target, &c.up)?;
        if let Some(m) = &c.motion {
            self.pose(
                "camera.motion.",
                &m.eye.unwrap_or(c.eye),
                &m.target.unwrap_or(c.target),
                &m.up.unwrap_or(c.up),
            )?;
            if let Some(keys) = &m.keys {
                if m.eye.is_some() || m.target.is_some() || m.up.is_some() {
                    return Err(self.err(
                        "camera.motion",
                        "give `keys` or the close pose (`eye`/`target`/`up`), not both",
                    ));
                }
                self.key_times("camera.motion.keys", keys.iter().map(|k| k.t))?;
                for (i, k) in keys.iter().enumerate() {
                    self.pose(
                        &format!("camera.motion.keys[{i}]."),
                        &k.eye.unwrap_or(c.eye),
                        &k.target.unwrap_or(c.target),
                        &k.up.unwrap_or(c.up),
                    )?;
                }
            }
        }
        Ok(())
    }

    /// Checks one camera pose; `prefix` names its fields in messages.
    fn pose(&self, prefix: &str, eye: &[f64; 3], target: &[f64; 3], up: &[f64; 3]) -> Result<()> {
        self.vec3(&format!("{prefix}eye"), eye)?;
        self.vec3(&format!("{prefix}target"), target)?;
        self.vec3(&format!("{prefix}up"), up)?;
        let d = glam::DVec3::from_array(*target) - glam::DVec3::from_array(*eye);
        if d.length_squared() == 0.0 {
            return Err(self.err(
                &format!("{prefix}target"),
                "must differ from the eye position",
            ));
        }
        if d.normalize()
            .cross(glam::DVec3::from_array(*up).normalize_or_zero())
            .length()
            < 1e-9
        {
            return Err(self.err(
                &format!("{prefix}up"),
                "must not be zero or parallel to the viewing direction",
            ));
        }
        Ok(())
    }

    /// Checks the shutter interval and response.
    fn shutter(&self, s: &ShutterDesc) -> Result<()> {
        self.finite("shutter.open", s.open)?;
        self.finite("shutter.close", s.close)?;
        if s.open >= s.close {
            return Err(self.err(
                "shutter.open",
                format!(
                    "must be less than shutter.close ({} >= {})",
                    s.open, s.close
                ),
            ));
        }
        if let ResponseDesc::PiecewiseLinear(pts) = &s.response {
            self.response(pts)?;
        }
        Ok(())
    }

    /// Checks splat object `i`.
    fn splat(&self, i: usize, s: &SplatDesc) -> Result<()> {
        let f = format!("splats[{i}] \"{}\"", s.name);
        self.shading(&f, &s.specular, &s.emissive, s.shininess)?;
        match &s.source {
            SplatSource::Ply(p) => {
                if p.is_empty() {
                    return Err(self.err(&format!("{f}.source.ply"), "empty path"));
                }
            }
            SplatSource::Sample(sd) => {
                self.mesh(&format!("{f}.source.sample.mesh"), &sd.mesh)?;
                self.count(
                    &format!("{f}.source.sample.count"),
                    sd.count.into(),
                    1,
                    MAX_SPLATS.into(),
                )?;
                if s.radius.is_none() {
                    return Err(self.err(&format!("{f}.radius"), "is required for sampled splats"));
                }
            }
        }
        if let Some(r) = s.radius {
            self.positive(&format!("{f}.radius"), r)?;
        }
        self.color(&format!("{f}.color"), &s.color)?;
        if let Some(t) = &s.transform {
            self.transform(&format!("{f}.transform"), t)?;
        }
        if let Some(m) = &s.motion {
            self.motion(&format!("{f}.motion"), m)?;
            let positions = m.keys.iter().flatten().position(|k| k.positions.is_some());
            if let Some(i) = positions {
                return Err(self.err(
                    &format!("{f}.motion.keys[{i}].positions"),
                    "a splat set's keys are transforms (`translate`, `rotate`, `scale`); \
                     per-point positions at keys are not supported",
                ));
            }
        }
        Ok(())
    }
}
