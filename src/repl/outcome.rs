//! What a command gives back: go on or leave, or why it failed. Its own
//! module so that the modules holding commands need not import the table
//! of commands that lists them.

use crate::lang::Diagnostic;

use super::console::Console;
use super::session::Session;

/// What the session does after a command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Flow {
    /// Read the next input.
    Continue,
    /// Leave.
    Quit,
}

/// Why a command did not do what was asked.
#[derive(Debug)]
pub(crate) enum CommandError {
    /// The arguments were wrong; the command's usage follows the message.
    Usage(String),
    /// It could not be done, for the reason given.
    Failed(String),
    /// Program text failed (`:load`, `:time` re-evaluation); already located.
    Program(Box<Diagnostic>),
    /// Ctrl-C stopped it; the session is as it was.
    Cancelled(String),
}

/// The result of a command.
pub(crate) type CommandResult = Result<Flow, CommandError>;

impl CommandError {
    /// Says on the console what went wrong.
    pub(crate) fn report(self, session: &Session, console: &mut Console) {
        match self {
            CommandError::Usage(message) | CommandError::Failed(message) => console.error(message),
            CommandError::Program(diagnostic) => console.diagnostic(&diagnostic, session.sources()),
            CommandError::Cancelled(message) => console.say(message),
        }
    }
}
