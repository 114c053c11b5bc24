//! Atomic, cancellable files: written into a temporary file in the target's
//! folder, then renamed over the target, and removed on an interruption.
//! An output that is a symbolic link is written through to the file it
//! leads to (the link stays a link), and one with hard links keeps its
//! inode (see [`PendingFile::commit`]).

use std::fs::{File, Metadata};
use std::io::{self, BufWriter, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

use super::error::{OutputError, io_error};

/// A cancel flag that is never raised, for writes that Ctrl-C does not stop
/// (it ends the process instead, see [`exit_discarding_unfinished`]).
pub(crate) static NEVER_CANCELLED: AtomicBool = AtomicBool::new(false);

/// The temporary files being written, which an interruption removes.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn unfinished() -> MutexGuard<'static, Vec<PathBuf>> {
    UNFINISHED.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The exit code after Ctrl-C or `kill` (128 + SIGINT, as shells report it).
pub const INTERRUPTED_EXIT_CODE: i32 = 130;

/// Removes the temporary files of unfinished writes and ends the process
/// with `code`: what an interruption (Ctrl-C, `kill`) does, so that it
/// leaves no temporary file behind and every target as it was.
pub(crate) fn exit_discarding_unfinished(code: i32) -> ! {
    discarding_unfinished(code, std::process::exit)
}

/// Removes the temporary files of unfinished writes, then ends the
/// process with `exit(code)`: a signal handler's end, which must not wait
/// for the main thread (stuck in a write to a pipe nobody reads, it holds
/// the lock of standard output, which `std::process::exit` would flush).
pub(crate) fn discarding_unfinished(code: i32, exit: fn(i32) -> !) -> ! {
    // The lock is held until the end: no write starts or finishes meanwhile.
    let unfinished = unfinished();
    for path in unfinished.iter() {
        let _ = std::fs::remove_file(path);
    }
    exit(code)
}

/// Makes a temporary file in `dir` and removes it at once: whether files
/// can be made there, checked before any work. While it exists it is
/// registered as unfinished, so an interruption removes it too.
pub(super) fn probe_folder(dir: &Path) -> io::Result<()> {
    let mut unfinished = unfinished();
    let temp = temp_file_in(dir)?;
    let path = temp.path().to_owned();
    unfinished.push(path.clone());
    drop(temp);
    unfinished.retain(|p| *p != path);
    Ok(())
}

/// A file being written: a temporary file next to its target, which
/// [`PendingFile::commit`] puts in place of the target. Dropped without a
/// commit, the temporary file is removed and the target left as it was.
pub(super) struct PendingFile {
    /// The output as named, for messages.
    pub(super) path: PathBuf,
    /// The file replaced: `path`, or the file its symbolic links lead to.
    target: PathBuf,
    pub(super) temp_path: PathBuf,
    temp: Option<tempfile::NamedTempFile>,
    pub(super) cancel: &'static AtomicBool,
}

impl PendingFile {
    /// A temporary file for `path` (in the folder of the file its links
    /// lead to, so that a rename can replace that file), and a writer into
    /// it that fails as soon as `cancel` is raised.
    pub(super) fn create(
        path: &Path,
        cancel: &'static AtomicBool,
    ) -> Result<(PendingFile, BufWriter<Cancellable<File>>), OutputError> {
        let target = link_target(path).map_err(|e| io_error(path, e))?;
        let mut unfinished = unfinished();
        let temp = temp_file_in(folder_of(&target)).map_err(|e| io_error(path, e))?;
        unfinished.push(temp.path().to_owned());
        let file = temp.as_file().try_clone().map_err(|e| io_error(path, e))?;
        let temp_path = temp.path().to_owned();
        let pending = PendingFile { path: path.to_owned(), target, temp_path, temp: Some(temp), cancel };
        Ok((pending, BufWriter::new(Cancellable { inner: file, cancel })))
    }

    /// Whether `cancel` was raised: the file is not to be put in place.
    pub(super) fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }

    /// `error`, or [`OutputError::Cancelled`] if the write failed because
    /// `cancel` was raised (encoders pass the writer's error on in their own
    /// words).
    pub(super) fn failure(&self, error: OutputError) -> OutputError {
        if self.cancelled() { OutputError::Cancelled { path: self.path.clone() } } else { error }
    }

    /// Puts the written file in place of the target, with the target's
    /// permissions and owner (where the process may give it) if it
    /// existed; not if `cancel` was raised meanwhile (syncing a large file
    /// to disk can take a while).
    ///
    /// A target with more than one hard link is not renamed over: that
    /// would split it from its other names, which would keep the old
    /// content. The whole new content is written and synced first (so a
    /// failure or Ctrl-C while encoding still leaves the target as it was),
    /// then copied into the existing file, which keeps its inode, its
    /// links, mode and owner. That copy is the one step that is not atomic:
    /// Ctrl-C and `kill` wait for it (they take the lock it holds), and
    /// only a crash during it can leave the file part new. Refusing such a
    /// target instead would make a hard-linked output unwritable.
    pub(super) fn commit(mut self) -> Result<(), OutputError> {
        let temp = self.temp.take().expect("a pending file is committed once");
        temp.as_file().sync_all().map_err(|e| io_error(&self.path, e))?;
        if self.cancelled() {
            return Err(OutputError::Cancelled { path: self.path.clone() });
        }
        let existing = std::fs::metadata(&self.target).ok();
        if let Some(existing) = &existing {
            keep_owner(temp.as_file(), existing);
            temp.as_file().set_permissions(existing.permissions()).map_err(|e| io_error(&self.path, e))?;
        }
        let mut unfinished = unfinished();
        let put = match existing {
            Some(existing) if hard_links(&existing) > 1 => {
                let copied = copy_into(temp.as_file(), &self.target);
                drop(temp);
                copied
            }
            _ => temp.persist(&self.target).map(drop).map_err(|e| e.error),
        };
        unfinished.retain(|p| *p != self.temp_path);
        put.map_err(|e| io_error(&self.path, e))
    }
}

