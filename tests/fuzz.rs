//! A fuzz harness over the whole path a request takes: JSON text → parse → validate →
//! prepare → epochs, for every method, with OBJ text among the meshes. Whatever the input,
//! the answer is an error naming a field or a response with finite numbers: never a panic,
//! a NaN or an infinity.
//!
//! Two generators, both seeded and deterministic (a failure prints its seed and the request
//! text, so it can be replayed):
//! - the shipped example requests (`scenes/*.json`), each mutated one to four times: a value
//!   anywhere in the tree replaced by one from a pool of hostile values (huge, tiny,
//!   negative, zero, wrong types, wrong lengths, unknown names), a key removed, a known key
//!   added with such a value, an array element repeated or dropped;
//! - random OBJ text: vertices with huge, tiny, `nan` and `inf` coordinates, faces with
//!   indices out of range, negative, repeated or too few, `usemtl` with unknown names,
//!   normals, texture coordinates and garbage lines.
//!
//! The work per case is bounded by [`LIMITS`] (as the service bounds it). CI runs
//! `GLINT_FUZZ_CASES` cases of each kind (default 120); `GLINT_FUZZ_SECONDS=N` runs each
//! generator for N seconds instead (the long local run), and `GLINT_FUZZ_SEED` starts
//! elsewhere.

mod common;

use glint::{Limits, Scene};
use serde_json::{json, Map, Value};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

/// What one case may cost: about what a synchronous service request may, scaled down so
/// that a case takes milliseconds in a debug build.
const LIMITS: Limits = Limits {
    max_triangles: 30_000,
    max_epochs: 400,
    max_triangle_epochs: 300_000,
    max_pixel_samples: 300_000,
};

/// splitmix64: a small, seedable generator (the harness must replay a seed exactly).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
}

/// Numbers that break arithmetic: zero of both signs, the ends of f64, values past the
/// validator's bounds, integers too large to be exact.
const NUMBERS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0,
    1e-300,
    -1e-300,
    5e-324,
    1e-12,
    1e300,
    -1e300,
    1e12,
    1e13,
    3.6e7,
    6.4e6,
    9.007_199_254_740_993e15,
    -9.2e18,
    1.8e19,
    90.0,
    180.0,
    360.0,
    1e-3,
];

const STRINGS: &[&str] = &[
    "",
    "auto",
    "adaptive",
    "centroid",
    "image",
    "convex",
    "silhouette",
    "coarse",
    "medium",
    "fine",
    "as-is",
    "sphere",
    "seed",
    "off",
    "lambert",
    "rough-conductor",
    "seed-microfacet",
    "ashikhmin-shirley",
    "seed-body-wrap",
    "separable",
    "correlated",
    "box-wing",
    "plate",
    "nadir",
    "tumble",
    "spin",
    "2026-11-22T04:50:00Z",
    "2026-13-45T99:99:99Z",
    "nan",
    "inf",
    "1e400",
    "\u{0}",
    "../../etc/passwd",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
];

/// Keys the request format knows, to add where they may not belong.
const KEYS: &[&str] = &[
    "method",
    "tolerance",
    "image_size",
    "image_samples",
    "thumbnails",
    "detail",
    "two_sided",
    "normalised",
    "shadowing",
    "tangent",
    "attitude",
    "sun_distance_au",
    "earth",
    "observer",
    "sun",
    "geometry",
    "epochs",
    "band_um",
    "earthshine",
    "albedo",
    "slope_rms",
    "alpha",
    "builtin",
    "obj",
    "material_ids",
];

