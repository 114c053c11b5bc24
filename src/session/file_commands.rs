//! The commands that read program files: `:load` and `:watch` (`:reload`
//! is in [`super::reload`], `:write` in [`super::write_back`]).

use std::path::Path;

use super::outcome::{CommandError, CommandResult, Flow};
use super::outputs::FrontEnd;
use super::picture_commands::render_command;
use super::reload;
use super::report::{self, show_printed, show_warnings};
use super::shell::Shell;
use crate::process::cancel::cancel_flag;

pub(crate) fn load(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let [file] = arguments else {
        let problem = if arguments.is_empty() {
            "give the file to load"
        } else {
            "give one file (put quotes around a name with spaces)"
        };
        return Err(CommandError::Usage(problem.to_string()));
    };
    load_file(shell, Path::new(file), front)
}

/// Runs the file at `path` into the session, reporting any failure on the
/// front; `Err(())` if it failed (the session is then unchanged).
pub(crate) fn load_reporting(shell: &mut Shell, path: &Path, front: &mut dyn FrontEnd) -> Result<(), ()> {
    let loaded = load_file(shell, path, front);
    show_printed(&shell.session, front);
    loaded.map(|_| ()).map_err(|error| error.report(&shell.session, front))
}

/// Runs `text` into the session as the file at `path`, as `:load` does,
/// reporting any failure on the front; `Err(())` if it failed (the session
/// is then unchanged). What it printed is left for the caller to show.
pub(crate) fn load_text_reporting(
    shell: &mut Shell,
    path: &Path,
    text: &str,
    front: &mut dyn FrontEnd,
) -> Result<(), ()> {
    load_text(shell, path, text, front).map(|_| ()).map_err(|error| error.report(&shell.session, front))
}

/// Runs the file at `path` into the session, as one input.
fn load_file(shell: &mut Shell, path: &Path, front: &mut dyn FrontEnd) -> CommandResult {
    let text = reload::read(path, cancel_flag(front.cancel()))?;
    load_text(shell, path, &text, front)
}

/// Runs `text`, the content of the file at `path`, into the session, as one input.
fn load_text(shell: &mut Shell, path: &Path, text: &str, front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let mut accepted = session.load(path, text).map_err(|d| CommandError::Program(Box::new(d)))?;
    show_warnings(session, &mut shell.warned, front, std::mem::take(&mut accepted.warnings));
    front.say(format!("loaded {}", path.display()));
    report::confirm(&accepted, session, front);
    Ok(Flow::Continue)
}

/// `:watch FILE`, rendering each version as `:render` does.
pub(crate) fn watch(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    reload::watch(shell, arguments, front, render_command)
}
