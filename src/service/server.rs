//! The connection loop: accepts TCP connections and serves the router on each with
//! hyper, as `axum::serve` does, but with a timer, so that a client that connects and
//! sends nothing (or sends its request head slowly, or idles between keep-alive
//! requests) is disconnected after `header_timeout` instead of holding a socket forever.
//!
//! A request head hyper will not take — over [`MAX_HEAD_BYTES`], over [`MAX_HEADERS`]
//! fields, a target over 64 KiB, or one it cannot parse — is answered by hyper itself,
//! before any of the service's code runs, with an empty `431`, `414` or `400`.
//! [`JsonHeadErrors`] rewrites that answer on its way out into the service's JSON error,
//! so every 4xx has one shape.

use super::errors::ErrorBody;
use axum::Router;
use hyper::server::conn::http1::Builder;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::server::graceful::GracefulShutdown;
use hyper_util::service::TowerToHyperService;
use std::io::IoSlice;
use std::pin::Pin;
use std::task::{ready, Context, Poll};
use std::time::Duration;
use tokio::net::TcpListener;

/// Largest request head (request line and header fields) read, bytes; beyond, a `431`.
/// hyper's default would be its whole read buffer (~400 KiB) per connection.
pub const MAX_HEAD_BYTES: usize = 64 << 10;

/// Most header fields in a request; beyond, a `431`. hyper's default (raising it costs
/// every request a heap allocation).
pub const MAX_HEADERS: usize = 100;

/// How long in-flight connections may take to finish after a shutdown begins.
const DRAIN: Duration = Duration::from_secs(30);

/// Serves `router` on `listener` until `stop` resolves, then lets the connections in
/// flight finish (at most [`DRAIN`]).
pub async fn serve(
    listener: TcpListener,
    router: Router,
    header_timeout: Duration,
    stop: impl std::future::Future<Output = ()>,
) -> std::io::Result<()> {
    // HTTP/1.1 only (as axum's default features): an auto-detecting HTTP/1-or-2 reader
    // would wait for a silent client's first bytes with no timer at all
    let mut builder = Builder::new();
    builder
        .timer(TokioTimer::new())
        .header_read_timeout(header_timeout)
        .max_header_size(MAX_HEAD_BYTES);
    let graceful = GracefulShutdown::new();
    let mut stop = std::pin::pin!(stop);
    loop {
        let (stream, _peer) = tokio::select! {
            accepted = listener.accept() => match accepted {
                Ok(s) => s,
                // Out of file descriptors and the like: wait a little, keep serving.
                Err(e) => {
                    tracing::warn!("accept failed: {e}");
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            },
            _ = &mut stop => break,
        };
        let _ = stream.set_nodelay(true);
        let service = TowerToHyperService::new(router.clone());
        // no upgrades (WebSockets): the service has none
        let io = JsonHeadErrors::new(TokioIo::new(stream));
        let conn = graceful.watch(builder.serve_connection(io, service));
        tokio::spawn(async move {
            if let Err(e) = conn.await {
                tracing::debug!("connection ended: {e}");
            }
        });
    }
    drop(listener);
    if tokio::time::timeout(DRAIN, graceful.shutdown())
        .await
        .is_err()
    {
        tracing::warn!("connections still open {DRAIN:?} after shutdown began; closing them");
    }
    Ok(())
}

/// A connection's IO that passes everything through but hyper's own answer to a request
/// head it refused (a `400`, `414` or `431` head with `content-length: 0`, written before
/// any service code ran), which it replaces with the same status and a JSON [`ErrorBody`]
/// (naming `uri` or `headers` when that is the cause). The service's own 400s, 414s and
/// 431s carry a body, so they pass.
pub struct JsonHeadErrors<T> {
    io: T,
    /// The replacement being written, how much of it is written, and the length of
    /// hyper's buffer to report as written once it all is.
    replacing: Option<(Vec<u8>, usize, usize)>,
}

impl<T> JsonHeadErrors<T> {
    pub fn new(io: T) -> Self {
        JsonHeadErrors {
            io,
            replacing: None,
        }
    }
}

/// The JSON answer to write instead of `buf`, when `buf` is hyper's bodiless answer to a
/// refused request head.
pub fn json_head_error(buf: &[u8]) -> Option<Vec<u8>> {
    let (field, error) = if buf.starts_with(b"HTTP/1.1 431 ") {
        (
            Some("headers"),
            format!(
                "the request head is too large: at most {MAX_HEAD_BYTES} bytes of request \
                 line and header fields, and at most {MAX_HEADERS} fields"
            ),
        )
    } else if buf.starts_with(b"HTTP/1.1 414 ") {
        (Some("uri"), "the request target is too long".to_string())
    } else if buf.starts_with(b"HTTP/1.1 400 ") {
        // which part hyper could not read (method, target, version, a field) it keeps
        (
            None,
            "the request head is malformed: its request line or a header field cannot be \
             read as HTTP/1.1"
                .to_string(),
        )
    } else {
        return None;
    };
    // hyper's answer is a head alone, written at once: nothing after its blank line
    let head = std::str::from_utf8(buf.strip_suffix(b"\r\n\r\n")?).ok()?;
    if head.contains("\r\n\r\n") {
        return None;
    }
    let mut lines = head.split("\r\n");
    let status_line = lines.next()?;
    let fields: Vec<&str> = lines.collect();
    if !fields
        .iter()
        .any(|l| l.eq_ignore_ascii_case("content-length: 0"))
    {
        return None;
    }
    let id = uuid::Uuid::new_v4().to_string();
    let body = serde_json::to_vec(&ErrorBody {
        error,
        field: field.map(str::to_string),
        request_id: None,
    })
    .ok()?;
    tracing::info!(
        request_id = id.as_str(),
        "{status_line}: a request head refused before routing"
    );
    let mut out = format!("{status_line}\r\n");
    for f in fields {
        if !f.to_ascii_lowercase().starts_with("content-length:") {
            out.push_str(f);
            out.push_str("\r\n");
        }
    }
    out.push_str(&format!(
        "content-type: application/json\r\ncontent-length: {}\r\nx-request-id: {id}\r\n\r\n",
        body.len()
    ));
    let mut out = out.into_bytes();
    out.extend_from_slice(&body);
    Some(out)
}

impl<T: hyper::rt::Read + Unpin> hyper::rt::Read for JsonHeadErrors<T> {
    fn poll_read(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: hyper::rt::ReadBufCursor<'_>,
    ) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_read(cx, buf)
    }
}

