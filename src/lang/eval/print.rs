//! `print e, ...` (an extension of this project, `docs/language.md` section
//! 12): the values of expressions while a program runs, one line per `print`
//! run, such as `scene.ray:12: r = 2, r * 2 = 4`.
//!
//! Lines are kept with their spans and rendered only when shown, once the
//! source texts are at hand. At most [`PRINT_LIMIT`] are kept; the others
//! are counted, so a `print` in a procedure called a million times neither
//! floods the terminal nor fills memory.

use super::Interpreter;
use super::errors::EvalResult;
use super::value::Kind;
use crate::lang::ast::{Expr, ExprKind};
use crate::lang::number::format_number;
use crate::lang::source::{SourceMap, Span};
use crate::scene::{Counts, Primitive, Shape};

/// Most `print` lines shown at a time (for one input of a session, one
/// command, or a whole batch run); the rest are counted.
pub const PRINT_LIMIT: usize = 1000;

/// What one `print` wrote: where it is, and each expression with its value.
#[derive(Debug, Clone, PartialEq)]
pub struct PrintLine {
    /// The `print` instruction.
    pub span: Span,
    /// Each expression (its span) and its value in words.
    pub values: Vec<(Span, String)>,
}

impl PrintLine {
    /// `scene.ray:12: r = 2, r * 2 = 4`: the file and line of the `print`,
    /// then each expression as written with its value (a literal only once).
    pub fn render(&self, sources: &SourceMap) -> String {
        let file = sources.get(self.span.source);
        let (line, _) = file.line_col(self.span.start as usize);
        let values: Vec<String> = self
            .values
            .iter()
            .map(|(span, value)| {
                let text = sources.get(span.source).text.get(span.start as usize..span.end as usize).unwrap_or("");
                let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
                if text == *value { text } else { format!("{text} = {value}") }
            })
            .collect();
        format!("{}:{line}: {}", file.name, values.join(", "))
    }
}

/// The lines `print` wrote, at most [`PRINT_LIMIT`], and how many more there were.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PrintLog {
    /// The lines not yet taken.
    lines: Vec<PrintLine>,
    /// Lines kept since the log began, taken or not.
    kept: usize,
    /// Lines left out past the limit.
    hidden: usize,
}

impl PrintLog {
    /// Whether the next line would be left out.
    fn is_full(&self) -> bool {
        self.kept >= PRINT_LIMIT
    }

    /// Adds a line, or counts it past the limit.
    fn push(&mut self, line: PrintLine) {
        if self.is_full() {
            self.hidden += 1;
        } else {
            self.lines.push(line);
            self.kept += 1;
        }
    }

    /// Adds another log's lines after these, within this log's limit.
    pub fn absorb(&mut self, other: PrintLog) {
        self.hidden += other.hidden;
        for line in other.lines {
            self.push(line);
        }
    }

    /// The lines not yet taken. The log still counts them against the limit.
    pub fn take_lines(&mut self) -> Vec<PrintLine> {
        std::mem::take(&mut self.lines)
    }

    /// "`print` wrote 5 more lines, not shown ...", when lines were left out.
    pub fn hidden_note(&self) -> Option<String> {
        let lines = if self.hidden == 1 { "line" } else { "lines" };
        (self.hidden > 0).then(|| {
            format!("`print` wrote {} more {lines}, not shown: at most {PRINT_LIMIT} are shown at a time", self.hidden)
        })
    }
}

impl Interpreter {
    /// `print e, ...` at `span`: evaluates every expression (an error in one
    /// is an error, shown or not) and records the line. A name holding an
    /// object is described instead of being an error. Out of line: it stays
    /// off the path of the other instructions.
    #[inline(never)]
    pub(crate) fn exec_print(&mut self, values: &[Expr], span: Span) -> EvalResult<()> {
        let shown = !self.printed.is_full();
        let mut line = PrintLine { span, values: Vec::new() };
        for expr in values {
            let object = match &expr.kind {
                ExprKind::Var(name) => match self.env.lookup(*name).map(|value| &value.kind) {
                    Some(Kind::Object(primitives)) => Some(shown.then(|| describe_object(primitives))),
                    _ => None,
                },
                _ => None,
            };
            let text = match object {
                Some(description) => description,
                None => {
                    let number = self.eval_expr(expr)?;
                    shown.then(|| format_number(number.value))
                }
            };
            line.values.extend(text.map(|text| (expr.span, text)));
        }
        self.printed.push(line);
        Ok(())
    }
}

/// An object in a few words: its shape when it is one primitive
/// (`sphere center 0, 1, 0 radius 1`), its contents otherwise
/// (`group of 2 spheres and 1 box`).
fn describe_object(primitives: &[Primitive]) -> String {
    let triple = |v: glam::DVec3| format!("{}, {}, {}", format_number(v.x), format_number(v.y), format_number(v.z));
    match primitives {
        [] => "empty group".to_string(),
        [one] => match one.shape {
            Shape::Sphere { center, radius } => {
                format!("sphere center {} radius {}", triple(center), format_number(radius))
            }
            Shape::Plane { normal, shift } => format!("plane normal {} shift {}", triple(normal), format_number(shift)),
            Shape::Box { center, half, axes } => {
                let turned = if axes == glam::DMat3::IDENTITY { "" } else { ", turned" };
                format!("box center {} length {}{turned}", triple(center), triple(half * 2.0))
            }
        },
        many => format!("group of {}", Counts::of(many).primitives_in_words()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::source::SourceId;

    #[test]
    fn a_line_names_the_place_and_each_expression() {
        let mut sources = SourceMap::new();
        let id = sources.add("scene.ray", "let r = 2\nprint r,  r *\n 2, 7", 3);
        let line = PrintLine {
            span: Span::new(id, 10, 29),
            values: vec![
                (Span::new(id, 16, 17), "2".into()),
                (Span::new(id, 20, 26), "4".into()),
                (Span::new(id, 28, 29), "7".into()),
            ],
        };
        assert_eq!(line.render(&sources), "scene.ray:5: r = 2, r * 2 = 4, 7");
    }

    #[test]
    fn past_the_limit_lines_are_counted() {
        let line = PrintLine { span: Span::new(SourceId(0), 0, 1), values: Vec::new() };
        let mut log = PrintLog::default();
        for _ in 0..PRINT_LIMIT + 5 {
            log.push(line.clone());
        }
        assert_eq!(log.take_lines().len(), PRINT_LIMIT);
        log.push(line.clone());
        assert!(log.take_lines().is_empty(), "taking lines does not lift the limit");
        let mut total = PrintLog::default();
        total.absorb(log);
        assert_eq!(
            total.hidden_note().as_deref(),
            Some("`print` wrote 6 more lines, not shown: at most 1000 are shown at a time")
        );
    }
}
