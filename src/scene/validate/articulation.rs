//! `geometry.articulation` (or `articulation` with explicit epochs): each hinge's parts
//! found by name, its axis, pivot and law checked, nested hinges found, and the mesh's
//! vertices split where a hinge's triangles share them with what it hangs from.

use super::values::{err, in_range, vector};
use super::ValidationError;
use crate::geometry::articulation::{Articulation, Joint, JointLaw, BODY};
use crate::geometry::obj::Grouped;
use crate::geometry::Mesh;
use crate::orbit::time::parse_utc;
use crate::scene::request::{ArticulationSpec, Request, TimeSpec};
use crate::scene::{Epoch, Material};
use glam::DVec3;

/// Most hinges a request may have.
pub const MAX_JOINTS: usize = 16;

/// The request's articulation, if any: `groups` is the validated mesh with its named
/// groups (its vertices are split here), `epochs` the checked epochs (an `angles` law
/// must cover them), `origin` the Unix seconds a `geometry`'s series times count from
/// (0 with explicit epochs).
pub(super) fn articulation(
    req: &Request,
    groups: &mut Grouped,
    materials: &[Material],
    epochs: &[Epoch],
    origin: f64,
) -> Result<Option<Articulation>, ValidationError> {
    let (specs, prefix) = match (&req.geometry, &req.articulation) {
        (Some(_), Some(_)) => {
            return err(
                "articulation",
                "a `geometry` request gives it as `geometry.articulation`",
            )
        }
        (Some(g), None) => (g.articulation.as_deref(), "geometry.articulation"),
        (None, a) => (a.as_deref(), "articulation"),
    };
    let Some(specs) = specs.filter(|s| !s.is_empty()) else {
        return Ok(None);
    };
    if specs.len() > MAX_JOINTS {
        return err(prefix, format!("at most {MAX_JOINTS} hinges"));
    }
    let mut sets: Vec<Vec<bool>> = Vec::with_capacity(specs.len());
    let mut joints = Vec::with_capacity(specs.len());
    for (i, spec) in specs.iter().enumerate() {
        let f = format!("{prefix}[{i}]");
        let set = part_set(&f, spec, groups, materials)?;
        let parent = parent(&f, &set, &sets)?;
        let axis = vector(&format!("{f}.axis"), spec.axis)?.normalize();
        let pivot = match spec.pivot {
            None => DVec3::ZERO,
            Some(p) => {
                let v = DVec3::from_array(p);
                if !v.is_finite() || v.abs().max_element() > 1e12 {
                    return err(
                        format!("{f}.pivot"),
                        "must have three finite components (m)",
                    );
                }
                v
            }
        };
        let law = law(&f, spec, &groups.mesh, &set, axis, epochs, origin)?;
        sets.push(set);
        joints.push(Joint {
            axis,
            pivot,
            parent,
            law,
        });
    }
    let (link, on_hinge) = split_vertices(&mut groups.mesh, &sets, &joints);
    Ok(Some(Articulation {
        joints,
        link,
        on_hinge,
    }))
}

/// The triangles of a hinge's `parts`: each name an explicit group, or else a material;
/// at least one triangle.
fn part_set(
    f: &str,
    spec: &ArticulationSpec,
    g: &Grouped,
    materials: &[Material],
) -> Result<Vec<bool>, ValidationError> {
    if spec.parts.is_empty() {
        return err(format!("{f}.parts"), "must name at least one part");
    }
    let mut set = vec![false; g.mesh.triangles.len()];
    for (k, name) in spec.parts.iter().enumerate() {
        if let Some(gi) = g.names.iter().position(|n| n == name) {
            for (s, &of) in set.iter_mut().zip(&g.group_of) {
                *s |= of == gi as u32;
            }
        } else if let Some(mi) = materials.iter().position(|m| m.name == *name) {
            for (s, &m) in set.iter_mut().zip(&g.mesh.material_ids) {
                *s |= m == mi as u32;
            }
        } else {
            let mut known: Vec<&str> = g.names.iter().map(String::as_str).collect();
            known.extend(materials.iter().map(|m| m.name.as_str()));
            return err(
                format!("{f}.parts[{k}]"),
                format!(
                    "unknown part `{name}`: not a group of the mesh nor a material (known: {})",
                    known.join(", ")
                ),
            );
        }
    }
    if !set.iter().any(|&s| s) {
        return err(
            format!("{f}.parts"),
            "no triangle of the mesh is in these parts",
        );
    }
    Ok(set)
}

