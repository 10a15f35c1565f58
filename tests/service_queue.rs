//! The shared PostgreSQL queue against a real PostgreSQL, with the built binary as
//! separate processes: workers killed and restarted, the database restarted, many
//! submissions through two API processes, a cancel while chunks are in flight, and the
//! schema version check.
//!
//! Needs `GLINT_TEST_DATABASE_URL` (a server where the tests may create databases;
//! `.ci/run` starts one with `.ci/postgres.sh` and sets it). Without it each test says so
//! and passes without running.

mod service_support;

use service_support::*;
use std::io::{BufRead, BufReader};
use std::net::SocketAddr;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio_postgres::NoTls;

/// The test server's URL, or `None` (and the reason printed) when it is not set.
fn server_url(test: &str) -> Option<String> {
    match std::env::var("GLINT_TEST_DATABASE_URL") {
        Ok(u) if !u.is_empty() => Some(u),
        _ => {
            eprintln!(
                "skipped {test}: GLINT_TEST_DATABASE_URL is not set (.ci/run starts a \
                 PostgreSQL and sets it)"
            );
            None
        }
    }
}

/// `url` with its database replaced by `db`.
fn with_db(url: &str, db: &str) -> String {
    let (base, _) = url.rsplit_once('/').expect("a database in the URL");
    format!("{base}/{db}")
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap()
}

/// Runs SQL statements on `url`, returning the rows of the last as text.
fn sql(url: &str, statement: &str) -> Vec<Vec<Option<String>>> {
    runtime().block_on(async {
        let (client, conn) = tokio_postgres::connect(url, NoTls).await.expect("connect");
        tokio::spawn(conn);
        let msgs = client.simple_query(statement).await.expect(statement);
        msgs.into_iter()
            .filter_map(|m| match m {
                tokio_postgres::SimpleQueryMessage::Row(r) => {
                    Some((0..r.len()).map(|i| r.get(i).map(str::to_string)).collect())
                }
                _ => None,
            })
            .collect()
    })
}

/// One number from a query.
fn count(url: &str, statement: &str) -> i64 {
    sql(url, statement)[0][0]
        .as_deref()
        .unwrap()
        .parse()
        .unwrap()
}

/// A fresh, empty database on the test server for `name`, dropped again at the end.
struct TestDb {
    server: String,
    name: String,
    url: String,
}

impl TestDb {
    fn new(server: &str, name: &str) -> TestDb {
        let db = format!("glint_{name}_{}", std::process::id());
        sql(
            server,
            &format!("DROP DATABASE IF EXISTS {db} WITH (FORCE)"),
        );
        sql(server, &format!("CREATE DATABASE {db}"));
        TestDb {
            server: server.to_string(),
            url: with_db(server, &db),
            name: db,
        }
    }
}

impl Drop for TestDb {
    fn drop(&mut self) {
        let stmt = format!("DROP DATABASE IF EXISTS {} WITH (FORCE)", self.name);
        let server = self.server.clone();
        // best effort: a stopped server leaves it for the next run's DROP
        let _ = std::thread::spawn(move || sql(&server, &stmt)).join();
    }
}

/// A PostgreSQL of this test's own (`.ci/postgres.sh`), for a test that restarts it.
struct OwnPostgres {
    dir: std::path::PathBuf,
    url: String,
}

const PG_SCRIPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/.ci/postgres.sh");

impl OwnPostgres {
    fn start(name: &str) -> OwnPostgres {
        let dir = temp_dir(name).join("pgdata");
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let out = Command::new("bash")
            .args([PG_SCRIPT, "start"])
            .arg(&dir)
            .arg(port.to_string())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let url = String::from_utf8(out.stdout).unwrap().trim().to_string();
        OwnPostgres { dir, url }
    }

