//! `object.mesh`: one of three forms (inline `vertices` + `triangles`, `obj`, `builtin`)
//! made into a [`Mesh`], then checked as a whole — its size, its indices, its coordinates,
//! no triangle twice — and its degenerate triangles dropped.
//!
//! The steps run in that order and each stops at the first bad field, so a request with
//! several faults is told the first one in this order.

use super::values::err;
use super::{Limits, ValidationError};
use crate::geometry::mesh::written_rounding;
use crate::geometry::obj::Grouped;
use crate::geometry::{builtin, obj, Mesh};
use crate::scene::request::{MeshSpec, PartSpec};
use crate::scene::Material;
use glam::DVec3;
use rayon::prelude::*;

/// Largest mesh coordinate accepted, m.
const MAX_COORDINATE_M: f64 = 1e12;

/// The request's mesh, built from its one form and checked, with its triangles' named
/// groups (OBJ `g`/`o`, inline `parts`; none for built-in objects); `materials` are the
/// request's checked materials (the mesh's material ids index them).
pub(super) fn mesh(
    spec: &MeshSpec,
    materials: &[Material],
    limits: &Limits,
) -> Result<Grouped, ValidationError> {
    let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
    one_form(spec)?;
    let mut g = if let Some(name) = &spec.builtin {
        let mesh = builtin_mesh(name, spec, &names)?;
        Grouped {
            group_of: vec![u32::MAX; mesh.triangles.len()],
            mesh,
            names: Vec::new(),
        }
    } else if let Some(text) = &spec.obj {
        obj::parse_grouped(text, &names).map_err(|m| ValidationError::new("object.mesh.obj", m))?
    } else {
        let mesh = inline_mesh(spec, materials.len())?;
        let (names, group_of) = parts(spec.parts.as_deref().unwrap_or(&[]), mesh.triangles.len())?;
        Grouped {
            mesh,
            names,
            group_of,
        }
    };
    triangles_and_indices(&g.mesh, limits)?;
    coordinates(&g.mesh)?;
    no_triangle_twice(&g.mesh)?;
    drop_degenerate(&mut g)?;
    Ok(g)
}

/// An inline mesh's `parts`: names given once, not empty; triangle indices in range, each
/// triangle in one part at most. Returns the names and each triangle's part.
fn parts(parts: &[PartSpec], n: usize) -> Result<(Vec<String>, Vec<u32>), ValidationError> {
    let mut group_of = vec![u32::MAX; n];
    let mut names = Vec::with_capacity(parts.len());
    for (i, p) in parts.iter().enumerate() {
        let f = format!("object.mesh.parts[{i}]");
        if p.name.is_empty() || names.contains(&p.name) {
            return err(format!("{f}.name"), "must be a name given once");
        }
        if p.triangles.is_empty() {
            return err(format!("{f}.triangles"), "must list at least one triangle");
        }
        for (k, &t) in p.triangles.iter().enumerate() {
            let tf = format!("{f}.triangles[{k}]");
            match group_of.get(t as usize) {
                None => return err(tf, format!("triangle {t} out of range (there are {n})")),
                Some(&g) if g != u32::MAX => {
                    return err(
                        tf,
                        format!("triangle {t} is already in part `{}`", names[g as usize]),
                    )
                }
                Some(_) => group_of[t as usize] = i as u32,
            }
        }
        names.push(p.name.clone());
    }
    Ok((names, group_of))
}

/// Exactly one of the three forms, and no option that belongs to another form.
fn one_form(spec: &MeshSpec) -> Result<(), ValidationError> {
    let forms = [
        spec.vertices.is_some() || spec.triangles.is_some(),
        spec.obj.is_some(),
        spec.builtin.is_some(),
    ];
    if forms.iter().filter(|&&b| b).count() != 1 {
        return err(
            "object.mesh",
            "give exactly one of `vertices` + `triangles`, `obj` or `builtin`",
        );
    }
    if spec.material_ids.is_some() && spec.triangles.is_none() {
        return err(
            "object.mesh.material_ids",
            "goes only with inline `triangles` (OBJ and built-in meshes use material names)",
        );
    }
    if spec.parts.is_some() && spec.triangles.is_none() {
        return err(
            "object.mesh.parts",
            "goes only with inline `triangles` (OBJ text names its groups with `g` or `o`)",
        );
    }
    if spec.detail.is_some() && spec.builtin.is_none() {
        return err(
            "object.mesh.detail",
            "goes only with `builtin` (OBJ and inline meshes come as they are)",
        );
    }
    Ok(())
}

