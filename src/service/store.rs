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

use super::record::{JobKind, JobRecord};
use crate::scene::Response;
use base64::Engine as _;
use redb::{Database, ReadableDatabase, ReadableTable, TableDefinition, WriteTransaction};
use std::io::Write;
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

/// Bytes of one stored chunk. A little under a power of two: redb keeps a large value in
/// a page of the next power of two, so 1 MiB exactly would take 2 MiB on disk.
pub const CHUNK_BYTES: usize = (1 << 20) - 4096;

/// redb's page cache (reads and writes together). Its default, 1 GiB, would fill with
/// the pages of the results being written and downloaded; the records need little.
const CACHE_BYTES: usize = 16 << 20;

/// What a finished job stores.
#[derive(Debug)]
pub enum Output {
    /// A light curve: served as its JSON, its CSV and its thumbnails.
    Lightcurve(Response),
    /// A light-curve fit's result, as its JSON: served as JSON only.
    Fit(Vec<u8>),
}

/// A form in which a result is stored and served.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// The result, as `serde_json` writes it.
    Json,
    /// The light curve as CSV ([`crate::report::csv`]); a fit has none (0 bytes).
    Csv,
}

impl Form {
    fn tag(self) -> u8 {
        match self {
            Form::Json => 0,
            Form::Csv => 1,
        }
    }
}

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

    /// Rewrites each result kept whole (by a version before results were chunked) in the
    /// chunked forms, one result a transaction: a fit job's (its record says so) as its
    /// JSON, as it was. A light curve that does not parse is dropped from the old table and
    /// logged: its job then answers 404 for it, as for an expired one.
    fn move_legacy_results(&self) -> Result<(), StoreError> {
        let ids: Vec<String> = self.with_db(|db| {
            let tx = db.begin_read()?;
            let t = match tx.open_table(LEGACY_RESULTS) {
                Ok(t) => t,
                Err(redb::TableError::TableDoesNotExist(_)) => return Ok(Vec::new()),
                Err(e) => return Err(e.into()),
            };
            let mut ids = Vec::new();
            for row in t.iter()? {
                ids.push(row?.0.value().to_string());
            }
            Ok(ids)
        })?;
        for id in ids {
            self.with_db(|db| {
                let tx = db.begin_write()?;
                let fit = match tx.open_table(JOBS)?.get(id.as_str())? {
                    Some(v) => serde_json::from_slice::<JobRecord>(v.value())
                        .is_ok_and(|r| r.kind == JobKind::FitLightcurve),
                    None => false,
                };
                let parsed = {
                    let mut t = tx.open_table(LEGACY_RESULTS)?;
                    let old = t.remove(id.as_str())?;
                    old.map(|v| {
                        if fit {
                            Ok(Output::Fit(v.value().to_vec()))
                        } else {
                            serde_json::from_slice::<Response>(v.value()).map(Output::Lightcurve)
                        }
                    })
                };
                match parsed {
                    Some(Ok(out)) => {
                        write_result(&tx, &id, &out)?;
                    }
                    Some(Err(e)) => {
                        tracing::warn!(
                            job = id,
                            "dropped a stored result that does not parse: {e}"
                        );
                    }
                    None => {}
                }
                tx.commit()?;
                Ok(())
            })?;
        }
        Ok(())
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

    /// Bytes of a finished job's result in `form`; `None` when no result is stored.
    pub fn result_len(&self, id: &str, form: Form) -> Result<Option<u64>, StoreError> {
        self.with_db(|db| {
            let tx = db.begin_read()?;
            let t = tx.open_table(RESULT_SIZES)?;
            Ok(t.get(id)?.map(|v| {
                let (json, csv, _) = v.value();
                match form {
                    Form::Json => json,
                    Form::Csv => csv,
                }
            }))
        })
    }

    /// Chunk `index` (from 0) of a result in `form`, each in its own read transaction (a
    /// slow download holds no snapshot of the database); `None` past the last one, or
    /// when the result was removed meanwhile.
    pub fn result_chunk(
        &self,
        id: &str,
        form: Form,
        index: u32,
    ) -> Result<Option<Vec<u8>>, StoreError> {
        self.with_db(|db| {
            let tx = db.begin_read()?;
            let t = tx.open_table(RESULT_CHUNKS)?;
            Ok(t.get((id, form.tag(), index))?.map(|v| v.value().to_vec()))
        })
    }

    /// The PNG of epoch `epoch`'s thumbnail of a finished job, if it has one.
    pub fn thumbnail(&self, id: &str, epoch: u64) -> Result<Option<Vec<u8>>, StoreError> {
        self.with_db(|db| {
            let tx = db.begin_read()?;
            let t = tx.open_table(THUMBNAILS)?;
            Ok(t.get((id, epoch))?.map(|v| v.value().to_vec()))
        })
    }

    /// A whole result in `form`, chunks joined (tests and tools; the service streams).
    pub fn read_result(&self, id: &str, form: Form) -> Result<Option<Vec<u8>>, StoreError> {
        let Some(len) = self.result_len(id, form)? else {
            return Ok(None);
        };
        let mut out = Vec::with_capacity(len as usize);
        let mut index = 0;
        while (out.len() as u64) < len {
            match self.result_chunk(id, form, index)? {
                Some(c) => out.extend_from_slice(&c),
                None => return Ok(None),
            }
            index += 1;
        }
        Ok(Some(out))
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

/// Writes `out` for job `id` in every form it is served in within `tx`; returns the bytes
/// stored.
fn write_result(tx: &WriteTransaction, id: &str, out: &Output) -> Result<u64, StoreError> {
    let resp = match out {
        Output::Lightcurve(resp) => resp,
        Output::Fit(json) => {
            let mut chunks = tx.open_table(RESULT_CHUNKS)?;
            let mut w = Chunks::new(&mut chunks, id, Form::Json);
            w.write_all(json).map_err(|e| w.error(e))?;
            let n = w.finish()?;
            drop(chunks);
            tx.open_table(RESULT_SIZES)?.insert(id, (n, 0, 0))?;
            return Ok(n);
        }
    };
    let mut chunks = tx.open_table(RESULT_CHUNKS)?;
    let mut json = Chunks::new(&mut chunks, id, Form::Json);
    serde_json::to_writer(&mut json, resp).map_err(|e| json.error(e.into()))?;
    let json = json.finish()?;
    let mut csv = Chunks::new(&mut chunks, id, Form::Csv);
    crate::report::csv::write_csv(resp, &mut csv).map_err(|e| csv.error(e))?;
    let csv = csv.finish()?;
    drop(chunks);
    let mut png = 0u64;
    let mut thumbs = tx.open_table(THUMBNAILS)?;
    for t in resp.thumbnails.iter().flatten() {
        // The engine made this base64 itself: a failure is a fault, not bad input
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(t.png_base64.as_bytes())
            .map_err(|e| StoreError::Io(std::io::Error::other(format!("thumbnail: {e}"))))?;
        png += bytes.len() as u64;
        thumbs.insert((id, t.epoch as u64), bytes.as_slice())?;
    }
    tx.open_table(RESULT_SIZES)?.insert(id, (json, csv, png))?;
    Ok(json + csv + png)
}

/// Removes job `id`'s result (every form) within `tx`; returns the bytes freed.
fn remove_result(tx: &WriteTransaction, id: &str) -> Result<u64, StoreError> {
    let Some((json, csv, png)) = tx.open_table(RESULT_SIZES)?.remove(id)?.map(|v| v.value()) else {
        return Ok(0);
    };
    let mut chunks = tx.open_table(RESULT_CHUNKS)?;
    for form in [Form::Json, Form::Csv] {
        chunks.retain_in((id, form.tag(), 0)..=(id, form.tag(), u32::MAX), |_, _| {
            false
        })?;
    }
    tx.open_table(THUMBNAILS)?
        .retain_in((id, 0)..=(id, u64::MAX), |_, _| false)?;
    Ok(json + csv + png)
}

/// A writer that stores what it is given as numbered chunks of [`CHUNK_BYTES`] (the last
/// shorter), so that a result is serialised straight into the database.
struct Chunks<'a, 't> {
    table: &'a mut redb::Table<'t, (&'static str, u8, u32), &'static [u8]>,
    id: &'a str,
    form: Form,
    buf: Vec<u8>,
    index: u32,
    written: u64,
    /// The database's error behind an `io::Error` returned to the serialiser.
    failed: Option<StoreError>,
}

impl<'a, 't> Chunks<'a, 't> {
    fn new(
        table: &'a mut redb::Table<'t, (&'static str, u8, u32), &'static [u8]>,
        id: &'a str,
        form: Form,
    ) -> Self {
        Chunks {
            table,
            id,
            form,
            buf: Vec::with_capacity(CHUNK_BYTES),
            index: 0,
            written: 0,
            failed: None,
        }
    }

    fn store(&mut self) -> std::io::Result<()> {
        let r = self
            .table
            .insert((self.id, self.form.tag(), self.index), self.buf.as_slice());
        if let Err(e) = r {
            self.failed = Some(e.into());
            return Err(std::io::Error::other("the job store failed"));
        }
        self.written += self.buf.len() as u64;
        self.index += 1;
        self.buf.clear();
        Ok(())
    }

    /// The error to report for `e`, a failure of writing: the database's own if it failed.
    fn error(&mut self, e: std::io::Error) -> StoreError {
        self.failed.take().unwrap_or(StoreError::Io(e))
    }

    /// Stores what is left; returns the bytes written in all.
    fn finish(mut self) -> Result<u64, StoreError> {
        if !self.buf.is_empty() {
            self.store().map_err(|e| self.error(e))?;
        }
        Ok(self.written)
    }
}

impl Write for Chunks<'_, '_> {
    fn write(&mut self, mut data: &[u8]) -> std::io::Result<usize> {
        let n = data.len();
        while !data.is_empty() {
            let take = (CHUNK_BYTES - self.buf.len()).min(data.len());
            self.buf.extend_from_slice(&data[..take]);
            data = &data[take..];
            if self.buf.len() == CHUNK_BYTES {
                self.store()?;
            }
        }
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::service::record::JobState;

    fn done_record(id: &str) -> JobRecord {
        JobRecord {
            id: id.to_string(),
            state: JobState::Done,
            epochs_total: 0,
            epochs_done: 0,
            created_ms: 1,
            started_ms: Some(2),
            finished_ms: Some(3),
            error: None,
            attempts: 1,
            idempotency: None,
            kind: JobKind::Lightcurve,
            evaluations: None,
        }
    }

    /// A light curve of `n` epochs with two thumbnails: over a megabyte of JSON at 4000.
    fn response(n: usize) -> Response {
        let mut req = crate::service::routes::example_request();
        let epochs = req["epochs"].as_array().unwrap().clone();
        req["epochs"] = epochs.iter().cycle().take(n).cloned().collect();
        req["thumbnails"] = serde_json::json!({ "size": 8, "samples": 1, "epochs": [0, 1] });
        let scene =
            crate::Scene::from_json(&req.to_string(), &crate::scene::Limits::unlimited()).unwrap();
        crate::simulate(&scene)
    }

    fn temp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("glint-store-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn a_result_is_stored_in_chunks_that_join_to_its_json_csv_and_images() {
        let dir = temp("chunks");
        let store = Store::open(&dir).unwrap();
        let resp = response(4000);
        let json = serde_json::to_vec(&resp).unwrap();
        let csv = crate::report::csv::to_csv(&resp).into_bytes();
        assert!(
            json.len() > CHUNK_BYTES,
            "{} bytes: one chunk only",
            json.len()
        );
        store
            .update(&done_record("a"), Some(&Output::Lightcurve(resp.clone())))
            .unwrap();

        assert_eq!(
            store.result_len("a", Form::Json).unwrap(),
            Some(json.len() as u64)
        );
        assert_eq!(
            store.read_result("a", Form::Json).unwrap().as_deref(),
            Some(&json[..])
        );
        assert_eq!(
            store.read_result("a", Form::Csv).unwrap().as_deref(),
            Some(&csv[..])
        );
        let first = store.result_chunk("a", Form::Json, 0).unwrap().unwrap();
        assert_eq!(first.len(), CHUNK_BYTES);
        let thumbs = resp.thumbnails.as_ref().unwrap();
        let png = base64::engine::general_purpose::STANDARD
            .decode(&thumbs[1].png_base64)
            .unwrap();
        assert_eq!(store.thumbnail("a", 1).unwrap(), Some(png));
        assert_eq!(store.thumbnail("a", 2).unwrap(), None);

        // every form counts, in the running total and when counted again at open
        let total = store.result_bytes();
        assert!(total > (json.len() + csv.len()) as u64);
        drop(store);
        let store = Store::open(&dir).unwrap();
        assert_eq!(store.result_bytes(), total);
        store.remove("a").unwrap();
        assert_eq!(store.result_bytes(), 0);
        assert_eq!(store.result_len("a", Form::Json).unwrap(), None);
        assert_eq!(store.result_chunk("a", Form::Json, 0).unwrap(), None);
        assert_eq!(store.thumbnail("a", 1).unwrap(), None);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_result_kept_whole_by_an_earlier_version_is_moved_into_chunks_at_open() {
        let dir = temp("legacy");
        std::fs::create_dir_all(&dir).unwrap();
        let resp = response(30);
        let json = serde_json::to_vec(&resp).unwrap();
        {
            // the earlier layout: the record and the whole JSON in `results`
            let db = Database::create(dir.join(FILE_NAME)).unwrap();
            let tx = db.begin_write().unwrap();
            {
                let rec = serde_json::to_vec(&done_record("old")).unwrap();
                tx.open_table(JOBS)
                    .unwrap()
                    .insert("old", rec.as_slice())
                    .unwrap();
                tx.open_table(REQUESTS).unwrap();
                let mut t = tx.open_table(LEGACY_RESULTS).unwrap();
                t.insert("old", json.as_slice()).unwrap();
                t.insert("bad", &b"{not json"[..]).unwrap();
            }
            tx.commit().unwrap();
        }
        let store = Store::open(&dir).unwrap();
        assert_eq!(store.read_result("old", Form::Json).unwrap(), Some(json));
        let csv = crate::report::csv::to_csv(&resp).into_bytes();
        assert_eq!(store.read_result("old", Form::Csv).unwrap(), Some(csv));
        assert!(store.thumbnail("old", 0).unwrap().is_some());
        // one that does not parse is dropped (and logged), not a failure to start
        assert_eq!(store.result_len("bad", Form::Json).unwrap(), None);
        assert_eq!(store.load_all().unwrap().len(), 1);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_fits_result_is_stored_as_its_json_only_and_moved_as_it_was() {
        let dir = temp("fit");
        std::fs::create_dir_all(&dir).unwrap();
        let json = br#"{"parameters":{"materials.surface.albedo":0.25}}"#.to_vec();
        let fit_record = |id: &str| JobRecord {
            kind: JobKind::FitLightcurve,
            ..done_record(id)
        };
        {
            // kept whole by an earlier version: not a light curve, yet not dropped
            let db = Database::create(dir.join(FILE_NAME)).unwrap();
            let tx = db.begin_write().unwrap();
            {
                let rec = serde_json::to_vec(&fit_record("old")).unwrap();
                tx.open_table(JOBS)
                    .unwrap()
                    .insert("old", rec.as_slice())
                    .unwrap();
                tx.open_table(REQUESTS).unwrap();
                tx.open_table(LEGACY_RESULTS)
                    .unwrap()
                    .insert("old", json.as_slice())
                    .unwrap();
            }
            tx.commit().unwrap();
        }
        let store = Store::open(&dir).unwrap();
        store
            .update(&fit_record("new"), Some(&Output::Fit(json.clone())))
            .unwrap();
        for id in ["old", "new"] {
            assert_eq!(
                store.read_result(id, Form::Json).unwrap().as_ref(),
                Some(&json)
            );
            assert_eq!(store.result_len(id, Form::Csv).unwrap(), Some(0));
            assert_eq!(store.thumbnail(id, 0).unwrap(), None);
        }
        assert_eq!(store.result_bytes(), 2 * json.len() as u64);
        store.remove("new").unwrap();
        assert_eq!(store.result_bytes(), json.len() as u64);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
