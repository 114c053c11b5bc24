//! The terminal layer: what rayrepl does on a terminal, around the session
//! core and the batch renderer. Previews of pictures ([`preview`]) and animations played in place
//! ([`play`]), progress bars ([`progress`]), following a file's saves
//! ([`watch`]), the line editor ([`editor`]) with its history file
//! (`history`) and the interactive session ([`interactive`]) with its
//! front-end (`front_end`), and piped scripts (`script`), whose outputs a
//! `console` writes on two streams. Built with the
//! `terminal` feature (on by default), which brings their crates.

mod console;
pub(crate) mod editor;
mod front_end;
mod history;
pub mod interactive;
mod play;
pub(crate) mod preview;
pub mod progress;
mod script;
pub(crate) mod watch;

use std::process::ExitCode;

pub use interactive::{ReplError, run_interactive, run_typed};
pub use script::run_script;

use crate::session::{CancelSwitch, SessionOptions};
use script::run_script_keeping_session;

/// Runs the interactive session on the terminal; fails (status 1) when
/// the terminal cannot be used.
pub fn run_session(options: &SessionOptions) -> ExitCode {
    match run_interactive(options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            crate::process::failure::report_failure(error);
            ExitCode::FAILURE
        }
    }
}

/// Runs the script read from standard input (messages on standard output,
/// diagnostics on standard error), which `cancel` (Ctrl-C) stops. Fails
/// after an error (status 1, or 130 when Ctrl-C stopped it).
pub fn run_script_on_stdin(options: &SessionOptions, cancel: Option<&'static CancelSwitch>) -> ExitCode {
    let stdin = std::io::stdin();
    let (mut out, mut err) = (std::io::stdout(), std::io::stderr());
    let (code, session) = run_script_keeping_session(stdin.lock(), &mut out, &mut err, options, cancel);
    // The process ends now: freeing a long script's inputs one by one
    // would only add to its time.
    std::mem::forget(session);
    ExitCode::from(u8::try_from(code).unwrap_or(1))
}
