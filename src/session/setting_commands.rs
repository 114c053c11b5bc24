//! The commands that set how later pictures are made: `:time`, `:size`,
//! `:depth`, `:samples` and `:limits`.

use crate::settings::{DEPTH, Limit, SAMPLES, parse_time};

use super::outcome::{CommandError, CommandResult, Flow, parse_count, parse_size, usage};
use super::outputs::FrontEnd;
use super::rendering::{RenderSettings, Size};
use super::report::number;
use super::shell::Shell;
use super::state::Session;

pub(crate) fn time(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let [value] = arguments else {
        if arguments.is_empty() {
            front.say(format!("time = {}", number(session.settings().time)));
            return Ok(Flow::Continue);
        }
        return Err(CommandError::Usage("give one number".to_string()));
    };
    let value = parse_time(value).map_err(usage)?;
    let previous = session.settings().time;
    match session.set_time(value) {
        Ok(false) => front.say(format!("time = {}", number(value))),
        Ok(true) => front.say(format!("time = {} (the scene was computed again)", number(value))),
        Err(diagnostic) => {
            front.diagnostic(&diagnostic, session.sources());
            return Err(CommandError::Failed(format!(
                "at time {} an earlier input fails, so time stays {}",
                number(value),
                number(previous)
            )));
        }
    }
    Ok(Flow::Continue)
}

pub(crate) fn size(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    match arguments {
        [] => {}
        [width, height] => {
            let size = parse_size(width, height)?;
            session.set_size(size.width, size.height);
        }
        _ => {
            return Err(CommandError::Usage("give a width and a height in pixels".to_string()));
        }
    }
    let settings = session.settings();
    front.say(format!("size = {}", Size { width: settings.width, height: settings.height }));
    Ok(Flow::Continue)
}

pub(crate) fn depth(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let setting = CountSetting { name: "depth", limit: &DEPTH, set: Session::set_depth, get: |s| s.depth };
    count_setting(session, arguments, front, &setting)
}

pub(crate) fn samples(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let setting = CountSetting { name: "samples", limit: &SAMPLES, set: Session::set_samples, get: |s| s.samples };
    count_setting(session, arguments, front, &setting)
}

/// A whole-number render setting, as `:depth` and `:samples` set it.
struct CountSetting {
    /// Its name in the confirmation (`depth = 5`).
    name: &'static str,
    /// The values it takes.
    limit: &'static Limit,
    /// Sets it in the session.
    set: fn(&mut Session, u32),
    /// Reads it from the settings.
    get: fn(&RenderSettings) -> u32,
}

/// Sets `setting` from the one argument, if there is one, and says its value.
fn count_setting(
    session: &mut Session,
    arguments: &[String],
    front: &mut dyn FrontEnd,
    setting: &CountSetting,
) -> CommandResult {
    match arguments {
        [] => {}
        [value] => (setting.set)(session, parse_count(value, setting.limit)?),
        _ => return Err(CommandError::Usage("give one whole number".to_string())),
    }
    front.say(format!("{} = {}", setting.name, (setting.get)(session.settings())));
    Ok(Flow::Continue)
}

pub(crate) fn limits(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let mut limits = session.limits();
    for pair in arguments.chunks(2) {
        let [name, value] = pair else {
            return Err(CommandError::Usage(format!("give a number after `{}`", pair[0])));
        };
        let value = value.parse::<usize>().ok().filter(|n| *n > 0);
        let value = value.ok_or_else(|| CommandError::Usage(format!("`{name}` takes a whole number above 0")))?;
        match name.as_str() {
            "calls" => limits.max_call_depth = value,
            "primitives" => limits.max_primitives = value,
            _ => return Err(CommandError::Usage(format!("there is no limit `{name}`: `calls` or `primitives`"))),
        }
    }
    session.set_limits(limits).map_err(|error| CommandError::Program(Box::new(error)))?;
    front.say(format!(
        "calls = {} (deepest chain of procedure calls), primitives = {}",
        limits.max_call_depth, limits.max_primitives
    ));
    Ok(Flow::Continue)
}
