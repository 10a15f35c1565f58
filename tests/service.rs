//! The HTTP service, in process on a loopback port, spoken to over real HTTP.
//!
//! The truths checked here are the engine's own direct results (the service must add
//! nothing and lose nothing: JSON round-trips f64 exactly, so results are compared for
//! equality), the committed OpenAPI file, and the documented error shapes.

mod service_support;

use glint::service::openapi::spec_json;
use service_support::*;
use std::time::Duration;

const JSON: (&str, &str) = ("Content-Type", "application/json");

/// Every error answer has the documented shape: a JSON object with an `error` string and,
/// when given, a `field` string.
fn assert_error(r: &Reply, status: u16, field: Option<&str>) {
    assert_eq!(r.status, status, "{}", r.text());
    assert!(
        r.header("content-type")
            .unwrap_or("")
            .starts_with("application/json"),
        "{:?}",
        r.headers
    );
    let v = r.json();
    assert!(v["error"].as_str().is_some_and(|s| !s.is_empty()), "{v}");
    if let Some(f) = field {
        assert_eq!(v["field"].as_str(), Some(f), "{v}");
    }
}

#[test]
fn lightcurve_json_and_csv_equal_the_engine() {
    let server = Server::start("sync", |_| {});
    let req = scene_request("box-wing", 12);
    let want = direct(&req);

    let r = post_json(server.addr, "/v1/lightcurves", &req);
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.header("content-type"), Some("application/json"));
    let got: glint::Response = serde_json::from_slice(&r.body).unwrap();
    // Same engine, same input: bit-identical epochs (serde_json round-trips f64 exactly).
    assert_eq!(got.epochs, want.epochs);
    assert_eq!(got.summary.triangles, want.summary.triangles);
    assert_eq!(got.summary.rays, want.summary.rays);

    let r = http(
        server.addr,
        "POST",
        "/v1/lightcurves",
        &[JSON, ("Accept", "text/csv")],
        req.as_bytes(),
    );
    assert_eq!(r.status, 200, "{}", r.text());
    assert!(r.header("content-type").unwrap().starts_with("text/csv"));
    assert_eq!(r.text(), glint::report::csv::to_csv(&want));

    // The request counts and epochs show up in the metrics.
    let m = get(server.addr, "/metrics").text();
    assert!(
        m.contains(&format!(
            "glint_epochs_computed_total{{kind=\"sync\"}} {}",
            2 * 12
        )),
        "{m}"
    );
    assert!(
        m.contains(
            "glint_http_requests_total{method=\"POST\",route=\"/v1/lightcurves\",status=\"200\"} 2"
        ),
        "{m}"
    );
}

#[test]
fn job_submitted_polled_fetched_and_removed() {
    let server = Server::start("job", |_| {});
    let req = scene_request("box-wing", 40);
    let want = direct(&req);

    let r = post_json(server.addr, "/v1/jobs", &req);
    assert_eq!(r.status, 202, "{}", r.text());
    let status = r.json();
    let id = status["id"].as_str().unwrap().to_string();
    assert_eq!(
        r.header("location"),
        Some(format!("/v1/jobs/{id}").as_str())
    );
    assert_eq!(status["epochs_total"], 40);
    assert!(status["created_at"].as_str().unwrap().ends_with('Z'));

    let s = wait_final(server.addr, &id, &[], Duration::from_secs(120));
    assert_eq!(s["state"], "done", "{s}");
    assert_eq!(s["epochs_done"], 40);
    assert_eq!(s["percent"], 100.0);
    assert_eq!(s["attempts"], 1);
    for k in ["started_at", "finished_at", "expires_at"] {
        assert!(s[k].is_string(), "{k} missing in {s}");
    }
    assert_eq!(s["result_url"], format!("/v1/jobs/{id}/result"));

    let r = get(server.addr, &format!("/v1/jobs/{id}/result"));
    assert_eq!(r.status, 200, "{}", r.text());
    let got: glint::Response = serde_json::from_slice(&r.body).unwrap();
    assert_eq!(got.epochs, want.epochs);

    let r = http(
        server.addr,
        "GET",
        &format!("/v1/jobs/{id}/result"),
        &[("Accept", "text/csv")],
        b"",
    );
    assert_eq!(r.text(), glint::report::csv::to_csv(&want));

    // No renderer output in this request: no thumbnail for any epoch.
    let r = get(server.addr, &format!("/v1/jobs/{id}/thumbnails/0.png"));
    assert_error(&r, 404, Some("epoch"));

    let list = get(server.addr, "/v1/jobs?limit=10").json();
    assert_eq!(list.as_array().unwrap().len(), 1);
    assert_eq!(list[0]["id"], id.as_str());
    assert_eq!(
        get(server.addr, "/v1/jobs?state=queued").json(),
        serde_json::json!([])
    );
    assert_error(&get(server.addr, "/v1/jobs?limit=0"), 400, Some("limit"));
    assert_error(
        &get(server.addr, "/v1/jobs?state=sleeping"),
        400,
        Some("state"),
    );
    assert_error(&get(server.addr, "/v1/jobs?limit=abc"), 400, Some("limit"));

    let m = get(server.addr, "/metrics").text();
    assert!(m.contains("glint_jobs{state=\"done\"} 1"), "{m}");
    assert!(
        m.contains("glint_epochs_computed_total{kind=\"job\"} 40"),
        "{m}"
    );

    // A finished job is removed by DELETE, result and all.
    let r = http(server.addr, "DELETE", &format!("/v1/jobs/{id}"), &[], b"");
    assert_eq!(r.status, 204, "{}", r.text());
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}")),
        404,
        Some("id"),
    );
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}/result")),
        404,
        Some("id"),
    );
}

