//! The command line as a user runs it: `glint simulate` on the shipped scenes writes a
//! CSV with the header, a JSON response or an SVG plot; a bad request exits non-zero
//! with the field named, never a panic.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

fn glint() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_glint"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

/// A fresh path in cargo's per-test scratch directory.
fn tmp(name: &str) -> PathBuf {
    let dir =
        PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn run(args: &[&str]) -> Output {
    glint().args(args).output().expect("run glint")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Epochs in a request file.
fn epochs_in(path: &str) -> usize {
    let text = std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["epochs"].as_array().unwrap().len()
}

/// The per-epoch fields, in the response's order.
const COLUMNS: [&str; 14] = [
    "t",
    "irradiance_w_m2",
    "sun_w_m2",
    "earthshine_w_m2",
    "intensity_w_sr",
    "magnitude",
    "magnitude_1000km",
    "magnitude_standard",
    "magnitude_intrinsic",
    "phase_angle_deg",
    "range_m",
    "lit_visible_area_m2",
    "eclipse",
    "earth_blocks_view",
];

#[test]
fn simulate_box_wing_to_csv() {
    let out = tmp("box-wing.csv");
    let o = run(&[
        "simulate",
        "scenes/box-wing.json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(
        summary.contains("epochs") && summary.contains("mag"),
        "summary: {summary}"
    );
    // quiet: nothing but errors
    let o = run(&[
        "simulate",
        "scenes/box-wing.json",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.is_empty() && o.stderr.is_empty(), "{o:?}");
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header, COLUMNS);
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), epochs_in("scenes/box-wing.json"));
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), COLUMNS.len(), "row {i}");
        for (cell, name) in row.iter().zip(COLUMNS) {
            // an absent magnitude (no light) is an empty cell; everything else a finite number
            if cell.is_empty() {
                assert!(name.starts_with("magnitude"), "row {i}: empty {name}");
            } else {
                let x: f64 = cell
                    .parse()
                    .unwrap_or_else(|_| panic!("row {i}: {name} = {cell:?}"));
                assert!(x.is_finite(), "row {i}: {name} = {cell}");
            }
        }
    }
}

