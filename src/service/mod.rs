//! The HTTP service (routes, jobs, storage) — see the service issue.