#[test]
fn cancellation_and_a_full_service() {
    // One computation slot and no waiting room: a running job makes the service busy.
    let server = Server::start("cancel", |c| {
        c.limits.max_concurrent = 1;
        c.limits.max_queued = 0;
        c.limits.max_running_jobs = 1;
    });
    // Long enough (tens of seconds in a debug build) to be cancelled mid-run.
    let big = scene_request_repeated("box-wing", 40_000);
    let a = post_json(server.addr, "/v1/jobs", &big).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let b = post_json(server.addr, "/v1/jobs", &big).json()["id"]
        .as_str()
        .unwrap()
        .to_string();

    // Wait until `a` is running and has computed something.
    let start = std::time::Instant::now();
    loop {
        let s = get(server.addr, &format!("/v1/jobs/{a}")).json();
        if s["state"] == "running" && s["epochs_done"].as_u64().unwrap() > 0 {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "job never ran: {s}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    // `b` waits behind `a` (one job at a time).
    assert_eq!(
        get(server.addr, &format!("/v1/jobs/{b}")).json()["state"],
        "queued"
    );

    // The only slot is taken: a light curve is turned away with Retry-After.
    let small = scene_request("plate", 2);
    let r = post_json(server.addr, "/v1/lightcurves", &small);
    assert_error(&r, 503, None);
    assert_eq!(r.header("retry-after"), Some("1"));
    // …but bad input still gets its 4xx, not the 503: validation comes first.
    assert_error(&post_json(server.addr, "/v1/lightcurves", "{}"), 422, None);

    // Cancel the queued one, then the running one.
    for id in [&b, &a] {
        let r = http(server.addr, "DELETE", &format!("/v1/jobs/{id}"), &[], b"");
        assert_eq!(r.status, 200, "{}", r.text());
        assert_eq!(r.json()["state"], "cancelled");
    }
    let s = get(server.addr, &format!("/v1/jobs/{a}")).json();
    let done = s["epochs_done"].as_u64().unwrap();
    assert!(done > 0 && done < 40_000, "{s}");
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{a}/result")),
        409,
        None,
    );

    // The slot comes back once the engine stops at its next epoch.
    let start = std::time::Instant::now();
    loop {
        let r = post_json(server.addr, "/v1/lightcurves", &small);
        if r.status == 200 {
            break;
        }
        assert_error(&r, 503, None);
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "slot never freed"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    // Both stay cancelled: nothing runs them again.
    std::thread::sleep(Duration::from_millis(300));
    for id in [&a, &b] {
        assert_eq!(
            get(server.addr, &format!("/v1/jobs/{id}")).json()["state"],
            "cancelled"
        );
    }
}

#[test]
fn every_error_class_has_the_json_shape() {
    let server = Server::start("errors", |c| {
        c.limits.max_body_bytes = 64 * 1024;
        c.limits.max_sync_epochs = 10;
        c.limits.max_job_epochs = 20;
        c.limits.max_triangles = 100;
    });
    let addr = server.addr;
    let ok = scene_request("plate", 3);

    // 415: no or wrong content type.
    assert_error(
        &http(addr, "POST", "/v1/lightcurves", &[], ok.as_bytes()),
        415,
        Some("Content-Type"),
    );
    assert_error(
        &http(
            addr,
            "POST",
            "/v1/jobs",
            &[("Content-Type", "text/plain")],
            ok.as_bytes(),
        ),
        415,
        Some("Content-Type"),
    );
    // 400: broken JSON, empty body.
    assert_error(
        &post_json(addr, "/v1/lightcurves", "{\"object\": "),
        400,
        None,
    );
    assert_error(&post_json(addr, "/v1/lightcurves", ""), 400, Some("body"));
    // 422: a field given twice, an array of the wrong length, each named
    assert_error(
        &post_json(
            addr,
            "/v1/lightcurves",
            r#"{"method": "auto", "method": "image"}"#,
        ),
        422,
        Some("method"),
    );
    let mut v: serde_json::Value = serde_json::from_str(&ok).unwrap();
    v["epochs"][0]["sun"] = serde_json::json!([1, 0, 0, 1]);
    assert_error(
        &post_json(addr, "/v1/lightcurves", &v.to_string()),
        422,
        Some("epochs[0].sun"),
    );
    // 422: unknown field, wrong type, bad value — each naming its field.
    let mut v: serde_json::Value = serde_json::from_str(&ok).unwrap();
    v["colour"] = "red".into();
    assert_error(
        &post_json(addr, "/v1/lightcurves", &v.to_string()),
        422,
        Some("colour"),
    );
    let mut v: serde_json::Value = serde_json::from_str(&ok).unwrap();
    v["epochs"][1]["sun"] = "up".into();
    assert_error(
        &post_json(addr, "/v1/lightcurves", &v.to_string()),
        422,
        Some("epochs[1].sun"),
    );
    let mut v: serde_json::Value = serde_json::from_str(&ok).unwrap();
    v["epochs"][2]["observer"] = serde_json::json!([0.0, 0.0, 0.0]);
    assert_error(
        &post_json(addr, "/v1/lightcurves", &v.to_string()),
        422,
        Some("epochs[2].observer"),
    );
    // 413: body over the byte limit; epochs over the synchronous limit (a job takes them);
    // epochs over the job limit; a mesh over the triangle limit.
    let huge = format!("{{\"pad\": \"{}\"}}", "x".repeat(100 * 1024));
    assert_error(
        &post_json(addr, "/v1/lightcurves", &huge),
        413,
        Some("body"),
    );
    assert_error(&post_json(addr, "/v1/jobs", &huge), 413, Some("body"));
    let eleven = scene_request("plate", 11);
    assert_error(
        &post_json(addr, "/v1/lightcurves", &eleven),
        413,
        Some("epochs"),
    );
    assert_eq!(post_json(addr, "/v1/jobs", &eleven).status, 202);
    assert_error(
        &post_json(addr, "/v1/jobs", &scene_request("plate", 21)),
        413,
        Some("epochs"),
    );
    let sphere = scene_request("sphere", 1); // 1280 triangles
    let r = post_json(addr, "/v1/lightcurves", &sphere);
    assert_error(&r, 413, None);
    // 404: unknown route, job, scene; 405 on a known route.
    assert_error(&get(addr, "/v2/nothing"), 404, None);
    assert_error(&get(addr, "/v1/jobs/not-a-job"), 404, Some("id"));
    assert_error(
        &http(addr, "DELETE", "/v1/jobs/not-a-job", &[], b""),
        404,
        Some("id"),
    );
    assert_error(&get(addr, "/v1/scenes/teapot"), 404, Some("name"));
    let r = get(addr, "/v1/lightcurves");
    assert_error(&r, 405, None);
    assert_eq!(r.header("allow"), Some("POST"));
    // Still healthy after all that.
    assert_eq!(get(addr, "/healthz").status, 200);
}

#[test]
fn bearer_token_when_set_and_loopback_when_not() {
    let server = Server::start("auth", |c| c.token = Some("s3cret".into()));
    let addr = server.addr;
    assert_eq!(get(addr, "/healthz").status, 200);
    assert_eq!(get(addr, "/readyz").status, 200);
    for path in ["/v1/scenes", "/v1/jobs", "/metrics", "/openapi.json"] {
        let r = get(addr, path);
        assert_error(&r, 401, Some("Authorization"));
        assert_eq!(r.header("www-authenticate"), Some("Bearer"));
        assert_error(
            &http(addr, "GET", path, &[("Authorization", "Bearer nope")], b""),
            401,
            None,
        );
        let r = http(
            addr,
            "GET",
            path,
            &[("Authorization", "Bearer s3cret")],
            b"",
        );
        assert_eq!(r.status, 200, "{path}: {}", r.text());
        // the scheme is case-insensitive (RFC 9110 §11.1), the token is not
        for auth in ["bearer s3cret", "BEARER  s3cret"] {
            let r = http(addr, "GET", path, &[("Authorization", auth)], b"");
            assert_eq!(r.status, 200, "{auth} on {path}: {}", r.text());
        }
        for auth in ["Bearer S3CRET", "Basic s3cret", "Bearers3cret"] {
            assert_error(
                &http(addr, "GET", path, &[("Authorization", auth)], b""),
                401,
                None,
            );
        }
    }
    let req = scene_request("plate", 2);
    assert_error(&post_json(addr, "/v1/lightcurves", &req), 401, None);
    let r = http(
        addr,
        "POST",
        "/v1/lightcurves",
        &[JSON, ("Authorization", "Bearer s3cret")],
        req.as_bytes(),
    );
    assert_eq!(r.status, 200, "{}", r.text());

    // Without a token everything is open…
    let open = Server::start("noauth", |_| {});
    assert_eq!(get(open.addr, "/v1/scenes").status, 200);
    // …which is only allowed on loopback unless explicitly accepted.
    let rt = tokio::runtime::Runtime::new().unwrap();
    let config = glint::service::Config {
        addr: "0.0.0.0:0".parse().unwrap(),
        data_dir: temp_dir("refuse"),
        ..Default::default()
    };
    let err = rt
        .block_on(glint::service::start(config))
        .err()
        .expect("refused");
    assert!(err.to_string().contains("GLINT_API_TOKEN"), "{err}");
}

#[test]
fn scenes_are_the_builtins_and_the_example_files() {
    let server = Server::start("scenes", |_| {});
    let list = get(server.addr, "/v1/scenes").json();
    for b in glint::geometry::builtin::BUILTINS {
        let s = list
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == b.name)
            .unwrap_or_else(|| panic!("{} not listed", b.name));
        assert_eq!(s["triangles"], b.mesh().triangles.len());
        assert_eq!(s["materials"], serde_json::json!(b.material_names));
    }
    for name in ["box-wing", "sphere", "plate", "iss-pass", "geo-night"] {
        let r = get(server.addr, &format!("/v1/scenes/{name}"));
        assert_eq!(r.status, 200);
        let file =
            std::fs::read_to_string(format!("{}/scenes/{name}.json", env!("CARGO_MANIFEST_DIR")))
                .unwrap();
        let want: serde_json::Value = serde_json::from_str(&file).unwrap();
        assert_eq!(r.json(), want, "{name}");
    }
}

#[test]
fn docs_and_spec_are_served_and_the_spec_example_is_a_valid_request() {
    let server = Server::start("docs", |_| {});
    let spec = get(server.addr, "/openapi.json").json();
    let example = spec["paths"]["/v1/lightcurves"]["post"]["requestBody"]["content"]
        ["application/json"]["example"]
        .clone();
    assert!(example.is_object(), "no example in the spec");
    let r = post_json(server.addr, "/v1/lightcurves", &example.to_string());
    assert_eq!(r.status, 200, "{}", r.text());
    let r = get(server.addr, "/docs/");
    assert_eq!(r.status, 200);
    assert!(r.text().contains("swagger"), "{}", r.text());
}

/// Regenerate with `cargo run -- openapi > openapi/openapi.json`.
#[test]
fn committed_openapi_matches_the_code() {
    let path = format!("{}/openapi/openapi.json", env!("CARGO_MANIFEST_DIR"));
    let committed = std::fs::read_to_string(&path).expect("openapi/openapi.json exists");
    let generated = spec_json();
    if committed != generated {
        let line = committed
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .map_or(
                committed.lines().count().min(generated.lines().count()),
                |i| i,
            );
        panic!(
            "openapi/openapi.json differs from the code from line {} on; regenerate it with \
             `cargo run -- openapi > openapi/openapi.json`",
            line + 1
        );
    }
}

#[test]
fn thumbnails_of_a_finished_job_are_served_as_png() {
    let server = Server::start("thumbs", |_| {});
    let mut req: serde_json::Value = serde_json::from_str(&scene_request("box-wing", 6)).unwrap();
    req["thumbnails"] = serde_json::json!({ "size": 16, "samples": 1, "epochs": [0, 4] });
    let r = post_json(server.addr, "/v1/jobs", &req.to_string());
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().unwrap().to_string();
    assert_eq!(
        wait_final(server.addr, &id, &[], Duration::from_secs(120))["state"],
        "done"
    );
    let result: glint::Response =
        serde_json::from_slice(&get(server.addr, &format!("/v1/jobs/{id}/result")).body).unwrap();
    let thumbs = result.thumbnails.expect("the request asked for thumbnails");
    for t in &thumbs {
        let r = get(
            server.addr,
            &format!("/v1/jobs/{id}/thumbnails/{}.png", t.epoch),
        );
        assert_eq!(r.status, 200, "{}", r.text());
        assert_eq!(r.header("content-type"), Some("image/png"));
        // The served bytes are the stored image, decoded from base64, and a PNG of the
        // requested size.
        use base64::Engine as _;
        let want = base64::engine::general_purpose::STANDARD
            .decode(&t.png_base64)
            .unwrap();
        assert_eq!(r.body, want);
        let img = image::load_from_memory_with_format(&r.body, image::ImageFormat::Png).unwrap();
        assert_eq!((img.width(), img.height()), (16, 16));
    }
    assert_eq!(
        thumbs.iter().map(|t| t.epoch).collect::<Vec<_>>(),
        vec![0, 4]
    );
    // An epoch that was not rendered, and a file name that is not `{epoch}.png`.
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}/thumbnails/1.png")),
        404,
        Some("epoch"),
    );
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}/thumbnails/zero.png")),
        404,
        Some("epoch"),
    );
}

