//! Looking inside the session: `:env` lists the names defined, `:scene`
//! what the scene holds, `:show NAME` prints a definition as it was
//! written, `:list` the inputs the session holds, `:history` the lines
//! typed in the line editor.

use crate::lang::ast::{Instr, Item, ProcDef};
use crate::lang::suggest::closest;
use crate::lang::walk::{bound_name, same_level};

use super::excerpt::{item_text, location};
use super::outcome::{CommandError, CommandResult, Flow, no_arguments};
use super::outputs::FrontEnd;
use super::rendering::Size;
use super::report::{self, counted, number};
use super::shell::Shell;
use super::state::Session;

/// How many lines `:history` prints unless told.
const HISTORY_SHOWN: usize = 20;

pub(crate) fn env(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    no_arguments(arguments)?;
    let numbers: Vec<String> =
        session.numbers().iter().map(|(name, value)| format!("{name} = {}", number(*value))).collect();
    let objects: Vec<String> = session.objects().iter().map(|(name, what)| format!("{name} ({what})")).collect();
    let procedures: Vec<String> = session
        .procedures()
        .iter()
        .map(|(name, params)| format!("{name}({})", params.iter().map(|p| p.as_str()).collect::<Vec<_>>().join(", ")))
        .collect();
    front.say(format!("numbers:    {}", numbers.join(", ")));
    let no_objects = format!("none yet: `object {} = sphere ... end` names one", free_name(session, "ball"));
    front.say(format!("objects:    {}", or_none(&objects, &no_objects)));
    let no_procedures = "none yet: see `:help proc`";
    front.say(format!("procedures: {}", or_none(&procedures, no_procedures)));
    Ok(Flow::Continue)
}

/// `base`, or `base2`, `base3`...: the first that names nothing yet, so an
/// example never suggests redefining a number or a procedure.
fn free_name(session: &Session, base: &str) -> String {
    let taken = |name: &str| {
        session.numbers().iter().any(|(n, _)| &**n == name) || session.procedures().iter().any(|(n, _)| &**n == name)
    };
    let mut candidates = std::iter::once(base.to_string()).chain((2..).map(|n| format!("{base}{n}")));
    candidates.find(|name| !taken(name)).unwrap_or_default()
}

fn or_none(items: &[String], none: &str) -> String {
    if items.is_empty() { none.to_string() } else { items.join(", ") }
}

pub(crate) fn scene(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    no_arguments(arguments)?;
    let scene = session.scene();
    let default = |given: bool| {
        if given { "" } else { " (default: none given yet)" }
    };
    front.say(format!(
        "camera:   distance {}, angle {}{}",
        number(scene.camera.distance),
        number(scene.camera.angle),
        default(session.has_camera())
    ));
    front.say(format!("ambient:  {}{}", number(scene.ambient), default(session.has_ambient())));
    front.say(format!("lights:   {}", scene.lights.len()));
    for (index, light) in scene.lights.iter().enumerate() {
        let d = light.direction;
        front.say(format!(
            "  {}. towards ({}, {}, {}), intensity {}",
            index + 1,
            number(d.x),
            number(d.y),
            number(d.z),
            number(light.intensity)
        ));
    }
    let counts = scene.counts();
    let mut objects = format!(
        "objects:  {} ({}, {}, {})",
        report::objects(&counts),
        counted(counts.spheres, "sphere"),
        counted(counts.planes, "plane"),
        counted(counts.boxes, "box")
    );
    if !scene.timed_primitives.is_empty() {
        objects.push_str(&format!(", {} depending on time", scene.timed_primitives.len()));
    }
    front.say(objects);
    let s = session.settings();
    front.say(format!(
        "settings: time {}, size {}, depth {}, samples {}",
        number(s.time),
        Size { width: s.width, height: s.height },
        s.depth,
        s.samples
    ));
    Ok(Flow::Continue)
}

/// `:show NAME`: the latest definition of a procedure, object or number,
/// with where it came from.
pub(crate) fn show(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let [name] = arguments else {
        return Err(CommandError::Usage("give the name of a procedure, an object or a number".to_string()));
    };
    let (procedure, binding) = latest_definitions(session, name);
    let sources = session.sources();
    if let Some(def) = procedure {
        front.say(format!("# {}", location(sources, def.span)));
        front.say(item_text(sources, def.span));
    }
    let value = match (session.global_number(name), session.describe_object(name)) {
        (Some(value), _) => Some(format!("{name} = {} now", number(value))),
        (None, Some(what)) => Some(format!("{name}: {what}")),
        (None, None) => None,
    };
    match (binding, value) {
        (Some((binding, top)), Some(value)) => {
            // A name bound inside an `if` shows the whole `if`, which says when.
            front.say(format!("# {} ({value})", location(sources, binding.span)));
            front.say(item_text(sources, top.span));
        }
        (None, Some(value)) if name == "time" => {
            front.say(format!("# predefined ({value}): the time renders use, set with `:time N`"));
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
pub(crate) fn list(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    no_arguments(arguments)?;
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
        front.say("the session holds no input yet");
    }
    let width = rows.iter().map(|(label, _)| label.chars().count()).max().unwrap_or(0);
    for (label, text) in rows {
        front.say(indented(&format!("{label:<width$}  "), &text));
    }
    Ok(Flow::Continue)
}

/// `:history [N]`: the last N lines typed in the line editor (in this
/// session and the ones before), from its history file.
pub(crate) fn history(_shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let shown = match arguments {
        [] => HISTORY_SHOWN,
        [count] => {
            count.parse::<usize>().map_err(|_| CommandError::Usage(format!("`{count}` is not a number of lines")))?
        }
        _ => return Err(CommandError::Usage("give at most one number".to_string())),
    };
    let entries = front.history();
    let first = entries.len().saturating_sub(shown);
    if first > 0 {
        front.say(format!("({} before these: `:history {}` shows them all)", counted(first, "line"), entries.len()));
    }
    for (index, entry) in entries.iter().enumerate().skip(first) {
        front.say(indented(&format!("{:>4}  ", index + 1), entry));
    }
    if entries.is_empty() {
        front.say("the history is empty");
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
