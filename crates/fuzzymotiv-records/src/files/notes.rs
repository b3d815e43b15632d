//! Notes: what the libraries say on the way that is not an error (a config's motivations were
//! normalised, `--force` replaces an output, a job is locked by another worker). A library
//! never prints them: it returns them as data (e.g. [`Loaded::notes`]) or hands them to the
//! caller's [`Notes`], and each front shows them its own way — the command line on stderr,
//! Python as `warnings.warn`, the lab on its page.
//!
//! [`Loaded::notes`]: crate::files::inputs::Loaded::notes

use std::sync::{Mutex, PoisonError};

/// Where a library's notes go: the caller's (see the module docs). Shared between the threads
/// a sweep's jobs run on.
pub trait Notes: Sync {
    /// One note, a line without its newline.
    fn note(&self, line: &str);
}

/// Notes kept in order, for a front that shows them once the work is done (Python's
/// warnings, the lab's page).
#[derive(Debug, Default)]
pub struct NoteList(Mutex<Vec<String>>);

impl NoteList {
    /// The notes so far, in order, leaving the list empty.
    pub fn take(&self) -> Vec<String> {
        std::mem::take(&mut *self.lock())
    }

    /// The notes so far, in order, kept.
    pub fn lines(&self) -> Vec<String> {
        self.lock().clone()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<String>> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl Notes for NoteList {
    fn note(&self, line: &str) {
        self.lock().push(line.to_string());
    }
}

/// Notes nobody reads (a caller that knows there is nothing to say, e.g. without `force`).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoNotes;

impl Notes for NoNotes {
    fn note(&self, _line: &str) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A list keeps the notes in order and hands them over once.
    #[test]
    fn a_note_list_keeps_notes_in_order_and_hands_them_over_once() {
        let list = NoteList::default();
        let notes: &dyn Notes = &list;
        notes.note("first");
        notes.note("second");
        assert_eq!(list.lines(), ["first", "second"]);
        assert_eq!(list.take(), ["first", "second"]);
        assert!(list.take().is_empty());
    }
}
