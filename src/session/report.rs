//! The short confirmations printed after an accepted input.

use std::fmt::{self, Display};

use crate::lang::Diagnostic;
use crate::lang::ast::{InstrKind, Item};
use crate::lang::diagnostic::shown_name;
use crate::lang::number::Number;
/// Numbers the way a learner writes them (`3`, not `3.0`), as everywhere.
pub(crate) use crate::lang::number::format_number as number;
use crate::scene::Counts;

use crate::lint::Picture;

use super::outputs::FrontEnd;
use super::rendering::Size;
use super::state::{Accepted, Session};
use crate::warned::Warned;

/// Above this many definitions in one input, they are listed on one line.
const MAX_DEFINITION_LINES: usize = 4;

/// Says the lines confirming what an accepted input did, for example
/// `r = 2` or `put 1 sphere (3 objects in the scene)`, each formatted
/// straight into the front's line.
pub(crate) fn confirm(accepted: &Accepted, session: &Session, front: &mut dyn FrontEnd) {
    // One pass over the items: a `:load`ed file may hold a million.
    let definitions: Vec<&Item> = accepted.program.items.iter().filter(|item| defines(item)).collect();
    if definitions.len() > MAX_DEFINITION_LINES {
        front.say(format_args!("defined {}", definition_names(&definitions).join(", ")));
    } else {
        say_definitions(&definitions, accepted, session, front);
    }
    let after = session.counts();
    let before = accepted.counts_before;
    if after.lights > before.lights {
        front.say(format_args!(
            "{} added ({} in the scene)",
            Counted(after.lights - before.lights, "light"),
            Counted(after.lights, "light")
        ));
    }
    if objects(&after) > objects(&before) {
        front.say(format_args!("put {} ({} in the scene)", added(&before, &after), Counted(objects(&after), "object")));
    } else if has_call(accepted) {
        front.say("nothing was put");
    }
}

/// How many primitives `counts` holds.
pub(crate) fn objects(counts: &Counts) -> usize {
    counts.spheres + counts.planes + counts.boxes
}

/// Whether `item` defines something that [`say_definitions`] confirms.
fn defines(item: &Item) -> bool {
    match item {
        Item::Camera(_) | Item::Ambient(_) | Item::Proc(_) => true,
        Item::Instr(instr) => matches!(instr.kind, InstrKind::Let(..) | InstrKind::Object(..)),
        Item::Light(_) => false,
    }
}

fn say_definitions(definitions: &[&Item], accepted: &Accepted, session: &Session, front: &mut dyn FrontEnd) {
    let scene = session.scene();
    for item in definitions {
        match item {
            Item::Camera(_) => front.say(format_args!(
                "camera: distance {}, angle {}",
                Number(scene.camera.distance),
                Number(scene.camera.angle)
            )),
            Item::Ambient(_) => front.say(format_args!("ambient light: {}", Number(scene.ambient))),
            Item::Proc(proc_def) => {
                let name = proc_def.name.name;
                let known = accepted.redefined.contains(&name);
                let verb = if known { "redefined" } else { "defined" };
                let params: Vec<_> = proc_def.params.iter().map(|p| shown_name(&p.name)).collect();
                front.say(format_args!("{verb} proc {}({})", shown_name(&name), params.join(", ")));
            }
            Item::Instr(instr) => match &instr.kind {
                InstrKind::Let(name, _) => match session.global_number(&name.name) {
                    Some(value) => front.say(format_args!("{} = {}", shown_name(&name.name), Number(value))),
                    None => front.say(format_args!("{} defined", shown_name(&name.name))),
                },
                InstrKind::Object(name, _) => {
                    let what = session.describe_object(&name.name).unwrap_or_else(|| "object".to_string());
                    front.say(format_args!("object {} = {what}", shown_name(&name.name)));
                }
                InstrKind::Call(..) | InstrKind::Put(_) | InstrKind::If(..) | InstrKind::Print(_) => {}
            },
            Item::Light(_) => {}
        }
    }
}

