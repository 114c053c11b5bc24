//! Telling when a file is saved, from the system's file events (`notify`,
//! with its debouncer gathering the several events of one save).
//!
//! The folder is watched rather than the file: an editor that saves by
//! writing a new file and renaming it over the old one replaces the file
//! that a watch on the file itself would follow.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

use notify_debouncer_full::notify::event::{AccessKind, AccessMode};
use notify_debouncer_full::notify::{self, EventKind, RecommendedWatcher, RecursiveMode};
use notify_debouncer_full::{DebounceEventResult, DebouncedEvent, Debouncer, RecommendedCache, new_debouncer};

use crate::repl::{SaveWatcher, Waited};

/// How long the events of one save are gathered before it is reported.
const SETTLE: Duration = Duration::from_millis(150);

/// How often a wait looks at its cancel flag.
const CANCEL_CHECK: Duration = Duration::from_millis(50);

/// Follows one file through its saves.
pub(crate) struct FileWatcher {
    /// Kept for its thread and its system watch, which end when it drops.
    _debouncer: Debouncer<RecommendedWatcher, RecommendedCache>,
    events: Receiver<DebounceEventResult>,
    /// The file, in its folder's canonical form, as events name it.
    file: PathBuf,
}

/// Why a file cannot be watched.
#[derive(Debug)]
pub(crate) struct WatchError {
    /// The file.
    path: PathBuf,
    /// What the system said, in words.
    reason: String,
}

impl fmt::Display for WatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot watch `{}`: {}", self.path.display(), self.reason)
    }
}

impl std::error::Error for WatchError {}

impl FileWatcher {
    /// Starts following the file at `path`, whose folder must exist.
    pub(crate) fn new(path: &Path) -> Result<FileWatcher, WatchError> {
        let failed = |reason: String| WatchError { path: path.to_path_buf(), reason };
        let name = path.file_name().ok_or_else(|| failed("it names no file".to_string()))?;
        let folder = match path.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        let folder = folder.canonicalize().map_err(|e| failed(crate::output::io_reason(&e)))?;
        let (sender, events) = channel();
        let mut debouncer = new_debouncer(SETTLE, None, sender).map_err(|e| failed(e.to_string()))?;
        debouncer.watch(&folder, RecursiveMode::NonRecursive).map_err(|e| failed(e.to_string()))?;
        Ok(FileWatcher { _debouncer: debouncer, events, file: folder.join(name) })
    }

    /// Waits until the file is saved, or until `cancel` is raised.
    pub(crate) fn wait(&self, cancel: &AtomicBool) -> Result<Waited, WatchError> {
        let failed = |reason: String| WatchError { path: self.file.clone(), reason };
        loop {
            if cancel.load(Ordering::SeqCst) {
                return Ok(Waited::Cancelled);
            }
            match self.events.recv_timeout(CANCEL_CHECK) {
                Ok(Ok(events)) if events.iter().any(|event| self.is_save(event)) => return Ok(Waited::Saved),
                Ok(Ok(_)) | Err(RecvTimeoutError::Timeout) => {}
                Ok(Err(errors)) => {
                    let reasons: Vec<String> = errors.iter().map(notify::Error::to_string).collect();
                    return Err(failed(reasons.join("; ")));
                }
                Err(RecvTimeoutError::Disconnected) => return Err(failed("the watch stopped".to_string())),
            }
        }
    }

    /// Whether `event` writes or replaces the file: reading it (as the
    /// renders do) or removing it (in the middle of some saves) does not.
    fn is_save(&self, event: &DebouncedEvent) -> bool {
        let writes = match event.kind {
            EventKind::Create(_) | EventKind::Modify(_) => true,
            EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
            EventKind::Access(_) | EventKind::Remove(_) | EventKind::Any | EventKind::Other => false,
        };
        writes && event.paths.contains(&self.file)
    }
}

/// The session's `:watch` waits on it as the batch `--watch` does.
impl SaveWatcher for FileWatcher {
    fn wait(&self, cancel: &AtomicBool) -> Result<Waited, String> {
        // The inherent `wait`, its error in words.
        FileWatcher::wait(self, cancel).map_err(|error| error.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_in_a_missing_folder_cannot_be_watched() {
        let error = FileWatcher::new(Path::new("no/such/folder/a.ray")).err().expect("refused");
        assert_eq!(error.to_string(), "cannot watch `no/such/folder/a.ray`: no such file or folder");
    }

    #[test]
    fn a_raised_flag_ends_the_wait() {
        let folder = tempfile::tempdir().expect("temporary folder");
        let watcher = FileWatcher::new(&folder.path().join("a.ray")).expect("the folder can be watched");
        assert_eq!(watcher.wait(&AtomicBool::new(true)).ok(), Some(Waited::Cancelled));
    }
}
