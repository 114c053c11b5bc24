//! How the program speaks on standard error, and says that it, rather
//! than a scene, failed: one line after its name (`rayrepl: cannot read
//! ...`), written here only, so the name is written in one place.
//!
//! Standard error may be a closed pipe (`2>&1 | head -c1`) or a full disk
//! (`2> /dev/full`): a closed pipe ends the program quietly with the status
//! a shell gives a program killed by SIGPIPE, leaving no unfinished file; a
//! line that cannot be written otherwise is remembered, and the exit status
//! then says the run failed ([`unwritten_messages`]).

use std::fmt::Display;
use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

use crate::output::exit_discarding_unfinished;
use crate::process::interruption::may_block;

/// The name in front of the program's own failures.
const PROGRAM: &str = "rayrepl";

/// The exit status after a closed pipe: 128 + SIGPIPE, as shells report a
/// program the signal ended.
pub const CLOSED_PIPE_EXIT_CODE: i32 = 141;

/// Set when a line could not be written on standard error.
static UNWRITTEN: AtomicBool = AtomicBool::new(false);

/// Writes `message` on standard error as a failure of the program.
pub fn report_failure(message: impl Display) {
    tell_line(format_args!("{PROGRAM}: {}", message.to_string().trim_end()));
}

/// `eprintln!` for the program's messages (what was written, how long it
/// took, notes), which [`tell_line`] writes.
#[cfg(feature = "terminal")]
macro_rules! tell {
    ($($arg:tt)*) => {
        $crate::process::failure::tell_line(format_args!($($arg)*))
    };
}
#[cfg(feature = "terminal")]
pub(crate) use tell;

/// Writes `line` and a newline on standard error, as this module says
/// when it cannot.
pub fn tell_line(line: impl Display) {
    // Formatted first: only the write may block (`crate::process::interruption`).
    let text = format!("{line}\n");
    let written = may_block(|| {
        let mut stderr = std::io::stderr().lock();
        stderr.write_all(text.as_bytes()).and_then(|()| stderr.flush())
    });
    if let Err(error) = written {
        end_if_closed_pipe(&error);
        UNWRITTEN.store(true, Ordering::SeqCst);
    }
}

/// Ends the program quietly if `error` is a closed pipe (the reader of
/// standard output or error went away): status 141, no unfinished file.
pub fn end_if_closed_pipe(error: &std::io::Error) {
    if error.kind() == ErrorKind::BrokenPipe {
        exit_discarding_unfinished(CLOSED_PIPE_EXIT_CODE);
    }
}

/// Whether a line could not be written on standard error (a full disk):
/// the run then fails, even if it did everything else.
pub fn unwritten_messages() -> bool {
    UNWRITTEN.load(Ordering::SeqCst)
}
