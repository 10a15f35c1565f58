//! The box-wing satellite: a cube bus, two solar panels on booms and a parabolic dish.

use super::parts::{push_box, push_quad, subdivide};
use crate::geometry::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::TAU;

/// The box-wing satellite: the usual test object of this field.
pub fn box_wing() -> Mesh {
    box_wing_with(5, 24, 0)
}

/// The box-wing with its dish tessellated into `rings` × `sectors` (curved: one face per
/// triangle) and its flat parts subdivided `flat_levels` times (they still merge into the
/// same faces). Benchmarks use this for the ~15k-triangle object of the performance targets.
pub fn box_wing_with(rings: u32, sectors: u32, flat_levels: u32) -> Mesh {
    let mut mesh = Mesh::default();
    // bus: 2 m cube
    push_box(&mut mesh, DVec3::splat(-1.0), DVec3::splat(1.0), 0);
    // booms: 0.1 m square, from the bus to the panels
    for s in [-1.0, 1.0] {
        let (y0, y1) = if s > 0.0 { (1.0, 1.5) } else { (-1.5, -1.0) };
        push_box(
            &mut mesh,
            DVec3::new(-0.05, y0, -0.05),
            DVec3::new(0.05, y1, 0.05),
            0,
        );
    }
    // panels: 5 m x 2 m in the x = 0 plane, normal +x (two-sided material)
    for s in [-1.0, 1.0] {
        let (y0, y1) = if s > 0.0 { (1.5, 6.5) } else { (-6.5, -1.5) };
        push_quad(
            &mut mesh,
            [
                DVec3::new(0.0, y0, -1.0),
                DVec3::new(0.0, y1, -1.0),
                DVec3::new(0.0, y1, 1.0),
                DVec3::new(0.0, y0, 1.0),
            ],
            1,
        );
    }
    // dish: paraboloid z = z0 + r²/(4f), rim radius 0.8 m, opening +z, on a mast
    push_box(
        &mut mesh,
        DVec3::new(-0.05, -0.05, 1.0),
        DVec3::new(0.05, 0.05, 1.2),
        0,
    );
    let mut mesh = subdivide(&mesh, flat_levels);
    let (z0, f, rim) = (1.2, 0.8, 0.8);
    let base = mesh.vertices.len() as u32;
    mesh.vertices.push(DVec3::new(0.0, 0.0, z0));
    for i in 1..=rings {
        let r = rim * i as f64 / rings as f64;
        for j in 0..sectors {
            let phi = TAU * j as f64 / sectors as f64;
            mesh.vertices.push(DVec3::new(
                r * phi.cos(),
                r * phi.sin(),
                z0 + r * r / (4.0 * f),
            ));
        }
    }
    let ring = |i: u32, j: u32| base + 1 + (i - 1) * sectors + (j % sectors);
    for j in 0..sectors {
        // concave side faces +z: counter-clockwise seen from above
        mesh.triangles.push([base, ring(1, j), ring(1, j + 1)]);
        mesh.material_ids.push(2);
    }
    for i in 1..rings {
        for j in 0..sectors {
            mesh.triangles
                .push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
            mesh.triangles
                .push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
            mesh.material_ids.extend([2, 2]);
        }
    }
    mesh
}
