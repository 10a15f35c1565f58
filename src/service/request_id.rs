//! Request ids and the request log: every request gets an id (the client's `X-Request-Id`
//! when it sends a sane one, else a new UUID), answered in the `X-Request-Id` header and
//! logged with the request's method, path, status and duration. A 5xx body names it too
//! ([`super::errors::ErrorBody::request_id`]), so a fault a client reports can be found in
//! the log.

use super::errors::{ApiError, REQUEST_ID};
use axum::extract::Request;
use axum::http::{HeaderName, HeaderValue};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use std::sync::Arc;
use std::time::Instant;

/// The header carrying the id, both ways.
pub static X_REQUEST_ID: HeaderName = HeaderName::from_static("x-request-id");

/// Longest client-given id kept; a longer or odder one is replaced by a fresh id.
const MAX_CLIENT_ID: usize = 128;

/// Whether a client's id is safe to echo and log: short, printable ASCII without spaces.
fn acceptable(id: &str) -> bool {
    !id.is_empty()
        && id.len() <= MAX_CLIENT_ID
        && id
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_.:".contains(&b))
}

/// The outermost middleware: tags the request, runs it with the id in scope, logs it.
pub async fn tag(req: Request, next: Next) -> Response {
    let id: Arc<str> = req
        .headers()
        .get(&X_REQUEST_ID)
        .and_then(|v| v.to_str().ok())
        .filter(|v| acceptable(v))
        .map(Arc::from)
        .unwrap_or_else(|| Arc::from(uuid::Uuid::new_v4().to_string()));
    let method = req.method().clone();
    // A path can be kilobytes long (a 414 is still logged): keep its start
    let path: String = req.uri().path().chars().take(200).collect();
    let start = Instant::now();
    let mut resp = REQUEST_ID.scope(id.clone(), next.run(req)).await;
    if let Ok(v) = HeaderValue::from_str(&id) {
        resp.headers_mut().insert(X_REQUEST_ID.clone(), v);
    }
    let status = resp.status().as_u16();
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if status >= 500 {
        tracing::warn!(request_id = &*id, %method, path, status, ms, "request");
    } else {
        tracing::info!(request_id = &*id, %method, path, status, ms, "request");
    }
    resp
}

/// The answer to a panic in a handler (for `tower_http`'s `CatchPanicLayer`): a JSON 500
/// naming the request id, the panic's text only in the log.
pub fn panicked(payload: Box<dyn std::any::Any + Send + 'static>) -> Response {
    ApiError::from_panic("the request's handler", &*payload).into_response()
}

/// Logs every panic of the process with its thread and backtrace (installed by
/// `glint serve`; a panic in the engine's thread pools is answered as a 500 by the
/// handler that waited for it, and this puts its backtrace beside that answer's log line).
pub fn log_panics() {
    std::panic::set_hook(Box::new(|info| {
        let backtrace = std::backtrace::Backtrace::force_capture();
        let thread = std::thread::current();
        tracing::error!(
            thread = thread.name().unwrap_or("unnamed"),
            "panic: {info}\n{backtrace}"
        );
    }));
}

#[cfg(test)]
mod tests {
    use super::acceptable;

    #[test]
    fn client_ids_are_kept_only_when_safe_to_echo() {
        assert!(acceptable("3f2a-77_b.c:1"));
        assert!(!acceptable(""));
        assert!(!acceptable("a b"));
        assert!(!acceptable("a\nb"));
        assert!(!acceptable(&"x".repeat(129)));
    }
}
