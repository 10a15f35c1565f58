//! The orthographic camera: the object as the observer sees it.
//!
//! The observer is far away compared with the object, so the view is a parallel
//! projection along −v (v: unit vector object → observer), exactly the geometry of the
//! light curve's Eq. 12. The image is framed on the object's projected extent, and its
//! "up" is the Sun's direction projected on the image plane, so that a sequence keeps
//! the lit side on top and does not spin as the observer moves.

use crate::geometry::Mesh;
use glam::DVec3;

/// Margin around the projected extent, as a fraction of the frame's side on each side.
const MARGIN: f64 = 0.04;

/// Below this length of the Sun's projection on the image plane (sine of the angle
/// between the Sun and the view axis, ≈ 0.06°), "up" falls back to a body axis.
const MIN_SUN_PROJECTION: f64 = 1e-3;

/// A parallel-projection camera. Pixel (0, 0) is the top-left corner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Unit vector object → observer (the rays travel along `-view`).
    pub view: DVec3,
    /// Unit image-plane vector pointing to the right of the image.
    pub right: DVec3,
    /// Unit image-plane vector pointing to the top of the image.
    pub up: DVec3,
    /// Centre of the image, on the plane through the body origin, m (body frame).
    pub centre: DVec3,
    /// Side of the square frame, m.
    pub side_m: f64,
    /// Pixels on a side.
    pub size: u32,
    /// Distance from `centre` back along `view` to the ray origins, m (in front of
    /// every vertex).
    pub standoff_m: f64,
}

impl Camera {
    /// Frames `mesh` seen from direction `view` (unit, object → observer) with the Sun
    /// in direction `sun` (unit, object → Sun), on a `size`×`size` image.
    pub fn frame(mesh: &Mesh, view: DVec3, sun: DVec3, size: u32) -> Camera {
        let up = image_up(view, sun);
        // right-handed image: looking along −view with `up` on top, `right` is up × view
        let right = up.cross(view).normalize();
        let (mut lo_x, mut hi_x) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut lo_y, mut hi_y) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut depth = f64::NEG_INFINITY;
        for p in &mesh.vertices {
            let (x, y) = (p.dot(right), p.dot(up));
            lo_x = lo_x.min(x);
            hi_x = hi_x.max(x);
            lo_y = lo_y.min(y);
            hi_y = hi_y.max(y);
            depth = depth.max(p.dot(view));
        }
        let extent = (hi_x - lo_x).max(hi_y - lo_y);
        let (_, radius) = mesh.bounding_sphere();
        // A mesh seen exactly edge-on in both image directions cannot exist (triangles
        // have area), but keep the frame finite whatever happens.
        let extent = if extent > 0.0 {
            extent
        } else {
            radius.max(1e-9)
        };
        let side = extent / (1.0 - 2.0 * MARGIN);
        let centre = right * (0.5 * (lo_x + hi_x)) + up * (0.5 * (lo_y + hi_y));
        Camera {
            view,
            right,
            up,
            centre,
            side_m: side,
            size: size.max(1),
            standoff_m: depth.max(0.0) + radius.max(1e-9),
        }
    }

    /// Pixel side, m.
    #[inline]
    pub fn metres_per_pixel(&self) -> f64 {
        self.side_m / self.size as f64
    }

    /// Area of one pixel on the image plane, m².
    #[inline]
    pub fn pixel_area_m2(&self) -> f64 {
        let m = self.metres_per_pixel();
        m * m
    }

    /// Origin (m, body frame) of the ray through image coordinates `(u, v)` in pixels
    /// from the top-left corner (fractional). The ray's direction is `-self.view`.
    #[inline]
    pub fn ray_origin(&self, u: f64, v: f64) -> DVec3 {
        let m = self.metres_per_pixel();
        let x = (u - 0.5 * self.size as f64) * m;
        let y = (0.5 * self.size as f64 - v) * m;
        self.centre + self.right * x + self.up * y + self.view * self.standoff_m
    }

    /// Image coordinates (pixels from the top-left corner) of the body-frame point `p`.
    pub fn project(&self, p: DVec3) -> (f64, f64) {
        let m = self.metres_per_pixel();
        let d = p - self.centre;
        (
            d.dot(self.right) / m + 0.5 * self.size as f64,
            0.5 * self.size as f64 - d.dot(self.up) / m,
        )
    }
}

/// "Up" on the image: the Sun's direction projected on the image plane; when the Sun
/// is (anti-)along the view axis, the body's +z, else +y, projected the same way.
pub fn image_up(view: DVec3, sun: DVec3) -> DVec3 {
    for axis in [sun, DVec3::Z, DVec3::Y] {
        let p = axis - view * axis.dot(view);
        if p.length() > MIN_SUN_PROJECTION {
            return p.normalize();
        }
    }
    // view is along both z and y: impossible for a unit vector, but stay total.
    DVec3::X
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn up_follows_the_sun_and_basis_is_orthonormal() {
        let view = DVec3::new(1.0, 2.0, 0.5).normalize();
        let sun = DVec3::new(-0.3, 0.1, 1.0).normalize();
        let c = Camera::frame(&builtin::box_wing(), view, sun, 64);
        assert!(c.up.dot(sun) > 0.0);
        assert!(c.up.dot(view).abs() < 1e-12 && c.right.dot(view).abs() < 1e-12);
        assert!(c.right.dot(c.up).abs() < 1e-12);
        // right-handed: right × up = view (towards the observer)
        assert!((c.right.cross(c.up) - view).length() < 1e-12);
    }

    #[test]
    fn sun_on_the_view_axis_falls_back_to_body_z() {
        let view = DVec3::new(1.0, 0.0, 0.0);
        assert_eq!(image_up(view, view), DVec3::Z);
        assert_eq!(image_up(DVec3::Z, -DVec3::Z), DVec3::Y);
    }

    #[test]
    fn every_vertex_is_inside_the_frame() {
        let mesh = builtin::box_wing();
        let view = DVec3::new(0.2, -1.0, 0.4).normalize();
        let c = Camera::frame(&mesh, view, DVec3::X, 100);
        for p in &mesh.vertices {
            let (u, v) = c.project(*p);
            assert!(
                (0.0..=100.0).contains(&u) && (0.0..=100.0).contains(&v),
                "{u} {v}"
            );
            // the ray origin lies in front of the vertex
            assert!((c.ray_origin(u, v) - *p).dot(view) > 0.0);
        }
    }
}
