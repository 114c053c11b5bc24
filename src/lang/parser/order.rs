//! The order of a file's parts (SPEC 2): `camera`, `ambient`, lights,
//! procedures, instructions.
//!
//! The grammar accepts items in any order (the interactive session needs
//! that); for a file, [`ItemOrder`] checks each item as soon as the parser
//! has read it, so that the message names what is out of place.

use std::cell::Cell;

use crate::lang::ast::Item;
use crate::lang::diagnostic::Diagnostic;
use crate::lang::source::{SourceId, Span};

/// How far a file has got through its parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Phase {
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

/// Checks the order of a file's items as the parser completes them; accepts
/// anything for a session input.
#[derive(Debug)]
pub(crate) struct ItemOrder<'t> {
    /// `None` for a session input, where any order is fine.
    file: Option<FileText<'t>>,
    phase: Cell<Phase>,
    /// Where the camera, and then the first procedure or instruction, were.
    first_camera: Cell<Option<Span>>,
    first_ambient: Cell<Option<Span>>,
    first_proc_or_instr: Cell<Option<Span>>,
    first_instr: Cell<Option<Span>>,
}

/// The text being parsed, to point at an item's first word.
#[derive(Debug, Clone, Copy)]
struct FileText<'t> {
    source: SourceId,
    text: &'t str,
}

impl<'t> ItemOrder<'t> {
    /// The order check for a whole file.
    pub(crate) fn file(source: SourceId, text: &'t str) -> ItemOrder<'t> {
        ItemOrder { file: Some(FileText { source, text }), ..ItemOrder::any() }
    }

    /// No check: a session input takes items in any order.
    pub(crate) fn any() -> ItemOrder<'t> {
        ItemOrder {
            file: None,
            phase: Cell::new(Phase::Start),
            first_camera: Cell::new(None),
            first_ambient: Cell::new(None),
            first_proc_or_instr: Cell::new(None),
            first_instr: Cell::new(None),
        }
    }

    /// Whether this checks a file (rather than accepting anything).
    pub(crate) fn is_file(&self) -> bool {
        self.file.is_some()
    }

    /// How far the file has got.
    pub(crate) fn phase(&self) -> Phase {
        self.phase.get()
    }

    /// Accepts `item`, spanning `span`, if it may come at this point of a
    /// file; otherwise says what is out of place.
    pub(crate) fn check(&self, item: &Item, span: Span) -> Result<(), Box<Diagnostic>> {
        let Some(file) = self.file else { return Ok(()) };
        let at = first_word(file, span);
        let phase = self.phase.get();
        let error = match (phase, item) {
            (Phase::Start, Item::Camera(_)) => None,
            (Phase::Start, _) => Some(start_error(at)),
            (_, Item::Camera(_)) => Some(self.only_one(at, "camera", self.first_camera.get())),
            (Phase::Camera, Item::Ambient(_)) => None,
            (Phase::Camera, _) => Some(ambient_missing(at)),
            (_, Item::Ambient(_)) => Some(self.only_one(at, "ambient", self.first_ambient.get())),
            (Phase::Lights, _) => None,
            (_, Item::Light(_)) => Some(out_of_place(
                at,
                "a `light` must come before procedures and instructions",
                "this `light` comes too late",
                self.first_proc_or_instr.get(),
                "the first of them",
            )),
            (Phase::Instrs, Item::Proc(_)) => Some(out_of_place(
                at,
                "a `proc` must come before the instructions",
                "this `proc` comes too late",
                self.first_instr.get(),
                "the first instruction",
            )),
            _ => None,
        };
        if let Some(error) = error {
            return Err(Box::new(error.with_note(ORDER_NOTE)));
        }
        self.advance(item, at);
        Ok(())
    }

    /// Records that `item`, whose first word is `at`, was accepted.
    fn advance(&self, item: &Item, at: Span) {
        let next = match item {
            Item::Camera(_) => {
                self.first_camera.set(Some(at));
                Phase::Camera
            }
            Item::Ambient(_) => {
                self.first_ambient.set(Some(at));
                Phase::Lights
            }
            Item::Light(_) => Phase::Lights,
            Item::Proc(_) => Phase::Procs,
            Item::Instr(_) => {
                if self.first_instr.get().is_none() {
                    self.first_instr.set(Some(at));
                }
                Phase::Instrs
            }
        };
        if matches!(item, Item::Proc(_) | Item::Instr(_)) && self.first_proc_or_instr.get().is_none() {
            self.first_proc_or_instr.set(Some(at));
        }
        self.phase.set(next);
    }

    /// Checks, once the whole file is read, that its required parts came.
    pub(crate) fn check_end(&self, text: &str) -> Result<(), Diagnostic> {
        let Some(file) = self.file else { return Ok(()) };
        let end = end_of_text(file.source, text);
        match self.phase.get() {
            Phase::Start => Err(start_error(end).with_label("the file ends here").with_note(ORDER_NOTE)),
            Phase::Camera => {
                Err(Diagnostic::error(end, "unexpected end of file: `ambient` must come right after the camera")
                    .with_label("the file ends here")
                    .with_note(ORDER_NOTE))
            }
            _ => Ok(()),
        }
    }

    /// The error for a second `camera` or `ambient`.
    fn only_one(&self, at: Span, what: &str, first: Option<Span>) -> Diagnostic {
        let error =
            Diagnostic::error(at, format!("a file has only one `{what}`")).with_label(format!("a second `{what}`"));
        match first {
            Some(first) => error.with_related(first, format!("the first `{what}`")),
            None => error,
        }
    }
}

/// An item that should have come before `earlier`.
fn out_of_place(at: Span, message: &str, label: &str, earlier: Option<Span>, earlier_name: &str) -> Diagnostic {
    let error = Diagnostic::error(at, message).with_label(label);
    match earlier {
        Some(earlier) => error.with_related(earlier, format!("{earlier_name} is here")),
        None => error,
    }
}

/// The error for a file that does not start with the camera.
fn start_error(at: Span) -> Diagnostic {
    Diagnostic::error(at, "a scenario file must start with `camera ... end`")
        .with_label("expected `camera` here")
        .with_help("begin the file with, for example, `camera distance 10 angle 1 end` then `ambient 0.2`")
}

/// The error for a file whose camera is not followed by `ambient`.
fn ambient_missing(at: Span) -> Diagnostic {
    Diagnostic::error(at, "`ambient` must come right after the camera").with_label("expected `ambient` here")
}

/// The span of the first word of the item spanning `span`.
fn first_word(file: FileText<'_>, span: Span) -> Span {
    let start = span.start as usize;
    let rest = file.text.get(start..span.end as usize).unwrap_or("");
    let len = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
    Span::new(file.source, start, start + len.max(1).min(rest.len()))
}

/// The 1-based line number, as the user sees it, of byte `offset` of `text`.
pub(super) fn line_number(text: &str, offset: usize, line_offset: usize) -> usize {
    let before = text.as_bytes().get(..offset).unwrap_or(text.as_bytes());
    before.iter().filter(|&&b| b == b'\n').count() + 1 + line_offset
}

/// The empty span just after the last character of `text` that is not
/// blank: where an "unexpected end of file" points.
pub(crate) fn end_of_text(source: SourceId, text: &str) -> Span {
    let end = text.trim_end().len();
    Span::new(source, end, end)
}
