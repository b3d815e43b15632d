//! A sweep job's lock: `jobs/ID.lock`, held (an exclusive `flock`, std's [`File::lock`]) by
//! the one process running job `ID`, so two workers — two array tasks with overlapping shards,
//! two executors, or a resubmitted task beside a dying one — never run or write the same job.
//!
//! The rule, for the CLI's `sweep` and Python's `run_job` alike: a worker that finds the lock
//! held **waits** for it (saying so in a note to the caller's [`Notes`]), then looks again —
//! the job is skipped if the holder finished it, resumed from its checkpoint if the holder
//! died. The operating system drops the lock of a process that dies, however it dies, so a
//! killed worker never leaves a job locked. [`JobLock::try_acquire`] is the variant that
//! returns at once instead of waiting.
//!
//! Lock files stay after the job (removing one while another process waits on it would let a
//! third lock a new file of the same name); they are fuzzymotiv's own files
//! ([`is_lock_name`]), removed with their sweep by `--force`.

use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::notes::Notes;

/// A held job lock; dropping it (or the process ending) releases it.
#[derive(Debug)]
pub struct JobLock {
    _file: File,
}

/// Where the lock of job `id` lives: `jobs_dir/ID.lock`.
pub fn lock_path(jobs_dir: &Path, id: &str) -> PathBuf {
    jobs_dir.join(format!("{id}.lock"))
}

/// Whether a file name is a job lock's (16 lowercase hexadecimal digits, then `.lock`).
pub fn is_lock_name(name: &str) -> bool {
    name.strip_suffix(".lock").is_some_and(|id| {
        id.len() == 16
            && id
                .bytes()
                .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
    })
}

/// An I/O error on `path` (as the guard words them; the guard imports this module, so not its
/// `io_err`, which would make a circle).
fn io_err(path: &Path, e: std::io::Error) -> CliError {
    CliError::Io {
        path: path.to_path_buf(),
        source: e,
    }
}

fn open(path: &Path) -> Result<File, CliError> {
    OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
        .map_err(|e| io_err(path, e))
}

impl JobLock {
    /// Takes the lock of job `id` under `jobs_dir`, waiting while another process holds it
    /// (after a note to `notes` naming the job and the lock file).
    pub fn acquire(jobs_dir: &Path, id: &str, notes: &dyn Notes) -> Result<JobLock, CliError> {
        if let Some(lock) = Self::try_acquire(jobs_dir, id)? {
            return Ok(lock);
        }
        let path = lock_path(jobs_dir, id);
        notes.note(&format!(
            "job {id}: another worker is running it (it holds {}); waiting for it to finish or die",
            path.display()
        ));
        let file = open(&path)?;
        file.lock().map_err(|e| io_err(&path, e))?;
        Ok(JobLock { _file: file })
    }

    /// Takes the lock of job `id` if no other process holds it; `None` if one does.
    pub fn try_acquire(jobs_dir: &Path, id: &str) -> Result<Option<JobLock>, CliError> {
        let path = lock_path(jobs_dir, id);
        let file = open(&path)?;
        match file.try_lock() {
            Ok(()) => Ok(Some(JobLock { _file: file })),
            Err(TryLockError::WouldBlock) => Ok(None),
            Err(TryLockError::Error(e)) => Err(io_err(&path, e)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_held_lock_is_refused_until_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let id = "0123456789abcdef";
        let held = JobLock::try_acquire(dir.path(), id).unwrap();
        assert!(held.is_some());
        // Another open file description (as another process has) cannot take it.
        assert!(JobLock::try_acquire(dir.path(), id).unwrap().is_none());
        drop(held);
        assert!(JobLock::try_acquire(dir.path(), id).unwrap().is_some());
        assert!(dir.path().join(format!("{id}.lock")).is_file());
    }

    #[test]
    fn lock_names_are_job_ids() {
        assert!(is_lock_name("0123456789abcdef.lock"));
        assert!(!is_lock_name("notes.lock"));
        assert!(!is_lock_name("0123456789ABCDEF.lock"));
        assert!(!is_lock_name("0123456789abcdef"));
    }
}
