//! `dish-sat`: a communications satellite with a large dish, about 11.9 m across its
//! solar arrays.
//!
//! - bus (`body`): a 1.5 m × 1.5 m × 2.0 m box centred at the origin (z the long axis);
//! - solar arrays (`panel`, single sheets: use two_sided): two 4.0 m × 1.6 m wings on
//!   booms along ±y (y from 1.3 to 5.3 m), both turned 30° about the y axis, so no wing is
//!   parallel to a face of the bus;
//! - dish (`dish`, a single sheet: use two_sided): a paraboloid of 1.1 m rim radius and
//!   0.8 m focal length on a 0.55 m boom from the −x face, opening towards −x (vertex at
//!   x = −1.3 m, rim at x = −1.68 m);
//! - four feed struts (`strut`) from near the dish rim to the feed, a 0.2 m cylinder at
//!   the focus (x = −2.1 m); the booms are `strut` too.
//!
//! The bus, booms, struts and feed are closed prisms. Coarse: dish 16 rings × 48 sectors,
//! 8-sided struts (2 064 triangles); medium (default): 56 × 160, 16 sides (19 808); fine:
//! 170 × 540, 48 sides (203 284); the flat bus and wings are gridded finer with each level.

use super::{push_grid_box, push_grid_quad, push_tube, Builtin, Detail};
use crate::geometry::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::TAU;

pub const BUILTIN: Builtin = Builtin {
    name: "dish-sat",
    description: "1.5 m x 1.5 m x 2 m box bus (`body`), two 4 m x 1.6 m solar wings on \
                  booms along ±y turned 30° about y (`panel`, thin: use two_sided), a 2.2 m \
                  parabolic dish on a boom from the -x face opening to -x (`dish`, thin: use \
                  two_sided) with four feed struts to the feed and booms (`strut`); detail \
                  coarse 2k, medium (default) 20k, fine 203k triangles",
    material_names: &["body", "panel", "dish", "strut"],
    default_detail: Detail::Medium,
    build,
};

const RIM: f64 = 1.1;
const FOCAL: f64 = 0.8;
const DISH_X: f64 = -1.3;

/// The point of the dish at radius r and angle phi about its axis (−x).
fn dish_point(r: f64, phi: f64) -> DVec3 {
    DVec3::new(DISH_X - r * r / (4.0 * FOCAL), r * phi.cos(), r * phi.sin())
}

/// The satellite at `detail`.
pub fn build(detail: Detail) -> Mesh {
    let (rings, sectors, sides) = detail.pick((16, 48, 8), (56, 160, 16), (170, 540, 48));
    let bus_cells = detail.pick([4, 4, 5], [8, 8, 10], [24, 24, 32]);
    let (wing_cells_y, wing_cells_w) = detail.pick((8, 3), (20, 8), (80, 32));
    let mut mesh = Mesh::default();
    push_grid_box(
        &mut mesh,
        DVec3::new(-0.75, -0.75, -1.0),
        DVec3::new(0.75, 0.75, 1.0),
        bus_cells,
        0,
    );
    // wings: across-wing direction w turned 30° from z towards x
    let (s, c) = 30f64.to_radians().sin_cos();
    let w = DVec3::new(s, 0.0, c) * 1.6;
    for sign in [-1.0, 1.0] {
        let (y0, y1) = (1.3 * sign, 5.3 * sign);
        push_tube(
            &mut mesh,
            DVec3::new(0.0, 0.7 * sign, 0.0),
            DVec3::new(0.0, y0, 0.0),
            0.04,
            sides,
            3,
        );
        // normal along (y1 − y0) × w: +x-ish for the +y wing, its mirror for the other
        let along = DVec3::new(0.0, y1 - y0, 0.0);
        let (origin, u, v) = if sign > 0.0 {
            (DVec3::new(0.0, y0, 0.0) - 0.5 * w, along, w)
        } else {
            (DVec3::new(0.0, y0, 0.0) - 0.5 * w, w, along)
        };
        let (nu, nv) = if sign > 0.0 {
            (wing_cells_y, wing_cells_w)
        } else {
            (wing_cells_w, wing_cells_y)
        };
        push_grid_quad(&mut mesh, origin, u, v, nu, nv, 1);
    }
    // dish boom, stopping 2 mm behind the dish's vertex
    push_tube(
        &mut mesh,
        DVec3::new(-0.7, 0.0, 0.0),
        DVec3::new(DISH_X + 0.002, 0.0, 0.0),
        0.06,
        sides,
        3,
    );
    // dish: concave side towards −x (its normal there)
    let base = mesh.vertices.len() as u32;
    mesh.vertices.push(dish_point(0.0, 0.0));
    for i in 1..=rings {
        let r = RIM * i as f64 / rings as f64;
        for j in 0..sectors {
            mesh.vertices
                .push(dish_point(r, TAU * j as f64 / sectors as f64));
        }
    }
    let ring = |i: u32, j: u32| base + 1 + (i - 1) * sectors + (j % sectors);
    for j in 0..sectors {
        mesh.triangles.push([base, ring(1, j + 1), ring(1, j)]);
        mesh.material_ids.push(2);
    }
    for i in 1..rings {
        for j in 0..sectors {
            mesh.triangles
                .push([ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)]);
            mesh.triangles
                .push([ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)]);
            mesh.material_ids.extend([2, 2]);
        }
    }
    // feed at the focus, and four struts from 5 cm inside the rim (3 cm in front of the
    // dish) into the feed's back
    let focus = DVec3::new(DISH_X - FOCAL, 0.0, 0.0);
    push_tube(
        &mut mesh,
        focus + DVec3::new(0.1, 0.0, 0.0),
        focus - DVec3::new(0.1, 0.0, 0.0),
        0.09,
        sides,
        3,
    );
    for k in 0..4 {
        let phi = TAU * (k as f64 + 0.5) / 4.0;
        let foot = dish_point(RIM - 0.05, phi) - DVec3::new(0.03, 0.0, 0.0);
        let head = focus + DVec3::new(0.09, 0.06 * phi.cos(), 0.06 * phi.sin());
        push_tube(&mut mesh, foot, head, 0.015, sides, 3);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn three_levels_with_closed_bus_and_struts() {
        assert_levels(&BUILTIN);
        for d in Detail::ALL {
            let mesh = build(d);
            assert_closed_outward(&part(&mesh, &[0]), "bus");
            assert_closed_outward(&part(&mesh, &[3]), "struts");
        }
    }

    #[test]
    fn the_wings_are_canted_and_the_dish_faces_minus_x() {
        let mesh = build(Detail::Coarse);
        for (i, &m) in mesh.material_ids.iter().enumerate() {
            let n = mesh.area_vector(i).normalize();
            if m == 1 {
                // not parallel to any bus face
                assert!(n.abs().max_element() < 0.9, "{n}");
                assert!((n.abs().x - 30f64.to_radians().cos()).abs() < 1e-9, "{n}");
            }
            if m == 2 {
                assert!(n.x < 0.0, "{n}");
            }
        }
    }
}
