//! The command registry: the function that runs each command of the
//! session (`:render`, `:time`, `:save`, ...), paired by name with the
//! command's description (name, other names, usage, help page, files),
//! which is defined once in [`crate::ide::commands`]; and the dispatcher
//! that runs a command line. The handlers live in the modules of their
//! topic, below this one: none of them imports it.

use crate::ide::commands::{COMMANDS, Command, find, help_pages};
use crate::ide::help;
use crate::lang::suggest::closest;

use super::file_commands;
use super::inspect;
use super::lesson_commands;
pub(crate) use super::outcome::Flow;
use super::outcome::{CommandError, CommandResult};
use super::outputs::FrontEnd;
use super::picture_commands;
use super::play;
use super::reload;
use super::report::show_printed;
use super::session_commands;
use super::setting_commands;
use super::shell::Shell;
use super::write_back;

/// The function that runs a command on its arguments.
type Run = fn(&mut Shell, &[String], &mut dyn FrontEnd) -> CommandResult;

/// What runs one command: the command's name (as its description in
/// [`crate::ide::commands::COMMANDS`] gives it) and its function.
struct Handler {
    /// The command's name, colon included.
    name: &'static str,
    /// Runs it on its arguments.
    run: Run,
}

/// The function of every command, in the order of the descriptions.
const HANDLERS: &[Handler] = &[
    Handler { name: ":lesson", run: lesson_commands::lesson },
    Handler { name: ":goal", run: lesson_commands::goal },
    Handler { name: ":render", run: picture_commands::render_command },
    Handler { name: ":save", run: picture_commands::save },
    Handler { name: ":anim", run: picture_commands::anim },
    Handler { name: ":play", run: play::play },
    Handler { name: ":time", run: setting_commands::time },
    Handler { name: ":size", run: setting_commands::size },
    Handler { name: ":depth", run: setting_commands::depth },
    Handler { name: ":samples", run: setting_commands::samples },
    Handler { name: ":preview", run: picture_commands::preview_command },
    Handler { name: ":pick", run: picture_commands::pick },
    Handler { name: ":load", run: file_commands::load },
    Handler { name: ":reload", run: reload::reload },
    Handler { name: ":watch", run: file_commands::watch },
    Handler { name: ":write", run: write_back::write },
    Handler { name: ":env", run: inspect::env },
    Handler { name: ":scene", run: inspect::scene },
    Handler { name: ":show", run: inspect::show },
    Handler { name: ":list", run: inspect::list },
    Handler { name: ":history", run: inspect::history },
    Handler { name: ":help", run: help_command },
    Handler { name: ":undo", run: session_commands::undo },
    Handler { name: ":reset", run: session_commands::reset },
    Handler { name: ":limits", run: setting_commands::limits },
    Handler { name: ":clear", run: session_commands::clear },
    Handler { name: ":quit", run: session_commands::quit },
];

/// The function that runs `command`.
fn handler(command: &Command) -> Run {
    let found = HANDLERS.iter().find(|handler| handler.name == command.topic.name);
    found.expect("every command described has a handler (a test checks)").run
}

/// Runs the command on `line`, reporting any failure on the front.
/// Returns `Err(())` if it failed, so scripts can count errors.
pub(crate) fn execute(shell: &mut Shell, line: &str, front: &mut dyn FrontEnd) -> Result<Flow, ()> {
    let result = split_arguments(line).map_err(CommandError::Failed).and_then(|words| dispatch(shell, &words, front));
    show_printed(&shell.session, front);
    match result {
        Ok(flow) => Ok(flow),
        Err(error) => {
            error.report(&shell.session, front);
            Err(())
        }
    }
}

fn dispatch(shell: &mut Shell, words: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let Some((name, arguments)) = words.split_first().filter(|(name, _)| name.as_str() != ":") else {
        return Err(CommandError::Failed("type a command name after `:`, for example `:help`".to_string()));
    };
    let Some(command) = find(name) else {
        return Err(unknown_command(name));
    };
    handler(command)(shell, arguments, front).map_err(|error| match error {
        CommandError::Usage(problem) => CommandError::Usage(format!("{problem}\nusage: {}", command.usage)),
        other => other,
    })
}

fn unknown_command(name: &str) -> CommandError {
    let names = COMMANDS.iter().flat_map(Command::typed_names);
    let mut message = format!("there is no command `{name}`");
    if let Some(close) = closest(name, names) {
        message.push_str(&format!("; did you mean `{close}`?"));
    }
    message.push_str("\n`:help` lists the commands");
    CommandError::Failed(message)
}

/// Splits a command line into words. Double quotes keep spaces in a word,
/// and (except on Windows, where it separates folders) a backslash keeps the
/// next character as it is, as file name completion writes `my\ scene.ray`.
pub(crate) fn split_arguments(line: &str) -> Result<Vec<String>, String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quoted = false;
    let mut chars = line.trim().chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                quoted = !quoted;
                word.get_or_insert_with(String::new);
            }
            '\\' if cfg!(not(windows)) && !quoted => {
                let escaped = chars.next().unwrap_or('\\');
                word.get_or_insert_with(String::new).push(escaped);
            }
            c if c.is_whitespace() && !quoted => words.extend(word.take()),
            c => word.get_or_insert_with(String::new).push(c),
        }
    }
    if quoted {
        return Err("a `\"` is not closed".to_string());
    }
    words.extend(word);
    Ok(words)
}

/// `:help [NAME]`: the overview, or the page about one name.
fn help_command(_shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let pages = help_pages();
    match arguments {
        [] => front.say(help::overview(&pages)),
        [name] => match help::find(name, &pages) {
            Some(topic) => front.say(topic.text),
            None => {
                let hint = help::suggestion(name, &pages).map(|s| format!("; did you mean `{s}`?")).unwrap_or_default();
                return Err(CommandError::Failed(format!(
                    "no help about `{name}`{hint}\n`:help` lists what it explains"
                )));
            }
        },
        _ => {
            return Err(CommandError::Usage("ask about one name at a time".to_string()));
        }
    }
    Ok(Flow::Continue)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_split_on_spaces_and_keep_quoted_ones() {
        assert_eq!(split_arguments(" :save  a.png 10 20 ").unwrap(), vec![":save", "a.png", "10", "20"]);
        assert_eq!(split_arguments(":load \"my scene.ray\"").unwrap(), vec![":load", "my scene.ray"]);
        assert_eq!(split_arguments(":load \"\"").unwrap(), vec![":load", ""]);
        assert!(split_arguments(":load \"oops").is_err());
        if cfg!(not(windows)) {
            assert_eq!(split_arguments(r":load my\ scene.ray").unwrap(), vec![":load", "my scene.ray"]);
        }
    }

    #[test]
    fn every_command_described_has_one_handler_and_every_handler_a_command() {
        let described: Vec<&str> = COMMANDS.iter().map(|command| command.topic.name).collect();
        let handled: Vec<&str> = HANDLERS.iter().map(|handler| handler.name).collect();
        assert_eq!(handled, described, "the handlers follow the descriptions, one each, in order");
    }
}