fn definition_names(definitions: &[&Item]) -> Vec<String> {
    let mut names = Vec::new();
    for item in definitions {
        match item {
            Item::Camera(_) => names.push("the camera".to_string()),
            Item::Ambient(_) => names.push("the ambient light".to_string()),
            Item::Proc(proc_def) => names.push(format!("proc {}", shown_name(&proc_def.name.name))),
            Item::Instr(instr) => match &instr.kind {
                InstrKind::Let(name, _) | InstrKind::Object(name, _) => names.push(shown_name(&name.name).into_owned()),
                _ => {}
            },
            Item::Light(_) => {}
        }
    }
    names
}

fn has_call(accepted: &Accepted) -> bool {
    accepted
        .program
        .items
        .iter()
        .any(|item| matches!(item, Item::Instr(instr) if matches!(instr.kind, InstrKind::Call(..))))
}

/// "1 sphere", "2 spheres and 1 box", "3 spheres, 1 plane and 2 boxes".
fn added(before: &Counts, after: &Counts) -> String {
    let more = |after: usize, before: usize| after - before.min(after);
    let added = Counts {
        spheres: more(after.spheres, before.spheres),
        planes: more(after.planes, before.planes),
        boxes: more(after.boxes, before.boxes),
        lights: 0,
    };
    added.primitives_in_words()
}

/// `count` and `noun`, plural when it is not 1: "1 sphere", "2 boxes".
pub(crate) fn counted(count: usize, noun: &str) -> String {
    Counted(count, noun).to_string()
}

/// [`counted`], formatted straight into the line that shows it.
struct Counted<'n>(usize, &'n str);

impl Display for Counted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match *self {
            Counted(1, noun) => write!(f, "1 {noun}"),
            Counted(count, "box") => write!(f, "{count} boxes"),
            Counted(count, noun) => write!(f, "{count} {noun}s"),
        }
    }
}

/// Shows what `print` wrote since the last time, and how many lines were
/// left out past the limit.
pub(crate) fn show_printed(session: &Session, front: &mut dyn FrontEnd) {
    let mut printed = session.take_printed();
    for line in printed.take_lines() {
        front.printed(line.render(session.sources()));
    }
    if let Some(note) = printed.hidden_note() {
        front.printed_note(note);
    }
}

/// Shows the warnings about the scene that a render of `size` (an
/// animation's frames, if `animation`) should heed, those not `warned`
/// about before.
pub(crate) fn show_scene_warnings(
    session: &Session,
    warned: &mut Warned,
    front: &mut dyn FrontEnd,
    size: Size,
    animation: bool,
) {
    let screen = session.settings().screen;
    let picture = Picture { width: size.width, height: size.height, screen, animation };
    show_warnings(session, warned, front, session.scene_warnings(&picture));
}

/// Shows those of `warnings` (of an evaluation, or about the scene) not
/// `warned` about before.
pub(crate) fn show_warnings(
    session: &Session,
    warned: &mut Warned,
    front: &mut dyn FrontEnd,
    warnings: Vec<Diagnostic>,
) {
    for warning in warned.unseen(warnings) {
        front.diagnostic(&warning, session.sources());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_plural_when_not_one() {
        assert_eq!(counted(1, "sphere"), "1 sphere");
        assert_eq!(counted(2, "box"), "2 boxes");
        assert_eq!(counted(0, "light"), "0 lights");
        let before = Counts::default();
        let after = Counts { spheres: 2, planes: 1, boxes: 3, lights: 0 };
        assert_eq!(added(&before, &after), "2 spheres, 1 plane and 3 boxes");
        assert_eq!(added(&before, &Counts { boxes: 1, ..before }), "1 box");
        assert_eq!(added(&before, &Counts { spheres: 1, boxes: 2, ..before }), "1 sphere and 2 boxes");
        assert_eq!(added(&after, &after), "nothing");
    }
}
