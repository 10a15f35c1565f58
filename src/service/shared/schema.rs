//! The PostgreSQL schema: its migrations, applied at start in one transaction under an
//! advisory lock (so that processes starting together apply each once), and the version
//! check that refuses a database newer than this binary (or older, when migrating is off).
//!
//! | table | a row |
//! |---|---|
//! | `glint_schema_version` | a migration applied |
//! | `glint_jobs` | a job: its request (until it is final), state, idempotency key, times |
//! | `glint_chunks` | a run of consecutive epochs of a job: queued, running under a lease, done |
//! | `glint_results` | a done chunk's result, keyed by (job, chunk): stored once |

use super::PgError;
use tokio_postgres::Client;

/// The schema this binary reads and writes.
pub const SCHEMA_VERSION: i32 = 1;

/// Advisory lock key held while migrating ("glint" in ASCII).
const MIGRATION_LOCK: i64 = 0x0067_6c69_6e74;

/// Each migration's SQL, by the version it brings the schema to.
const MIGRATIONS: &[(i32, &str)] = &[(
    1,
    "CREATE TABLE glint_jobs (
        id text PRIMARY KEY,
        kind text NOT NULL,
        state text NOT NULL CHECK (state IN ('queued', 'running', 'done', 'failed', 'cancelled')),
        request bytea,
        epochs_total bigint NOT NULL,
        chunk_epochs bigint NOT NULL,
        created_ms bigint NOT NULL,
        started_ms bigint,
        finished_ms bigint,
        error text,
        attempts integer NOT NULL DEFAULT 0,
        idem_key text UNIQUE,
        idem_digest text,
        eval_max bigint,
        eval_done bigint,
        result_bytes bigint NOT NULL DEFAULT 0
    );
    CREATE INDEX glint_jobs_created ON glint_jobs (created_ms DESC, id);
    CREATE INDEX glint_jobs_unfinished ON glint_jobs (state) WHERE state IN ('queued', 'running');
    CREATE TABLE glint_chunks (
        job_id text NOT NULL REFERENCES glint_jobs (id) ON DELETE CASCADE,
        idx integer NOT NULL,
        first_epoch bigint NOT NULL,
        epochs bigint NOT NULL,
        state text NOT NULL CHECK (state IN ('queued', 'running', 'done')),
        lease_until timestamptz,
        worker text,
        claims integer NOT NULL DEFAULT 0,
        done_by text,
        epochs_computed bigint NOT NULL DEFAULT 0,
        PRIMARY KEY (job_id, idx)
    );
    CREATE INDEX glint_chunks_open ON glint_chunks (job_id, idx) WHERE state <> 'done';
    CREATE TABLE glint_results (
        job_id text NOT NULL REFERENCES glint_jobs (id) ON DELETE CASCADE,
        idx integer NOT NULL,
        data bytea NOT NULL,
        PRIMARY KEY (job_id, idx)
    );",
)];

/// Brings the database to [`SCHEMA_VERSION`] (`apply`), or only checks that it is there.
/// Idempotent. A database newer than this binary is an error either way; one older is an
/// error only when `apply` is false. Returns the version found before.
pub async fn migrate(client: &mut Client, apply: bool) -> Result<i32, PgError> {
    let tx = client.transaction().await?;
    tx.execute("SELECT pg_advisory_xact_lock($1)", &[&MIGRATION_LOCK])
        .await?;
    tx.batch_execute(
        "CREATE TABLE IF NOT EXISTS glint_schema_version (
            version integer PRIMARY KEY,
            applied_at timestamptz NOT NULL DEFAULT now()
        )",
    )
    .await?;
    let found: i32 = tx
        .query_one(
            "SELECT coalesce(max(version), 0) FROM glint_schema_version",
            &[],
        )
        .await?
        .get(0);
    if found > SCHEMA_VERSION {
        return Err(PgError::SchemaNewer {
            found,
            ours: SCHEMA_VERSION,
        });
    }
    if found < SCHEMA_VERSION && !apply {
        return Err(PgError::SchemaOlder {
            found,
            ours: SCHEMA_VERSION,
        });
    }
    for (version, sql) in MIGRATIONS.iter().filter(|(v, _)| *v > found) {
        tx.batch_execute(sql).await?;
        tx.execute(
            "INSERT INTO glint_schema_version (version) VALUES ($1)",
            &[version],
        )
        .await?;
        tracing::info!("database schema migrated to version {version}");
    }
    tx.commit().await?;
    Ok(found)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_migrations_lead_to_the_binarys_version_one_step_at_a_time() {
        let versions: Vec<i32> = MIGRATIONS.iter().map(|(v, _)| *v).collect();
        let expected: Vec<i32> = (1..=SCHEMA_VERSION).collect();
        assert_eq!(versions, expected);
    }
}
