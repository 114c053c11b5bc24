//! Errors and warnings about a program, and how they are shown to people.
//!
//! A [`Diagnostic`] points at a [`Span`]; [`Diagnostic::render`] prints it the
//! way a learner needs it: file, line and column, the source line, a caret
//! under the spot, and a `help:` line when there is an obvious fix.

use super::source::{SourceMap, Span};

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The program cannot go on.
    Error,
    /// Something was adjusted (a clamped colour, ...); the program goes on.
    Warning,
}

/// One error or warning about the program, with where it happened.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// What is wrong, in plain words ("expected `end` to close the `sphere` opened at line 12").
    pub message: String,
    /// The spot the caret points at.
    pub span: Span,
    /// A short text shown next to the caret, if any.
    pub label: Option<String>,
    /// Other places worth showing (where a `sphere` was opened, where a procedure was called from...).
    pub related: Vec<(Span, String)>,
    /// Extra lines of explanation (a call chain, ...).
    pub notes: Vec<String>,
    /// An obvious fix ("did you mean `sphere`?").
    pub help: Option<String>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            span,
            label: None,
            related: Vec::new(),
            notes: Vec::new(),
            help: None,
        }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, ..Diagnostic::error(span, message) }
    }

    /// Adds the text shown next to the caret.
    pub fn with_label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = Some(label.into());
        self
    }

    /// Adds another place to show.
    pub fn with_related(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.related.push((span, text.into()));
        self
    }

    /// Adds a line of explanation.
    pub fn with_note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// Adds a suggested fix.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    /// Renders the diagnostic for a person: a header naming file, line and
    /// column, the source line with a caret, then notes and help. `color`
    /// turns ANSI colours on (for terminals only).
    pub fn render(&self, sources: &SourceMap, color: bool) -> String {
        let _ = (sources, color);
        todo!("rendered with ariadne")
    }
}