fn hostile_value(rng: &mut Rng) -> Value {
    let n = |rng: &mut Rng| json!(*rng.pick(NUMBERS));
    match rng.below(12) {
        0..=3 => n(rng),
        4..=5 => json!(*rng.pick(STRINGS)),
        6 => json!(rng.below(2) == 0),
        7 => Value::Null,
        8 => json!([n(rng), n(rng), n(rng)]),
        9 => {
            let len = *rng.pick(&[0usize, 1, 2, 4, 5]);
            Value::Array((0..len).map(|_| n(rng)).collect())
        }
        10 => json!([[0, 1, 2], [0, 0, 0], [5, 6, 7]]),
        _ => match rng.below(4) {
            0 => json!({}),
            1 => json!({ "builtin": *rng.pick(&["sphere", "plate", "box-wing", "cubesat"]) }),
            2 => json!({ "obj": random_obj(rng) }),
            _ => json!({ "size": 16, "every": 1 }),
        },
    }
}

/// Every place in the tree, as a path of keys and indices.
fn paths(v: &Value, here: &mut Vec<Value>, out: &mut Vec<Vec<Value>>) {
    out.push(here.clone());
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                here.push(json!(k));
                paths(x, here, out);
                here.pop();
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                here.push(json!(i));
                paths(x, here, out);
                here.pop();
            }
        }
        _ => {}
    }
}

fn at<'a>(v: &'a mut Value, path: &[Value]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match k {
        Value::String(k) => &mut v[k.as_str()],
        k => &mut v[k.as_u64().unwrap() as usize],
    })
}

/// One mutation somewhere in the request.
fn mutate(v: &mut Value, rng: &mut Rng) {
    let mut all = Vec::new();
    paths(v, &mut Vec::new(), &mut all);
    let path = rng.pick(&all).clone();
    let value = hostile_value(rng);
    let node = at(v, &path);
    match (rng.below(5), node) {
        (0, Value::Object(m)) if !m.is_empty() => {
            let k = m.keys().nth(rng.below(m.len())).unwrap().clone();
            m.remove(&k);
        }
        (1, Value::Object(m)) => {
            m.insert(rng.pick(KEYS).to_string(), value);
        }
        (2, Value::Array(a)) if !a.is_empty() => {
            let i = rng.below(a.len());
            if rng.below(2) == 0 {
                let x = a[i].clone();
                a.insert(i, x);
            } else {
                a.remove(i);
            }
        }
        (_, node) => *node = value,
    }
}

/// One number in the request scaled, negated, or replaced by one from [`NUMBERS`].
fn renumber(v: &mut Value, rng: &mut Rng) {
    let mut all = Vec::new();
    paths(v, &mut Vec::new(), &mut all);
    let numbers: Vec<_> = all.into_iter().filter(|p| at(v, p).is_number()).collect();
    if numbers.is_empty() {
        return;
    }
    let path = rng.pick(&numbers[..]).clone();
    let node = at(v, &path);
    let x = node.as_f64().unwrap();
    let y = match rng.below(4) {
        0 => x * *rng.pick(&[1e-6, 1e-3, 0.5, 2.0, 1e3, 1e6]),
        1 => -x,
        2 => x + *rng.pick(&[1e-9, -1e-9, 1.0, -1.0]),
        _ => *rng.pick(NUMBERS),
    };
    *node = json!(y);
}

/// The shipped example requests, cut to a few epochs (a `geometry` window is left as it
/// is: the epoch limit bounds it).
fn examples() -> Vec<(String, Value)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        if let Some(Value::Array(epochs)) = v.get_mut("epochs") {
            epochs.truncate(3);
        }
        if let Some(mesh) = v.pointer_mut("/object/mesh") {
            if mesh.get("builtin").is_some() {
                mesh["detail"] = json!("coarse");
            }
        }
        if let Some(Value::Object(t)) = v.get_mut("thumbnails") {
            t.insert("size".into(), json!(16));
        }
        out.push((path.file_name().unwrap().to_string_lossy().into_owned(), v));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    assert!(out.len() >= 5, "examples in {dir}: {}", out.len());
    out
}

