//! A failure of the job store: never the client's fault (a 5xx); whether it is the
//! disk's (which closes the database until it is reopened) or a full disk.

use std::path::PathBuf;

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