/// The most symbolic links followed from an output to its file (Linux's
/// own limit).
const MOST_LINKS: usize = 40;

/// The file a write to `path` replaces: `path` itself, or, if it is a
/// symbolic link, the file its links lead to (made if it does not exist
/// yet), so that the link stays a link.
pub(super) fn link_target(path: &Path) -> io::Result<PathBuf> {
    let mut target = path.to_owned();
    for _ in 0..MOST_LINKS {
        match std::fs::symlink_metadata(&target) {
            // A relative link is read from the link's folder.
            Ok(meta) if meta.file_type().is_symlink() => target = folder_of(&target).join(std::fs::read_link(&target)?),
            _ => return Ok(target),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// How many names (hard links) the file of `meta` has.
fn hard_links(meta: &Metadata) -> u64 {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        meta.nlink()
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        1
    }
}

/// Gives `file` the owner and group of the file it replaces, as far as the
/// process may: both as root, else the group if the process is in it, else
/// neither (the new file is then the process's own, as any file it makes).
fn keep_owner(file: &File, existing: &Metadata) {
    #[cfg(unix)]
    {
        use std::os::unix::fs::{MetadataExt, fchown};
        if fchown(file, Some(existing.uid()), Some(existing.gid())).is_err() {
            let _ = fchown(file, None, Some(existing.gid()));
        }
    }
    #[cfg(not(unix))]
    let _ = (file, existing);
}

/// Copies the whole of `written` into the existing file at `target`, in
/// place: same inode, same links (see [`PendingFile::commit`]).
fn copy_into(written: &File, target: &Path) -> io::Result<()> {
    let mut source = written.try_clone()?;
    source.rewind()?;
    let mut file = std::fs::OpenOptions::new().write(true).open(target)?;
    let length = io::copy(&mut source, &mut file)?;
    file.set_len(length)?;
    file.sync_all()
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        let mut unfinished = unfinished();
        drop(self.temp.take());
        unfinished.retain(|p| *p != self.temp_path);
    }
}

/// The largest piece written at once, so that a large image written in one
/// call still sees Ctrl-C within a few milliseconds.
const CANCELLABLE_PIECE: usize = 1 << 20;

/// A file (or a pipe) whose writes fail once `cancel` is raised. It sits
/// under a `BufWriter`, so the flag is read once per buffer's worth, not
/// per byte.
pub(super) struct Cancellable<W> {
    pub(super) inner: W,
    pub(super) cancel: &'static AtomicBool,
}

impl<W: Write> Write for Cancellable<W> {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        if self.cancel.load(Ordering::Relaxed) {
            // Not `ErrorKind::Interrupted`: `write_all` would retry it.
            return Err(io::Error::other("cancelled"));
        }
        self.inner.write(&bytes[..bytes.len().min(CANCELLABLE_PIECE)])
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// The folder a file at `path` goes into.
pub(super) fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// A temporary file in `dir`, readable by others like an ordinary new file
/// (tempfile's default is owner-only).
fn temp_file_in(dir: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".rayrepl-").suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    builder.tempfile_in(dir)
}