impl<T: hyper::rt::Write + Unpin> hyper::rt::Write for JsonHeadErrors<T> {
    fn poll_write(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        let me = self.get_mut();
        if me.replacing.is_none() {
            if let Some(answer) = json_head_error(buf) {
                me.replacing = Some((answer, 0, buf.len()));
            }
        }
        if let Some((answer, done, reported)) = &mut me.replacing {
            while *done < answer.len() {
                let n = ready!(Pin::new(&mut me.io).poll_write(cx, &answer[*done..]))?;
                if n == 0 {
                    return Poll::Ready(Err(std::io::ErrorKind::WriteZero.into()));
                }
                *done += n;
            }
            let n = *reported;
            me.replacing = None;
            return Poll::Ready(Ok(n));
        }
        Pin::new(&mut me.io).poll_write(cx, buf)
    }

    fn poll_write_vectored(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[IoSlice<'_>],
    ) -> Poll<std::io::Result<usize>> {
        // hyper's answer to a refused head is one buffer: the head, with no body after it
        let first = bufs.iter().find(|b| !b.is_empty());
        let alone = bufs.iter().filter(|b| !b.is_empty()).count() == 1;
        match first {
            Some(b) if self.replacing.is_some() || (alone && json_head_error(b).is_some()) => {
                self.poll_write(cx, b)
            }
            _ => Pin::new(&mut self.get_mut().io).poll_write_vectored(cx, bufs),
        }
    }

    fn is_write_vectored(&self) -> bool {
        self.io.is_write_vectored()
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_flush(cx)
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_shutdown(cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hypers_bodiless_431_and_414_become_json_errors_naming_the_part() {
        let hyper_431 = b"HTTP/1.1 431 Request Header Fields Too Large\r\nconnection: close\r\n\
                          content-length: 0\r\ndate: Thu, 03 Dec 2026 12:00:00 GMT\r\n\r\n";
        let out = String::from_utf8(json_head_error(hyper_431).unwrap()).unwrap();
        let (head, body) = out.split_once("\r\n\r\n").unwrap();
        assert!(head.starts_with("HTTP/1.1 431 Request Header Fields Too Large\r\n"));
        assert!(head.contains("\r\nconnection: close\r\n"));
        assert!(head.contains("\r\ndate: Thu, 03 Dec 2026 12:00:00 GMT\r\n"));
        assert!(head.contains("\r\ncontent-type: application/json\r\n"));
        assert!(head.contains(&format!("\r\ncontent-length: {}\r\n", body.len())));
        assert!(!head.contains("content-length: 0"));
        let e: ErrorBody = serde_json::from_str(body).unwrap();
        assert_eq!(e.field.as_deref(), Some("headers"));

        let hyper_414 =
            b"HTTP/1.1 414 URI Too Long\r\nconnection: close\r\ncontent-length: 0\r\n\r\n";
        let out = String::from_utf8(json_head_error(hyper_414).unwrap()).unwrap();
        let e: ErrorBody = serde_json::from_str(out.split_once("\r\n\r\n").unwrap().1).unwrap();
        assert_eq!(e.field.as_deref(), Some("uri"));

        let hyper_400 =
            b"HTTP/1.1 400 Bad Request\r\nconnection: close\r\ncontent-length: 0\r\n\r\n";
        let out = String::from_utf8(json_head_error(hyper_400).unwrap()).unwrap();
        let e: ErrorBody = serde_json::from_str(out.split_once("\r\n\r\n").unwrap().1).unwrap();
        assert!(e.error.contains("malformed"), "{}", e.error);
    }

    #[test]
    fn every_other_write_passes_unchanged() {
        for buf in [
            &b"HTTP/1.1 200 OK\r\ncontent-length: 0\r\n\r\n"[..],
            // the service's own 431, with its body
            b"HTTP/1.1 431 Request Header Fields Too Large\r\ncontent-length: 2\r\n\r\n{}",
            b"HTTP/1.1 414 URI Too Long\r\ncontent-type: application/json\r\ncontent-length: 9\r\n\r\n",
            // a body chunk that happens to look like a head
            b"HTTP/1.1 431 x\r\ncontent-length: 0\r\n\r\nmore",
            b"",
        ] {
            assert_eq!(json_head_error(buf), None, "{}", String::from_utf8_lossy(buf));
        }
    }
}