#[test]
fn a_light_curve_over_the_request_timeout_is_stopped_and_frees_its_slot() {
    let server = Server::start("timeout", |c| {
        c.limits.request_timeout = Duration::from_millis(1);
        c.limits.max_concurrent = 1;
    });
    // 20 000 epochs take over a minute in a debug build, and cannot finish in 1 ms.
    let r = post_json(
        server.addr,
        "/v1/lightcurves",
        &scene_request_repeated("box-wing", 20_000),
    );
    assert_error(&r, 503, None);
    assert!(
        r.json()["error"]
            .as_str()
            .unwrap()
            .contains("POST /v1/jobs"),
        "{}",
        r.text()
    );
    // The engine is told to stop at its next epoch, so the only slot comes back long
    // before the 20 000 epochs could have been computed (the gauge reads 0 again).
    let start = std::time::Instant::now();
    loop {
        let m = get(server.addr, "/metrics").text();
        if m.contains("glint_computations_running 0") {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(30), "{m}");
        std::thread::sleep(Duration::from_millis(20));
    }
    let m = get(server.addr, "/metrics").text();
    assert!(
        m.contains("glint_epochs_computed_total{kind=\"sync\"} 0"),
        "{m}"
    );
}

#[test]
fn a_light_curve_is_answered_while_a_long_job_runs() {
    // Two slots: one for the job, one for light curves.
    let server = Server::start("share", |c| c.limits.max_concurrent = 2);
    let big = scene_request_repeated("box-wing", 40_000);
    let job = post_json(server.addr, "/v1/jobs", &big).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let start = std::time::Instant::now();
    while get(server.addr, &format!("/v1/jobs/{job}")).json()["epochs_done"]
        .as_u64()
        .unwrap()
        == 0
    {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the job never started"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    // The light curve does not queue behind the job's epochs: it is answered while the
    // job (minutes of work in a debug build) is still running.
    let r = post_json(
        server.addr,
        "/v1/lightcurves",
        &scene_request("box-wing", 4),
    );
    assert_eq!(r.status, 200, "{}", r.text());
    let s = get(server.addr, &format!("/v1/jobs/{job}")).json();
    assert_eq!(s["state"], "running", "{s}");
    assert_eq!(
        http(server.addr, "DELETE", &format!("/v1/jobs/{job}"), &[], b"").status,
        200
    );
}

#[test]
fn finished_jobs_expire_after_the_time_to_live() {
    let server = Server::start("ttl", |c| c.result_ttl = Duration::from_secs(1));
    let r = post_json(server.addr, "/v1/jobs", &scene_request("plate", 3));
    let id = r.json()["id"].as_str().unwrap().to_string();
    let s = wait_final(server.addr, &id, &[], Duration::from_secs(60));
    assert_eq!(s["state"], "done");
    assert!(s["expires_at"].is_string(), "{s}");
    // The sweeper runs every second here; give it ample time.
    let start = std::time::Instant::now();
    while get(server.addr, &format!("/v1/jobs/{id}")).status != 404 {
        assert!(start.elapsed() < Duration::from_secs(30), "never expired");
        std::thread::sleep(Duration::from_millis(100));
    }
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}/result")),
        404,
        Some("id"),
    );
    assert_eq!(get(server.addr, "/v1/jobs").json(), serde_json::json!([]));
}