/// The hinge a new one (its triangles `set`) is nested in: the last earlier one it shares
/// triangles with, which must hold all of them.
fn parent(f: &str, set: &[bool], earlier: &[Vec<bool>]) -> Result<Option<usize>, ValidationError> {
    for (i, e) in earlier.iter().enumerate().rev() {
        let overlap = set.iter().zip(e).any(|(&a, &b)| a && b);
        if !overlap {
            continue;
        }
        if set.iter().zip(e).any(|(&a, &b)| a && !b) {
            return err(
                format!("{f}.parts"),
                format!(
                    "shares triangles with hinge [{i}] but does not lie within its parts: \
                     a nested hinge's parts must be a subset of its parent's"
                ),
            );
        }
        return Ok(Some(i));
    }
    Ok(None)
}

/// Rejects a parameter the law does not take, naming it.
fn only(f: &str, spec: &ArticulationSpec, allowed: &[&str]) -> Result<(), ValidationError> {
    let given = [
        ("normal", spec.normal.is_some()),
        ("angle_deg", spec.angle_deg.is_some()),
        ("series", spec.series.is_some()),
    ];
    for (name, present) in given {
        if present && !allowed.contains(&name) {
            return err(
                format!("{f}.{name}"),
                format!("is not a parameter of law `{}`", spec.law),
            );
        }
    }
    Ok(())
}

fn law(
    f: &str,
    spec: &ArticulationSpec,
    mesh: &Mesh,
    set: &[bool],
    axis: DVec3,
    epochs: &[Epoch],
    origin: f64,
) -> Result<JointLaw, ValidationError> {
    match spec.law.as_str() {
        "sun-tracking" => {
            only(f, spec, &["normal"])?;
            let normal = match spec.normal {
                Some(n) => vector(&format!("{f}.normal"), n)?.normalize(),
                None => {
                    let sum: DVec3 = (0..mesh.triangles.len())
                        .filter(|&t| set[t])
                        .map(|t| mesh.area_vector(t))
                        .sum();
                    let total: f64 = (0..mesh.triangles.len())
                        .filter(|&t| set[t])
                        .map(|t| mesh.area_vector(t).length())
                        .sum();
                    if sum.length() <= 1e-9 * total {
                        return err(
                            format!("{f}.normal"),
                            "is required: the part's triangles face every way (a closed \
                             surface has no one normal)",
                        );
                    }
                    sum.normalize()
                }
            };
            if (normal - axis * axis.dot(normal)).length() < 1e-6 {
                return err(
                    format!("{f}.normal"),
                    "lies along the axis: turning about the axis cannot point it anywhere",
                );
            }
            Ok(JointLaw::SunTracking { normal })
        }
        "fixed" => {
            only(f, spec, &["angle_deg"])?;
            let Some(a) = spec.angle_deg else {
                return err(format!("{f}.angle_deg"), "is required by law `fixed`");
            };
            let a = in_range(&format!("{f}.angle_deg"), a, -360.0, 360.0)?;
            Ok(JointLaw::Fixed {
                angle: a.to_radians(),
            })
        }
        "angles" => {
            only(f, spec, &["series"])?;
            series(f, spec, epochs, origin)
        }
        other => err(
            format!("{f}.law"),
            format!("unknown law `{other}`; expected sun-tracking, fixed or angles"),
        ),
    }
}

