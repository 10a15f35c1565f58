//! Durable job storage: a redb database in the data directory.
//!
//! Three tables keyed by job id: the job record (JSON), the request body as received, and
//! the response JSON once done. Every change is one committed transaction with redb's
//! default `Durability::Immediate` (fsync before `commit` returns), so a job whose 202 was
//! sent is on disk, and a crash (even `kill -9`) loses nothing that was answered.

use super::record::JobRecord;
use redb::{Database, ReadableDatabase, ReadableTable, TableDefinition};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::RwLock;

const JOBS: TableDefinition<&str, &[u8]> = TableDefinition::new("jobs");
const REQUESTS: TableDefinition<&str, &[u8]> = TableDefinition::new("requests");
const RESULTS: TableDefinition<&str, &[u8]> = TableDefinition::new("results");

/// File name of the database inside `--data-dir`.
pub const FILE_NAME: &str = "glint.redb";

/// A storage failure (disk, corruption): never the client's fault (a 5xx).
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    #[error("storage: {0}")]
    Db(#[from] redb::Error),
    #[error("storage: {0}")]
    Io(#[from] std::io::Error),
    #[error("storage: corrupt record: {0}")]
    Corrupt(#[from] serde_json::Error),
    #[error("cannot open the job database {}: {source}", path.display())]
    Open { path: PathBuf, source: redb::Error },
    #[error("the job database {} is gone (deleted while the service runs?)", .0.display())]
    Missing(PathBuf),
}

impl StoreError {
    /// A failure of the disk under the database (which closes it until reopened).
    pub fn is_io(&self) -> bool {
        match self {
            StoreError::Io(_) => true,
            StoreError::Db(e) | StoreError::Open { source: e, .. } => {
                matches!(e, redb::Error::Io(_) | redb::Error::PreviousIo)
            }
            _ => false,
        }
    }

    /// The disk is full (ENOSPC, or a quota).
    pub fn is_full(&self) -> bool {
        let io = match self {
            StoreError::Io(e) => Some(e),
            StoreError::Db(redb::Error::Io(e)) => Some(e),
            StoreError::Open {
                source: redb::Error::Io(e),
                ..
            } => Some(e),
            _ => None,
        };
        io.is_some_and(|e| {
            matches!(
                e.kind(),
                std::io::ErrorKind::StorageFull | std::io::ErrorKind::QuotaExceeded
            )
        })
    }
}

macro_rules! from_redb {
    ($($t:ty),*) => {$(
        impl From<$t> for StoreError {
            fn from(e: $t) -> Self {
                StoreError::Db(e.into())
            }
        }
    )*};
}
from_redb!(
    redb::DatabaseError,
    redb::TransactionError,
    redb::TableError,
    redb::StorageError,
    redb::CommitError
);

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
        let bytes = store.with_db(|db| {
            let tx = db.begin_read()?;
            let t = tx.open_table(RESULTS)?;
            let mut n = 0u64;
            for row in t.iter()? {
                n += row?.1.value().len() as u64;
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

    /// Rewrites a job record. With `result`, also stores the response; a job that reached
    /// a final state drops its request body (it will not run again).
    pub fn update(&self, rec: &JobRecord, result: Option<&[u8]>) -> Result<(), StoreError> {
        let value = serde_json::to_vec(rec)?;
        let replaced = self.with_db(|db| {
            let tx = db.begin_write()?;
            let mut replaced = 0u64;
            {
                tx.open_table(JOBS)?
                    .insert(rec.id.as_str(), value.as_slice())?;
                if let Some(r) = result {
                    if let Some(old) = tx.open_table(RESULTS)?.insert(rec.id.as_str(), r)? {
                        replaced = old.value().len() as u64;
                    }
                }
                if rec.state.is_final() {
                    tx.open_table(REQUESTS)?.remove(rec.id.as_str())?;
                }
            }
            tx.commit()?;
            Ok(replaced)
        })?;
        if let Some(r) = result {
            self.result_bytes
                .fetch_add(r.len() as u64, Ordering::Relaxed);
            self.result_bytes.fetch_sub(replaced, Ordering::Relaxed);
        }
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
                freed = tx
                    .open_table(RESULTS)?
                    .remove(id)?
                    .map_or(0, |v| v.value().len() as u64);
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

    /// The response JSON of a finished job.
    pub fn result(&self, id: &str) -> Result<Option<Vec<u8>>, StoreError> {
        self.get(RESULTS, id)
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
    let db = Database::create(path).map_err(|e| named(e.into()))?;
    let tx = db.begin_write().map_err(|e| named(e.into()))?;
    for t in [JOBS, REQUESTS, RESULTS] {
        tx.open_table(t).map_err(|e| named(e.into()))?;
    }
    tx.commit().map_err(|e| named(e.into()))?;
    Ok(db)
}
