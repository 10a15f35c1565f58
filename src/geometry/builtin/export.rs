//! A mesh written as OBJ text: how `scenes/objects/*.obj` are made from the built-in
//! objects.

use crate::geometry::mesh::Mesh;

/// Writes a mesh as OBJ text with `usemtl` groups named by `material_names`.
pub fn to_obj(mesh: &Mesh, material_names: &[&str], comment: &str) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for line in comment.lines() {
        let _ = writeln!(s, "# {line}");
    }
    for v in &mesh.vertices {
        let _ = writeln!(s, "v {} {} {}", v.x, v.y, v.z);
    }
    let mut current = u32::MAX;
    for (tri, &m) in mesh.triangles.iter().zip(&mesh.material_ids) {
        if m != current {
            let _ = writeln!(s, "usemtl {}", material_names[m as usize]);
            current = m;
        }
        let _ = writeln!(s, "f {} {} {}", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    }
    s
}