/// An engine that fails the way a bug would: a panic inside the engine's thread pool,
/// with a message that must never reach a client.
fn panicking_engine(
    _: &glint::Scene,
    _: &glint::Progress,
) -> Result<glint::Response, glint::Cancelled> {
    use rayon::prelude::*;
    (0..8).into_par_iter().for_each(|i| {
        if i == 5 {
            panic!("secret detail of the fault");
        }
    });
    unreachable!("the panic above always happens")
}

#[test]
fn a_panic_in_a_computation_is_a_500_with_the_request_id_and_frees_the_slot() {
    // One slot and no waiting room: a slot the panic kept would turn the next request
    // into a 503.
    let server = Server::start("panic", |c| {
        c.engine = panicking_engine;
        c.limits.max_concurrent = 1;
        c.limits.max_queued = 0;
    });
    let req = scene_request("plate", 2);
    for i in 0..3 {
        let id = format!("client-id-{i}");
        let r = http(
            server.addr,
            "POST",
            "/v1/lightcurves",
            &[JSON, ("X-Request-Id", &id)],
            req.as_bytes(),
        );
        assert_error(&r, 500, None);
        assert!(!r.text().contains("secret"), "{}", r.text());
        assert_eq!(r.header("x-request-id"), Some(id.as_str()));
        assert_eq!(r.json()["request_id"], id.as_str(), "{}", r.text());
        assert!(r.json()["error"].as_str().unwrap().contains(&id));
    }
    // Without the client's id the service makes one and answers it the same way.
    let r = post_json(server.addr, "/v1/lightcurves", &req);
    assert_error(&r, 500, None);
    let id = r.header("x-request-id").expect("an id").to_string();
    assert_eq!(r.json()["request_id"], id.as_str());
    // Every answer carries an id, not only faults.
    assert!(get(server.addr, "/healthz")
        .header("x-request-id")
        .is_some());

    // A job's computation fails the same way: `failed`, no panic text, and the slot
    // comes back for the next request.
    let job = post_json(server.addr, "/v1/jobs", &req).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let s = wait_final(server.addr, &job, &[], Duration::from_secs(30));
    assert_eq!(s["state"], "failed", "{s}");
    let msg = s["error"].as_str().unwrap();
    assert!(!msg.contains("secret") && msg.contains(&job), "{s}");
    assert_error(&post_json(server.addr, "/v1/lightcurves", &req), 500, None);
}

#[test]
fn work_is_bounded_before_it_starts() {
    let server = Server::start("work", |c| {
        c.limits.max_sync_pixel_samples = 1_000_000;
        c.limits.max_sync_triangle_epochs = 1_000;
    });
    // 1 epoch × 512² px × 4² samples = 4.2 M samples: over the light-curve limit…
    let mut v: serde_json::Value = serde_json::from_str(&scene_request("plate", 1)).unwrap();
    v["method"] = "image".into();
    v["image_size"] = 512.into();
    v["image_samples"] = 4.into();
    let r = post_json(server.addr, "/v1/lightcurves", &v.to_string());
    assert_error(&r, 413, Some("image_size"));
    assert!(r.text().contains("POST /v1/jobs") || r.text().contains("job"));
    // …within a job's (100×)
    assert_eq!(
        post_json(server.addr, "/v1/jobs", &v.to_string()).status,
        202
    );

    // triangles × epochs: the plate's 2 triangles × 600 epochs = 1,200 > 1,000
    let r = post_json(
        server.addr,
        "/v1/lightcurves",
        &scene_request_repeated("plate", 600),
    );
    assert_error(&r, 413, Some("epochs"));
    let ok = post_json(
        server.addr,
        "/v1/lightcurves",
        &scene_request_repeated("plate", 500),
    );
    assert_eq!(ok.status, 200, "{}", ok.text());
}