/// Law `angles`: samples at increasing times that cover every epoch.
fn series(
    f: &str,
    spec: &ArticulationSpec,
    epochs: &[Epoch],
    origin: f64,
) -> Result<JointLaw, ValidationError> {
    let Some(samples) = spec.series.as_ref().filter(|s| !s.is_empty()) else {
        return err(
            format!("{f}.series"),
            "is required by law `angles` (one sample at least)",
        );
    };
    let mut series: Vec<(f64, f64)> = Vec::with_capacity(samples.len());
    for (i, s) in samples.iter().enumerate() {
        let tf = format!("{f}.series[{i}].t");
        let t = match &s.t {
            TimeSpec::Seconds(x) => origin + in_range(&tf, *x, -1e10, 1e10)?,
            TimeSpec::Iso(text) => parse_utc(text)
                .map_err(|m| ValidationError::new(&tf, m))?
                .unix(),
        };
        if let Some(&(prev, _)) = series.last() {
            if t <= prev {
                return err(tf, "times must increase from sample to sample");
            }
        }
        let a = in_range(
            &format!("{f}.series[{i}].angle_deg"),
            s.angle_deg,
            -1e6,
            1e6,
        )?;
        series.push((t, a.to_radians()));
    }
    let (first, last) = (series[0].0, series[series.len() - 1].0);
    if let Some(e) = epochs.iter().find(|e| e.t < first || e.t > last) {
        return err(
            format!("{f}.series"),
            format!(
                "covers t = {} to {} s but an epoch is at {} s (seconds {}): the series must \
                 cover every epoch (no extrapolation)",
                first - origin,
                last - origin,
                e.t - origin,
                if origin == 0.0 {
                    "as the epochs give them"
                } else {
                    "after times.start"
                }
            ),
        );
    }
    Ok(JointLaw::Series { series })
}

/// Gives every triangle the deepest hinge holding it, splits each vertex its triangles
/// share between links (one copy per link, appended), and returns each vertex's link and
/// whether it lies on its own hinge line (1e-12 of the mesh's size).
fn split_vertices(mesh: &mut Mesh, sets: &[Vec<bool>], joints: &[Joint]) -> (Vec<u32>, Vec<bool>) {
    let tri_link: Vec<u32> = (0..mesh.triangles.len())
        .map(|t| {
            (0..sets.len())
                .rev()
                .find(|&j| sets[j][t])
                .map_or(BODY, |j| j as u32)
        })
        .collect();
    let n = mesh.vertices.len();
    let mut link = vec![None::<u32>; n];
    // (original vertex, link) → its copy
    let mut copies: std::collections::HashMap<(u32, u32), u32> = Default::default();
    for (t, tri) in mesh.triangles.iter_mut().enumerate() {
        let l = tri_link[t];
        for v in tri.iter_mut() {
            match link[*v as usize] {
                None => link[*v as usize] = Some(l),
                Some(own) if own == l => {}
                Some(_) => {
                    let key = (*v, l);
                    let copy = *copies.entry(key).or_insert_with(|| {
                        mesh.vertices.push(mesh.vertices[*v as usize]);
                        link.push(Some(l));
                        (mesh.vertices.len() - 1) as u32
                    });
                    *v = copy;
                }
            }
        }
    }
    let link: Vec<u32> = link.into_iter().map(|l| l.unwrap_or(BODY)).collect();
    let (_, scale) = mesh.bounding_sphere();
    let on_hinge = mesh
        .vertices
        .iter()
        .zip(&link)
        .map(|(&v, &l)| {
            if l == BODY {
                return false;
            }
            let j = &joints[l as usize];
            let d = v - j.pivot;
            (d - j.axis * j.axis.dot(d)).length() <= 1e-12 * scale
        })
        .collect();
    (link, on_hinge)
}

/// The radius (m) about `centre` that holds every vertex in every pose: a vertex of a link
/// stays |v − pivot| from its hinge's pivot, which its parent moves in turn.
pub(super) fn swept_radius(mesh: &Mesh, a: &Articulation, centre: DVec3) -> f64 {
    // how far from `centre` each joint's pivot can be
    let mut reach: Vec<f64> = Vec::with_capacity(a.joints.len());
    for j in &a.joints {
        let r = match j.parent {
            None => (j.pivot - centre).length(),
            Some(p) => reach[p] + (j.pivot - a.joints[p].pivot).length(),
        };
        reach.push(r);
    }
    mesh.vertices
        .iter()
        .zip(&a.link)
        .map(|(&v, &l)| {
            if l == BODY {
                (v - centre).length()
            } else {
                reach[l as usize] + (v - a.joints[l as usize].pivot).length()
            }
        })
        .fold(0.0, f64::max)
}

