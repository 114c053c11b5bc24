//! Where rayrepl keeps what outlives a session (the history of inputs, the
//! lessons' progress): `rayrepl` in the user's data directory. Without the
//! `terminal` feature (which brings the `dirs` crate) there is none, and
//! nothing is kept.

use std::path::PathBuf;

/// `rayrepl` in the user's data directory, if there is one.
pub(crate) fn data_dir() -> Option<PathBuf> {
    #[cfg(feature = "terminal")]
    return dirs::data_dir().map(|directory| directory.join("rayrepl"));
    #[cfg(not(feature = "terminal"))]
    return None;
}
