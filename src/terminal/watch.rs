//! Telling when a file is saved, from the system's file events (`notify`,
//! with its debouncer gathering the several events of one save).
//!
//! The folder is watched rather than the file: an editor that saves by
//! writing a new file and renaming it over the old one replaces the file
//! that a watch on the file itself would follow.
//!
//! A system watch follows the folder it was set on, not its name: when the
//! folder is removed and made again (a `git checkout`, a build tool), or
//! another one is renamed in its place, the watch would go silent. So every
//! check of the cancel flag also looks at which folder the name gives; when
//! it changes, the watch moves to the new one, and a file already in it is
//! a save. While the folder is missing, the name is looked at alone.

use std::cell::RefCell;
use std::fmt;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

use notify_debouncer_full::notify::event::{AccessKind, AccessMode};
use notify_debouncer_full::notify::{self, EventKind, RecommendedWatcher, RecursiveMode};
use notify_debouncer_full::{DebounceEventResult, DebouncedEvent, Debouncer, RecommendedCache, new_debouncer};

use crate::session::{SaveWatcher, Waited};

/// How long the events of one save are gathered before it is reported.
const SETTLE: Duration = Duration::from_millis(150);

/// How often a wait looks at its cancel flag.
const CANCEL_CHECK: Duration = Duration::from_millis(50);

/// Follows one file through its saves.
pub(crate) struct FileWatcher {
    /// Its thread and its system watch end when it drops.
    debouncer: RefCell<Debouncer<RecommendedWatcher, RecommendedCache>>,
    events: Receiver<DebounceEventResult>,
    /// The folder, in canonical form.
    folder: PathBuf,
    /// The file, in its folder's canonical form, as events name it.
    file: PathBuf,
    /// The folder the system watch is on, `None` while the name gives none.
    watched: RefCell<Option<FolderIdentity>>,
}

/// Which folder a name gives: its device and inode where the system has
/// them (elsewhere a folder made again is not told from the old one).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct FolderIdentity(u64, u64);

impl FolderIdentity {
    /// The folder `path` gives now, if it gives one.
    fn of(path: &Path) -> Option<FolderIdentity> {
        let metadata = fs::metadata(path).ok().filter(fs::Metadata::is_dir)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            Some(FolderIdentity(metadata.dev(), metadata.ino()))
        }
        #[cfg(not(unix))]
        {
            let _ = metadata;
            Some(FolderIdentity(0, 0))
        }
    }
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
        let identity = FolderIdentity::of(&folder);
        debouncer.watch(&folder, RecursiveMode::NonRecursive).map_err(|e| failed(e.to_string()))?;
        Ok(FileWatcher {
            debouncer: RefCell::new(debouncer),
            events,
            file: folder.join(name),
            folder,
            watched: RefCell::new(identity),
        })
    }

    /// Moves the system watch to the folder the name gives now, if that is
    /// another one. Whether the file is there after a move (a save made
    /// with the folder, which the old watch could not see).
    fn follow_folder(&self) -> Result<bool, String> {
        let now = FolderIdentity::of(&self.folder);
        let mut watched = self.watched.borrow_mut();
        if now == *watched {
            return Ok(false);
        }
        let mut debouncer = self.debouncer.borrow_mut();
        // The old folder may be gone, and its watch with it.
        let _ = debouncer.unwatch(&self.folder);
        *watched = None;
        if now.is_none() {
            return Ok(false);
        }
        match debouncer.watch(&self.folder, RecursiveMode::NonRecursive) {
            Ok(()) => {}
            // Removed again before the watch was set: looked at next time.
            Err(_) if FolderIdentity::of(&self.folder) != now => return Ok(false),
            Err(error) => return Err(error.to_string()),
        }
        *watched = now;
        Ok(self.file.is_file())
    }

    /// Waits until the file is saved, or until `cancel` is raised.
    pub(crate) fn wait(&self, cancel: &AtomicBool) -> Result<Waited, WatchError> {
        let failed = |reason: String| WatchError { path: self.file.clone(), reason };
        loop {
            if cancel.load(Ordering::SeqCst) {
                return Ok(Waited::Cancelled);
            }
            if self.follow_folder().map_err(failed)? {
                return Ok(Waited::Saved);
            }
            match self.events.recv_timeout(CANCEL_CHECK) {
                Ok(Ok(events)) if events.iter().any(|event| self.is_save(event)) => return Ok(Waited::Saved),
                Ok(Ok(events)) if events.iter().any(|event| event.paths.contains(&self.folder)) => {
                    // The folder itself was removed or moved: a new one by
                    // its name (maybe with the same inode) is followed anew.
                    *self.watched.borrow_mut() = None;
                }
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

    /// Waits on `watcher` with a generous time limit, as tests must not hang.
    fn wait_at_most_a_minute(watcher: &FileWatcher) -> Waited {
        let cancel = std::sync::Arc::new(AtomicBool::new(false));
        let raiser = std::sync::Arc::clone(&cancel);
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_secs(60));
            raiser.store(true, Ordering::SeqCst);
        });
        watcher.wait(&cancel).expect("the watch holds")
    }

    #[test]
    fn a_save_in_a_folder_made_again_is_seen() {
        let root = tempfile::tempdir().expect("temporary folder");
        let folder = root.path().join("scenes");
        let file = folder.join("a.ray");
        fs::create_dir(&folder).expect("made");
        fs::write(&file, "").expect("written");
        let watcher = FileWatcher::new(&file).expect("the folder can be watched");
        // Made again with the file in it before the wait looks.
        fs::remove_dir_all(&folder).expect("removed");
        fs::create_dir(&folder).expect("made again");
        fs::write(&file, "put").expect("written again");
        assert_eq!(wait_at_most_a_minute(&watcher), Waited::Saved);
        // Made again while the wait runs, the file saved later.
        let saver = {
            let (folder, file) = (folder.clone(), file.clone());
            std::thread::spawn(move || {
                std::thread::sleep(Duration::from_millis(300));
                fs::remove_dir_all(&folder).expect("removed");
                std::thread::sleep(Duration::from_millis(300));
                fs::create_dir(&folder).expect("made again");
                std::thread::sleep(Duration::from_millis(300));
                fs::write(&file, "put sphere").expect("saved");
            })
        };
        assert_eq!(wait_at_most_a_minute(&watcher), Waited::Saved);
        saver.join().expect("the saves were made");
        assert!(FolderIdentity::of(&folder).is_some());
        // And it is followed from then on.
        let saver = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(300));
            fs::write(&file, "put box").expect("saved");
        });
        assert_eq!(wait_at_most_a_minute(&watcher), Waited::Saved);
        saver.join().expect("the save was made");
    }

    #[test]
    fn a_raised_flag_ends_the_wait() {
        let folder = tempfile::tempdir().expect("temporary folder");
        let watcher = FileWatcher::new(&folder.path().join("a.ray")).expect("the folder can be watched");
        assert_eq!(watcher.wait(&AtomicBool::new(true)).ok(), Some(Waited::Cancelled));
    }
}
