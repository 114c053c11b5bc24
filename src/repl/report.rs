//! The short confirmations printed after an accepted input, and number
//! formatting for learners (`3`, not `3.0`).

use crate::lang::ast::{InstrKind, Item};

use crate::scene::Counts;

use super::session::{Accepted, Session};

/// Above this many definitions in one input, they are listed on one line.
const MAX_DEFINITION_LINES: usize = 4;

/// The lines confirming what an accepted input did, for example
/// `r = 2` or `put 1 sphere (3 objects in the scene)`.
pub(crate) fn confirmations(accepted: &Accepted, session: &Session) -> Vec<String> {
    let mut lines = definitions(accepted, session);
    if lines.len() > MAX_DEFINITION_LINES {
        lines = vec![format!("defined {}", definition_names(accepted).join(", "))];
    }
    let after = session.counts();
    let before = accepted.counts_before;
    if after.lights > before.lights {
        lines.push(format!(
            "{} ({} in the scene)",
            counted(after.lights - before.lights, "light") + " added",
            counted(after.lights, "light")
        ));
    }
    if objects(&after) > objects(&before) {
        lines.push(format!("put {} ({} in the scene)", added(&before, &after), counted(objects(&after), "object")));
    } else if has_call(accepted) {
        lines.push("nothing was put".to_string());
    }
    lines
}

/// How many primitives `counts` holds.
pub(crate) fn objects(counts: &Counts) -> usize {
    counts.spheres + counts.planes + counts.boxes
}

fn definitions(accepted: &Accepted, session: &Session) -> Vec<String> {
    let scene = session.scene();
    let mut lines = Vec::new();
    for item in &accepted.program.items {
        match item {
            Item::Camera(_) => lines.push(format!(
                "camera: distance {}, angle {}",
                number(scene.camera.distance),
                number(scene.camera.angle)
            )),
            Item::Ambient(_) => lines.push(format!("ambient light: {}", number(scene.ambient))),
            Item::Proc(proc_def) => {
                let name = &*proc_def.name.name;
                let known = accepted.procedures_before.iter().any(|before| &**before == name);
                let verb = if known { "redefined" } else { "defined" };
                let params: Vec<&str> = proc_def.params.iter().map(|p| &*p.name).collect();
                lines.push(format!("{verb} proc {name}({})", params.join(", ")));
            }
            Item::Instr(instr) => match &instr.kind {
                InstrKind::Let(name, _) => lines.push(match session.global_number(&name.name) {
                    Some(value) => format!("{} = {}", name.name, number(value)),
                    None => format!("{} defined", name.name),
                }),
                InstrKind::Object(name, _) => {
                    let what = session.describe_object(&name.name).unwrap_or_else(|| "object".to_string());
                    lines.push(format!("object {} = {what}", name.name));
                }
                InstrKind::Call(..) | InstrKind::Put(_) | InstrKind::If(..) => {}
            },
            Item::Light(_) => {}
        }
    }
    lines
}

fn definition_names(accepted: &Accepted) -> Vec<String> {
    let mut names = Vec::new();
    for item in &accepted.program.items {
        match item {
            Item::Camera(_) => names.push("the camera".to_string()),
            Item::Ambient(_) => names.push("the ambient light".to_string()),
            Item::Proc(proc_def) => names.push(format!("proc {}", proc_def.name.name)),
            Item::Instr(instr) => match &instr.kind {
                InstrKind::Let(name, _) | InstrKind::Object(name, _) => names.push(name.name.to_string()),
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
    let parts: Vec<String> = [
        (after.spheres - before.spheres.min(after.spheres), "sphere"),
        (after.planes - before.planes.min(after.planes), "plane"),
        (after.boxes - before.boxes.min(after.boxes), "box"),
    ]
    .into_iter()
    .filter(|(count, _)| *count > 0)
    .map(|(count, noun)| counted(count, noun))
    .collect();
    match parts.as_slice() {
        [] => "nothing".to_string(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// `count` and `noun`, plural when it is not 1: "1 sphere", "2 boxes".
pub(crate) fn counted(count: usize, noun: &str) -> String {
    match (count, noun) {
        (1, _) => format!("1 {noun}"),
        (_, "box") => format!("{count} boxes"),
        _ => format!("{count} {noun}s"),
    }
}

/// A number the way a learner writes it: `3`, `0.75`, `-1.570796`.
pub(crate) fn number(value: f64) -> String {
    if value == value.trunc() && value.abs() < 1e15 {
        return format!("{value:.0}");
    }
    let text = format!("{value:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "0" || text == "-0" { format!("{value:e}") } else { text.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_like_the_language() {
        assert_eq!(number(3.0), "3");
        assert_eq!(number(-2.0), "-2");
        assert_eq!(number(0.75), "0.75");
        assert_eq!(number(std::f64::consts::PI), "3.141593");
        assert_eq!(number(1e-9), "1e-9");
        assert_eq!(number(0.0), "0");
    }

    #[test]
    fn counts_are_plural_when_not_one() {
        assert_eq!(counted(1, "sphere"), "1 sphere");
        assert_eq!(counted(2, "box"), "2 boxes");
        assert_eq!(counted(0, "light"), "0 lights");
        let before = Counts::default();
        let after = Counts { spheres: 2, planes: 1, boxes: 3, lights: 0 };
        assert_eq!(added(&before, &after), "2 spheres, 1 plane and 3 boxes");
        assert_eq!(added(&before, &Counts { boxes: 1, ..before }), "1 box");
    }
}
