//! The shared queue's database: its URL, the pool of connections, the schema prepared
//! at start, and what a failure of it answers.

use super::schema;
use crate::service::errors::ApiError;
use deadpool_postgres::{Manager, ManagerConfig, Pool, RecyclingMethod};
use std::time::Duration;
use tokio_postgres::NoTls;

/// A database failure: never the client's fault, a `503` with `Retry-After`.
#[derive(Debug, thiserror::Error)]
pub enum PgError {
    #[error("database: {0}")]
    Db(#[from] tokio_postgres::Error),
    #[error("database: {0}")]
    Pool(#[from] deadpool_postgres::PoolError),
    #[error("database: {0}")]
    Build(#[from] deadpool_postgres::BuildError),
    #[error(
        "the database's schema is version {found}, newer than this glint's {ours}: run a \
         glint at least as new as the one that migrated it"
    )]
    SchemaNewer { found: i32, ours: i32 },
    #[error(
        "the database's schema is version {found}, older than this glint's {ours}: start it \
         without --no-migrate (or `glint serve` of this version) to migrate it"
    )]
    SchemaOlder { found: i32, ours: i32 },
    #[error("database: a stored row is not valid: {0}")]
    Corrupt(String),
}

impl From<PgError> for ApiError {
    fn from(e: PgError) -> Self {
        ApiError {
            retry_after_s: Some(2),
            ..ApiError::new(
                axum::http::StatusCode::SERVICE_UNAVAILABLE,
                format!("the job database cannot be reached or refused the query now ({e})"),
            )
        }
    }
}

/// The connection settings of `url` (`postgres://user:pass@host:port/db`), with a
/// connect timeout; the error names the flag.
pub fn parse_url(url: &str) -> anyhow::Result<tokio_postgres::Config> {
    let mut cfg: tokio_postgres::Config = url.parse().map_err(|e| {
        anyhow::anyhow!("--database-url / GLINT_DATABASE_URL: not a PostgreSQL URL ({e})")
    })?;
    if cfg.get_connect_timeout().is_none() {
        cfg.connect_timeout(Duration::from_secs(5));
    }
    if cfg.get_application_name().is_none() {
        cfg.application_name("glint");
    }
    Ok(cfg)
}

/// A pool of up to `size` connections; a broken connection (the server restarted) is
/// dropped when next taken and a new one made.
pub fn pool(cfg: tokio_postgres::Config, size: usize) -> Result<Pool, PgError> {
    let mgr = Manager::from_config(
        cfg,
        NoTls,
        ManagerConfig {
            recycling_method: RecyclingMethod::Verified,
        },
    );
    Ok(Pool::builder(mgr)
        .max_size(size.max(2))
        .runtime(deadpool_postgres::Runtime::Tokio1)
        .wait_timeout(Some(Duration::from_secs(10)))
        .create_timeout(Some(Duration::from_secs(5)))
        .recycle_timeout(Some(Duration::from_secs(5)))
        .build()?)
}

/// Connects once and applies the migrations (or checks the version), with the reason on
/// failure: a service must not start on a database it cannot use.
pub async fn prepare(cfg: &tokio_postgres::Config, apply: bool) -> anyhow::Result<()> {
    let (mut client, conn) = cfg
        .connect(NoTls)
        .await
        .map_err(|e| anyhow::anyhow!("cannot connect to the job database: {e}"))?;
    let driver = tokio::spawn(conn);
    let out = schema::migrate(&mut client, apply).await;
    drop(client);
    let _ = driver.await;
    out.map(|_| ()).map_err(anyhow::Error::from)
}
