//! Camera matrices and the projection of world points to 2DH pixel coordinates.
//!
//! A vertex projects to (x, y, w) with x and y already in pixel units before the division by
//! w (the viewport is folded into the projection), image row 0 at the top so y grows
//! downward, pixel (i, j) centred at (i + 0.5, j + 0.5) — the convention of
//! `docs/ARCHITECTURE.md` and Gribel 2010, §3 (2DH vertices).

use glam::{DMat4, DVec3, DVec4};

/// The projection of a camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
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

/// What a camera pose needs besides its position: image size, projection and clip depths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lens {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// Near clipping distance (view-space depth).
    pub near: f64,
    /// Far clipping distance.
    pub far: f64,
}

/// A projected vertex: 2DH position in pixel units and view-space depth.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vertex2dh {
    /// x in pixels times w.
    pub x: f64,
    /// y in pixels (downward) times w.
    pub y: f64,
    /// Homogeneous w (view-space depth for perspective, 1 for orthographic).
    pub w: f64,
    /// View-space depth: distance along the viewing direction (smaller is nearer).
    pub depth: f64,
}

impl Vertex2dh {
    /// Linear interpolation p(t) = (1 - t) q + t r (Gribel 2010, Eq. 2).
    pub fn lerp(self, r: Vertex2dh, t: f64) -> Vertex2dh {
        let l = |a: f64, b: f64| a + (b - a) * t;
        Vertex2dh {
            x: l(self.x, r.x),
            y: l(self.y, r.y),
            w: l(self.w, r.w),
            depth: l(self.depth, r.depth),
        }
    }

    /// Screen position (x / w, y / w) in pixels; only meaningful when w > 0.
    pub fn screen(self) -> (f64, f64) {
        (self.x / self.w, self.y / self.w)
    }
}

/// The camera at one instant (shutter open or close).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraFrame {
    /// Eye position.
    pub eye: DVec3,
    /// Look-at point.
    pub target: DVec3,
    /// Up direction.
    pub up: DVec3,
    /// World to view (right-handed, looking down -Z).
    pub view: DMat4,
    /// View to OpenGL clip space.
    pub clip_from_view: DMat4,
    /// Clip space to 2DH pixel space: x' = (x + w) W / 2, y' = (w - y) H / 2, w' = w.
    pub pixel_from_clip: DMat4,
}

impl CameraFrame {
    /// Builds the matrices for one pose.
    pub fn new(desc: &Lens, eye: DVec3, target: DVec3, up: DVec3) -> Self {
        let (w, h) = (f64::from(desc.width), f64::from(desc.height));
        let aspect = w / h;
        let (n, f) = (desc.near, desc.far);
        // Right-handed look-at: the camera looks down -Z of view space.
        let fw = (target - eye).normalize();
        let side = fw.cross(up).normalize();
        let u = side.cross(fw);
        let view = DMat4::from_cols(
            DVec4::new(side.x, u.x, -fw.x, 0.0),
            DVec4::new(side.y, u.y, -fw.y, 0.0),
            DVec4::new(side.z, u.z, -fw.z, 0.0),
            DVec4::new(-side.dot(eye), -u.dot(eye), fw.dot(eye), 1.0),
        );
        // OpenGL-style projections (clip z maps near..far to -1..1; only x, y, w are used).
        let clip_from_view = match desc.projection {
            Projection::Perspective { fov_y_deg } => {
                let g = 1.0 / (0.5 * fov_y_deg.to_radians()).tan();
                DMat4::from_cols(
                    DVec4::new(g / aspect, 0.0, 0.0, 0.0),
                    DVec4::new(0.0, g, 0.0, 0.0),
                    DVec4::new(0.0, 0.0, (f + n) / (n - f), -1.0),
                    DVec4::new(0.0, 0.0, 2.0 * f * n / (n - f), 0.0),
                )
            }
            Projection::Orthographic { height } => {
                let (hh, hw) = (0.5 * height, 0.5 * height * aspect);
                DMat4::from_cols(
                    DVec4::new(1.0 / hw, 0.0, 0.0, 0.0),
                    DVec4::new(0.0, 1.0 / hh, 0.0, 0.0),
                    DVec4::new(0.0, 0.0, -2.0 / (f - n), 0.0),
                    DVec4::new(0.0, 0.0, -(f + n) / (f - n), 1.0),
                )
            }
        };
        let pixel_from_clip = DMat4::from_cols(
            DVec4::new(0.5 * w, 0.0, 0.0, 0.0),
            DVec4::new(0.0, -0.5 * h, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(0.5 * w, 0.5 * h, 0.0, 1.0),
        );
        CameraFrame {
            eye,
            target,
            up,
            view,
            clip_from_view,
            pixel_from_clip,
        }
    }

    /// Projects a world-space point to 2DH pixel coordinates and view depth.
    pub fn project(&self, p: DVec3) -> Vertex2dh {
        let v = self.view * p.extend(1.0);
        let c = self.pixel_from_clip * (self.clip_from_view * v);
        Vertex2dh {
            x: c.x,
            y: c.y,
            w: c.w,
            depth: -v.z,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(projection: Projection) -> Lens {
        Lens {
            width: 200,
            height: 100,
            projection,
            near: 0.1,
            far: 100.0,
        }
    }

    #[test]
    fn perspective_maps_frustum_corners_to_image_corners() {
        let d = cam(Projection::Perspective { fov_y_deg: 90.0 });
        let f = CameraFrame::new(&d, DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y);
        // At depth 5 with fov 90 the half height is 5 and the half width 10.
        let top_left = f.project(DVec3::new(-10.0, 5.0, 0.0));
        let (x, y) = top_left.screen();
        assert!((x - 0.0).abs() < 1e-9 && (y - 0.0).abs() < 1e-9, "{x} {y}");
        let bottom_right = f.project(DVec3::new(10.0, -5.0, 0.0));
        let (x, y) = bottom_right.screen();
        assert!((x - 200.0).abs() < 1e-9 && (y - 100.0).abs() < 1e-9);
        assert!((top_left.w - 5.0).abs() < 1e-12 && (top_left.depth - 5.0).abs() < 1e-12);
    }

    #[test]
    fn orthographic_has_unit_w_and_view_depth() {
        let d = cam(Projection::Orthographic { height: 2.0 });
        let f = CameraFrame::new(&d, DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y);
        let v = f.project(DVec3::new(2.0, 1.0, -1.0));
        assert!((v.w - 1.0).abs() < 1e-12);
        assert!((v.depth - 6.0).abs() < 1e-12);
        assert!((v.x - 200.0).abs() < 1e-9 && (v.y - 0.0).abs() < 1e-9);
    }
}
