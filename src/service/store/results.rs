//! A finished job's result, stored in the forms it is served in: a light curve's response
//! JSON and its CSV as numbered chunks, each thumbnail as its PNG; a fit's JSON only, in
//! chunks too; with their sizes. Read a chunk at a time, never whole (but in tests and
//! tools).

use super::chunks::{Chunks, Form};
use super::{Store, StoreError, RESULT_CHUNKS, RESULT_SIZES, THUMBNAILS};
use crate::scene::Response;
use base64::Engine as _;
use redb::{ReadableDatabase, WriteTransaction};
use std::io::Write;

/// What a finished job stores.
#[derive(Debug)]
pub enum Output {
    /// A light curve: served as its JSON, its CSV and its thumbnails.
    Lightcurve(Response),
    /// A light-curve fit's result, as its JSON: served as JSON only.
    Fit(Vec<u8>),
}

impl Store {
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
}

/// Writes `out` for job `id` in every form it is served in within `tx`; returns the bytes
/// stored.
pub(super) fn write_result(
    tx: &WriteTransaction,
    id: &str,
    out: &Output,
) -> Result<u64, StoreError> {
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
pub(super) fn remove_result(tx: &WriteTransaction, id: &str) -> Result<u64, StoreError> {
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

#[cfg(test)]
mod tests {
    use super::super::test_fixtures::{done_record, response, temp};
    use super::super::CHUNK_BYTES;
    use super::*;

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
}
