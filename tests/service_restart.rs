//! Jobs survive the server process: the built binary is started, killed with SIGKILL in
//! the middle of a job, and started again on the same data directory.

mod service_support;

use service_support::*;
use std::io::{BufRead, BufReader};
use std::net::SocketAddr;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

struct Proc {
    child: Child,
    addr: SocketAddr,
}

/// Starts `glint serve` on a free loopback port and reads the port from its first line.
fn spawn(dir: &Path) -> Proc {
    spawn_with(dir, &[])
}

fn spawn_with(dir: &Path, extra: &[&str]) -> Proc {
    let mut child = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args([
            "serve",
            "--addr",
            "127.0.0.1:0",
            "--max-running-jobs",
            "1",
            "--data-dir",
        ])
        .arg(dir)
        .args(extra)
        .env_remove("GLINT_API_TOKEN")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn glint serve");
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let first = lines.next().expect("a first line").unwrap();
    let addr = first
        .split("http://")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .unwrap_or_else(|| panic!("no address in {first:?}"))
        .parse()
        .unwrap();
    // Keep draining stderr so the server never blocks on a full pipe.
    std::thread::spawn(move || for _ in lines {});
    Proc { child, addr }
}

#[test]
fn jobs_survive_kill_9_and_a_graceful_restart() {
    let dir = temp_dir("restart");
    let p = spawn(&dir);

    // A finished job…
    let small = scene_request("box-wing", 30);
    let r = post_json(p.addr, "/v1/jobs", &small);
    assert_eq!(r.status, 202, "{}", r.text());
    let j1 = r.json()["id"].as_str().unwrap().to_string();
    assert_eq!(
        wait_final(p.addr, &j1, &[], Duration::from_secs(120))["state"],
        "done"
    );
    let r1 = get(p.addr, &format!("/v1/jobs/{j1}/result"));
    assert_eq!(r1.status, 200);

    // …one killed mid-run, and one accepted just before the kill (queued behind it).
    let big = scene_request_repeated("box-wing", 1500);
    let j2 = post_json(p.addr, "/v1/jobs", &big).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let start = Instant::now();
    loop {
        let s = get(p.addr, &format!("/v1/jobs/{j2}")).json();
        if s["state"] == "running" && s["epochs_done"].as_u64().unwrap() > 0 {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(60), "never ran: {s}");
        std::thread::sleep(Duration::from_millis(10));
    }
    let r = post_json(p.addr, "/v1/jobs", &small);
    assert_eq!(r.status, 202);
    let j3 = r.json()["id"].as_str().unwrap().to_string();
    let mut child = p.child;
    child.kill().unwrap(); // SIGKILL: no shutdown code runs
    child.wait().unwrap();

    let p = spawn(&dir);
    // The finished result is served unchanged, byte for byte.
    let again = get(p.addr, &format!("/v1/jobs/{j1}/result"));
    assert_eq!(again.status, 200);
    assert_eq!(again.body, r1.body);
    // The interrupted job runs again and gives the engine's answer.
    let s = wait_final(p.addr, &j2, &[], Duration::from_secs(300));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["attempts"], 2, "{s}");
    let got: glint::Response =
        serde_json::from_slice(&get(p.addr, &format!("/v1/jobs/{j2}/result")).body).unwrap();
    assert_eq!(got.epochs, direct(&big).epochs);
    // The job accepted right before the kill was not lost.
    let s = wait_final(p.addr, &j3, &[], Duration::from_secs(120));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["attempts"], 1, "{s}");

    // SIGTERM: a graceful stop with exit status 0.
    let mut child = p.child;
    let ok = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok);
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "no exit after SIGTERM"
        );
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success(), "{status}");

    // And once more: still all there after the graceful stop.
    let mut p = spawn(&dir);
    let list = get(p.addr, "/v1/jobs").json();
    assert_eq!(list.as_array().unwrap().len(), 3, "{list}");
    // The container's HEALTHCHECK command: 0 while the service answers, 1 once it is gone.
    let health = || {
        Command::new(env!("CARGO_BIN_EXE_glint"))
            .args(["healthcheck", "--addr", &p.addr.to_string()])
            .stderr(Stdio::null())
            .status()
            .unwrap()
            .code()
    };
    assert_eq!(health(), Some(0));
    p.child.kill().unwrap();
    p.child.wait().unwrap();
    assert_eq!(health(), Some(1));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn glint_openapi_prints_the_committed_spec() {
    let out = Command::new(env!("CARGO_BIN_EXE_glint"))
        .arg("openapi")
        .output()
        .unwrap();
    assert!(out.status.success());
    let committed = std::fs::read(format!(
        "{}/openapi/openapi.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    assert!(
        out.stdout == committed,
        "`glint openapi` differs from openapi/openapi.json"
    );
}

#[test]
fn a_stored_job_over_the_new_limits_fails_with_the_reason() {
    let dir = temp_dir("limits");
    let mut p = spawn(&dir);
    // A long job keeps the only job slot; the second waits, queued, when the server dies.
    let long = post_json(
        p.addr,
        "/v1/jobs",
        &scene_request_repeated("box-wing", 20_000),
    );
    assert_eq!(long.status, 202);
    let small = post_json(p.addr, "/v1/jobs", &scene_request("box-wing", 50));
    assert_eq!(small.status, 202);
    let id = small.json()["id"].as_str().unwrap().to_string();
    p.child.kill().unwrap();
    p.child.wait().unwrap();

    // Restarted with a lower epoch limit, the stored job cannot run: it fails, and says why.
    let mut p = spawn_with(&dir, &["--max-job-epochs", "40"]);
    let s = wait_final(p.addr, &id, &[], Duration::from_secs(120));
    assert_eq!(s["state"], "failed", "{s}");
    let error = s["error"].as_str().unwrap();
    assert!(error.contains("epochs"), "{error}");
    assert!(s["finished_at"].is_string(), "{s}");
    assert_eq!(get(p.addr, &format!("/v1/jobs/{id}/result")).status, 409);
    p.child.kill().unwrap();
    p.child.wait().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

/// A kibibyte figure of the process's `/proc/<pid>/status` (`VmRSS`, `VmHWM`), in bytes.
#[cfg(target_os = "linux")]
fn proc_status_bytes(pid: u32, key: &str) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let line = status
        .lines()
        .find(|l| l.starts_with(key))
        .unwrap_or_else(|| panic!("no {key} in /proc/{pid}/status"));
    line.split_whitespace()
        .nth(1)
        .unwrap()
        .parse::<u64>()
        .unwrap()
        * 1024
}

/// Downloads `path` to its end without keeping it; returns (status line, body bytes).
fn drain(addr: SocketAddr, path: &str, accept: &str) -> (String, u64) {
    use std::io::{Read, Write};
    let mut s = std::net::TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {addr}\r\nAccept: {accept}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        assert_eq!(
            s.read(&mut byte).unwrap(),
            1,
            "the answer's head ended early"
        );
        head.push(byte[0]);
    }
    let head = String::from_utf8(head).unwrap();
    let len: u64 = head
        .lines()
        .find_map(|l| {
            l.to_ascii_lowercase()
                .strip_prefix("content-length:")
                .map(|v| v.trim().parse().unwrap())
        })
        .unwrap_or_else(|| panic!("no Content-Length in {head}"));
    let mut buf = vec![0u8; 1 << 16];
    let mut got = 0u64;
    loop {
        let n = s.read(&mut buf).unwrap();
        if n == 0 {
            break;
        }
        got += n as u64;
    }
    assert_eq!(got, len, "the body is cut short of its Content-Length");
    (head.lines().next().unwrap().to_string(), got)
}

