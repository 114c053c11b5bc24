//! Running one input of program text and saying what it did, or its error.

use crate::ide::commands;
use crate::lang::Diagnostic;

use super::lesson_commands;
use super::outputs::FrontEnd;
use super::report::{self, show_printed, show_warnings};
use super::shell::Shell;
use super::state::Accepted;

/// Prints what the input `text` did (`result`), or its error.
/// `Err(())` tells the caller it failed (the session is unchanged).
pub(crate) fn report_input(
    shell: &mut Shell,
    front: &mut dyn FrontEnd,
    text: &str,
    result: Result<Accepted, Diagnostic>,
) -> Result<(), ()> {
    let session = &shell.session;
    show_printed(session, front);
    match result {
        Ok(mut accepted) => {
            let warnings = std::mem::take(&mut accepted.warnings);
            show_warnings(session, &mut shell.warned, front, warnings);
            report::confirm(&accepted, session, front);
            lesson_commands::check_input(shell, front);
            Ok(())
        }
        Err(error) => {
            front.diagnostic(&error, session.sources());
            if let Some(command) = bare_command(text) {
                front.note(format!("commands start with a colon: did you mean `{command}`?"));
            }
            Err(())
        }
    }
}

/// The command a learner probably meant by typing its name without the
/// colon (`help`, `quit`), if the input is just that.
fn bare_command(text: &str) -> Option<&'static str> {
    let command = commands::find(&format!(":{}", text.trim()))?;
    Some(command.topic.name)
}