    fn pg(&self, cmd: &str) {
        let out = Command::new("bash")
            .args([PG_SCRIPT, cmd])
            .arg(&self.dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

impl Drop for OwnPostgres {
    fn drop(&mut self) {
        let _ = Command::new("bash")
            .args([PG_SCRIPT, "stop"])
            .arg(&self.dir)
            .output();
        if let Some(parent) = self.dir.parent() {
            let _ = std::fs::remove_dir_all(parent);
        }
    }
}

/// A `glint serve` or `glint worker` process; killed (by its id) when dropped.
struct Proc {
    child: Child,
    addr: Option<SocketAddr>,
    log: Arc<Mutex<Vec<String>>>,
}

impl Proc {
    fn pid(&self) -> u32 {
        self.child.id()
    }
    fn addr(&self) -> SocketAddr {
        self.addr.expect("an API process")
    }
    fn signal(&self, sig: &str) {
        let ok = Command::new("kill")
            .args([sig, &self.pid().to_string()])
            .status()
            .unwrap()
            .success();
        assert!(ok, "kill {sig} {}", self.pid());
    }
    /// SIGTERM, and the process waited for.
    fn stop(mut self) {
        self.signal("-TERM");
        let _ = self.child.wait();
    }
    fn log(&self) -> String {
        self.log.lock().unwrap().join("\n")
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts the binary with `args` and waits for its first line (`listening on …` for
/// `serve`, the worker's name for `worker`); its stderr is kept for failure messages.
fn spawn(args: &[&str]) -> Proc {
    let mut child = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .env_remove("GLINT_API_TOKEN")
        .env_remove("GLINT_DATABASE_URL")
        .env("GLINT_LOG", "warn")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn glint");
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let log = Arc::new(Mutex::new(Vec::new()));
    let mut addr = None;
    for line in lines.by_ref() {
        let line = line.unwrap();
        log.lock().unwrap().push(line.clone());
        if let Some(rest) = line.split("listening on http://").nth(1) {
            addr = Some(rest.split_whitespace().next().unwrap().parse().unwrap());
            break;
        }
        if line.starts_with("glint worker:") {
            break;
        }
    }
    let kept = log.clone();
    std::thread::spawn(move || {
        for l in lines.map_while(Result::ok) {
            kept.lock().unwrap().push(l);
        }
    });
    if addr.is_none() && !args.contains(&"worker") {
        panic!(
            "glint {args:?} did not start: {}",
            log.lock().unwrap().join("\n")
        );
    }
    Proc { child, addr, log }
}

/// `glint serve` on the queue at `url` with `workers` workers in it.
fn api(url: &str, workers: usize, extra: &[&str]) -> Proc {
    let w = workers.to_string();
    let mut args = vec![
        "serve",
        "--addr",
        "127.0.0.1:0",
        "--database-url",
        url,
        "--workers",
        &w,
        "--lease-secs",
        "2",
    ];
    args.extend_from_slice(extra);
    spawn(&args)
}

/// `glint worker` on the queue at `url`.
fn worker(url: &str) -> Proc {
    spawn(&[
        "worker",
        "--database-url",
        url,
        "--lease-secs",
        "2",
        "--threads",
        "1",
    ])
}

/// The worker name prefix of process `pid` in the queue's rows (`host:pid/n`).
fn rows_of(pid: u32) -> String {
    format!("%:{pid}/%")
}

/// Polls a job over HTTP until it is final, tolerating a database away meanwhile (503).
fn wait_done(addr: SocketAddr, id: &str, limit: Duration) -> serde_json::Value {
    let start = Instant::now();
    loop {
        let r = get(addr, &format!("/v1/jobs/{id}"));
        if r.status == 200 {
            let s = r.json();
            if ["done", "failed", "cancelled"].contains(&s["state"].as_str().unwrap()) {
                return s;
            }
        } else {
            assert_eq!(r.status, 503, "{}", r.text());
        }
        assert!(
            start.elapsed() < limit,
            "job {id} not final after {limit:?}"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn submit(addr: SocketAddr, body: &str, key: Option<&str>) -> serde_json::Value {
    let mut headers = vec![("Content-Type", "application/json")];
    if let Some(k) = key {
        headers.push(("Idempotency-Key", k));
    }
    let r = http(addr, "POST", "/v1/jobs", &headers, body.as_bytes());
    assert_eq!(r.status, 202, "{}", r.text());
    r.json()
}

fn result(addr: SocketAddr, id: &str, accept: &str) -> Vec<u8> {
    let r = http(
        addr,
        "GET",
        &format!("/v1/jobs/{id}/result"),
        &[("Accept", accept)],
        b"",
    );
    assert_eq!(r.status, 200, "{}", r.text());
    r.body
}

/// Every chunk of job `id` done exactly once: each done, each with exactly one result row.
fn assert_every_chunk_done_once(url: &str, id: &str, chunks: i64) {
    let q = |s: &str| count(url, &s.replace("$ID", id));
    assert_eq!(
        q("SELECT count(*) FROM glint_chunks WHERE job_id = '$ID'"),
        chunks
    );
    assert_eq!(
        q("SELECT count(*) FROM glint_chunks WHERE job_id = '$ID' AND state = 'done'"),
        chunks
    );
    assert_eq!(
        q("SELECT count(*) FROM glint_results WHERE job_id = '$ID'"),
        chunks
    );
    assert_eq!(
        q("SELECT count(DISTINCT idx) FROM glint_results WHERE job_id = '$ID'"),
        chunks
    );
}

/// The light curve's JSON `epochs` and its CSV, from the embedded store (in process).
fn embedded(body: &str) -> (serde_json::Value, Vec<u8>) {
    let server = Server::start("queue-embedded", |_| {});
    let id = submit(server.addr, body, None)["id"]
        .as_str()
        .unwrap()
        .to_string();
    let s = wait_final(server.addr, &id, &[], Duration::from_secs(600));
    assert_eq!(s["state"], "done", "{s}");
    let json: serde_json::Value =
        serde_json::from_slice(&result(server.addr, &id, "application/json")).unwrap();
    (json["epochs"].clone(), result(server.addr, &id, "text/csv"))
}

#[test]
fn three_workers_one_killed_mid_chunk_one_restarted_finish_the_job_once_bit_identical() {
    let Some(server) = server_url("three_workers_…") else {
        return;
    };
    let db = TestDb::new(&server, "kill");
    let api = api(&db.url, 0, &["--chunk-epochs", "250"]);
    let mut workers: Vec<Proc> = (0..3).map(|_| worker(&db.url)).collect();
    let body = scene_request_repeated("box-wing", 10_000);
    let id = submit(api.addr(), &body, None)["id"]
        .as_str()
        .unwrap()
        .to_string();

    // Worker 0 is frozen while it holds a chunk (so it cannot write it), then killed.
    let victim = workers.remove(0);
    let held = loop {
        victim.signal("-STOP");
        let rows = sql(
            &db.url,
            &format!(
                "SELECT idx FROM glint_chunks WHERE job_id = '{id}' AND state = 'running' \
                 AND worker LIKE '{}'",
                rows_of(victim.pid())
            ),
        );
        if let Some(r) = rows.first() {
            break r[0].clone().unwrap();
        }
        victim.signal("-CONT");
        std::thread::sleep(Duration::from_millis(20));
    };
    victim.signal("-KILL");
    let victim_rows = rows_of(victim.pid()).replace('%', "");
    drop(victim);

    // Another is stopped gracefully once some chunks are done, and started again.
    while count(
        &db.url,
        &format!("SELECT count(*) FROM glint_chunks WHERE job_id = '{id}' AND state = 'done'"),
    ) < 8
    {
        std::thread::sleep(Duration::from_millis(50));
    }
    workers.remove(0).stop();
    workers.push(worker(&db.url));

    let s = wait_done(api.addr(), &id, Duration::from_secs(900));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["epochs_done"], 10_000);
    assert_every_chunk_done_once(&db.url, &id, 40);
    // the killed worker's chunk went back to the queue and was done by another
    let row = &sql(
        &db.url,
        &format!("SELECT done_by, claims FROM glint_chunks WHERE job_id = '{id}' AND idx = {held}"),
    )[0];
    let done_by = row[0].clone().unwrap();
    assert!(!done_by.contains(&victim_rows), "{row:?}");
    assert!(
        row[1].as_deref().unwrap().parse::<i64>().unwrap() >= 2,
        "{row:?}"
    );

    let json: serde_json::Value =
        serde_json::from_slice(&result(api.addr(), &id, "application/json")).unwrap();
    let csv = result(api.addr(), &id, "text/csv");
    let (epochs, embedded_csv) = embedded(&body);
    assert!(
        csv == embedded_csv,
        "the CSV differs from the embedded store's"
    );
    assert_eq!(
        serde_json::to_string(&json["epochs"]).unwrap(),
        serde_json::to_string(&epochs).unwrap()
    );
    assert_eq!(json["summary"]["epochs"], 10_000);
    for w in &workers {
        assert!(!w.log().contains("panicked"), "{}", w.log());
    }
}

#[test]
fn postgres_restarted_mid_job_workers_reconnect_and_the_job_finishes() {
    let Some(_) = server_url("postgres_restarted_…") else {
        return;
    };
    let pg = OwnPostgres::start("queue-pg-restart");
    let api = api(&pg.url, 1, &["--chunk-epochs", "100"]);
    let _w = worker(&pg.url);
    let body = scene_request_repeated("box-wing", 3_000);
    let id = submit(api.addr(), &body, None)["id"]
        .as_str()
        .unwrap()
        .to_string();
    while count(
        &pg.url,
        &format!("SELECT count(*) FROM glint_chunks WHERE job_id = '{id}' AND state = 'done'"),
    ) < 3
    {
        std::thread::sleep(Duration::from_millis(50));
    }
    pg.pg("stop");
    // a database fault is a 503 with Retry-After, not a 500
    let r = get(api.addr(), &format!("/v1/jobs/{id}"));
    assert_eq!(r.status, 503, "{}", r.text());
    assert!(r.header("retry-after").is_some());
    assert!(r.json()["error"].as_str().unwrap().contains("database"));
    let ready = get(api.addr(), "/readyz");
    assert_eq!(ready.status, 503);
    std::thread::sleep(Duration::from_secs(3));
    pg.pg("resume");

    let s = wait_done(api.addr(), &id, Duration::from_secs(600));
    assert_eq!(s["state"], "done", "{s}\n{}", api.log());
    assert_every_chunk_done_once(&pg.url, &id, 30);
    assert_eq!(get(api.addr(), "/readyz").status, 200);
    let csv = result(api.addr(), &id, "text/csv");
    let direct = glint::report::csv::to_csv(&direct(&body)).into_bytes();
    assert!(csv == direct, "the CSV differs from the engine's");
}

#[test]
fn two_hundred_jobs_through_two_api_processes_are_neither_lost_nor_duplicated() {
    let Some(server) = server_url("two_hundred_jobs_…") else {
        return;
    };
    let db = TestDb::new(&server, "many");
    let apis = [api(&db.url, 1, &[]), api(&db.url, 1, &[])];
    let addrs: Vec<SocketAddr> = apis.iter().map(Proc::addr).collect();
    let body = Arc::new(scene_request("box-wing", 3));
    // 200 submissions from 20 threads, alternating between the two APIs; each is sent
    // twice with its Idempotency-Key, the retry through the other API.
    let ids: Vec<(String, String)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..20)
            .map(|t| {
                let addrs = addrs.clone();
                let body = body.clone();
                s.spawn(move || {
                    (0..10)
                        .map(|i| {
                            let n = t * 10 + i;
                            let key = format!("job-{n}");
                            let first = submit(addrs[n % 2], &body, Some(&key));
                            let again = submit(addrs[(n + 1) % 2], &body, Some(&key));
                            (
                                first["id"].as_str().unwrap().to_string(),
                                again["id"].as_str().unwrap().to_string(),
                            )
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    assert_eq!(ids.len(), 200);
    for (a, b) in &ids {
        assert_eq!(a, b, "a retry with the same key made a second job");
    }
    let unique: std::collections::HashSet<&String> = ids.iter().map(|(a, _)| a).collect();
    assert_eq!(unique.len(), 200);
    assert_eq!(count(&db.url, "SELECT count(*) FROM glint_jobs"), 200);
    for (n, (id, _)) in ids.iter().enumerate() {
        let s = wait_done(addrs[n % 2], id, Duration::from_secs(600));
        assert_eq!(s["state"], "done", "{s}");
        let json: serde_json::Value =
            serde_json::from_slice(&result(addrs[(n + 1) % 2], id, "application/json")).unwrap();
        assert_eq!(json["epochs"].as_array().unwrap().len(), 3);
    }
    assert_eq!(
        count(&db.url, "SELECT count(*) FROM glint_results"),
        200,
        "one result row a job (each is one chunk)"
    );
    let listed = get(addrs[0], "/v1/jobs?limit=1000&state=done").json();
    assert_eq!(listed.as_array().unwrap().len(), 200);
}

#[test]
fn a_cancel_while_chunks_are_in_flight_lets_no_chunk_be_written_after_it() {
    let Some(server) = server_url("a_cancel_…") else {
        return;
    };
    let db = TestDb::new(&server, "cancel");
    let api = api(&db.url, 1, &["--chunk-epochs", "200"]);
    let _w = worker(&db.url);
    let body = scene_request_repeated("box-wing", 20_000);
    let id = submit(api.addr(), &body, None)["id"]
        .as_str()
        .unwrap()
        .to_string();
    let done_q =
        format!("SELECT count(*) FROM glint_chunks WHERE job_id = '{id}' AND state = 'done'");
    let running_q =
        format!("SELECT count(*) FROM glint_chunks WHERE job_id = '{id}' AND state = 'running'");
    while count(&db.url, &done_q) < 2 || count(&db.url, &running_q) == 0 {
        std::thread::sleep(Duration::from_millis(10));
    }
    let r = http(api.addr(), "DELETE", &format!("/v1/jobs/{id}"), &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["state"], "cancelled");
    // what the cancel committed: nothing is added after it
    let results_q = format!("SELECT count(*) FROM glint_results WHERE job_id = '{id}'");
    let (done, results) = (count(&db.url, &done_q), count(&db.url, &results_q));
    assert_eq!(done, results);
    assert!(
        done < 100,
        "the job finished before the cancel: {done} chunks"
    );
    // longer than a chunk and a lease: any chunk in flight has been stopped or refused
    std::thread::sleep(Duration::from_secs(5));
    assert_eq!(count(&db.url, &done_q), done);
    assert_eq!(count(&db.url, &results_q), results);
    let s = get(api.addr(), &format!("/v1/jobs/{id}")).json();
    assert_eq!(s["state"], "cancelled");
    assert_eq!(
        count(
            &db.url,
            "SELECT count(*) FROM glint_chunks c JOIN glint_jobs j ON j.id = c.job_id \
             WHERE j.state IN ('queued', 'running')"
        ),
        0
    );
    // a DELETE of the cancelled job removes it with its chunks and results
    let r = http(api.addr(), "DELETE", &format!("/v1/jobs/{id}"), &[], b"");
    assert_eq!(r.status, 204);
    assert_eq!(count(&db.url, &results_q), 0);
    assert_eq!(get(api.addr(), &format!("/v1/jobs/{id}")).status, 404);
}

#[test]
fn a_database_of_another_schema_version_is_refused_with_the_reason() {
    let Some(server) = server_url("a_database_of_another_schema_version_…") else {
        return;
    };
    let db = TestDb::new(&server, "schema");
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_glint"))
            .args(["worker", "--database-url", &db.url])
            .args(extra)
            .env_remove("GLINT_DATABASE_URL")
            .stdin(Stdio::null())
            .output()
            .unwrap();
        (
            out.status.success(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    // an empty database is older than the binary: refused when migrating is off
    let (ok, err) = run(&["--no-migrate"]);
    assert!(!ok);
    assert!(
        err.contains("schema is version 0, older than this glint's 1"),
        "{err}"
    );
    // migrated by the first process that starts (idempotent: twice is the same)
    let a = api(&db.url, 0, &[]);
    let b = api(&db.url, 0, &[]);
    assert_eq!(
        count(&db.url, "SELECT count(*) FROM glint_schema_version"),
        1
    );
    drop((a, b));
    sql(
        &db.url,
        "INSERT INTO glint_schema_version (version) VALUES (2)",
    );
    let (ok, err) = run(&[]);
    assert!(!ok);
    assert!(
        err.contains("schema is version 2, newer than this glint's 1"),
        "{err}"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["serve", "--addr", "127.0.0.1:0", "--database-url", &db.url])
        .env_remove("GLINT_DATABASE_URL")
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("newer than this glint's 1"));
}

#[test]
fn the_api_is_the_same_on_the_shared_queue_fits_thumbnails_and_errors() {
    let Some(server) = server_url("the_api_is_the_same_…") else {
        return;
    };
    let db = TestDb::new(&server, "api");
    let api = api(&db.url, 1, &[]);
    // a request with thumbnails is one chunk; its images are served as on the embedded store
    let mut req: serde_json::Value = serde_json::from_str(&scene_request("box-wing", 6)).unwrap();
    req["thumbnails"] = serde_json::json!({ "size": 16, "samples": 1, "epochs": [0, 4] });
    let body = req.to_string();
    let id = submit(api.addr(), &body, None)["id"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(
        wait_done(api.addr(), &id, Duration::from_secs(300))["state"],
        "done"
    );
    let png = get(api.addr(), &format!("/v1/jobs/{id}/thumbnails/4.png"));
    assert_eq!(png.status, 200);
    assert!(png.body.starts_with(b"\x89PNG"));
    assert_eq!(
        get(api.addr(), &format!("/v1/jobs/{id}/thumbnails/3.png")).status,
        404
    );
    let want = direct(&body);
    let json: glint::Response =
        serde_json::from_slice(&result(api.addr(), &id, "application/json")).unwrap();
    assert_eq!(json.epochs, want.epochs);
    assert_eq!(json.thumbnails, want.thumbnails);

    // bad input: the same 4xx naming the field, never a 5xx
    let r = post_json(api.addr(), "/v1/jobs", r#"{"object": 3}"#);
    assert_eq!(r.status, 422, "{}", r.text());
    assert_eq!(r.json()["field"], "object");
    let r = http(
        api.addr(),
        "POST",
        "/v1/jobs",
        &[
            ("Content-Type", "application/json"),
            ("Idempotency-Key", "k1"),
        ],
        body.as_bytes(),
    );
    assert_eq!(r.status, 202);
    let r = http(
        api.addr(),
        "POST",
        "/v1/jobs",
        &[
            ("Content-Type", "application/json"),
            ("Idempotency-Key", "k1"),
        ],
        scene_request("box-wing", 2).as_bytes(),
    );
    assert_eq!(r.status, 422);
    assert_eq!(r.json()["field"], "Idempotency-Key");
    assert_eq!(get(api.addr(), "/v1/jobs/nope").status, 404);

    // a fit job is one chunk, and gives the library's fit
    let (request, observed) = fit_inputs("box-wing", 24, 1, 0.25, 0.4, 7);
    let fit_body = serde_json::json!({
        "request": request, "observed": observed, "free": ["materials.panel.albedo"],
    });
    let r = post_json(api.addr(), "/v1/fits/lightcurve", &fit_body.to_string());
    assert_eq!(r.status, 202, "{}", r.text());
    let fid = r.json()["id"].as_str().unwrap().to_string();
    let s = wait_done(api.addr(), &fid, Duration::from_secs(600));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["percent"], 100.0);
    let fit: serde_json::Value =
        serde_json::from_slice(&result(api.addr(), &fid, "application/json")).unwrap();
    let want = serde_json::to_value(direct_fit(&fit_body)).unwrap();
    assert_eq!(fit["parameters"], want["parameters"]);
    let csv = http(
        api.addr(),
        "GET",
        &format!("/v1/jobs/{fid}/result"),
        &[("Accept", "text/csv")],
        b"",
    );
    assert_eq!(csv.status, 406);
}