/// OBJ text: a small valid mesh (a few vertices, triangles and quads over them), then
/// none to three corruptions: a coordinate `nan`, `inf`, huge, tiny or not a number, a
/// vertex of two coordinates, a face index out of range, zero, negative or repeated, a
/// face of one index, an unknown `usemtl`, normals, texture coordinates and other lines.
fn random_obj(rng: &mut Rng) -> String {
    let nv = 4 + rng.below(5);
    let mut lines: Vec<String> = (0..nv)
        .map(|_| {
            let c: Vec<String> = (0..3)
                .map(|_| format!("{:.3}", rng.below(2001) as f64 / 1000.0 - 1.0))
                .collect();
            format!("v {}", c.join(" "))
        })
        .collect();
    // faces over distinct sets of corners (the same triangle twice is refused, rightly)
    let mut used: Vec<Vec<usize>> = Vec::new();
    for _ in 0..2 + rng.below(5) {
        let k = if rng.below(4) == 0 { 4 } else { 3 };
        let mut idx: Vec<usize> = Vec::new();
        while idx.len() < k {
            let i = 1 + rng.below(nv);
            if !idx.contains(&i) {
                idx.push(i);
            }
        }
        let mut key = idx.clone();
        key.sort_unstable();
        if used.contains(&key) {
            continue;
        }
        used.push(key);
        let idx: Vec<String> = idx.iter().map(|i| i.to_string()).collect();
        lines.push(format!("f {}", idx.join(" ")));
    }
    // half of the texts valid, the rest with one to three corruptions
    let corruptions = if rng.below(2) == 0 {
        0
    } else {
        1 + rng.below(3)
    };
    for _ in 0..corruptions {
        let at = rng.below(lines.len());
        let bad = match rng.below(12) {
            0 => "v nan 0 0".to_string(),
            1 => "v inf 1 0".to_string(),
            2 => "v 1e400 0 1".to_string(),
            3 => format!(
                "v {} {} {}",
                rng.pick(NUMBERS),
                rng.pick(NUMBERS),
                rng.pick(NUMBERS)
            ),
            4 => "v 0 1".to_string(),
            5 => "v x y z".to_string(),
            6 => format!("f 1 2 {}", nv + 1 + rng.below(3)),
            7 => "f 0 1 2".to_string(),
            8 => format!("f -1 -2 -{}", 1 + rng.below(nv + 2)),
            9 => "f 1 1 2".to_string(),
            10 => format!("usemtl {}", rng.pick(&["surface", "body", "nope", ""])),
            _ => rng
                .pick(&[
                    "vn 0 0 1",
                    "vt 0.5 0.5",
                    "f 1/1/1 2/2/2 3/3/3",
                    "f 1",
                    "# c",
                    "g x",
                    "o y",
                    "s off",
                    "junk",
                ])
                .to_string(),
        };
        lines.insert(at, bad);
    }
    lines.join("\n") + "\n"
}

/// A request around random OBJ text, with a random method.
fn obj_request(rng: &mut Rng) -> Value {
    let method = *rng.pick(&[
        "auto",
        "adaptive",
        "centroid",
        "convex",
        "image",
        "silhouette",
    ]);
    let mut v = json!({
        "object": {
            "mesh": { "obj": random_obj(rng) },
            "materials": [{ "name": "surface", "model": "lambert", "albedo": 0.4, "two_sided": rng.below(2) == 0 }]
        },
        "epochs": [
            { "t": 0, "sun": [1, 0.2, 0.1], "observer": [0.3, 1e6, 2e5], "earth": [0, 0, -7e6] },
            { "t": 1, "sun": [0, 0, 1], "observer": [1e7, 0, 0], "earth": [-7e6, 0, 0] }
        ],
        "illumination": { "earthshine": *rng.pick(&["off", "seed", "sphere"]) },
        "method": method
    });
    if method == "image" {
        v["image_size"] = json!(16);
    }
    v
}

