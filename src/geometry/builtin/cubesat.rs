//! `cubesat`: a 6U CubeSat, body 0.226 m (x) × 0.100 m (y) × 0.340 m (z) centred at the
//! origin (`body`, closed), with four deployable solar panels (`panel`, single sheets:
//! use two_sided), each the size of the side face it folds against (0.226 m or 0.100 m by
//! 0.340 m), hinged 5 mm off the body at the face's +z edge and open at 30° (+y face),
//! 60° (+x), 90° (−y) and 120° (−x) from stowed: at 90° a panel stands straight out,
//! beyond it it leans towards +z.
//!
//! Everything is flat, so the faces are gridded (as CAD exports mesh them): cells of about
//! 22 mm (coarse, 2 000 triangles), 7 mm (medium, default, 19 824) and 2.2 mm (fine,
//! 198 288).

use super::{push_grid_box, push_grid_quad, Builtin, Detail};
use crate::geometry::mesh::Mesh;
use glam::DVec3;

pub const BUILTIN: Builtin = Builtin {
    name: "cubesat",
    description: "6U CubeSat, 0.226 m x 0.1 m x 0.34 m body (`body`) with four deployable \
                  panels hinged at the +z edges of its side faces, open at 30°, 60°, 90° \
                  and 120° (`panel`, thin: use two_sided); detail coarse 2k, medium \
                  (default) 20k, fine 200k triangles",
    material_names: &["body", "panel"],
    default_detail: Detail::Medium,
    build,
};

const HALF: DVec3 = DVec3::new(0.113, 0.05, 0.17);
const HINGE_GAP: f64 = 0.005;

/// The CubeSat at `detail`.
pub fn build(detail: Detail) -> Mesh {
    let cell = detail.pick(0.0222, 0.0070, 0.00222);
    let cells = |len: f64| ((len / cell).round() as u32).max(1);
    let mut mesh = Mesh::default();
    push_grid_box(
        &mut mesh,
        -HALF,
        HALF,
        [
            cells(2.0 * HALF.x),
            cells(2.0 * HALF.y),
            cells(2.0 * HALF.z),
        ],
        0,
    );
    // (outward normal of the face, hinge direction along the edge, opening angle)
    let panels = [
        (DVec3::Y, DVec3::X, 30.0),
        (DVec3::X, DVec3::Y, 60.0),
        (DVec3::NEG_Y, DVec3::X, 90.0),
        (DVec3::NEG_X, DVec3::Y, 120.0),
    ];
    for (n, h, deg) in panels {
        let half_width = h.dot(HALF).abs();
        let hinge = n * (n.abs().dot(HALF) + HINGE_GAP) + DVec3::Z * HALF.z;
        let (s, c) = f64::to_radians(deg).sin_cos();
        // from the hinge, stowed down along −z, opened outwards towards n
        let down = (-c * DVec3::Z + s * n) * (2.0 * HALF.z);
        let across = h * (2.0 * half_width);
        let origin = hinge - 0.5 * across;
        push_grid_quad(
            &mut mesh,
            origin,
            across,
            down,
            cells(2.0 * half_width),
            cells(2.0 * HALF.z),
            1,
        );
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn three_levels_with_a_closed_body() {
        assert_levels(&BUILTIN);
        for d in Detail::ALL {
            let mesh = build(d);
            let body = part(&mesh, &[0]);
            assert_closed_outward(&body, "body");
            assert!((volume(&body) - 0.226 * 0.1 * 0.34).abs() < 1e-12);
        }
    }

    #[test]
    fn the_panels_open_at_four_angles() {
        let mesh = build(Detail::Coarse);
        let mut angles: Vec<i64> = Vec::new();
        for (i, &m) in mesh.material_ids.iter().enumerate() {
            if m == 1 {
                // the angle between the panel's plane and the body's z axis
                let n = mesh.area_vector(i).normalize();
                let a = n.z.abs().asin().to_degrees().round() as i64;
                if !angles.contains(&a) {
                    angles.push(a);
                }
            }
        }
        angles.sort_unstable();
        // 30° and 120° panels lie 30° from the axis, 60° 60°, 90° flat across it
        assert_eq!(angles, vec![30, 60, 90]);
    }
}
