//! A result's chunks: the forms a result is stored in, the size of a chunk, and the
//! writer that stores what it is given as numbered chunks, so that a result is
//! serialised straight into the database, never whole in memory.

use super::StoreError;
use std::io::Write;

/// Bytes of one stored chunk. A little under a power of two: redb keeps a large value in
/// a page of the next power of two, so 1 MiB exactly would take 2 MiB on disk.
pub const CHUNK_BYTES: usize = (1 << 20) - 4096;

/// A form in which a result is stored and served.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// The result, as `serde_json` writes it.
    Json,
    /// The light curve as CSV ([`crate::report::csv`]); a fit has none (0 bytes).
    Csv,
}

impl Form {
    pub(super) fn tag(self) -> u8 {
        match self {
            Form::Json => 0,
            Form::Csv => 1,
        }
    }
}

/// A writer that stores what it is given as numbered chunks of [`CHUNK_BYTES`] (the last
/// shorter), so that a result is serialised straight into the database.
pub(super) struct Chunks<'a, 't> {
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
    pub(super) fn new(
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
    pub(super) fn error(&mut self, e: std::io::Error) -> StoreError {
        self.failed.take().unwrap_or(StoreError::Io(e))
    }

    /// Stores what is left; returns the bytes written in all.
    pub(super) fn finish(mut self) -> Result<u64, StoreError> {
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
