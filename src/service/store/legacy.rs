//! Results kept whole by a version before results were chunked, moved into the chunked
//! tables when the store is opened.

use super::results::{write_result, Output};
use super::{Store, StoreError, JOBS, LEGACY_RESULTS};
use crate::scene::Response;
use crate::service::record::{JobKind, JobRecord};
use redb::{ReadableDatabase, ReadableTable};

impl Store {
    /// Rewrites each result kept whole (by a version before results were chunked) in the
    /// chunked forms, one result a transaction: a fit job's (its record says so) as its
    /// JSON, as it was. A light curve that does not parse is dropped from the old table and
    /// logged: its job then answers 404 for it, as for an expired one.
    pub(super) fn move_legacy_results(&self) -> Result<(), StoreError> {
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
}

#[cfg(test)]
mod tests {
    use super::super::test_fixtures::{done_record, response, temp};
    use super::super::{Form, Output, FILE_NAME, REQUESTS};
    use super::*;
    use redb::Database;

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