#[test]
fn simulate_to_json_and_plot() {
    let out = tmp("sphere.json");
    let plot = tmp("sphere.svg");
    let o = run(&[
        "simulate",
        "scenes/sphere.json",
        "--out",
        out.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).expect("valid JSON");
    let epochs = v["epochs"].as_array().expect("epochs array");
    assert_eq!(epochs.len(), epochs_in("scenes/sphere.json"));
    for e in epochs {
        for c in COLUMNS {
            assert!(e.get(c).is_some(), "missing {c} in {e}");
        }
        assert!(e["irradiance_w_m2"].as_f64().is_some_and(f64::is_finite));
    }
    assert_eq!(v["summary"]["epochs"].as_u64(), Some(epochs.len() as u64));
    assert!(v["summary"]["method"].is_string());
    let svg = std::fs::read_to_string(&plot).unwrap();
    assert!(svg.contains("<svg") && svg.contains("</svg>"), "not an SVG");
}

#[test]
fn request_on_standard_input() {
    let mut child = glint()
        .args([
            "simulate",
            "-",
            "-q",
            "--out",
            tmp("stdin.csv").to_str().unwrap(),
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let text = std::fs::read(format!("{}/scenes/plate.json", env!("CARGO_MANIFEST_DIR"))).unwrap();
    child.stdin.take().unwrap().write_all(&text).unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(tmp("stdin.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + epochs_in("scenes/plate.json"));
}

/// An edit that breaks a request.
type Edit = Box<dyn Fn(&mut serde_json::Value)>;

/// A bad request: non-zero exit, the field and the problem on stderr, no panic, no output
/// file.
#[test]
fn bad_requests_exit_non_zero_naming_the_field() {
    let base = serde_json::json!({
        "object": { "mesh": { "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]] },
                    "materials": [ { "name": "a", "model": "lambert", "albedo": 0.3 } ] },
        "epochs": [ { "t": 0, "sun": [0, 0, 1], "observer": [0, 0, 1e7] } ]
    });
    let cases: Vec<(&str, Edit)> = vec![
        (
            "object.materials[0].albedo",
            Box::new(|v| v["object"]["materials"][0]["albedo"] = (-0.3).into()),
        ),
        (
            "object.materials[0].albdo",
            Box::new(|v| v["object"]["materials"][0]["albdo"] = 0.3.into()),
        ),
        (
            "object.mesh.triangles[0]",
            Box::new(|v| v["object"]["mesh"]["triangles"][0] = serde_json::json!([0, 1, 7])),
        ),
        (
            "object.mesh.material_ids[0]",
            Box::new(|v| v["object"]["mesh"]["material_ids"] = serde_json::json!([3])),
        ),
        (
            "epochs[0].sun",
            Box::new(|v| v["epochs"][0]["sun"] = serde_json::json!([0, 0, 0])),
        ),
        (
            "epochs[0].earth",
            Box::new(|v| v["illumination"] = serde_json::json!({ "earthshine": "sphere" })),
        ),
        (
            "object.mesh.triangles",
            Box::new(|v| {
                v["object"]["mesh"] = serde_json::json!({ "vertices": [], "triangles": [] })
            }),
        ),
        (
            "object.mesh.builtin",
            Box::new(|v| v["object"]["mesh"] = serde_json::json!({ "builtin": "tardis" })),
        ),
        (
            "object.materials[0].model",
            Box::new(|v| v["object"]["materials"][0]["model"] = "chrome".into()),
        ),
        (
            "illumination.earthshine",
            Box::new(|v| v["illumination"] = serde_json::json!({ "earthshine": "moon" })),
        ),
        ("bogus", Box::new(|v| v["bogus"] = 1.into())),
    ];
    for (field, edit) in cases {
        let mut v = base.clone();
        edit(&mut v);
        let req = tmp("bad.json");
        std::fs::write(&req, v.to_string()).unwrap();
        let out = tmp("bad-out.csv");
        let _ = std::fs::remove_file(&out);
        let o = run(&[
            "simulate",
            req.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "-q",
        ]);
        let err = stderr(&o);
        assert!(!o.status.success(), "{field}: accepted");
        assert!(
            err.contains(field),
            "{field}: stderr does not name it: {err}"
        );
        assert!(!err.contains("panicked"), "{field}: {err}");
        assert!(!out.exists(), "{field}: wrote an output file");
    }
    // the control: the base request is fine
    let req = tmp("good.json");
    std::fs::write(&req, base.to_string()).unwrap();
    assert!(run(&["simulate", req.to_str().unwrap(), "-q"])
        .status
        .success());
}

#[test]
fn unreadable_or_malformed_files_exit_non_zero() {
    let o = run(&["simulate", "scenes/no-such-file.json", "-q"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("no-such-file.json"), "{}", stderr(&o));
    let req = tmp("broken.json");
    std::fs::write(&req, "{ \"object\": ").unwrap();
    let o = run(&["simulate", req.to_str().unwrap(), "-q"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("JSON"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"));
    // an unknown subcommand or option
    assert!(!run(&["simulat", "scenes/plate.json"]).status.success());
    assert!(!run(&["simulate", "scenes/plate.json", "--outt", "x.csv"])
        .status
        .success());
}

/// `glint simulate` takes a `geometry` request as the service does: the CSV has the
/// site's view after the usual columns, one row per epoch kept by `visible_only`.
#[test]
fn simulate_a_pass_from_a_tle() {
    let out = tmp("iss-pass.csv");
    let o = run(&[
        "simulate",
        "scenes/iss-pass.json",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(&out).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.starts_with(&COLUMNS.join(",")));
    assert!(header.ends_with("azimuth_deg,elevation_deg,sun_elevation_deg,in_earth_shadow"));
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert!(!rows.is_empty());
    for row in rows {
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells.len(), COLUMNS.len() + 4);
        let el: f64 = cells[COLUMNS.len() + 1].parse().unwrap();
        let sun_el: f64 = cells[COLUMNS.len() + 2].parse().unwrap();
        assert!(el >= 10.0 && sun_el <= -6.0, "{row}");
    }
}
#[test]
fn fit_brdf_fits_the_committed_white_paint_samples() {
    // scenes/white-paint-brdf.csv is synthetic (`glint sample-brdf` from the paper's white
    // paint, 5 % log-normal noise, seed 1): the fit must give back k^D = 0.1 and δ = 0.007
    // within 3σ and write its JSON and both plots.
    let (json, svg, png) = (tmp("fit.json"), tmp("fit.svg"), tmp("fit.png"));
    for plot in [&svg, &png] {
        let o = run(&[
            "fit-brdf",
            "scenes/white-paint-brdf.csv",
            "--model",
            "seed-microfacet",
            "--fix",
            "n=0.2,k=2.5",
            "--out",
            json.to_str().unwrap(),
            "--plot",
            plot.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    for (name, truth) in [("kd", 0.1), ("km", 0.2), ("slope_rms", 0.007)] {
        let (p, s) = (
            v["parameters"][name].as_f64().unwrap(),
            v["uncertainty"][name].as_f64().unwrap(),
        );
        assert!((p - truth).abs() < 3.0 * s, "{name}: {p} ± {s}");
    }
    assert_eq!(v["material"]["model"], "seed-microfacet");
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    // the PNG needs a system font; without one the error says so
    if let Ok(bytes) = std::fs::read(&png) {
        assert_eq!(&bytes[1..4], b"PNG");
    }
}

#[test]
fn fit_commands_name_what_is_wrong() {
    let bad = tmp("bad.csv");
    std::fs::write(
        &bad,
        "theta_i_deg,theta_r_deg,phi_deg,brdf_sr\n10,10,180,0.5\n10,91,180,0.4\n",
    )
    .unwrap();
    let o = run(&["fit-brdf", bad.to_str().unwrap(), "--model", "lambert"]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("samples[1].theta_r_deg") && stderr(&o).contains("line 3"),
        "{}",
        stderr(&o)
    );
    let o = run(&[
        "fit-brdf",
        "scenes/white-paint-brdf.csv",
        "--model",
        "lambert",
        "--fix",
        "km=0.1",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--fix km"), "{}", stderr(&o));
    let obs = tmp("obs.csv");
    std::fs::write(
        &obs,
        "t,magnitude,sigma\n0,12.0,0.02\n60,12.1,0.02\n120,12.2,0.02\n",
    )
    .unwrap();
    let o = run(&[
        "fit-lightcurve",
        "scenes/box-wing.json",
        "--observed",
        obs.to_str().unwrap(),
        "--free",
        "materials.panel.albedo,materials.wing.albedo",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("no material named `wing`"),
        "{}",
        stderr(&o)
    );
}
