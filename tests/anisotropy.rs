//! The tangent of an anisotropic material is the body's, not the mesh's vertex order
//! (issue: the Ashikhmin–Shirley tangent followed each face's first edge).
use glint::scene::{Limits, Request, Scene};

/// A 2 m × 2 m plate facing +z as two triangles, with `tri` as its triangle list, an
/// Ashikhmin–Shirley material (`extra` appended to it), Sun and observer off the normal
/// in different azimuths so that the lobe's orientation matters.
fn plate(tri: &str, nu: f64, nv: f64, extra: &str) -> Scene {
    let json = format!(
        r#"{{"object":{{"mesh":{{"vertices":[[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]],"triangles":{tri}}},
            "materials":[{{"name":"m","model":"ashikhmin-shirley","rd":0.2,"rs":0.5,"nu":{nu},"nv":{nv}{extra}}}]}},
            "epochs":[{{"t":0,"sun":[0.3,0.1,1],"observer":[-2e5,-1.3e5,1e6]}},
                      {{"t":1,"sun":[0.1,0.4,1],"observer":[-0.5e5,-3e5,1e6]}}],
            "illumination":{{"earthshine":"off"}}}}"#
    );
    let req: Request = serde_json::from_str(&json).expect("request");
    glint::scene::validate::validate(&req, &Limits::default()).expect("valid")
}

fn curve(s: &Scene) -> Vec<f64> {
    glint::simulate(s)
        .epochs
        .iter()
        .map(|e| e.irradiance_w_m2)
        .collect()
}

#[test]
fn relisting_a_triangles_vertices_changes_nothing() {
    // the same two triangles, their corners listed from each of their three starts: the
    // faces' tangents (and so the curve) must not move; before, the first edge set it and
    // the three listings gave three curves
    let listings = [
        "[[0,1,2],[0,2,3]]",
        "[[1,2,0],[2,3,0]]",
        "[[2,0,1],[3,0,2]]",
    ];
    let first = curve(&plate(listings[0], 10.0, 1000.0, ""));
    assert!(first.iter().all(|&e| e > 0.0));
    for l in &listings[1..] {
        let c = curve(&plate(l, 10.0, 1000.0, ""));
        for (a, b) in first.iter().zip(&c) {
            // the same sums in the same order: equal to rounding
            assert!((a - b).abs() <= 1e-14 * a, "{l}: {a} vs {b}");
        }
    }
}

#[test]
fn a_tangent_turned_a_quarter_swaps_the_exponents() {
    // nu along y is nv along x: the lobe is the same ellipse (an identity of the model,
    // not of the code's tangent rule)
    let tri = "[[0,1,2],[0,2,3]]";
    let along_y = curve(&plate(tri, 10.0, 1000.0, r#","tangent":[0,3,0]"#));
    let swapped = curve(&plate(tri, 1000.0, 10.0, ""));
    let default = curve(&plate(tri, 10.0, 1000.0, ""));
    for ((a, b), c) in along_y.iter().zip(&swapped).zip(&default) {
        assert!((a - b).abs() <= 1e-12 * a, "{a} vs {b}");
        // and the orientation matters here, or the test would prove nothing
        assert!((a - c).abs() > 1e-3 * a, "{a} vs {c}");
    }
}

#[test]
fn a_tangent_is_refused_where_it_means_nothing() {
    let refuse = |extra: &str, model: &str, field: &str| {
        let json = format!(
            r#"{{"object":{{"mesh":{{"builtin":"plate"}},"materials":[{{"name":"m",{model}{extra}}}]}},
                "epochs":[{{"t":0,"sun":[0,0,1],"observer":[0,0.1,1e6]}}]}}"#
        );
        let req: Request = serde_json::from_str(&json).expect("request");
        let e = glint::scene::validate::validate(&req, &Limits::default()).expect_err("refused");
        assert_eq!(e.field, field, "{e:?}");
    };
    let a_s = r#""model":"ashikhmin-shirley","rd":0.2,"rs":0.5,"nu":10,"nv":100"#;
    refuse(r#","tangent":[0,0,0]"#, a_s, "object.materials[0].tangent");
    refuse(
        r#","tangent":[1,0,0]"#,
        r#""model":"lambert","albedo":0.5"#,
        "object.materials[0].tangent",
    );
}
