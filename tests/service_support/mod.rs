//! Shared by the service tests: a tiny HTTP/1.1 client over a raw TCP stream (no HTTP
//! client crate is a dependency), an in-process server, and request builders.
#![allow(dead_code)]

use glint::service::{self, Config};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::PathBuf;
use std::time::Duration;

/// An HTTP answer.
#[derive(Debug)]
pub struct Reply {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

impl Reply {
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.text()))
    }
}

/// One request on a fresh connection (`Connection: close`), the whole answer read.
pub fn http(
    addr: SocketAddr,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> Reply {
    let mut s = TcpStream::connect(addr).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    let mut head = format!("{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n");
    for (k, v) in headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    if !body.is_empty() || method == "POST" {
        head.push_str(&format!("Content-Length: {}\r\n", body.len()));
    }
    head.push_str("\r\n");
    s.write_all(head.as_bytes()).unwrap();
    // The server may answer (413) before reading a large body: ignore a broken pipe.
    let _ = s.write_all(body);
    let mut raw = Vec::new();
    let _ = s.read_to_end(&mut raw);
    reply_of(&raw)
}

/// The answer in `raw`, the bytes a server sent (a chunked body is joined).
pub fn reply_of(raw: &[u8]) -> Reply {
    let end = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no header end in {:?}", String::from_utf8_lossy(raw)));
    let head = std::str::from_utf8(&raw[..end]).unwrap();
    let mut lines = head.split("\r\n");
    let status: u16 = lines
        .next()
        .unwrap()
        .split(' ')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect();
    let mut body = raw[end + 4..].to_vec();
    let chunked = headers
        .iter()
        .any(|(k, v)| k.eq_ignore_ascii_case("transfer-encoding") && v.contains("chunked"));
    if chunked {
        let mut out = Vec::new();
        let mut rest = &body[..];
        loop {
            let nl = rest.windows(2).position(|w| w == b"\r\n").unwrap();
            let size = usize::from_str_radix(std::str::from_utf8(&rest[..nl]).unwrap().trim(), 16)
                .unwrap();
            if size == 0 {
                break;
            }
            out.extend_from_slice(&rest[nl + 2..nl + 2 + size]);
            rest = &rest[nl + 2 + size + 2..];
        }
        body = out;
    }
    Reply {
        status,
        headers,
        body,
    }
}

pub fn get(addr: SocketAddr, path: &str) -> Reply {
    http(addr, "GET", path, &[], b"")
}

pub fn post_json(addr: SocketAddr, path: &str, body: &str) -> Reply {
    http(
        addr,
        "POST",
        path,
        &[("Content-Type", "application/json")],
        body.as_bytes(),
    )
}

/// A fresh, empty directory under the system temp dir.
pub fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("glint-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The service running in this process on a free loopback port.
pub struct Server {
    pub addr: SocketAddr,
    pub dir: PathBuf,
    running: Option<service::Running>,
    rt: tokio::runtime::Runtime,
}

impl Server {
    pub fn start(name: &str, tweak: impl FnOnce(&mut Config)) -> Server {
        let dir = temp_dir(name);
        let mut config = Config {
            addr: "127.0.0.1:0".parse().unwrap(),
            data_dir: dir.clone(),
            ..Config::default()
        };
        tweak(&mut config);
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .unwrap();
        let running = rt.block_on(service::start(config)).expect("service starts");
        Server {
            addr: running.addr,
            dir,
            running: Some(running),
            rt,
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        if let Some(r) = self.running.take() {
            let _ = self.rt.block_on(r.shutdown());
        }
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The example request `scenes/<name>.json` cut to its first `n` epochs.
pub fn scene_request(name: &str, n: usize) -> String {
    let text =
        std::fs::read_to_string(format!("{}/scenes/{name}.json", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let epochs = v["epochs"].as_array_mut().unwrap();
    epochs.truncate(n);
    v.to_string()
}

/// The example request `scenes/<name>.json` with its epochs repeated to `n` epochs.
pub fn scene_request_repeated(name: &str, n: usize) -> String {
    let text =
        std::fs::read_to_string(format!("{}/scenes/{name}.json", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let epochs = v["epochs"].as_array().unwrap().clone();
    v["epochs"] = epochs.iter().cycle().take(n).cloned().collect();
    v.to_string()
}

/// The engine's own answer to a request, computed directly.
pub fn direct(request: &str) -> glint::Response {
    let scene =
        glint::Scene::from_json(request, &glint::Limits::unlimited()).expect("valid request");
    glint::simulate(&scene)
}

/// Polls a job until it reaches a final state (or `limit` passes), returning its status.
pub fn wait_final(
    addr: SocketAddr,
    id: &str,
    headers: &[(&str, &str)],
    limit: Duration,
) -> serde_json::Value {
    let start = std::time::Instant::now();
    loop {
        let r = http(addr, "GET", &format!("/v1/jobs/{id}"), headers, b"");
        assert_eq!(r.status, 200, "{}", r.text());
        let s = r.json();
        let state = s["state"].as_str().unwrap().to_string();
        if ["done", "failed", "cancelled"].contains(&state.as_str()) || start.elapsed() > limit {
            return s;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A light-curve fit's inputs made from a known truth: `scenes/<name>.json`, every
/// `step`-th epoch, with material `material`'s albedo at `truth` is simulated here by the
/// library (not by the fit), its magnitudes noised by N(0, 0.02 mag) from a seeded
/// generator; the request handed to the fit has that albedo at `start` instead. Returns
/// the request (JSON) and the observations.
pub fn fit_inputs(
    name: &str,
    step: usize,
    material: usize,
    truth: f64,
    start: f64,
    seed: u64,
) -> (serde_json::Value, Vec<glint::fit::lightcurve::Observation>) {
    let text =
        std::fs::read_to_string(format!("{}/scenes/{name}.json", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let epochs: Vec<serde_json::Value> = v["epochs"]
        .as_array()
        .unwrap()
        .iter()
        .step_by(step)
        .cloned()
        .collect();
    v["epochs"] = serde_json::Value::Array(epochs);
    v["object"]["materials"][material]["albedo"] = serde_json::json!(truth);
    let curve = direct(&v.to_string());
    // splitmix64 → uniform, Box–Muller → N(0, 1)
    let mut state = seed;
    let mut uniform = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    };
    let observed = curve
        .epochs
        .iter()
        .filter_map(|e| {
            let (u1, u2) = (uniform().max(1e-300), uniform());
            let normal = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
            e.magnitude.map(|m| glint::fit::lightcurve::Observation {
                t: e.t,
                magnitude: m + 0.02 * normal,
                sigma: 0.02,
            })
        })
        .collect();
    v["object"]["materials"][material]["albedo"] = serde_json::json!(start);
    (v, observed)
}

/// The library's own fit of a fit body (the truth the service must give back unchanged).
pub fn direct_fit(body: &serde_json::Value) -> glint::fit::lightcurve::LightcurveFit {
    use glint::fit::lightcurve::{fit, LightcurveFitRequest, Options};
    let req: LightcurveFitRequest = serde_json::from_value(body.clone()).unwrap();
    fit(
        &req.request,
        &req.observed,
        &Options::from_request(&req).unwrap(),
    )
    .unwrap()
}
