//! Durable job storage: a redb database in the data directory.
//!
//! Tables keyed by job id: the job record (JSON), the request body as received, and once
//! done the result, written in the forms it is served in — a light curve's response JSON
//! and its CSV as numbered chunks, each thumbnail as its PNG; a fit's JSON only, in
//! chunks too — with their sizes. A result is never
//! read whole: a download reads one chunk at a time, so a large result costs the service
//! a chunk of memory per download, not the result. Every change is one committed
//! transaction with redb's default `Durability::Immediate` (fsync before `commit`
//! returns), so a job whose 202 was sent is on disk, and a crash (even `kill -9`) loses
//! nothing that was answered.
//!
//! | concept | file |
//! |---|---|
//! | the database: its tables, opening (and reopening after an I/O failure), job records and requests, the health check | `mod.rs` |
//! | a failure of the store, and whether it is the disk's | `error.rs` |
//! | a finished job's result: written in the forms it is served in, read, removed | `results.rs` |
//! | the forms and the chunk size; the writer that stores a result as numbered chunks | `chunks.rs` |
//! | results kept whole by an earlier version, moved into chunks at open | `legacy.rs` |

mod chunks;
mod error;
mod legacy;
mod results;
#[cfg(test)]
mod test_fixtures;

pub use chunks::{Form, CHUNK_BYTES};
pub use error::StoreError;
pub use results::Output;

use results::{remove_result, write_result};

use super::record::JobRecord;
use redb::{Database, ReadableDatabase, ReadableTable, TableDefinition};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::RwLock;

const JOBS: TableDefinition<&str, &[u8]> = TableDefinition::new("jobs");
const REQUESTS: TableDefinition<&str, &[u8]> = TableDefinition::new("requests");
/// Whole response JSON by job id: how results were kept before they were chunked. Read
/// only to move them into the chunked tables when the store is opened.
const LEGACY_RESULTS: TableDefinition<&str, &[u8]> = TableDefinition::new("results");
/// A result's serialised forms, by (job id, form, chunk number from 0).
const RESULT_CHUNKS: TableDefinition<(&str, u8, u32), &[u8]> =
    TableDefinition::new("result_chunks");
/// A result's bytes in each form (JSON, CSV, all PNGs), by job id.
const RESULT_SIZES: TableDefinition<&str, (u64, u64, u64)> = TableDefinition::new("result_sizes");
/// A finished job's thumbnails, decoded, by (job id, epoch index).
const THUMBNAILS: TableDefinition<(&str, u64), &[u8]> = TableDefinition::new("thumbnails");

/// redb's page cache (reads and writes together). Its default, 1 GiB, would fill with
/// the pages of the results being written and downloaded; the records need little.
const CACHE_BYTES: usize = 16 << 20;

/// File name of the database inside `--data-dir`.
pub const FILE_NAME: &str = "glint.redb";

/// The job database.
///
/// A failed write (a full disk above all) leaves redb refusing every later operation
/// ("previous I/O error"): the store then drops the database and opens it again on the
/// next operation, so it recovers by itself once space returns, without a restart.
pub struct Store {
    path: PathBuf,
    /// `None` after an I/O failure, until a reopen succeeds.
    db: RwLock<Option<Database>>,
    /// Bytes of stored results (the response JSON of finished jobs).
    result_bytes: AtomicU64,
}

const HEALTH: TableDefinition<&str, u64> = TableDefinition::new("health");

impl Store {
    /// Opens (or creates) the database in `dir`, creating the directory. redb repairs
    /// itself here after an unclean shutdown. Errors name the path.
    pub fn open(dir: &Path) -> Result<Store, StoreError> {
        let path = dir.join(FILE_NAME);
        std::fs::create_dir_all(dir).map_err(|e| StoreError::Open {
            path: dir.to_path_buf(),
            source: e.into(),
        })?;
        let db = open_db(&path)?;
        let store = Store {
            path,
            db: RwLock::new(Some(db)),
            result_bytes: AtomicU64::new(0),
        };
        store.move_legacy_results()?;
        // The sizes, not the results: opening reads a few bytes a job
        let bytes = store.with_db(|db| {
            let tx = db.begin_read()?;
            let t = tx.open_table(RESULT_SIZES)?;
            let mut n = 0u64;
            for row in t.iter()? {
                let (json, csv, png) = row?.1.value();
                n += json + csv + png;
            }
            Ok(n)
        })?;
        store.result_bytes.store(bytes, Ordering::Relaxed);
        Ok(store)
    }

    /// Path of the database file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Bytes of the results stored now.
    pub fn result_bytes(&self) -> u64 {
        self.result_bytes.load(Ordering::Relaxed)
    }

    /// Runs `f` on the database, reopening it first if an earlier I/O failure closed it,
    /// and closing it if `f` fails on I/O (so that the next call reopens it).
    fn with_db<T>(
        &self,
        f: impl FnOnce(&Database) -> Result<T, StoreError>,
    ) -> Result<T, StoreError> {
        {
            let guard = self.db.read().unwrap_or_else(|e| e.into_inner());
            if let Some(db) = guard.as_ref() {
                let out = f(db);
                if !matches!(&out, Err(e) if e.is_io()) {
                    return out;
                }
                drop(guard);
                // Close it; a concurrent caller may already have reopened a fresh one, so
                // only the failed handle is dropped (a fresh one fails again and is dropped
                // on its own next failure).
                *self.db.write().unwrap_or_else(|e| e.into_inner()) = None;
                return out;
            }
        }
        let mut guard = self.db.write().unwrap_or_else(|e| e.into_inner());
        if guard.is_none() {
            *guard = Some(open_db(&self.path)?);
        }
        let out = f(guard.as_ref().expect("just opened"));
        if matches!(&out, Err(e) if e.is_io()) {
            *guard = None;
        }
        out
    }

