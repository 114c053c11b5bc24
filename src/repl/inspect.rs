//! Looking inside the session: `:show NAME` prints a definition as it was
//! written, `:list` the inputs the session holds, `:history` the lines
//! typed in the line editor.

use rustyline::history::{FileHistory, History};

use crate::lang::ast::{Instr, Item, ProcDef};
use crate::lang::suggest::closest;
use crate::lang::walk::{bound_name, same_level};

use super::console::Console;
use super::excerpt::{item_text, location};
use super::interactive::history_path;
use super::outcome::{CommandError, CommandResult, Flow};
use super::report::{counted, number};
use super::session::Session;

/// How many lines `:history` prints unless told.
const HISTORY_SHOWN: usize = 20;

/// `:show NAME`: the latest definition of a procedure, object or number,
/// with where it came from.
pub(crate) fn show(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let [name] = arguments else {
        return Err(CommandError::Usage("give the name of a procedure, an object or a number".to_string()));
    };
    let (procedure, binding) = latest_definitions(session, name);
    let sources = session.sources();
    if let Some(def) = procedure {
        console.say(format!("# {}", location(sources, def.span)));
        console.say(item_text(sources, def.span));
    }
    let value = match (session.global_number(name), session.describe_object(name)) {
        (Some(value), _) => Some(format!("{name} = {} now", number(value))),
        (None, Some(what)) => Some(format!("{name}: {what}")),
        (None, None) => None,
    };
    match (binding, value) {
        (Some((binding, top)), Some(value)) => {
            // A name bound inside an `if` shows the whole `if`, which says when.
            console.say(format!("# {} ({value})", location(sources, binding.span)));
            console.say(item_text(sources, top.span));
        }
        (None, Some(value)) if name == "time" => {
            console.say(format!("# predefined ({value}): the time renders use, set with `:time N`"));
        }
        _ if procedure.is_some() => {}
        _ => return Err(not_defined(session, name)),
    }
    Ok(Flow::Continue)
}

/// The last procedure named `name`, and the last top-level instruction
/// binding it (with the top-level instruction holding it, an `if` or itself).
fn latest_definitions<'s>(session: &'s Session, name: &str) -> (Option<&'s ProcDef>, Option<(&'s Instr, &'s Instr)>) {
    let (mut procedure, mut binding) = (None, None);
    for item in session.inputs().iter().flat_map(|input| &input.program.items) {
        match item {
            Item::Proc(def) if &*def.name.name == name => procedure = Some(&**def),
            Item::Instr(top) => {
                let bindings =
                    same_level(std::iter::once(top)).filter(|instr| bound_name(instr).is_some_and(|n| &**n == name));
                if let Some(instr) = bindings.last() {
                    binding = Some((instr, top));
                }
            }
            _ => {}
        }
    }
    (procedure, binding)
}

fn not_defined(session: &Session, name: &str) -> CommandError {
    let vocabulary = session.vocabulary();
    let names = vocabulary.variables.iter().chain(vocabulary.procedures.iter().map(|(name, _)| name));
    let mut message = format!("`{name}` is not defined");
    if let Some(close) = closest(name, names.map(String::as_str)) {
        message.push_str(&format!("; did you mean `{close}`?"));
    }
    message.push_str("\n`:env` lists the names defined");
    CommandError::Failed(message)
}

/// `:list`: the inputs the session holds, in the order they run, each named
/// as messages name it (`<input 3>:1`, `<stdin>:12`) or by its file.
pub(crate) fn list(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    if !arguments.is_empty() {
        return Err(CommandError::Usage("this command takes no arguments".to_string()));
    }
    let sources = session.sources();
    let rows: Vec<(String, String)> = session
        .inputs()
        .iter()
        .map(|input| match &input.loaded_from {
            Some(path) => {
                (path.display().to_string(), format!("{} ({})", input.text, counted(input.program.items.len(), "item")))
            }
            None => {
                let label = input.program.items.first().map(|item| location(sources, item.span()));
                (label.unwrap_or_default(), input.text.trim().to_string())
            }
        })
        .collect();
    if rows.is_empty() {
        console.say("the session holds no input yet");
    }
    let width = rows.iter().map(|(label, _)| label.chars().count()).max().unwrap_or(0);
    for (label, text) in rows {
        console.say(indented(&format!("{label:<width$}  "), &text));
    }
    Ok(Flow::Continue)
}

/// `:history [N]`: the last N lines typed in the line editor (in this
/// session and the ones before), from its history file.
pub(crate) fn history(_session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let shown = match arguments {
        [] => HISTORY_SHOWN,
        [count] => {
            count.parse::<usize>().map_err(|_| CommandError::Usage(format!("`{count}` is not a number of lines")))?
        }
        _ => return Err(CommandError::Usage("give at most one number".to_string())),
    };
    let mut history = FileHistory::new();
    if let Some(path) = history_path() {
        // No file yet is an empty history.
        let _ = history.load(&path);
    }
    let entries: Vec<&String> = history.iter().collect();
    let first = entries.len().saturating_sub(shown);
    if first > 0 {
        console.say(format!("({} before these: `:history {}` shows them all)", counted(first, "line"), entries.len()));
    }
    for (index, entry) in entries.iter().enumerate().skip(first) {
        console.say(indented(&format!("{:>4}  ", index + 1), entry));
    }
    if entries.is_empty() {
        console.say("the history is empty");
    }
    Ok(Flow::Continue)
}

/// `text` after `label`, its other lines indented to line up with its first.
fn indented(label: &str, text: &str) -> String {
    let margin = " ".repeat(label.chars().count());
    let mut lines = text.lines();
    let mut out = format!("{label}{}", lines.next().unwrap_or_default());
    for line in lines {
        out.push_str(&format!("\n{margin}{line}"));
    }
    out
}
