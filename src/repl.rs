//! The interactive session (SPEC 7) and piped scripts.
//!
//! A [`Session`] keeps one interpreter across inputs: items typed one at a
//! time accumulate into one global environment and one scene, and an input
//! that fails changes nothing. Around it:
//!
//! - [`run_interactive`]: the line editor (history, multi-line input,
//!   completion, colours) and previews of renders in the terminal;
//!   [`run_typed`] runs its entry loop on lines given in advance;
//! - [`run_script`]: the same session fed line by line from a reader, with
//!   no prompts or previews, for `cat script | rayrepl`;
//! - [`run`]: picks one of the two, as `main` needs.
//!
//! Commands (`:render`, `:save`, `:time`, ...) are defined once in the
//! registry, `commands`, and run by the modules of their topic below it
//! (`picture_commands`, `setting_commands`, `file_commands`, `inspect`,
//! `session_commands`, `play`, `reload`, `write_back`, `lessons`).

mod cancel;
mod commands;
mod console;
mod describe;
mod editor;
mod excerpt;
mod file_commands;
mod help;
mod inputs;
mod inspect;
mod interactive;
mod lessons;
mod options;
mod outcome;
mod picture_commands;
mod play;
mod preview;
mod reload;
mod render_steps;
mod rendering;
mod report;
mod script;
mod session;
mod session_commands;
mod setting_commands;
mod shell;
mod syntax;
mod write_back;

use std::io::IsTerminal;
use std::process::ExitCode;

pub(crate) use cancel::{CancelSwitch, cancel_flag};
pub use interactive::{ReplError, run_interactive, run_typed};
pub use options::SessionOptions;
pub(crate) use preview::Preview;
pub use rendering::RenderSettings;
pub use script::run_script;
pub use session::Session;

/// Runs a session the way `rayrepl` without a scene to render does:
/// interactively when standard input is a terminal, otherwise as a script
/// read from standard input (messages on standard output, diagnostics on
/// standard error). Fails after an error in a script (status 1, or 130 when
/// Ctrl-C stopped it), or when the terminal cannot be used.
pub fn run(options: &SessionOptions) -> ExitCode {
    let code = if std::io::stdin().is_terminal() {
        match run_interactive(options) {
            Ok(()) => 0,
            Err(error) => {
                crate::failure::report_failure(error);
                1
            }
        }
    } else {
        let stdin = std::io::stdin();
        let (code, session) =
            script::run_script_keeping_session(stdin.lock(), &mut std::io::stdout(), &mut std::io::stderr(), options);
        // The process ends now: freeing a long script's inputs one by one
        // would only add to its time.
        std::mem::forget(session);
        code
    };
    ExitCode::from(u8::try_from(code).unwrap_or(1))
}