/// Runs one request through the whole path; on a panic or a non-finite number, fails
/// with the seed and the request text.
fn run_case(kind: &str, seed: u64, text: &str) -> bool {
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        match Scene::from_json(text, &LIMITS) {
            Err(e) => {
                if std::env::var_os("GLINT_FUZZ_VERBOSE").is_some() {
                    println!("{kind} {seed}: {}: {}", e.field, e.message);
                }
                assert!(
                    !e.field.is_empty() && !e.message.is_empty(),
                    "an error names no field: {e:?}"
                );
                false
            }
            Ok(scene) => {
                let response = glint::simulate(&scene);
                common::assert_sane(&response);
                // and it serialises to JSON without a NaN turning into null silently
                let out = serde_json::to_value(&response).unwrap();
                assert_finite(&out, "");
                true
            }
        }
    }));
    match outcome {
        Ok(accepted) => accepted,
        Err(e) => {
            let msg = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            panic!("{kind} case, seed {seed}: {msg}\nrequest: {text}");
        }
    }
}

fn assert_finite(v: &Value, path: &str) {
    match v {
        Value::Number(n) => assert!(
            n.as_f64().is_some_and(f64::is_finite),
            "{path} = {n} is not finite"
        ),
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                assert_finite(x, &format!("{path}[{i}]"));
            }
        }
        Value::Object(m) => {
            for (k, x) in m {
                assert_finite(x, &format!("{path}.{k}"));
            }
        }
        _ => {}
    }
}

/// How many cases (or for how long) each generator runs.
struct Budget {
    cases: u64,
    until: Option<Instant>,
    seed: u64,
}

impl Budget {
    fn from_env() -> Budget {
        let var = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
        Budget {
            cases: var("GLINT_FUZZ_CASES").unwrap_or(120),
            until: var("GLINT_FUZZ_SECONDS").map(|s| Instant::now() + Duration::from_secs(s)),
            seed: var("GLINT_FUZZ_SEED").unwrap_or(0),
        }
    }
    fn more(&self, done: u64) -> bool {
        match self.until {
            Some(t) => Instant::now() < t,
            None => done < self.cases,
        }
    }
}

#[test]
fn mutated_example_requests_error_by_field_or_give_finite_numbers() {
    let examples = examples();
    let budget = Budget::from_env();
    let (mut done, mut accepted) = (0u64, 0u64);
    while budget.more(done) {
        let seed = budget.seed + done;
        let mut rng = Rng(seed ^ 0x6a09_e667_f3bc_c908);
        let (_, base) = rng.pick(&examples);
        let mut v = base.clone();
        // half the cases change numbers only (a request that stays well-formed reaches
        // the engine with odd values), the rest anything anywhere
        if rng.below(2) == 0 {
            for _ in 0..1 + rng.below(3) {
                renumber(&mut v, &mut rng);
            }
        } else {
            for _ in 0..1 + rng.below(4) {
                mutate(&mut v, &mut rng);
            }
        }
        accepted += run_case("mutated request", seed, &v.to_string()) as u64;
        done += 1;
    }
    println!("mutated requests: {done} cases, {accepted} accepted and simulated");
    // the harness must reach the engine, not only the validator
    assert!(
        accepted * 10 >= done,
        "only {accepted} of {done} were valid"
    );
}

#[test]
fn random_obj_text_errors_by_field_or_gives_finite_numbers() {
    let budget = Budget::from_env();
    let (mut done, mut accepted) = (0u64, 0u64);
    while budget.more(done) {
        let seed = budget.seed + done;
        let mut rng = Rng(seed ^ 0xbb67_ae85_84ca_a73b);
        let v = obj_request(&mut rng);
        accepted += run_case("OBJ", seed, &v.to_string()) as u64;
        done += 1;
    }
    println!("OBJ texts: {done} cases, {accepted} accepted and simulated");
    assert!(accepted > 0, "no OBJ text of {done} was valid");
}

#[test]
fn the_generator_replays_a_seed_exactly() {
    let a = obj_request(&mut Rng(42)).to_string();
    let b = obj_request(&mut Rng(42)).to_string();
    assert_eq!(a, b);
    let mut m = Map::new();
    m.insert("k".into(), json!([1, 2, 3]));
    let (mut x, mut y) = (Value::Object(m.clone()), Value::Object(m));
    mutate(&mut x, &mut Rng(7));
    mutate(&mut y, &mut Rng(7));
    assert_eq!(x, y);
}