    /// Stores a new job and its request body in one transaction.
    pub fn insert(&self, rec: &JobRecord, request: &[u8]) -> Result<(), StoreError> {
        let value = serde_json::to_vec(rec)?;
        self.with_db(|db| {
            let tx = db.begin_write()?;
            {
                tx.open_table(JOBS)?
                    .insert(rec.id.as_str(), value.as_slice())?;
                tx.open_table(REQUESTS)?.insert(rec.id.as_str(), request)?;
            }
            tx.commit()?;
            Ok(())
        })
    }

    /// Rewrites a job record. With `result`, also stores it in its served forms (written
    /// chunk by chunk, never whole in memory); a job that reached a final state drops its
    /// request body (it will not run again).
    pub fn update(&self, rec: &JobRecord, result: Option<&Output>) -> Result<(), StoreError> {
        let value = serde_json::to_vec(rec)?;
        let (added, freed) = self.with_db(|db| {
            let tx = db.begin_write()?;
            let mut sizes = (0, 0);
            {
                tx.open_table(JOBS)?
                    .insert(rec.id.as_str(), value.as_slice())?;
                if let Some(r) = result {
                    let freed = remove_result(&tx, &rec.id)?;
                    sizes = (write_result(&tx, &rec.id, r)?, freed);
                }
                if rec.state.is_final() {
                    tx.open_table(REQUESTS)?.remove(rec.id.as_str())?;
                }
            }
            tx.commit()?;
            Ok(sizes)
        })?;
        self.result_bytes.fetch_add(added, Ordering::Relaxed);
        self.result_bytes.fetch_sub(freed, Ordering::Relaxed);
        Ok(())
    }

    /// Removes a job, its request and its result.
    pub fn remove(&self, id: &str) -> Result<(), StoreError> {
        let freed = self.with_db(|db| {
            let tx = db.begin_write()?;
            let freed;
            {
                tx.open_table(JOBS)?.remove(id)?;
                tx.open_table(REQUESTS)?.remove(id)?;
                freed = remove_result(&tx, id)?;
            }
            tx.commit()?;
            Ok(freed)
        })?;
        self.result_bytes.fetch_sub(freed, Ordering::Relaxed);
        Ok(())
    }

    /// Every job record.
    pub fn load_all(&self) -> Result<Vec<JobRecord>, StoreError> {
        self.with_db(|db| {
            let tx = db.begin_read()?;
            let table = tx.open_table(JOBS)?;
            let mut out = Vec::new();
            for row in table.iter()? {
                let (_, v) = row?;
                out.push(serde_json::from_slice(v.value())?);
            }
            Ok(out)
        })
    }

    /// The request body of a job that has not finished.
    pub fn request(&self, id: &str) -> Result<Option<Vec<u8>>, StoreError> {
        self.get(REQUESTS, id)
    }

    fn get(
        &self,
        table: TableDefinition<&str, &[u8]>,
        id: &str,
    ) -> Result<Option<Vec<u8>>, StoreError> {
        self.with_db(|db| {
            let tx = db.begin_read()?;
            let t = tx.open_table(table)?;
            Ok(t.get(id)?.map(|v| v.value().to_vec()))
        })
    }

    /// Whether the database can be read and written now (for `/readyz`): a read, and a
    /// committed write of the time into a one-row table. Reopens it if an earlier failure
    /// closed it, so readiness comes back by itself once the disk has room again.
    pub fn check(&self) -> Result<(), StoreError> {
        if !self.path.exists() {
            return Err(StoreError::Missing(self.path.clone()));
        }
        self.with_db(|db| {
            let tx = db.begin_read()?;
            tx.open_table(JOBS)?;
            drop(tx);
            let tx = db.begin_write()?;
            {
                let now = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_secs());
                tx.open_table(HEALTH)?.insert("last_write_s", now)?;
            }
            tx.commit()?;
            Ok(())
        })
    }
}

/// Opens or creates the database file and its tables, naming the path on failure.
fn open_db(path: &Path) -> Result<Database, StoreError> {
    let named = |e: redb::Error| StoreError::Open {
        path: path.to_path_buf(),
        source: e,
    };
    let db = Database::builder()
        .set_cache_size(CACHE_BYTES)
        .create(path)
        .map_err(|e| named(e.into()))?;
    let tx = db.begin_write().map_err(|e| named(e.into()))?;
    for t in [JOBS, REQUESTS] {
        tx.open_table(t).map_err(|e| named(e.into()))?;
    }
    tx.open_table(RESULT_CHUNKS).map_err(|e| named(e.into()))?;
    tx.open_table(RESULT_SIZES).map_err(|e| named(e.into()))?;
    tx.open_table(THUMBNAILS).map_err(|e| named(e.into()))?;
    tx.commit().map_err(|e| named(e.into()))?;
    Ok(db)
}