#[cfg(target_os = "linux")]
#[test]
fn downloads_of_a_large_result_hold_a_bounded_part_of_it() {
    let dir = temp_dir("large-result");
    // A plate along an orbit every 0.1 s: ~400 bytes of JSON an epoch, ~100 MB in all,
    // from a request of a few hundred bytes.
    let request = serde_json::json!({
        "object": { "mesh": { "builtin": "plate" },
                    "materials": [{ "name": "surface", "model": "lambert", "albedo": 0.5 }] },
        "geometry": {
            "orbit": { "tle": [
                "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
                "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995"] },
            "site": { "lat_deg": 32.78, "lon_deg": -105.82, "alt_m": 2790 },
            "times": { "start": "2026-12-03T00:00:00Z", "stop": "2026-12-03T06:56:40Z", "step_s": 0.1 },
            "attitude": { "law": "nadir", "yaw_deg": 0 }
        },
        "illumination": { "band_um": [0.4, 0.7], "earthshine": "off" }
    })
    .to_string();
    let mut p = spawn(&dir);
    let r = post_json(p.addr, "/v1/jobs", &request);
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().unwrap().to_string();
    let s = wait_final(p.addr, &id, &[], Duration::from_secs(300));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["epochs_total"], 250_001, "{s}");
    p.child.kill().unwrap();
    p.child.wait().unwrap();

    // A fresh process, so that its peak is the downloads' own
    let mut p = spawn(&dir);
    let pid = p.child.id();
    std::thread::sleep(Duration::from_millis(300));
    let before = proc_status_bytes(pid, "VmRSS:");
    let path = format!("/v1/jobs/{id}/result");
    let sizes: Vec<(String, u64)> = std::thread::scope(|sc| {
        let handles: Vec<_> = [
            "application/json",
            "application/json",
            "text/csv",
            "text/csv",
        ]
        .into_iter()
        .map(|accept| sc.spawn(|| drain(p.addr, &path, accept)))
        .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let peak = proc_status_bytes(pid, "VmHWM:");
    for (status, _) in &sizes {
        assert!(status.starts_with("HTTP/1.1 200"), "{status}");
    }
    let json = sizes[0].1;
    assert!(json > 90_000_000, "the result is {json} bytes");
    assert_eq!((sizes[1].1, sizes[3].1), (json, sizes[2].1));
    // Four downloads of a 100 MB result (two of its JSON, two of its CSV) add a bounded
    // amount: the store's page cache (16 MiB) and about a chunk (1 MiB) a download, not
    // the result (read whole, each download held it at least once: 400 MB and more).
    let grown = peak.saturating_sub(before);
    assert!(
        grown < 48 << 20,
        "peak RSS grew by {} MiB over {} MiB while downloading",
        grown >> 20,
        before >> 20
    );
    p.child.kill().unwrap();
    p.child.wait().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_fit_job_survives_kill_9_and_gives_the_librarys_fit() {
    // A fit with the yaw free (twelve yaw starts: a hundred or more light curves) is killed
    // while it runs; started again on the same data directory, it runs from the start and
    // gives exactly the library's fit of the same body (only the wall time differs).
    let dir = temp_dir("fit-restart");
    let p = spawn(&dir);
    let (request, observed) = fit_inputs("box-wing", 5, 1, 0.25, 0.4, 23);
    let body = serde_json::json!({
        "request": request,
        "observed": observed,
        "free": ["materials.panel.albedo", "attitude.yaw_deg"],
        "start": { "attitude.yaw_deg": 20.0 }
    });
    let r = post_json(p.addr, "/v1/fits/lightcurve", &body.to_string());
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().unwrap().to_string();
    let start = Instant::now();
    loop {
        let s = get(p.addr, &format!("/v1/jobs/{id}")).json();
        if s["state"] == "running" && s["evaluations_done"].as_u64().unwrap() > 2 {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(120), "never ran: {s}");
        std::thread::sleep(Duration::from_millis(10));
    }
    let mut child = p.child;
    child.kill().unwrap(); // SIGKILL mid-fit
    child.wait().unwrap();

    let mut p = spawn(&dir);
    let s = wait_final(p.addr, &id, &[], Duration::from_secs(600));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["attempts"], 2, "{s}");
    assert_eq!(s["kind"], "fit-lightcurve", "{s}");
    let got: serde_json::Value =
        serde_json::from_slice(&get(p.addr, &format!("/v1/jobs/{id}/result")).body).unwrap();
    let want = serde_json::to_value(direct_fit(&body)).unwrap();
    for k in ["parameters", "uncertainty", "chi2", "correlation", "curve"] {
        assert_eq!(got[k], want[k], "{k}");
    }
    assert_eq!(got["solver"]["evaluations"], want["solver"]["evaluations"]);
    assert_eq!(s["evaluations_done"], want["solver"]["evaluations"]);
    p.child.kill().unwrap();
    p.child.wait().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}
