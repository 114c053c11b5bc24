//! `:reload` and `:watch FILE`: the session follows a file as it changes.
//! What a file brought is replaced where it stood among the inputs, so the
//! inputs typed after it run again on the new version, nothing is doubled,
//! and `:undo` takes a reload back.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use crate::lang::source::text_of;
use crate::output;

use super::outcome::{CommandError, CommandResult, Flow};
use super::outputs::{FrontEnd, Waited};
use super::report::{self, counted};
use super::shell::Shell;
use super::state::Session;
use crate::process::cancel::{Stopped, cancel_flag, off_thread};

/// A command that renders the session, as `:render` does.
pub(crate) type Render = fn(&mut Shell, &[String], &mut dyn FrontEnd) -> CommandResult;

/// `:reload`: the file of the last `:load`, as it is now.
pub(crate) fn reload(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    if !arguments.is_empty() {
        return Err(CommandError::Usage("`:reload` reads the file of the last `:load` again".to_string()));
    }
    let Some(path) = session.last_loaded().map(Path::to_path_buf) else {
        return Err(CommandError::Failed(
            "nothing was loaded: `:load FILE` first, then `:reload` after changing the file".to_string(),
        ));
    };
    let text = read(&path, cancel_flag(front.cancel()))?;
    reload_text(session, &path, &text, front)
}

/// `:watch FILE`: loads the file (in place of what it brought before), then
/// again at every save, rendering with `render` each time, until Ctrl-C. A
/// version that fails, or an empty one, is reported and leaves the session,
/// and the last picture, as they were.
pub(crate) fn watch(
    shell: &mut Shell,
    arguments: &[String],
    front: &mut dyn FrontEnd,
    render: Render,
) -> CommandResult {
    let [file] = arguments else {
        return Err(CommandError::Usage("give the file to watch".to_string()));
    };
    let path = PathBuf::from(file);
    let watcher = front.watch(&path).map_err(CommandError::Failed)?;
    let Some(switch) = front.cancel() else {
        return Err(CommandError::Failed("Ctrl-C cannot be caught here, so nothing could stop a watch".to_string()));
    };
    let mut text = read(&path, switch.flag())?;
    front.say(format!("watching {}: every save loads it again and renders it; Ctrl-C stops", path.display()));
    let mut last_text = None;
    let result = loop {
        // Armed while waiting and evaluating: Ctrl-C then ends the watch
        // rather than the session. The render arms the switch itself.
        let armed = switch.arm();
        if last_text.is_some() {
            match watcher.wait(armed.flag()) {
                Ok(Waited::Saved) => {}
                Ok(Waited::Cancelled) => break Ok(Flow::Continue),
                Err(error) => break Err(CommandError::Failed(error)),
            }
            text = match read(&path, switch.flag()) {
                Ok(new) if Some(&new) == last_text.as_ref() => continue,
                Ok(new) if new.trim().is_empty() => {
                    // An editor that truncates the file before writing it
                    // leaves it empty for a moment: not a scene to load.
                    front.note(format!("{} is empty: the last version stays until it is saved again", path.display()));
                    continue;
                }
                Ok(new) => new,
                Err(error) => {
                    error.report(&shell.session, front);
                    continue;
                }
            };
        }
        let loaded = reload_text(&mut shell.session, &path, &text, front);
        last_text = Some(std::mem::take(&mut text));
        let interrupted = armed.pressed();
        drop(armed);
        if interrupted {
            break Ok(Flow::Continue);
        }
        match loaded.map(|_| render(shell, &[], front)) {
            Ok(Ok(_)) => {}
            Ok(Err(error @ CommandError::Cancelled(_))) => break Err(error),
            Ok(Err(error)) => error.report(&shell.session, front),
            Err(error) => {
                error.report(&shell.session, front);
                front.note("the last good version stays: fix the file and save it again");
            }
        }
    };
    front.say(format!("stopped watching {}", path.display()));
    result
}

/// Runs `text`, the content of the file at `path`, in place of what the
/// file brought before (as a new input if it brought nothing), and says
/// what the scene holds now.
fn reload_text(session: &mut Session, path: &Path, text: &str, front: &mut dyn FrontEnd) -> CommandResult {
    let verb = if session.inputs().iter().any(|input| input.loaded_from.as_deref() == Some(path)) {
        "reloaded"
    } else {
        "loaded"
    };
    let before = session.scene().counts();
    session.reload(path, text).map_err(|diagnostic| CommandError::Program(Box::new(diagnostic)))?;
    let after = session.scene().counts();
    let objects = counted(report::objects(&after), "object");
    let lights = counted(after.lights, "light");
    let change = if after == before { ", as many as before" } else { "" };
    front.say(format!("{verb} {} ({objects} and {lights} in the scene{change})", path.display()));
    Ok(Flow::Continue)
}

/// The text of the file at `path`, unless `cancel` is raised first. The
/// file is read on a thread of its own, which a cancelled read abandons:
/// `open` of a FIFO that no one writes waits forever, a large file takes a
/// while, and neither looks at a flag.
pub(crate) fn read(path: &Path, cancel: &'static AtomicBool) -> Result<String, CommandError> {
    let failed = |reason: String| CommandError::Failed(format!("cannot read {}: {reason}", path.display()));
    let file = path.to_owned();
    let read = match off_thread("read", cancel, move || std::fs::read(file)) {
        Ok(read) => read,
        Err(Stopped::Cancelled) => {
            let what = format!("reading {} was cancelled; the session is as it was", path.display());
            return Err(CommandError::Cancelled(what));
        }
        Err(Stopped::Failed) => Err(std::io::Error::other("the reading thread stopped")),
    };
    let bytes = read.map_err(|e| failed(output::io_reason(&e)))?;
    text_of(bytes).map_err(failed)
}
