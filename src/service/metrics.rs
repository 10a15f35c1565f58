//! Prometheus text metrics, kept by hand: a few counters and one latency histogram per
//! route do not need a metrics framework.

use axum::extract::{MatchedPath, Request, State};
use axum::middleware::Next;
use axum::response::Response;
use std::collections::BTreeMap;
use std::fmt::Write;
use std::sync::Mutex;
use std::time::Instant;

/// Upper bounds of the latency histogram buckets, seconds.
const BUCKETS_S: [f64; 14] = [
    0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 30.0,
];

#[derive(Default)]
struct Histogram {
    counts: [u64; BUCKETS_S.len()],
    sum_s: f64,
    count: u64,
}

#[derive(Default)]
struct Inner {
    /// (method, route, status) → requests.
    requests: BTreeMap<(String, String, u16), u64>,
    /// (method, route) → latency.
    latency: BTreeMap<(String, String), Histogram>,
    /// kind (`sync`, `job`) → epochs computed.
    epochs: BTreeMap<&'static str, u64>,
}

/// The service's counters.
#[derive(Default)]
pub struct Metrics {
    inner: Mutex<Inner>,
}

/// Values read at scrape time from elsewhere (slots, jobs).
pub struct Gauges {
    pub computations_running: usize,
    pub requests_waiting: usize,
    pub jobs: Vec<(&'static str, usize)>,
}

impl Metrics {
    fn lock(&self) -> std::sync::MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Records one answered request.
    pub fn observe(&self, method: &str, route: &str, status: u16, seconds: f64) {
        let mut m = self.lock();
        *m.requests
            .entry((method.to_string(), route.to_string(), status))
            .or_default() += 1;
        let h = m
            .latency
            .entry((method.to_string(), route.to_string()))
            .or_default();
        h.count += 1;
        h.sum_s += seconds;
        for (i, &b) in BUCKETS_S.iter().enumerate() {
            if seconds <= b {
                h.counts[i] += 1;
            }
        }
    }

    /// Counts epochs computed by a synchronous request (`sync`) or a job (`job`).
    pub fn add_epochs(&self, kind: &'static str, n: u64) {
        *self.lock().epochs.entry(kind).or_default() += n;
    }

    /// Epochs computed so far of one kind.
    pub fn epochs(&self, kind: &'static str) -> u64 {
        self.lock().epochs.get(kind).copied().unwrap_or(0)
    }

    /// The Prometheus text exposition (format 0.0.4).
    pub fn render(&self, g: &Gauges) -> String {
        let m = self.lock();
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# HELP glint_http_requests_total HTTP requests answered."
        );
        let _ = writeln!(s, "# TYPE glint_http_requests_total counter");
        for ((method, route, status), n) in &m.requests {
            let _ = writeln!(
                s,
                "glint_http_requests_total{{method=\"{method}\",route=\"{}\",status=\"{status}\"}} {n}",
                escape(route)
            );
        }
        let _ = writeln!(
            s,
            "# HELP glint_http_request_duration_seconds Time to answer, seconds."
        );
        let _ = writeln!(s, "# TYPE glint_http_request_duration_seconds histogram");
        for ((method, route), h) in &m.latency {
            let labels = format!("method=\"{method}\",route=\"{}\"", escape(route));
            for (b, c) in BUCKETS_S.iter().zip(h.counts) {
                let _ = writeln!(
                    s,
                    "glint_http_request_duration_seconds_bucket{{{labels},le=\"{b}\"}} {c}"
                );
            }
            let _ = writeln!(
                s,
                "glint_http_request_duration_seconds_bucket{{{labels},le=\"+Inf\"}} {}",
                h.count
            );
            let _ = writeln!(
                s,
                "glint_http_request_duration_seconds_sum{{{labels}}} {}",
                h.sum_s
            );
            let _ = writeln!(
                s,
                "glint_http_request_duration_seconds_count{{{labels}}} {}",
                h.count
            );
        }
        let _ = writeln!(s, "# HELP glint_epochs_computed_total Epochs computed.");
        let _ = writeln!(s, "# TYPE glint_epochs_computed_total counter");
        for kind in ["sync", "job"] {
            let n = m.epochs.get(kind).copied().unwrap_or(0);
            let _ = writeln!(s, "glint_epochs_computed_total{{kind=\"{kind}\"}} {n}");
        }
        let _ = writeln!(s, "# HELP glint_jobs Jobs known to the service, by state.");
        let _ = writeln!(s, "# TYPE glint_jobs gauge");
        for (state, n) in &g.jobs {
            let _ = writeln!(s, "glint_jobs{{state=\"{state}\"}} {n}");
        }
        let _ = writeln!(
            s,
            "# HELP glint_computations_running Computations holding a slot."
        );
        let _ = writeln!(s, "# TYPE glint_computations_running gauge");
        let _ = writeln!(s, "glint_computations_running {}", g.computations_running);
        let _ = writeln!(
            s,
            "# HELP glint_requests_waiting Synchronous requests waiting for a slot."
        );
        let _ = writeln!(s, "# TYPE glint_requests_waiting gauge");
        let _ = writeln!(s, "glint_requests_waiting {}", g.requests_waiting);
        s
    }
}

fn escape(s: &str) -> String {
    s.replace('\\', "\\\\").replace('"', "\\\"")
}

/// Middleware: counts every request by its route template (not the raw path, which
/// would give one series per job id).
pub async fn track(
    State(metrics): State<std::sync::Arc<Metrics>>,
    req: Request,
    next: Next,
) -> Response {
    let start = Instant::now();
    let method = req.method().to_string();
    let route = req
        .extensions()
        .get::<MatchedPath>()
        .map_or_else(|| "unmatched".to_string(), |p| p.as_str().to_string());
    let resp = next.run(req).await;
    metrics.observe(
        &method,
        &route,
        resp.status().as_u16(),
        start.elapsed().as_secs_f64(),
    );
    resp
}
