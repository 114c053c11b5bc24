//! `rayrepl fmt`'s command line turned into a formatting job: files
//! rewritten in place, or standard input to standard output.

use std::path::{Path, PathBuf};

use super::JobError;
use crate::cli::FmtArgs;

/// What `rayrepl fmt` asks for, checked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FormattingJob {
    /// What is formatted.
    pub input: Formatted,
    /// Write nothing, only say what would change (`--check`).
    pub check: bool,
}

/// What `rayrepl fmt` formats.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Formatted {
    /// These files, each rewritten in place if its text changes.
    Files(Vec<PathBuf>),
    /// Standard input (`-`), written formatted to standard output.
    Stdin,
}

/// The formatting job `args` ask for, or why there is none: `-` is
/// standard input only when given alone (its text goes to standard output,
/// where files' reports would mix with it).
pub(super) fn formatting_job(args: &FmtArgs) -> Result<FormattingJob, JobError> {
    let stdin = Path::new("-");
    let input = match args.files.as_slice() {
        [only] if only == stdin => Formatted::Stdin,
        files if files.iter().any(|file| file == stdin) => {
            return Err(JobError::Misuse(
                "`-` formats standard input to standard output: give it alone, without files".to_string(),
            ));
        }
        files => Formatted::Files(files.to_vec()),
    };
    Ok(FormattingJob { input, check: args.check })
}
