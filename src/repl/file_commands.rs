//! The commands that read program files: `:load` and `:watch` (`:reload`
//! is in [`super::reload`], `:write` in [`super::write_back`]).

use std::path::Path;

use super::console::Console;
use super::outcome::{CommandError, CommandResult, Flow};
use super::picture_commands::render_command;
use super::reload;
use super::report::{self, show_printed};
use super::session::Session;
use super::shell::Shell;

pub(crate) fn load(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    let session = &mut shell.session;
    let [file] = arguments else {
        let problem = if arguments.is_empty() {
            "give the file to load"
        } else {
            "give one file (put quotes around a name with spaces)"
        };
        return Err(CommandError::Usage(problem.to_string()));
    };
    load_file(session, Path::new(file), console)
}

/// Runs the file at `path` into the session, reporting any failure on the
/// console; `Err(())` if it failed (the session is then unchanged).
pub(crate) fn load_reporting(session: &mut Session, path: &Path, console: &mut Console) -> Result<(), ()> {
    let loaded = load_file(session, path, console);
    show_printed(session, console);
    loaded.map(|_| ()).map_err(|error| error.report(session, console))
}

/// Runs the file at `path` into the session, as one input.
fn load_file(session: &mut Session, path: &Path, console: &mut Console) -> CommandResult {
    let text = reload::read(path)?;
    let accepted = session.load(path, &text).map_err(|d| CommandError::Program(Box::new(d)))?;
    for warning in &accepted.warnings {
        console.diagnostic(warning, session.sources());
    }
    console.say(format!("loaded {}", path.display()));
    report::confirm(&accepted, session, console);
    Ok(Flow::Continue)
}

/// `:watch FILE`, rendering each version as `:render` does.
pub(crate) fn watch(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    reload::watch(shell, arguments, console, render_command)
}
