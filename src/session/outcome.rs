//! What a command gives back: go on or leave, or why it failed, and the
//! checks of arguments that give the reasons. Its own module so that the
//! modules holding commands need not import the table of commands that
//! lists them.

use crate::lang::Diagnostic;
use crate::settings::{HEIGHT, Limit, WIDTH, check_size};

use super::outputs::FrontEnd;
use super::rendering::Size;
use super::state::Session;

/// What the session does after a command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Flow {
    /// Read the next input.
    Continue,
    /// Leave.
    Quit,
    /// Clear the screen, where there is one, then read the next input.
    ClearScreen,
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
    /// Says on the front what went wrong.
    pub(crate) fn report(self, session: &Session, front: &mut dyn FrontEnd) {
        match self {
            CommandError::Usage(message) | CommandError::Failed(message) => front.error(message),
            CommandError::Program(diagnostic) => front.diagnostic(&diagnostic, session.sources()),
            CommandError::Cancelled(message) => front.say(message),
        }
    }
}

/// Fails unless the command was given no arguments.
pub(crate) fn no_arguments(arguments: &[String]) -> Result<(), CommandError> {
    match arguments {
        [] => Ok(()),
        _ => Err(CommandError::Usage("this command takes no arguments".to_string())),
    }
}

/// A whole-number setting from `text`, within `limit`.
pub(crate) fn parse_count(text: &str, limit: &'static Limit) -> Result<u32, CommandError> {
    limit.parse(text).map_err(usage)
}

/// A picture size from `width` and `height`, each within its limit.
pub(crate) fn parse_size(width: &str, height: &str) -> Result<Size, CommandError> {
    let size = Size { width: parse_count(width, &WIDTH)?, height: parse_count(height, &HEIGHT)? };
    check_size(size.width, size.height).map_err(usage)?;
    Ok(size)
}

/// A usage error saying `error`.
pub(crate) fn usage(error: impl std::fmt::Display) -> CommandError {
    CommandError::Usage(error.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::DEPTH;

    #[test]
    fn counts_and_sizes_are_checked() {
        assert_eq!(parse_count("5", &DEPTH).ok(), Some(5));
        assert!(parse_count("-1", &DEPTH).is_err());
        assert!(parse_count("1001", &DEPTH).is_err());
        assert!(parse_count("x", &DEPTH).is_err());
        assert!(parse_size("0", "10").is_err());
        assert!(parse_size("65535", "65535").is_err());
    }
}
