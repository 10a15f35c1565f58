//! Durable job storage: a redb database in the data directory.
//!
//! Three tables keyed by job id: the job record (JSON), the request body as received, and
//! the response JSON once done. Every change is one committed transaction with redb's
//! default `Durability::Immediate` (fsync before `commit` returns), so a job whose 202 was
//! sent is on disk, and a crash (even `kill -9`) loses nothing that was answered.

use super::record::JobRecord;
use redb::{Database, ReadableDatabase, ReadableTable, TableDefinition};
use std::path::Path;

const JOBS: TableDefinition<&str, &[u8]> = TableDefinition::new("jobs");
const REQUESTS: TableDefinition<&str, &[u8]> = TableDefinition::new("requests");
const RESULTS: TableDefinition<&str, &[u8]> = TableDefinition::new("results");

/// File name of the database inside `--data-dir`.
pub const FILE_NAME: &str = "glint.redb";

/// A storage failure (disk, corruption): a 500, never the client's fault.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    #[error("storage: {0}")]
    Db(#[from] redb::Error),
    #[error("storage: {0}")]
    Io(#[from] std::io::Error),
    #[error("storage: corrupt record: {0}")]
    Corrupt(#[from] serde_json::Error),
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
pub struct Store {
    db: Database,
}

impl Store {
    /// Opens (or creates) the database in `dir`, creating the directory. redb repairs
    /// itself here after an unclean shutdown.
    pub fn open(dir: &Path) -> Result<Store, StoreError> {
        std::fs::create_dir_all(dir)?;
        let db = Database::create(dir.join(FILE_NAME))?;
        let tx = db.begin_write()?;
        tx.open_table(JOBS)?;
        tx.open_table(REQUESTS)?;
        tx.open_table(RESULTS)?;
        tx.commit()?;
        Ok(Store { db })
    }

    /// Stores a new job and its request body in one transaction.
    pub fn insert(&self, rec: &JobRecord, request: &[u8]) -> Result<(), StoreError> {
        let value = serde_json::to_vec(rec)?;
        let tx = self.db.begin_write()?;
        {
            tx.open_table(JOBS)?
                .insert(rec.id.as_str(), value.as_slice())?;
            tx.open_table(REQUESTS)?.insert(rec.id.as_str(), request)?;
        }
        tx.commit()?;
        Ok(())
    }

    /// Rewrites a job record. With `result`, also stores the response; a job that reached
    /// a final state drops its request body (it will not run again).
    pub fn update(&self, rec: &JobRecord, result: Option<&[u8]>) -> Result<(), StoreError> {
        let value = serde_json::to_vec(rec)?;
        let tx = self.db.begin_write()?;
        {
            tx.open_table(JOBS)?
                .insert(rec.id.as_str(), value.as_slice())?;
            if let Some(r) = result {
                tx.open_table(RESULTS)?.insert(rec.id.as_str(), r)?;
            }
            if rec.state.is_final() {
                tx.open_table(REQUESTS)?.remove(rec.id.as_str())?;
            }
        }
        tx.commit()?;
        Ok(())
    }

    /// Removes a job, its request and its result.
    pub fn remove(&self, id: &str) -> Result<(), StoreError> {
        let tx = self.db.begin_write()?;
        {
            tx.open_table(JOBS)?.remove(id)?;
            tx.open_table(REQUESTS)?.remove(id)?;
            tx.open_table(RESULTS)?.remove(id)?;
        }
        tx.commit()?;
        Ok(())
    }

    /// Every job record.
    pub fn load_all(&self) -> Result<Vec<JobRecord>, StoreError> {
        let tx = self.db.begin_read()?;
        let table = tx.open_table(JOBS)?;
        let mut out = Vec::new();
        for row in table.iter()? {
            let (_, v) = row?;
            out.push(serde_json::from_slice(v.value())?);
        }
        Ok(out)
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
        let tx = self.db.begin_read()?;
        let t = tx.open_table(table)?;
        Ok(t.get(id)?.map(|v| v.value().to_vec()))
    }

    /// Whether the database answers a read (for `/readyz`).
    pub fn check(&self) -> Result<(), StoreError> {
        let tx = self.db.begin_read()?;
        tx.open_table(JOBS)?;
        Ok(())
    }
}
