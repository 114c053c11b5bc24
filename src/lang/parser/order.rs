//! The order of a file's parts (SPEC 2): `camera`, `ambient`, lights,
//! procedures, instructions.
//!
//! The grammar accepts items in any order (the interactive session needs
//! that); for a file, [`check`] goes over the parsed items afterwards and
//! names the first one out of place.

use crate::lang::ast::{Item, Program};
use crate::lang::diagnostic::Diagnostic;
use crate::lang::source::{SourceId, Span};

/// How far a file has got through its parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Nothing read yet: the camera must come.
    Start,
    /// The camera was read: `ambient` must come.
    Camera,
    /// `ambient` was read: lights may come.
    Lights,
    /// A procedure was read.
    Procs,
    /// An instruction was read.
    Instrs,
}

/// The note attached to every order error.
const ORDER_NOTE: &str = "a file gives, in this order: `camera ... end`, `ambient`, \
                          the lights, the procedures, then the instructions";

/// Where the first item of each kind is, for the messages that point back.
#[derive(Debug, Default)]
struct Firsts {
    camera: Option<Span>,
    ambient: Option<Span>,
    proc_or_instr: Option<Span>,
    instr: Option<Span>,
}

/// Checks that the items of `program`, parsed from `text`, come in the order
/// of a file; the error names the first item out of place.
pub(super) fn check(source: SourceId, text: &str, program: &Program) -> Result<(), Diagnostic> {
    let mut phase = Phase::Start;
    let mut firsts = Firsts::default();
    for item in &program.items {
        let at = first_word(text, item.span());
        if let Some(error) = misplaced(phase, item, at, &firsts) {
            return Err(error.with_note(ORDER_NOTE));
        }
        phase = advance(item, at, &mut firsts);
    }
    let end = end_of_text(source, text);
    match phase {
        Phase::Start => Err(start_error(end).with_label("the file ends here").with_note(ORDER_NOTE)),
        Phase::Camera => {
            Err(Diagnostic::error(end, "unexpected end of file: `ambient` must come right after the camera")
                .with_code("ambient-missing")
                .with_label("the file ends here")
                .with_note(ORDER_NOTE))
        }
        _ => Ok(()),
    }
}

/// The error for `item`, whose first word is `at`, if it may not come in `phase`.
fn misplaced(phase: Phase, item: &Item, at: Span, firsts: &Firsts) -> Option<Diagnostic> {
    match (phase, item) {
        (Phase::Start, Item::Camera(_)) => None,
        (Phase::Start, _) => Some(start_error(at)),
        (_, Item::Camera(_)) => Some(only_one(at, "camera", firsts.camera)),
        (Phase::Camera, Item::Ambient(_)) => None,
        (Phase::Camera, _) => Some(ambient_missing(at)),
        (_, Item::Ambient(_)) => Some(only_one(at, "ambient", firsts.ambient)),
        (Phase::Lights, _) => None,
        (_, Item::Light(_)) => Some(out_of_place(
            at,
            "a `light` must come before procedures and instructions",
            "this `light` comes too late",
            firsts.proc_or_instr,
            "the first of them",
        )),
        (Phase::Instrs, Item::Proc(_)) => Some(out_of_place(
            at,
            "a `proc` must come before the instructions",
            "this `proc` comes too late",
            firsts.instr,
            "the first instruction",
        )),
        _ => None,
    }
}

/// The phase after `item`, whose first word is `at`; records the firsts.
fn advance(item: &Item, at: Span, firsts: &mut Firsts) -> Phase {
    if matches!(item, Item::Proc(_) | Item::Instr(_)) {
        firsts.proc_or_instr.get_or_insert(at);
    }
    match item {
        Item::Camera(_) => {
            firsts.camera = Some(at);
            Phase::Camera
        }
        Item::Ambient(_) => {
            firsts.ambient = Some(at);
            Phase::Lights
        }
        Item::Light(_) => Phase::Lights,
        Item::Proc(_) => Phase::Procs,
        Item::Instr(_) => {
            firsts.instr.get_or_insert(at);
            Phase::Instrs
        }
    }
}

/// The error for a second `camera` or `ambient`.
fn only_one(at: Span, what: &str, first: Option<Span>) -> Diagnostic {
    let error = Diagnostic::error(at, format!("a file has only one `{what}`"))
        .with_code("only-one")
        .with_label(format!("a second `{what}`"));
    match first {
        Some(first) => error.with_related(first, format!("the first `{what}`")),
        None => error,
    }
}

/// An item that should have come before `earlier`.
fn out_of_place(at: Span, message: &str, label: &str, earlier: Option<Span>, earlier_name: &str) -> Diagnostic {
    let error = Diagnostic::error(at, message).with_code("out-of-order").with_label(label);
    match earlier {
        Some(earlier) => error.with_related(earlier, format!("{earlier_name} is here")),
        None => error,
    }
}

/// The error for a file that does not start with the camera.
pub(super) fn start_error(at: Span) -> Diagnostic {
    Diagnostic::error(at, "a scenario file must start with `camera ... end`")
        .with_code("camera-first")
        .with_label("expected `camera` here")
        .with_help("begin the file with, for example, `camera distance 10 angle 1 end` then `ambient 0.2`")
}

/// The error for a file whose camera is not followed by `ambient`.
fn ambient_missing(at: Span) -> Diagnostic {
    Diagnostic::error(at, "`ambient` must come right after the camera")
        .with_code("ambient-missing")
        .with_label("expected `ambient` here")
}

/// The span of the first word of the item spanning `span` in `text`.
fn first_word(text: &str, span: Span) -> Span {
    let start = span.start as usize;
    let rest = text.get(start..span.end as usize).unwrap_or("");
    let len = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
    Span::new(span.source, start, start + len.max(1).min(rest.len()))
}

/// The empty span just after the last character of `text` that is not
/// blank: where an "unexpected end of file" points.
pub(crate) fn end_of_text(source: SourceId, text: &str) -> Span {
    let end = text.trim_end().len();
    Span::new(source, end, end)
}
