//! The camera: a view-projection matrix and a viewport, giving pixel rays and the 2DH
//! screen mapping (Heinzle 2010, Eq. 15: the viewport, projection and model-view matrices).

use glam::{DMat4, DVec3, DVec4};

/// A pinhole (or orthographic) camera given by its view-projection matrix (world to clip,
/// OpenGL conventions: NDC in [-1, 1]³, camera looking down -Z) and a viewport in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World to clip space.
    pub view_proj: DMat4,
    /// Viewport width in pixels.
    pub width: u32,
    /// Viewport height in pixels.
    pub height: u32,
}

impl Camera {
    /// A perspective camera at `eye` looking at `target` (right-handed look-at, OpenGL
    /// perspective with vertical field of view `fov_y` radians and clip planes `near`,
    /// `far`), for a `width` x `height` viewport.
    #[allow(clippy::too_many_arguments)]
    pub fn look_at_perspective(
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        fov_y: f64,
        near: f64,
        far: f64,
        width: u32,
        height: u32,
    ) -> Self {
        let f = (target - eye).normalize_or(DVec3::NEG_Z);
        let s = f.cross(up).normalize_or(DVec3::X);
        let u = s.cross(f);
        let view = DMat4::from_cols(
            DVec4::new(s.x, u.x, -f.x, 0.0),
            DVec4::new(s.y, u.y, -f.y, 0.0),
            DVec4::new(s.z, u.z, -f.z, 0.0),
            DVec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
        );
        let aspect = width.max(1) as f64 / height.max(1) as f64;
        let g = 1.0 / (0.5 * fov_y).tan();
        let proj = DMat4::from_cols(
            DVec4::new(g / aspect, 0.0, 0.0, 0.0),
            DVec4::new(0.0, g, 0.0, 0.0),
            DVec4::new(0.0, 0.0, (far + near) / (near - far), -1.0),
            DVec4::new(0.0, 0.0, 2.0 * far * near / (near - far), 0.0),
        );
        Self {
            view_proj: proj * view,
            width,
            height,
        }
    }

    /// The ray ewa-splat traces through pixel position (`px`, `py`) (pixel centres at
    /// i + 0.5, row 0 at the top): origin on the near plane, unit direction. Its parameter
    /// is the depth of splat fragments and of [`crate::SurfaceInterval`]s. `None` for a
    /// singular or non-finite camera or an empty viewport.
    pub fn pixel_ray(&self, px: f64, py: f64) -> Option<(DVec3, DVec3)> {
        CameraSetup::new(self)?.ray(px, py)
    }
}

/// A camera with its derived matrices, ready for per-pixel work.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CameraSetup {
    /// World to 2DH pixel coordinates: rows 0, 1, 3 give (x, y, w) with x, y in pixels before
    /// division by w (the viewport transform folded in, image row 0 at NDC y = +1).
    pub screen: DMat4,
    /// Inverse of `view_proj`.
    pub inv_view_proj: DMat4,
    pub width: u32,
    pub height: u32,
}

impl CameraSetup {
    pub fn new(camera: &Camera) -> Option<Self> {
        let vp = camera.view_proj;
        if !vp.is_finite() || camera.width == 0 || camera.height == 0 {
            return None;
        }
        let det = vp.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = vp.inverse();
        if !inv.is_finite() {
            return None;
        }
        let w = camera.width as f64;
        let h = camera.height as f64;
        // x_pix = (ndc_x + 1) W / 2, y_pix = (1 - ndc_y) H / 2, homogeneous in clip w.
        let viewport = DMat4::from_cols(
            DVec4::new(w / 2.0, 0.0, 0.0, 0.0),
            DVec4::new(0.0, -h / 2.0, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(w / 2.0, h / 2.0, 0.0, 1.0),
        );
        Some(Self {
            screen: viewport * vp,
            inv_view_proj: inv,
            width: camera.width,
            height: camera.height,
        })
    }

    /// The viewing ray through pixel position (px, py) (pixel centres at i + 0.5): origin on
    /// the near plane, unit direction. The ray parameter is the depth used for visibility.
    pub fn ray(&self, px: f64, py: f64) -> Option<(DVec3, DVec3)> {
        let nx = 2.0 * px / self.width as f64 - 1.0;
        let ny = 1.0 - 2.0 * py / self.height as f64;
        let near = self.inv_view_proj * DVec4::new(nx, ny, -1.0, 1.0);
        let far = self.inv_view_proj * DVec4::new(nx, ny, 1.0, 1.0);
        if near.w == 0.0 || far.w == 0.0 {
            return None;
        }
        let o = near.truncate() / near.w;
        let d = (far.truncate() / far.w - o).try_normalize()?;
        if !o.is_finite() {
            return None;
        }
        Some((o, d))
    }

    /// Screen-space Jacobian at a world point: gradients of the pixel x and y coordinates.
    /// `None` behind the eye (w <= 0).
    pub fn jacobian(&self, p: DVec3) -> Option<[DVec3; 2]> {
        let m = self.screen;
        let x = m.row(0);
        let y = m.row(1);
        let wr = m.row(3);
        let hp = p.extend(1.0);
        let (xs, ys, ws) = (x.dot(hp), y.dot(hp), wr.dot(hp));
        if ws.is_nan() || ws <= 0.0 {
            return None;
        }
        let gx = (x.truncate() * ws - wr.truncate() * xs) / (ws * ws);
        let gy = (y.truncate() * ws - wr.truncate() * ys) / (ws * ws);
        Some([gx, gy])
    }
}