/// The built-in object `name` at the request's `detail`, its material names mapped onto
/// the request's materials (`names`, in order).
fn builtin_mesh(name: &str, spec: &MeshSpec, names: &[&str]) -> Result<Mesh, ValidationError> {
    let b = builtin::find(name).ok_or_else(|| {
        let known: Vec<_> = builtin::BUILTINS.iter().map(|b| b.name).collect();
        ValidationError::new(
            "object.mesh.builtin",
            format!("unknown object `{name}`; built-in: {}", known.join(", ")),
        )
    })?;
    let detail = match &spec.detail {
        None => b.default_detail,
        Some(d) => builtin::Detail::parse(d).ok_or_else(|| {
            ValidationError::new(
                "object.mesh.detail",
                format!("unknown detail `{d}`; expected coarse, medium or fine"),
            )
        })?,
    };
    let mut mesh = (b.build)(detail);
    // map the object's material names onto the request's materials
    let mut map = Vec::new();
    for n in b.material_names {
        match names.iter().position(|m| m == n) {
            Some(i) => map.push(i as u32),
            None if mesh
                .material_ids
                .iter()
                .all(|&id| b.material_names[id as usize] != *n) =>
            {
                map.push(0)
            }
            None => {
                return err(
                    "object.materials",
                    format!(
                        "built-in object `{name}` needs a material named `{n}` (it uses: {})",
                        b.material_names.join(", ")
                    ),
                )
            }
        }
    }
    for id in &mut mesh.material_ids {
        *id = map[*id as usize];
    }
    Ok(mesh)
}

/// The inline form: `vertices` (m) and `triangles`, with `material_ids` (one per
/// triangle, each below `n_materials`) or material 0 for all.
fn inline_mesh(spec: &MeshSpec, n_materials: usize) -> Result<Mesh, ValidationError> {
    let vertices = spec.vertices.as_ref().ok_or_else(|| {
        ValidationError::new("object.mesh.vertices", "is required with `triangles`")
    })?;
    let triangles = spec.triangles.as_ref().ok_or_else(|| {
        ValidationError::new("object.mesh.triangles", "is required with `vertices`")
    })?;
    let mut mesh = Mesh {
        vertices: Vec::with_capacity(vertices.len()),
        triangles: triangles.clone(),
        material_ids: Vec::new(),
        rounding: 0.0,
    };
    for (i, v) in vertices.iter().enumerate() {
        let p = DVec3::from_array(*v);
        if !p.is_finite() {
            return err(
                format!("object.mesh.vertices[{i}]"),
                "must have three finite components",
            );
        }
        mesh.vertices.push(p);
    }
    mesh.material_ids = match &spec.material_ids {
        None => vec![0; triangles.len()],
        Some(ids) => {
            if ids.len() != triangles.len() {
                return err(
                    "object.mesh.material_ids",
                    format!(
                        "has {} entries but there are {} triangles",
                        ids.len(),
                        triangles.len()
                    ),
                );
            }
            for (i, &id) in ids.iter().enumerate() {
                if id as usize >= n_materials {
                    return err(
                        format!("object.mesh.material_ids[{i}]"),
                        format!(
                            "material index {id} out of range (there are {n_materials} materials)"
                        ),
                    );
                }
            }
            ids.clone()
        }
    };
    mesh.rounding = written_rounding(&mesh.vertices);
    Ok(mesh)
}

/// Some triangles, not more than the limit, each corner a vertex of the mesh.
fn triangles_and_indices(mesh: &Mesh, limits: &Limits) -> Result<(), ValidationError> {
    if mesh.triangles.is_empty() {
        return err("object.mesh.triangles", "the mesh has no triangles");
    }
    if mesh.triangles.len() > limits.max_triangles {
        return err(
            "object.mesh",
            format!(
                "too many triangles: {} (limit {})",
                mesh.triangles.len(),
                limits.max_triangles
            ),
        );
    }
    let nv = mesh.vertices.len();
    for (i, t) in mesh.triangles.iter().enumerate() {
        if let Some(&bad) = t.iter().find(|&&k| k as usize >= nv) {
            return err(
                format!("object.mesh.triangles[{i}]"),
                format!("vertex index {bad} out of range (there are {nv} vertices)"),
            );
        }
    }
    Ok(())
}

/// Every coordinate finite and within [`MAX_COORDINATE_M`].
fn coordinates(mesh: &Mesh) -> Result<(), ValidationError> {
    // Metres: beyond 1e12 m (7 AU) the squares of the triangles' areas overflow f64 and
    // every triangle would look degenerate; no object in orbit comes near it.
    if let Some(i) = mesh
        .vertices
        .iter()
        .position(|v| !v.is_finite() || v.abs().max_element() > MAX_COORDINATE_M)
    {
        return err(
            format!("object.mesh.vertices[{i}]"),
            format!(
                "a coordinate that is not a finite number or lies beyond \
                 {MAX_COORDINATE_M:e} m: give the mesh in metres"
            ),
        );
    }
    Ok(())
}