#[test]
fn an_image_epoch_over_the_deadline_stops_within_the_epoch() {
    // One epoch of the `image` method at 2048 px × 16² samples is ~10⁹ samples: minutes
    // of work, all inside one epoch. Cancellation is polled once a row, so the slot must
    // come back about one row's time after the deadline, not at the epoch's end.
    let server = Server::start("image-deadline", |c| {
        c.limits.request_timeout = Duration::from_millis(500);
        c.limits.max_concurrent = 1;
        c.limits.max_sync_pixel_samples = u64::MAX;
    });
    let mut v: serde_json::Value = serde_json::from_str(&scene_request("plate", 1)).unwrap();
    v["method"] = "image".into();
    v["image_size"] = 2048.into();
    v["image_samples"] = 16.into();
    let start = std::time::Instant::now();
    let r = post_json(server.addr, "/v1/lightcurves", &v.to_string());
    assert_error(&r, 503, None);
    let answered = start.elapsed();
    loop {
        let m = get(server.addr, "/metrics").text();
        if m.contains("glint_computations_running 0") {
            break;
        }
        // A row of 2048 px × 256 samples takes well under a second even in a debug
        // build; the whole epoch would take minutes.
        assert!(
            start.elapsed() < answered + Duration::from_secs(5),
            "the slot was held past the deadline: {m}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn jobs_beyond_the_queue_limit_get_429_and_room_comes_back() {
    let server = Server::start("queue-limit", |c| {
        c.limits.max_queued_jobs = 2;
        c.limits.max_running_jobs = 1;
    });
    let big = scene_request_repeated("box-wing", 40_000);
    let ids: Vec<String> = (0..2)
        .map(|_| {
            let r = post_json(server.addr, "/v1/jobs", &big);
            assert_eq!(r.status, 202, "{}", r.text());
            r.json()["id"].as_str().unwrap().to_string()
        })
        .collect();
    let r = post_json(server.addr, "/v1/jobs", &big);
    assert_error(&r, 429, None);
    assert!(r.header("retry-after").is_some());
    assert!(r.text().contains("limit 2"), "{}", r.text());
    // a cancelled job no longer counts
    assert_eq!(
        http(
            server.addr,
            "DELETE",
            &format!("/v1/jobs/{}", ids[1]),
            &[],
            b""
        )
        .status,
        200
    );
    assert_eq!(post_json(server.addr, "/v1/jobs", &big).status, 202);
    for j in get(server.addr, "/v1/jobs").json().as_array().unwrap() {
        let id = j["id"].as_str().unwrap();
        http(server.addr, "DELETE", &format!("/v1/jobs/{id}"), &[], b"");
    }
}

#[test]
fn an_idempotency_key_makes_a_retried_submission_find_its_job() {
    let server = Server::start("idempotency", |_| {});
    let req = scene_request("plate", 3);
    let post = |key: &str, body: &str| {
        http(
            server.addr,
            "POST",
            "/v1/jobs",
            &[JSON, ("Idempotency-Key", key)],
            body.as_bytes(),
        )
    };
    let first = post("retry-me-1", &req);
    assert_eq!(first.status, 202, "{}", first.text());
    let id = first.json()["id"].as_str().unwrap().to_string();
    // the client lost the 202 and retries: the same job, said to be a replay
    let again = post("retry-me-1", &req);
    assert_eq!(again.status, 202, "{}", again.text());
    assert_eq!(again.json()["id"], id.as_str());
    assert_eq!(again.header("idempotent-replayed"), Some("true"));
    assert_eq!(again.header("location"), first.header("location"));
    assert_eq!(
        get(server.addr, "/v1/jobs")
            .json()
            .as_array()
            .unwrap()
            .len(),
        1
    );
    // the same key with another body is a client error naming the header
    let other = scene_request("plate", 2);
    assert_error(&post("retry-me-1", &other), 422, Some("Idempotency-Key"));
    // another key makes another job; a malformed key is refused
    let r = post("retry-me-2", &req);
    assert_eq!(r.status, 202);
    assert_ne!(r.json()["id"], id.as_str());
    assert_error(&post(&"k".repeat(256), &req), 422, Some("Idempotency-Key"));
}

#[test]
fn concurrent_deletes_of_a_running_job_say_what_each_did() {
    let server = Server::start("delete-race", |c| c.limits.max_running_jobs = 1);
    let big = scene_request_repeated("box-wing", 40_000);
    for _ in 0..4 {
        let id = post_json(server.addr, "/v1/jobs", &big).json()["id"]
            .as_str()
            .unwrap()
            .to_string();
        let addr = server.addr;
        let path = format!("/v1/jobs/{id}");
        let answers: Vec<Reply> = std::thread::scope(|s| {
            let a = s.spawn(|| http(addr, "DELETE", &path, &[], b""));
            let b = s.spawn(|| http(addr, "DELETE", &path, &[], b""));
            vec![a.join().unwrap(), b.join().unwrap()]
        });
        let mut codes: Vec<u16> = answers.iter().map(|r| r.status).collect();
        codes.sort();
        // exactly one cancelled it (200, with the cancelled status); the other either
        // removed the cancelled job (204) or found it gone (404)
        assert!(
            codes == [200, 204] || codes == [200, 404],
            "{codes:?}: {:?}",
            answers.iter().map(Reply::text).collect::<Vec<_>>()
        );
        let cancelled = answers.iter().find(|r| r.status == 200).unwrap();
        assert_eq!(cancelled.json()["state"], "cancelled");
    }
}

#[test]
fn stored_results_are_bounded_and_deleting_makes_room() {
    let server = Server::start("result-bytes", |c| c.limits.max_result_bytes = 1);
    let req = scene_request("plate", 3);
    let id = post_json(server.addr, "/v1/jobs", &req).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(
        wait_final(server.addr, &id, &[], Duration::from_secs(60))["state"],
        "done"
    );
    // one stored result is over a 1-byte budget: no more submissions…
    let r = post_json(server.addr, "/v1/jobs", &req);
    assert_error(&r, 507, None);
    assert!(r.text().contains("DELETE"), "{}", r.text());
    // …until it is fetched and deleted
    assert_eq!(
        get(server.addr, &format!("/v1/jobs/{id}/result")).status,
        200
    );
    assert_eq!(
        http(server.addr, "DELETE", &format!("/v1/jobs/{id}"), &[], b"").status,
        204
    );
    assert_eq!(post_json(server.addr, "/v1/jobs", &req).status, 202);
}

/// A `geometry` request (TLE, site, window, attitude) through the service: 200 with the
/// site's view per epoch; bad orbits, sites and quaternions 422 naming the field; a
/// window over the synchronous epoch limit 413.
#[test]
fn geometry_requests_over_http() {
    let server = Server::start("geometry", |c| {
        c.limits.max_sync_epochs = 10;
    });
    let addr = server.addr;
    let tle = [
        "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
        "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995",
    ];
    let ok = serde_json::json!({
        "object": { "mesh": { "builtin": "plate" }, "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.5 } ] },
        "geometry": {
            "orbit": { "tle": tle },
            "site": { "lat_deg": 32.78, "lon_deg": -105.82, "alt_m": 2790 },
            "times": { "start": "2026-12-03T01:00:00Z", "stop": "2026-12-03T01:00:40Z", "step_s": 10 },
            "attitude": { "law": "nadir" }
        }
    });
    let r = post_json(addr, "/v1/lightcurves", &ok.to_string());
    assert_eq!(r.status, 200, "{}", r.text());
    let v = r.json();
    assert_eq!(v["epochs"].as_array().unwrap().len(), 5);
    assert!(v["epochs"][0]["elevation_deg"].as_f64().unwrap() > 10.0);
    assert!(v["epochs"][0]["azimuth_deg"].is_number());
    assert!(v["epochs"][0]["in_earth_shadow"].is_boolean());
    assert!(v["warnings"].to_string().contains("earth_orientation"));

    let bad = |path: &[&str], value: serde_json::Value| {
        let mut v = ok.clone();
        let mut at = &mut v;
        for p in &path[..path.len() - 1] {
            at = match p.parse::<usize>() {
                Ok(i) => &mut at[i],
                Err(_) => &mut at[*p],
            };
        }
        let last = path[path.len() - 1];
        match last.parse::<usize>() {
            Ok(i) => at[i] = value,
            Err(_) => at[last] = value,
        }
        post_json(addr, "/v1/lightcurves", &v.to_string())
    };
    // checksum: the last digit of line 2 changed
    let wrong = tle[1].replace("49995", "49996");
    assert_error(
        &bad(&["geometry", "orbit", "tle", "1"], wrong.into()),
        422,
        Some("geometry.orbit.tle[1]"),
    );
    assert_error(
        &bad(&["geometry", "site", "lat_deg"], 95.into()),
        422,
        Some("geometry.site.lat_deg"),
    );
    assert_error(
        &bad(
            &["geometry", "times", "start"],
            "2026-11-01T00:00:00Z".into(),
        ),
        422,
        Some("geometry.times.start"),
    );
    assert_error(
        &bad(
            &["geometry", "attitude"],
            serde_json::json!({ "law": "inertial", "quaternion": [1, 1, 0, 0] }),
        ),
        422,
        Some("geometry.attitude.quaternion"),
    );
    assert_error(
        &bad(&["geometry", "times", "step_s"], 1.into()),
        413,
        Some("geometry.times"),
    );
}

#[test]
fn a_silent_or_slow_connection_is_closed_after_the_header_timeout() {
    use std::io::{Read, Write};
    let server = Server::start("header-timeout", |c| {
        c.limits.header_timeout = Duration::from_millis(300);
    });
    // How long until the server closes a connection that got `sent` and then nothing
    // more (reading until EOF; an answer such as a 408 may come first).
    let closed_after = |sent: &[u8]| {
        let mut s = std::net::TcpStream::connect(server.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        s.write_all(sent).unwrap();
        let start = std::time::Instant::now();
        let mut buf = Vec::new();
        let _ = s.read_to_end(&mut buf);
        (start.elapsed(), String::from_utf8_lossy(&buf).into_owned())
    };
    // nothing at all; half a request head; a whole request, then idle on keep-alive
    let keep_alive = format!("GET /healthz HTTP/1.1\r\nHost: {}\r\n\r\n", server.addr);
    for sent in [
        &b""[..],
        b"GET /healthz HTTP/1.1\r\nHost: x",
        keep_alive.as_bytes(),
    ] {
        let (t, answer) = closed_after(sent);
        // 300 ms timeout; the 5 s bound leaves room for a loaded machine, and is far
        // below the tens of seconds a connection stayed open without a timer
        assert!(t < Duration::from_secs(5), "open {t:?}: {answer}");
        if sent == keep_alive.as_bytes() {
            assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
        }
    }
    // a request sent in time is answered as usual
    assert_eq!(get(server.addr, "/healthz").status, 200);
}
#[test]
fn brdf_fit_endpoint_gives_the_library_result_and_names_bad_fields() {
    // The endpoint adds nothing: its parameters are the library's on the same samples.
    use glint::fit::brdf;
    let server = Server::start("sync", |_| {});
    let truth = brdf::Model::Lambert.build(&[0.4]);
    let samples = brdf::synthetic(&truth, &brdf::paper_geometry(), 0.03, 4);
    let body = serde_json::json!({ "model": "lambert", "samples": samples, "plot": true });
    let r = post_json(server.addr, "/v1/fits/brdf", &body.to_string());
    assert_eq!(r.status, 200, "{}", r.text());
    let v = r.json();
    let opts = brdf::Options {
        model: brdf::Model::Lambert,
        fixed: Default::default(),
        loss: glint::fit::solve::Loss::Huber,
        space: brdf::Space::Log,
    };
    let direct = brdf::fit(&samples, &opts).unwrap();
    assert_eq!(
        v["parameters"]["albedo"].as_f64(),
        Some(direct.parameters["albedo"])
    );
    assert!(v["uncertainty"]["albedo"].as_f64().unwrap() > 0.0, "{v}");
    assert!(v["plot_svg"].as_str().unwrap().starts_with("<svg"));

    // bad input: 422 with the field
    let mut bad = body.clone();
    bad["samples"][3]["theta_i_deg"] = serde_json::json!(95.0);
    let r = post_json(server.addr, "/v1/fits/brdf", &bad.to_string());
    assert_error(&r, 422, Some("samples[3].theta_i_deg"));
    let mut bad = body.clone();
    bad["model"] = serde_json::json!("phong");
    assert_error(
        &post_json(server.addr, "/v1/fits/brdf", &bad.to_string()),
        422,
        Some("model"),
    );
    let mut bad = body.clone();
    bad["fixed"] = serde_json::json!({ "km": 0.1 });
    assert_error(
        &post_json(server.addr, "/v1/fits/brdf", &bad.to_string()),
        422,
        Some("fixed.km"),
    );
    let mut bad = body.clone();
    bad["samples"] = serde_json::json!([samples[0]]);
    assert_error(
        &post_json(server.addr, "/v1/fits/brdf", &bad.to_string()),
        422,
        Some("samples"),
    );
    let mut bad = body.clone();
    bad["samples"][1]["brdf"] = serde_json::json!(1.0);
    assert_error(
        &post_json(server.addr, "/v1/fits/brdf", &bad.to_string()),
        422,
        Some("samples[1].brdf"),
    );
}

/// The real engine, two seconds late: a computation that holds its request's admission.
fn slow_engine(
    scene: &glint::Scene,
    progress: &glint::Progress,
) -> Result<glint::Response, glint::Cancelled> {
    std::thread::sleep(Duration::from_secs(2));
    glint::simulate_with(scene, progress)
}

#[test]
fn request_bytes_in_flight_are_bounded_before_the_body_is_read() {
    let body = scene_request_repeated("plate", 200);
    let n = body.len();
    let server = Server::start("inflight", |c| {
        c.engine = slow_engine;
        c.limits.max_body_bytes = 2 * n;
        // room for one such body, not two
        c.limits.max_inflight_body_bytes = n * 3 / 2;
        c.limits.max_concurrent = 4;
    });
    let addr = server.addr;
    std::thread::scope(|s| {
        let first = s.spawn(|| post_json(addr, "/v1/lightcurves", &body));
        // wait until the first is admitted and computing
        let start = std::time::Instant::now();
        while !get(addr, "/metrics")
            .text()
            .contains("glint_computations_running 1")
        {
            assert!(start.elapsed() < Duration::from_secs(30));
            std::thread::sleep(Duration::from_millis(20));
        }
        let t = std::time::Instant::now();
        let second = post_json(addr, "/v1/lightcurves", &body);
        assert_error(&second, 503, None);
        assert_eq!(second.header("retry-after"), Some("1"));
        assert!(
            second.text().contains("bytes in flight"),
            "{}",
            second.text()
        );
        // turned away at once, not after the first's two seconds
        assert!(
            t.elapsed() < Duration::from_millis(1500),
            "{:?}",
            t.elapsed()
        );
        // requests without a body are not held back
        assert_eq!(get(addr, "/healthz").status, 200);
        assert_eq!(first.join().unwrap().status, 200);
    });
    // the first's bytes are released with its answer
    assert_eq!(post_json(addr, "/v1/lightcurves", &body).status, 200);
}

/// The answer to `raw` sent whole on a fresh connection, read until the server closes.
fn raw_exchange(addr: std::net::SocketAddr, raw: &[u8]) -> Reply {
    use std::io::{Read, Write};
    let mut s = std::net::TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    // the server may answer and close before it has read everything
    let _ = s.write_all(raw);
    let mut buf = Vec::new();
    let _ = s.read_to_end(&mut buf);
    reply_of(&buf)
}

#[test]
fn an_overlong_uri_or_request_head_is_a_json_414_or_431() {
    let server = Server::start("head-limits", |_| {});
    let addr = server.addr;
    let request = |target: &str, fields: &str| {
        format!("GET {target} HTTP/1.1\r\nHost: {addr}\r\n{fields}Connection: close\r\n\r\n")
    };
    // over the service's URI limit (hyper would take it): ours, naming `uri`
    let long = format!("/v1/jobs/{}", "a".repeat(10 << 10));
    let r = raw_exchange(addr, request(&long, "").as_bytes());
    assert_error(&r, 414, Some("uri"));
    assert!(r.header("x-request-id").is_some());
    // over hyper's own bounds, answered before any of the service's code runs: a 100 KiB
    // target, one 200 KiB header field, 150 header fields
    let huge = format!("/v1/jobs/{}", "a".repeat(100 << 10));
    let big_field = format!("X-Big: {}\r\n", "b".repeat(200 << 10));
    let many: String = (0..150).map(|i| format!("X-F{i}: {i}\r\n")).collect();
    for raw in [
        request(&huge, ""),
        request("/healthz", &big_field),
        request("/healthz", &many),
    ] {
        let r = raw_exchange(addr, raw.as_bytes());
        assert_error(&r, 431, Some("headers"));
        assert!(r.header("x-request-id").is_some(), "{:?}", r.headers);
        assert_eq!(r.header("connection"), Some("close"));
    }
    // a head hyper cannot read (a control character in a field): a JSON 400
    let r = raw_exchange(addr, request("/healthz", "X-Bad: a\x01b\r\n").as_bytes());
    assert_error(&r, 400, None);
    // a target of 8 KiB is still taken, and the service goes on answering
    let ok = format!("/healthz?{}", "q".repeat(8000));
    assert_eq!(raw_exchange(addr, request(&ok, "").as_bytes()).status, 200);
    assert_eq!(get(addr, "/healthz").status, 200);
}

#[test]
fn a_light_curve_turned_away_is_answered_before_its_body_is_read() {
    // One slot and no waiting room: while one light curve computes, the next is turned
    // away at once, without the service waiting for (or parsing) its body.
    let server = Server::start("admit-before-body", |c| {
        c.engine = slow_engine;
        c.limits.max_concurrent = 1;
        c.limits.max_queued = 0;
    });
    let addr = server.addr;
    let body = scene_request("plate", 2);
    std::thread::scope(|s| {
        let first = s.spawn(|| post_json(addr, "/v1/lightcurves", &body));
        let start = std::time::Instant::now();
        while !get(addr, "/metrics")
            .text()
            .contains("glint_computations_running 1")
        {
            assert!(start.elapsed() < Duration::from_secs(30));
            std::thread::sleep(Duration::from_millis(20));
        }
        // the head announces a body that never comes
        use std::io::{Read, Write};
        let mut c = std::net::TcpStream::connect(addr).unwrap();
        c.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        let t = std::time::Instant::now();
        c.write_all(
            format!(
                "POST /v1/lightcurves HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\n\
                 Content-Length: {}\r\n\r\n",
                body.len()
            )
            .as_bytes(),
        )
        .unwrap();
        let mut buf = vec![0; 4096];
        let n = c.read(&mut buf).unwrap_or(0);
        let answer = String::from_utf8_lossy(&buf[..n]).into_owned();
        assert!(answer.starts_with("HTTP/1.1 503"), "{answer:?}");
        assert!(
            answer.to_ascii_lowercase().contains("retry-after: 1"),
            "{answer}"
        );
        // at once, not after the first's two seconds
        assert!(
            t.elapsed() < Duration::from_millis(1500),
            "{:?}",
            t.elapsed()
        );
        assert_eq!(first.join().unwrap().status, 200);
    });
    // the place comes back with the answer
    assert_eq!(post_json(addr, "/v1/lightcurves", &body).status, 200);
}

#[test]
fn a_body_declared_over_the_limit_is_refused_before_it_is_sent() {
    let server = Server::start("declared-too-large", |c| c.limits.max_body_bytes = 1000);
    for path in ["/v1/lightcurves", "/v1/jobs"] {
        // the head alone: the body it announces never comes
        let head = format!(
            "POST {path} HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\n\
             Content-Length: 1000000000000\r\n\r\n",
            server.addr
        );
        let t = std::time::Instant::now();
        let r = raw_exchange(server.addr, head.as_bytes());
        assert_error(&r, 413, Some("body"));
        assert!(t.elapsed() < Duration::from_secs(3), "{:?}", t.elapsed());
    }
}

/// The fitted parameters, their 1σ, χ² and the light curves taken: what two fits of the
/// same input must share (the wall time differs).
fn fit_numbers(v: &serde_json::Value) -> serde_json::Value {
    serde_json::json!([
        v["parameters"],
        v["uncertainty"],
        v["chi2"],
        v["solver"]["evaluations"]
    ])
}

#[test]
fn lightcurve_fit_job_submitted_polled_fetched_and_its_errors_named() {
    // The truth: the box-wing's panel albedo 0.25 (every 10th epoch, 0.02 mag noise); the
    // fit starts from 0.4. Its result must hold the truth within 3σ, with χ²/dof within
    // 3 sd of 1 (sd √(2/dof) = 0.25 for 33 dof), and equal the library's own fit of the
    // same body: the service adds nothing.
    let server = Server::start("fit", |_| {});
    let (request, observed) = fit_inputs("box-wing", 10, 1, 0.25, 0.4, 21);
    let body = serde_json::json!({
        "request": request,
        "observed": observed,
        "free": ["materials.panel.albedo"],
        "max_evaluations": 60
    });
    let r = post_json(server.addr, "/v1/fits/lightcurve", &body.to_string());
    assert_eq!(r.status, 202, "{}", r.text());
    let s = r.json();
    let id = s["id"].as_str().unwrap().to_string();
    assert_eq!(
        r.header("location"),
        Some(format!("/v1/jobs/{id}").as_str())
    );
    assert_eq!(s["kind"], "fit-lightcurve");
    assert_eq!(s["evaluations_max"], 60);
    assert_eq!(s["epochs_total"], 60 * observed.len());

    // Progress: light curves evaluated against the bound, rising, 100 once done.
    let mut seen = Vec::new();
    let start = std::time::Instant::now();
    let s = loop {
        let s = get(server.addr, &format!("/v1/jobs/{id}")).json();
        if s["state"] == "running" {
            let (done, pct) = (
                s["evaluations_done"].as_u64().unwrap(),
                s["percent"].as_f64().unwrap(),
            );
            assert!((pct - 100.0 * done as f64 / 60.0).abs() < 1e-9, "{s}");
            assert_eq!(
                s["epochs_done"].as_u64().unwrap(),
                done * observed.len() as u64,
                "{s}"
            );
            seen.push(done);
        }
        if ["done", "failed", "cancelled"].contains(&s["state"].as_str().unwrap()) {
            break s;
        }
        assert!(start.elapsed() < Duration::from_secs(300), "{s}");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert_eq!(s["state"], "done", "{s}");
    assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{seen:?}");
    assert_eq!(s["percent"], 100.0);
    assert_eq!(s["result_url"], format!("/v1/jobs/{id}/result"));

    let r = get(server.addr, &format!("/v1/jobs/{id}/result"));
    assert_eq!(r.status, 200, "{}", r.text());
    let fit = r.json();
    let (a, sa) = (
        fit["parameters"]["materials.panel.albedo"]
            .as_f64()
            .unwrap(),
        fit["uncertainty"]["materials.panel.albedo"]
            .as_f64()
            .unwrap(),
    );
    println!(
        "fit job: albedo {a:.4} ± {sa:.4}, chi2/dof {}, {} light curves",
        fit["chi2_dof"], fit["solver"]["evaluations"]
    );
    assert!((a - 0.25).abs() < 3.0 * sa, "{a} ± {sa}");
    let chi2_dof = fit["chi2_dof"].as_f64().unwrap();
    assert!((0.25..1.75).contains(&chi2_dof), "{chi2_dof}");
    assert!(fit["solver"]["wall_time_s"].as_f64().unwrap() > 0.0);
    let evaluations = fit["solver"]["evaluations"].as_u64().unwrap();
    assert_eq!(s["evaluations_done"].as_u64(), Some(evaluations));
    assert_eq!(
        s["epochs_done"].as_u64(),
        Some(evaluations * observed.len() as u64)
    );
    let direct = serde_json::to_value(direct_fit(&body)).unwrap();
    assert_eq!(fit_numbers(&fit), fit_numbers(&direct));

    // A fit's result is JSON only, and it has no images.
    let r = http(
        server.addr,
        "GET",
        &format!("/v1/jobs/{id}/result"),
        &[("Accept", "text/csv")],
        b"",
    );
    assert_error(&r, 406, Some("Accept"));
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}/thumbnails/0.png")),
        404,
        Some("epoch"),
    );

    // Bad bodies: each named, nothing stored.
    let bad = |edit: &dyn Fn(&mut serde_json::Value), status: u16, field: &str| {
        let mut b = body.clone();
        edit(&mut b);
        let r = post_json(server.addr, "/v1/fits/lightcurve", &b.to_string());
        assert_error(&r, status, Some(field));
    };
    bad(
        &|b| b["request"]["object"]["materials"][1]["albedo"] = serde_json::json!(2.0),
        422,
        "request.object.materials[1].albedo",
    );
    bad(
        &|b| b["observed"][1]["t"] = serde_json::json!(1.5),
        422,
        "observed[1].t",
    );
    bad(
        &|b| b["free"] = serde_json::json!(["materials.wing.albedo"]),
        422,
        "free[0]",
    );
    bad(
        &|b| b["start"] = serde_json::json!({"materials.panel.albedo": 3.0}),
        422,
        "start.materials.panel.albedo",
    );
    bad(
        &|b| b["max_evaluations"] = serde_json::json!(3),
        422,
        "max_evaluations",
    );
    bad(
        &|b| b["yaw_starts"] = serde_json::json!(0),
        422,
        "yaw_starts",
    );
    bad(&|b| b["loss"] = serde_json::json!("l1"), 422, "loss");
    // its whole work bounded before it starts: 268 triangles × 34 epochs × 10⁹ curves
    bad(
        &|b| b["max_evaluations"] = serde_json::json!(1_000_000_000u64),
        413,
        "max_evaluations",
    );
    assert_eq!(
        get(server.addr, "/v1/jobs")
            .json()
            .as_array()
            .unwrap()
            .len(),
        1
    );
}

#[test]
fn a_running_fit_job_is_cancelled_within_a_light_curve() {
    let server = Server::start("fit-cancel", |_| {});
    let (request, observed) = fit_inputs("box-wing", 5, 1, 0.25, 0.4, 22);
    let body = serde_json::json!({
        "request": request,
        "observed": observed,
        "free": ["materials.panel.albedo", "attitude.yaw_deg"]
    });
    let r = post_json(server.addr, "/v1/fits/lightcurve", &body.to_string());
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().unwrap().to_string();
    let start = std::time::Instant::now();
    loop {
        let s = get(server.addr, &format!("/v1/jobs/{id}")).json();
        if s["state"] == "running" && s["evaluations_done"].as_u64().unwrap() > 0 {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(120), "never ran: {s}");
        std::thread::sleep(Duration::from_millis(20));
    }
    let r = http(server.addr, "DELETE", &format!("/v1/jobs/{id}"), &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    let s = r.json();
    assert_eq!(s["state"], "cancelled");
    let done = s["evaluations_done"].as_u64().unwrap();
    assert!(done > 0 && done < 400, "{s}");
    // it stays cancelled, and has no result
    std::thread::sleep(Duration::from_millis(500));
    let s = get(server.addr, &format!("/v1/jobs/{id}")).json();
    assert_eq!(
        (s["state"].as_str(), s["evaluations_done"].as_u64()),
        (Some("cancelled"), Some(done)),
        "{s}"
    );
    assert_error(
        &get(server.addr, &format!("/v1/jobs/{id}/result")),
        409,
        None,
    );
}
