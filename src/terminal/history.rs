//! The file of the lines typed in the terminal, kept between sessions.

use std::path::PathBuf;

/// `rayrepl/history` in the user's data directory, created if missing;
/// `None` if there is no such directory or it cannot be created.
pub(crate) fn history_path() -> Option<PathBuf> {
    let directory = crate::data_dir::data_dir()?;
    std::fs::create_dir_all(&directory).ok()?;
    Some(directory.join("history"))
}