/// No triangle given twice (same corners after welding, same winding).
fn no_triangle_twice(mesh: &Mesh) -> Result<(), ValidationError> {
    // The same triangle twice (same corners, same winding) would count its light twice;
    // two triangles back to back (opposite windings) are a thin plate, and are kept.
    let welded = mesh.welded_ids();
    let mut keyed: Vec<([u32; 3], usize)> = mesh
        .triangles
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let w = t.map(|k| welded[k as usize]);
            // rotated to start at its least corner: the winding kept
            let r = (0..3).min_by_key(|&k| w[k]).unwrap_or(0);
            ([w[r], w[(r + 1) % 3], w[(r + 2) % 3]], i)
        })
        .collect();
    // keys unique (the index is one): in parallel, the order of any sort
    keyed.par_sort_unstable();
    if let Some(pair) = keyed.windows(2).find(|p| p[0].0 == p[1].0) {
        let (a, b) = (pair[0].1.min(pair[1].1), pair[0].1.max(pair[1].1));
        return err(
            format!("object.mesh.triangles[{b}]"),
            format!(
                "has the same corners, wound the same way, as triangles[{a}]: its light \
                 would be counted twice"
            ),
        );
    }
    Ok(())
}

/// Drops the triangles of (almost) no area, with their material ids and groups; a mesh of
/// nothing else is an error.
fn drop_degenerate(g: &mut Grouped) -> Result<(), ValidationError> {
    let mesh = &mut g.mesh;
    // Degenerate triangles carry no area and no normal: drop them rather than fail, as
    // exporters often leave a few.
    let (_, scale) = mesh.bounding_sphere();
    let min_area2 = (1e-12 * scale * scale).powi(2);
    let keep: Vec<bool> = (0..mesh.triangles.len())
        .map(|i| mesh.area_vector(i).length_squared() > min_area2)
        .collect();
    if !keep.iter().any(|&k| k) {
        return err("object.mesh.triangles", "every triangle has zero area");
    }
    if keep.iter().any(|&k| !k) {
        let mut i = 0;
        mesh.triangles.retain(|_| {
            i += 1;
            keep[i - 1]
        });
        let mut j = 0;
        mesh.material_ids.retain(|_| {
            j += 1;
            keep[j - 1]
        });
        let mut k = 0;
        g.group_of.retain(|_| {
            k += 1;
            keep[k - 1]
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, refused};
    use crate::scene::validate::ValidationError;
    use serde_json::json;

    #[test]
    fn a_mesh_has_exactly_one_form() {
        let e = refused(|v| v["object"]["mesh"]["builtin"] = json!("plate"));
        assert_eq!(e.field, "object.mesh");
        assert!(e.message.starts_with("give exactly one of"), "{e}");
        let e = refused(|v| v["object"]["mesh"]["detail"] = json!("fine"));
        assert_eq!(e.field, "object.mesh.detail");
    }

    #[test]
    fn each_index_is_checked_and_named() {
        let e = refused(|v| v["object"]["mesh"]["triangles"][1] = json!([0, 2, 9]));
        assert_eq!(
            e,
            ValidationError::new(
                "object.mesh.triangles[1]",
                "vertex index 9 out of range (there are 4 vertices)"
            )
        );
        let e = refused(|v| v["object"]["mesh"]["material_ids"] = json!([0, 1]));
        assert_eq!(
            e,
            ValidationError::new(
                "object.mesh.material_ids[1]",
                "material index 1 out of range (there are 1 materials)"
            )
        );
    }

    #[test]
    fn a_coordinate_beyond_the_limit_is_refused() {
        let e = refused(|v| {
            v["object"]["mesh"]["vertices"]
                .as_array_mut()
                .unwrap()
                .push(json!([0.0, 0.0, 2e12]))
        });
        assert_eq!(e.field, "object.mesh.vertices[4]");
    }

    #[test]
    fn the_same_triangle_twice_is_refused_but_back_to_back_is_kept() {
        // [1, 2, 0] is [0, 1, 2] with its corners rotated: the same winding
        let e = refused(|v| {
            v["object"]["mesh"]["triangles"] = json!([[0, 1, 2], [0, 2, 3], [1, 2, 0]])
        });
        assert_eq!(e.field, "object.mesh.triangles[2]");
        assert!(e.message.contains("as triangles[0]"), "{e}");
        let scene =
            check(|v| v["object"]["mesh"]["triangles"] = json!([[0, 1, 2], [0, 2, 3], [0, 2, 1]]))
                .expect("a thin plate is valid");
        assert_eq!(scene.mesh.triangles.len(), 3);
    }

    #[test]
    fn degenerate_triangles_are_dropped_with_their_material_ids() {
        let scene =
            check(|v| v["object"]["mesh"]["triangles"] = json!([[0, 1, 2], [0, 1, 1], [0, 2, 3]]))
                .expect("valid");
        assert_eq!(scene.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(scene.mesh.material_ids.len(), 2);
        let e = refused(|v| v["object"]["mesh"]["triangles"] = json!([[0, 1, 1]]));
        assert_eq!(
            e,
            ValidationError::new("object.mesh.triangles", "every triangle has zero area")
        );
    }
}
