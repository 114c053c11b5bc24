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
//! Commands (`:render`, `:save`, `:time`, ...) live in `commands`, one
//! function each; the one call into the renderer is in `rendering`.

mod cancel;
mod commands;
mod console;
mod describe;
mod editor;
mod excerpt;
mod help;
mod inspect;
mod interactive;
mod lessons;
mod outcome;
mod play;
mod preview;
mod reload;
mod rendering;
mod report;
mod script;
mod session;
mod syntax;
mod write_back;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use crate::lang::{Diagnostic, Limits};
use crate::lint::{Allowed, Picture};

pub(crate) use cancel::{CancelSwitch, cancel_flag};
pub use interactive::{ReplError, run_interactive, run_typed};
pub(crate) use preview::Preview;
pub use rendering::RenderSettings;
pub use script::run_script;
pub use session::Session;

use console::Console;
use rendering::Size;
use session::Accepted;

/// How a session starts: what the command line asked for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SessionOptions {
    /// Never show renders in the terminal (`--no-preview`).
    pub no_preview: bool,
    /// In a script, go on after an error (`--keep-going`); the exit status is
    /// still 1 at the end.
    pub keep_going: bool,
    /// A file to load before the first input (`-i scene.ray`).
    pub initial_file: Option<PathBuf>,
    /// Size, depth, samples, time and screen convention to start with.
    pub settings: RenderSettings,
    /// Limits on procedure calls and primitives (`--max-calls`, `--max-primitives`).
    pub limits: Limits,
    /// The warnings about the scene turned off (`--allow`).
    pub allowed: Allowed,
}

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
                eprintln!("rayrepl: {error}");
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

/// Runs one input of program text and prints what it did, or its error.
/// `Err(())` tells the caller it failed (the session is unchanged).
pub(crate) fn handle_input(
    session: &mut Session,
    console: &mut Console,
    name: &str,
    text: &str,
    line_offset: usize,
) -> Result<(), ()> {
    let result = session.submit(name, text, line_offset);
    report_input(session, console, text, result)
}

/// Prints what the input `text` did (`result`), or its error.
/// `Err(())` tells the caller it failed (the session is unchanged).
pub(crate) fn report_input(
    session: &mut Session,
    console: &mut Console,
    text: &str,
    result: Result<Accepted, Diagnostic>,
) -> Result<(), ()> {
    show_printed(session, console);
    match result {
        Ok(accepted) => {
            for warning in &accepted.warnings {
                console.diagnostic(warning, session.sources());
            }
            report::confirm(&accepted, session, console);
            lessons::check_input(session, console);
            Ok(())
        }
        Err(error) => {
            console.diagnostic(&error, session.sources());
            if let Some(command) = bare_command(text) {
                console.note(format!("commands start with a colon: did you mean `{command}`?"));
            }
            Err(())
        }
    }
}

/// Shows what `print` wrote since the last time, and how many lines were
/// left out past the limit.
pub(crate) fn show_printed(session: &Session, console: &mut Console) {
    let mut printed = session.take_printed();
    for line in printed.take_lines() {
        console.printed(line.render(session.sources()));
    }
    if let Some(note) = printed.hidden_note() {
        console.printed_note(note);
    }
}

/// Shows the warnings about the scene that a render of `size` (an
/// animation's frames, if `animation`) should heed, each cause once.
pub(crate) fn show_scene_warnings(session: &mut Session, console: &mut Console, size: Size, animation: bool) {
    let screen = session.settings().screen;
    let picture = Picture { width: size.width, height: size.height, screen, animation };
    for warning in session.scene_warnings(&picture) {
        console.diagnostic(&warning, session.sources());
    }
}

/// The command a learner probably meant by typing its name without the
/// colon (`help`, `quit`), if the input is just that.
fn bare_command(text: &str) -> Option<String> {
    let command = match text.trim() {
        "exit" | "q" => ":quit".to_string(),
        word => format!(":{word}"),
    };
    commands::COMMANDS.iter().any(|c| c.name == command).then_some(command)
}

/// A session set up with `options`' settings and limits, whose evaluations
/// `cancel` (Ctrl-C) can stop.
fn new_session(options: &SessionOptions, cancel: Option<&'static cancel::CancelSwitch>) -> Session {
    let session = Session::new(options.settings, options.limits).allowing(options.allowed);
    match cancel {
        Some(switch) => session.interruptible(switch.flag()),
        None => session,
    }
}