/// Every observer outside the sphere the articulated mesh sweeps (Eq. 12 is a far-field
/// sum, as for a rigid mesh); the error names the epoch as `epochs` does.
pub(super) fn observers_outside(
    mesh: &Mesh,
    a: &Articulation,
    epochs: &[Epoch],
    geometry: bool,
) -> Result<(), ValidationError> {
    let (centre, _) = mesh.bounding_sphere();
    let radius = swept_radius(mesh, a, centre);
    for (i, e) in epochs.iter().enumerate() {
        let range = (e.observer - centre).length();
        if range <= radius {
            let name = if geometry {
                format!("geometry (epoch {i})")
            } else {
                format!("epochs[{i}]")
            };
            return err(
                format!("{name}.observer"),
                format!(
                    "the observer is {range:.3e} m from the object's centre, within the \
                     {radius:.3e} m its articulated parts can sweep: give it from outside"
                ),
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, refused};
    use serde_json::json;

    fn hinge(v: &mut serde_json::Value, h: serde_json::Value) {
        v["object"]["mesh"]["parts"] = json!([{ "name": "flap", "triangles": [1] }]);
        v["articulation"] = json!([h]);
    }

    /// Each bad input is refused naming its field (the service answers 422 with it).
    #[test]
    fn bad_hinges_are_named() {
        let base = json!({ "parts": ["flap"], "law": "fixed", "angle_deg": 10, "axis": [1, 0, 0] });
        let with = |k: &str, x: serde_json::Value| {
            let mut h = base.clone();
            h[k] = x;
            h
        };
        let cases = [
            (
                with("parts", json!(["flap", "wing"])),
                "articulation[0].parts[1]",
            ),
            (with("axis", json!([0, 0, 0])), "articulation[0].axis"),
            (
                with("pivot", json!([0, 1e300, 1e300])),
                "articulation[0].pivot",
            ),
            (with("law", json!("wobble")), "articulation[0].law"),
            (with("normal", json!([0, 0, 1])), "articulation[0].normal"),
            (with("angle_deg", json!(400)), "articulation[0].angle_deg"),
        ];
        for (h, field) in cases {
            let e = refused(|v| hinge(v, h.clone()));
            assert_eq!(e.field, field, "{e}");
        }
        let series = json!({ "parts": ["flap"], "law": "angles", "axis": [1, 0, 0],
            "series": [{ "t": -1, "angle_deg": 0 }, { "t": -1, "angle_deg": 5 }] });
        let e = refused(|v| hinge(v, series));
        assert_eq!(e.field, "articulation[0].series[1].t");
        let short = json!({ "parts": ["flap"], "law": "angles", "axis": [1, 0, 0],
            "series": [{ "t": 1, "angle_deg": 0 }, { "t": 2, "angle_deg": 5 }] });
        let e = refused(|v| hinge(v, short));
        assert_eq!(e.field, "articulation[0].series");
        // a normal along the axis cannot track
        let along = json!({ "parts": ["flap"], "law": "sun-tracking", "axis": [0, 0, 1] });
        let e = refused(|v| hinge(v, along));
        assert_eq!(e.field, "articulation[0].normal");
        let e =
            refused(|v| v["object"]["mesh"]["parts"] = json!([{ "name": "a", "triangles": [2] }]));
        assert_eq!(e.field, "object.mesh.parts[0].triangles[0]");
    }

    /// A flap hinged on the plate's diagonal is split from it: its own copies of the two
    /// shared vertices, both on the hinge line.
    #[test]
    fn a_hinged_triangle_gets_its_own_vertices() {
        let scene = check(|v| {
            hinge(
                v,
                json!({ "parts": ["flap"], "law": "fixed", "angle_deg": 10, "axis": [1, 1, 0] }),
            )
        })
        .expect("valid");
        let a = scene.articulation.expect("articulated");
        assert_eq!(scene.mesh.vertices.len(), 6);
        assert_eq!(a.link.iter().filter(|&&l| l == 0).count(), 3);
        assert_eq!(a.on_hinge.iter().filter(|&&h| h).count(), 2);
    }
}
