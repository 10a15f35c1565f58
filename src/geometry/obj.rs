//! Wavefront OBJ text → mesh, with materials matched by `usemtl` name.

use super::mesh::{written_rounding, Mesh};
use glam::DVec3;

/// Parses OBJ text (metres). Triangles take the index (in `material_names`) of their
/// `usemtl` name; faces before any `usemtl` take material 0. Polygons are
/// fan-triangulated; normals and texture coordinates are ignored (winding gives the normal).
pub fn parse(text: &str, material_names: &[&str]) -> Result<Mesh, String> {
    parse_grouped(text, material_names).map(|g| g.mesh)
}

/// A mesh with its triangles' named groups (`g` or `o` lines).
#[derive(Debug, Clone, Default)]
pub struct Grouped {
    pub mesh: Mesh,
    /// The group names, in order of first appearance.
    pub names: Vec<String>,
    /// Per triangle, the index of its group in `names`, or `u32::MAX` for none.
    pub group_of: Vec<u32>,
}

/// [`parse`], keeping each triangle's group (`g` or `o`; faces before any are in none).
pub fn parse_grouped(text: &str, material_names: &[&str]) -> Result<Grouped, String> {
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let first = words.next();
        // tobj reads `nan` and `inf` as numbers: a vertex must be a point
        if first == Some("v") {
            if let Some(w) = words
                .clone()
                .take(3)
                .find(|w| w.parse::<f64>().is_ok_and(|x| !x.is_finite()))
            {
                return Err(format!(
                    "line {}: vertex coordinate `{w}` is not a finite number",
                    number + 1
                ));
            }
        }
        if first == Some("usemtl") {
            let name = words.next().unwrap_or("");
            if !material_names.contains(&name) {
                return Err(format!(
                    "OBJ uses material `{name}`, which is not among object.materials ({})",
                    material_names.join(", ")
                ));
            }
        }
    }
    // tobj resolves `usemtl` only through a material library, so hand it one made of
    // our material names; any `mtllib` in the text is ignored in its favour.
    let mtl: String = material_names
        .iter()
        .map(|n| format!("newmtl {n}\n"))
        .collect();
    let body: String = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("mtllib"))
        .collect::<Vec<_>>()
        .join("\n");
    let full = format!("mtllib glint-materials\n{body}\n");
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut full.as_bytes(), &options, |_| {
        tobj::load_mtl_buf(&mut mtl.as_bytes())
    })
    .map_err(|e| format!("cannot parse OBJ text: {e}"))?;
    let mut mesh = Mesh::default();
    let (mut names, mut group_of) = (Vec::<String>::new(), Vec::new());
    for model in &models {
        let m = &model.mesh;
        // tobj names a model before any `g`/`o` line "unnamed_object"
        let group = if model.name == "unnamed_object" {
            u32::MAX
        } else {
            match names.iter().position(|n| *n == model.name) {
                Some(i) => i as u32,
                None => {
                    names.push(model.name.clone());
                    (names.len() - 1) as u32
                }
            }
        };
        let base = mesh.vertices.len() as u32;
        for p in m.positions.chunks_exact(3) {
            mesh.vertices.push(DVec3::new(p[0], p[1], p[2]));
        }
        let material = m.material_id.unwrap_or(0) as u32;
        for t in m.indices.chunks_exact(3) {
            mesh.triangles.push([base + t[0], base + t[1], base + t[2]]);
            mesh.material_ids.push(material);
            group_of.push(group);
        }
    }
    if mesh.triangles.is_empty() {
        return Err("OBJ text has no faces".into());
    }
    // most exporters write 6 decimals: coplanar triangles then merge within that
    mesh.rounding = written_rounding(&mesh.vertices);
    Ok(Grouped {
        mesh,
        names,
        group_of,
    })
}
