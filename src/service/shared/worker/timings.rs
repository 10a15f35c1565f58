//! What the chunks of a process took: the queue's part against the computation's.

use std::sync::atomic::{AtomicU64, Ordering};

/// Time spent on the chunks this process claimed and wrote, in nanoseconds: the
/// queue's part (the claim's transaction, the write's) against the computation's.
#[derive(Debug, Default)]
pub struct Timings {
    pub claimed: AtomicU64,
    pub claim_ns: AtomicU64,
    pub written: AtomicU64,
    pub write_ns: AtomicU64,
    pub compute_ns: AtomicU64,
}

impl Timings {
    /// One line: chunks, and the mean claim, write and computation per chunk in ms.
    pub fn summary(&self) -> String {
        let ms = |ns: &AtomicU64, n: &AtomicU64| {
            ns.load(Ordering::Relaxed) as f64 / 1e6 / n.load(Ordering::Relaxed).max(1) as f64
        };
        let claim = ms(&self.claim_ns, &self.claimed);
        let write = ms(&self.write_ns, &self.written);
        let compute = ms(&self.compute_ns, &self.written);
        format!(
            "{} chunks written; per chunk: claim {claim:.2} ms, write {write:.2} ms, \
             compute {compute:.1} ms (queue overhead {:.2} % of the computation)",
            self.written.load(Ordering::Relaxed),
            100.0 * (claim + write) / compute.max(1e-9)
        )
    }
}
