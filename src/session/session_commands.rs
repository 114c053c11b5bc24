//! The commands that change the session as a whole: `:undo`, `:reset`,
//! `:clear` and `:quit`.

use super::outcome::{CommandError, CommandResult, Flow, no_arguments};
use super::outputs::FrontEnd;
use super::report::{self, counted};
use super::shell::Shell;
use super::state::Undone;

pub(crate) fn undo(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    no_arguments(arguments)?;
    match session.undo().map_err(|d| CommandError::Program(Box::new(d)))? {
        Undone::Nothing => front.say("nothing to undo"),
        Undone::Input(text) => front.say(format!("took back: {}", first_line(&text))),
        Undone::Reset(count) => front.say(format!("took back the :reset ({} back)", counted(count, "input"))),
        Undone::Reload(path) => front.say(format!("took back the :reload of {}", path.display())),
    }
    front.say(format!("{} in the scene", counted(report::objects(&session.counts()), "object")));
    Ok(Flow::Continue)
}

pub(crate) fn reset(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    no_arguments(arguments)?;
    session.reset();
    front.say("the session is empty again (`:undo` brings it all back)");
    Ok(Flow::Continue)
}

pub(crate) fn clear(_shell: &mut Shell, arguments: &[String], _console: &mut dyn FrontEnd) -> CommandResult {
    no_arguments(arguments)?;
    Ok(Flow::ClearScreen)
}

pub(crate) fn quit(_shell: &mut Shell, arguments: &[String], _console: &mut dyn FrontEnd) -> CommandResult {
    no_arguments(arguments)?;
    Ok(Flow::Quit)
}

fn first_line(text: &str) -> String {
    let mut lines = text.lines().filter(|line| !line.trim().is_empty());
    let first = lines.next().unwrap_or("").trim().to_string();
    if lines.next().is_some() { format!("{first} ...") } else { first }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_input_is_named_by_its_first_line() {
        assert_eq!(first_line("\nput sphere\n  center"), "put sphere ...");
    }
}
