//! Errors and warnings about a program, and how they are shown to people.
//!
//! A [`Diagnostic`] points at a [`Span`]; [`Diagnostic::render`] prints it the
//! way a learner needs it: file, line and column, the source line, a caret
//! under the spot, and a `help:` line when there is an obvious fix.

use ariadne::{Color, Fmt};

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
    /// turns ANSI colours on (for terminals only); without it the output is
    /// plain text whose frame is drawn in ASCII.
    ///
    /// The header is `error: <message>` then ` --> file:line:column`, as in
    /// rustc; ariadne draws the source lines and labels in between; notes and
    /// help follow as `note: ...` and `help: ...` lines.
    pub fn render(&self, sources: &SourceMap, color: bool) -> String {
        let mut out = self.header(color);
        out.push_str(&render::snippet(self, sources, color));
        let notes = self.notes.iter().map(|note| ("note", note));
        for (kind, text) in notes.chain(self.help.iter().map(|help| ("help", help))) {
            out.push_str(&paint(kind, Color::Cyan, color));
            out.push_str(": ");
            out.push_str(text);
            out.push('\n');
        }
        out
    }

    /// `error: <message>`, the first line of the rendering.
    fn header(&self, color: bool) -> String {
        let (kind, kind_color) = match self.severity {
            Severity::Error => ("error", Color::Red),
            Severity::Warning => ("warning", Color::Yellow),
        };
        format!("{}: {}\n", paint(kind, kind_color, color), self.message)
    }
}

/// `text` in `color` when colours are on, as is otherwise.
fn paint(text: &str, color: Color, enabled: bool) -> String {
    if enabled { text.fg(color).to_string() } else { text.to_string() }
}

/// The source snippet drawn by ariadne, with the location line in rustc's style.
mod render {
    use std::collections::HashMap;
    use std::fmt;
    use std::ops::Range;

    use ariadne::{CharSet, Color, Config, IndexType, Label, Report, ReportKind, Source};

    use super::{Diagnostic, Severity};
    use crate::lang::source::{SourceId, SourceMap, Span};

    /// The texts a diagnostic refers to, in the shape ariadne reads them.
    ///
    /// ariadne 0.6 applies `with_display_line_offset` to the location line but
    /// not to the line numbers in the margin, so a text with a `line_offset`
    /// is instead padded with that many empty lines in front, and spans are
    /// shifted by as many bytes.
    struct Texts {
        files: HashMap<SourceId, (String, Source<String>)>,
    }

    impl Texts {
        /// The texts of every source that `diagnostic` points into.
        fn of(diagnostic: &Diagnostic, sources: &SourceMap) -> Texts {
            let mut files = HashMap::new();
            let spans = std::iter::once(diagnostic.span).chain(diagnostic.related.iter().map(|(s, _)| *s));
            for span in spans {
                files.entry(span.source).or_insert_with(|| {
                    let file = sources.get(span.source);
                    let padded = "\n".repeat(file.line_offset) + &printable(&file.text);
                    (file.name.clone(), Source::from(padded))
                });
            }
            Texts { files }
        }
    }

    /// `text` with its control characters (an escape could drive the
    /// terminal) replaced by as many `?` as they take bytes, so that byte
    /// offsets stay valid.
    fn printable(text: &str) -> String {
        text.chars()
            .flat_map(|c| {
                let shown = if c.is_control() && !matches!(c, '\n' | '\t' | '\r') { None } else { Some(c) };
                let count = if shown.is_some() { 1 } else { c.len_utf8() };
                std::iter::repeat_n(shown.unwrap_or('?'), count)
            })
            .collect()
    }

    impl ariadne::Cache<SourceId> for Texts {
        type Storage = String;

        fn fetch(&mut self, id: &SourceId) -> Result<&Source<String>, impl fmt::Debug> {
            self.files.get(id).map(|(_, source)| source).ok_or("unknown source")
        }

        fn display<'a>(&self, id: &'a SourceId) -> Option<impl fmt::Display + 'a> {
            self.files.get(id).map(|(name, _)| name.clone())
        }
    }

    /// The lines ariadne draws for `diagnostic`, after the header: the
    /// location, the source lines with their labels, and the closing line.
    pub(super) fn snippet(diagnostic: &Diagnostic, sources: &SourceMap, color: bool) -> String {
        if !color {
            return plain_snippet(diagnostic, sources);
        }
        let file = sources.get(diagnostic.span.source);
        let (line, column) = file.line_col(floor_boundary(&file.text, diagnostic.span.start as usize));
        let location = format!("{}:{line}:{column}", file.name);
        let Some(primary) = label_range(sources, diagnostic.span) else {
            return format!(" --> {location}\n");
        };
        let drawn = draw(diagnostic, sources, color, primary);
        // ariadne's first line is its own header and its second the
        // location inside a box; both are replaced by the rustc-style line.
        let mut lines = drawn.lines().skip(1);
        let boxed_location = lines.next().unwrap_or("");
        let margin = boxed_location.len() - boxed_location.trim_start().len();
        let mut out = format!("{}--> {location}\n", " ".repeat(margin.saturating_sub(1)));
        for line in lines {
            out.push_str(line.trim_end());
            out.push('\n');
        }
        out
    }

    /// The snippet in plain text, for pipes, logs and files (ariadne's ASCII
    /// drawing is hard to read): rustc's layout, each labelled line once with
    /// `^` under the spot and `-` under the related places.
    fn plain_snippet(diagnostic: &Diagnostic, sources: &SourceMap) -> String {
        let mut marks = vec![(diagnostic.span, '^', diagnostic.label.as_deref().unwrap_or(""))];
        marks.extend(diagnostic.related.iter().map(|(span, text)| (*span, '-', text.as_str())));
        marks.sort_by_key(|(span, _, _)| (span.source != diagnostic.span.source, span.source.0, span.start));
        let place = |span: Span| {
            let file = sources.get(span.source);
            let start = floor_boundary(&file.text, span.start as usize);
            let (line, column) = file.line_col(start);
            (file, start, line, column)
        };
        let width = marks.iter().map(|(span, _, _)| place(*span).2.to_string().len()).max().unwrap_or(1);
        let gutter = " ".repeat(width);
        let (file, _, line, column) = place(diagnostic.span);
        let mut out = format!("{gutter}--> {}:{line}:{column}\n{gutter} |\n", file.name);
        let mut current = diagnostic.span.source;
        for (span, mark, text) in marks {
            let (file, start, line, column) = place(span);
            if span.source != current {
                current = span.source;
                out.push_str(&format!("{gutter}::: {}:{line}:{column}\n{gutter} |\n", file.name));
            }
            let line_start = file.text[..start].rfind('\n').map_or(0, |i| i + 1);
            let line_end = file.text[start..].find('\n').map_or(file.text.len(), |i| start + i);
            let shown = printable(file.text[line_start..line_end].trim_end_matches('\r')).replace('\t', " ");
            let end = floor_boundary(&file.text, (span.end as usize).clamp(start, line_end));
            let marks = mark.to_string().repeat(file.text[start..end].chars().count().max(1));
            let under = format!("{gutter} | {}{marks} {text}", " ".repeat(column - 1));
            let source_line = format!("{line:>width$} | {shown}");
            out.push_str(&format!("{}\n{}\n", source_line.trim_end(), under.trim_end()));
        }
        out
    }

    /// Runs ariadne over the diagnostic's labels.
    fn draw(diagnostic: &Diagnostic, sources: &SourceMap, color: bool, primary: Range<usize>) -> String {
        let (primary_color, secondary_color) = match diagnostic.severity {
            Severity::Error => (Color::Red, Color::Blue),
            Severity::Warning => (Color::Yellow, Color::Blue),
        };
        let config = Config::new()
            .with_color(color)
            .with_char_set(if color { CharSet::Unicode } else { CharSet::Ascii })
            .with_index_type(IndexType::Byte);
        let source = diagnostic.span.source;
        let mut primary_label = Label::new((source, primary.clone())).with_color(primary_color);
        primary_label = primary_label.with_order(label_order(sources, diagnostic.span, source));
        // ariadne draws no underline for a label without a message.
        primary_label = primary_label.with_message(diagnostic.label.as_deref().unwrap_or("here"));
        let mut report =
            Report::build(ReportKind::Error, (source, primary)).with_config(config).with_label(primary_label);
        for (span, text) in &diagnostic.related {
            if let Some(range) = label_range(sources, *span) {
                let label = Label::new((span.source, range))
                    .with_message(text)
                    .with_color(secondary_color)
                    .with_order(label_order(sources, *span, source));
                report = report.with_label(label);
            }
        }
        let mut bytes = Vec::new();
        let written = report.finish().write(Texts::of(diagnostic, sources), &mut bytes);
        match written {
            Ok(()) => String::from_utf8_lossy(&bytes).into_owned(),
            Err(_) => String::new(),
        }
    }

    /// Labels are drawn in this order: by line in the primary source, which
    /// keeps them in one box, then the other sources.
    fn label_order(sources: &SourceMap, span: Span, primary_source: SourceId) -> i32 {
        let file = sources.get(span.source);
        let (line, _) = file.line_col(floor_boundary(&file.text, span.start as usize));
        let line = i32::try_from(line).unwrap_or(i32::MAX / 4).min(i32::MAX / 4);
        if span.source == primary_source { line } else { i32::MAX / 2 + line / 2 }
    }

    /// The byte range of `span` in the padded text: clamped to the text, on
    /// character boundaries, and at least one character wide when the text
    /// has any (an empty range would not be drawn). `None` for an empty text.
    fn label_range(sources: &SourceMap, span: Span) -> Option<Range<usize>> {
        let file = sources.get(span.source);
        let text: &str = &file.text;
        if text.is_empty() {
            return None;
        }
        let mut start = floor_boundary(text, (span.start as usize).min(text.len()));
        let mut end = ceil_boundary(text, (span.end as usize).clamp(start, text.len()));
        if start == end {
            if start == text.len() {
                start = floor_boundary(text, start - 1);
            } else {
                end = ceil_boundary(text, start + 1);
            }
        }
        Some(start + file.line_offset..end + file.line_offset)
    }

    /// The largest character boundary at or before `offset` (and at most
    /// the text's length).
    fn floor_boundary(text: &str, offset: usize) -> usize {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        offset
    }

    /// The smallest character boundary at or after `offset`.
    fn ceil_boundary(text: &str, mut offset: usize) -> usize {
        while !text.is_char_boundary(offset) {
            offset += 1;
        }
        offset
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::source::SourceId;

    fn map_with(name: &str, text: &str, line_offset: usize) -> (SourceMap, SourceId) {
        let mut map = SourceMap::new();
        let id = map.add(name, text, line_offset);
        (map, id)
    }

    #[test]
    fn plain_rendering_names_the_place_and_draws_a_caret() {
        let (map, id) = map_with("scene.ray", "let x = 1\nput spher\n", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 14, 19), "unknown object `spher`")
            .with_label("not defined")
            .with_help("did you mean `sphere`?");
        let expected = "\
error: unknown object `spher`
 --> scene.ray:2:5
  |
2 | put spher
  |     ^^^^^ not defined
help: did you mean `sphere`?
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    #[test]
    fn line_offsets_show_in_the_header_and_the_margin() {
        let (map, id) = map_with("script.ray", "let x = 1\nlet y = $\n", 16);
        let diagnostic = Diagnostic::error(Span::new(id, 18, 19), "unexpected character `$`");
        let expected = "\
error: unexpected character `$`
  --> script.ray:18:9
   |
18 | let y = $
   |         ^
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    #[test]
    fn related_spans_may_be_in_other_sources_and_notes_follow() {
        let mut map = SourceMap::new();
        let definition = map.add("scene.ray", "proc p(a)\nend\n", 0);
        let call = map.add("<input>", "p(1, 2)", 0);
        let diagnostic = Diagnostic::error(Span::new(call, 0, 7), "`p` takes 1 argument, but 2 are given")
            .with_label("2 arguments")
            .with_related(Span::new(definition, 0, 9), "`p` is defined here")
            .with_note("called from the top level");
        let expected = "\
error: `p` takes 1 argument, but 2 are given
 --> <input>:1:1
  |
1 | p(1, 2)
  | ^^^^^^^ 2 arguments
 ::: scene.ray:1:1
  |
1 | proc p(a)
  | --------- `p` is defined here
note: called from the top level
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    #[test]
    fn warnings_say_so() {
        let (map, id) = map_with("a.ray", "color 300, 0, 0", 0);
        let rendered = Diagnostic::warning(Span::new(id, 6, 9), "clamped to 255").render(&map, false);
        assert!(rendered.starts_with("warning: clamped to 255\n --> a.ray:1:7\n"), "{rendered}");
    }

    #[test]
    fn colours_only_when_asked() {
        let (map, id) = map_with("a.ray", "let x = $", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 8, 9), "unexpected character `$`").with_help("remove it");
        assert!(!diagnostic.render(&map, false).contains('\u{1b}'));
        assert!(diagnostic.render(&map, false).is_ascii());
        let coloured = diagnostic.render(&map, true);
        assert!(coloured.contains('\u{1b}'));
        assert!(coloured.contains("a.ray:1:9"));
    }

    #[test]
    fn an_empty_text_or_a_span_past_its_end_still_renders() {
        let (map, id) = map_with("empty.ray", "", 0);
        let rendered = Diagnostic::error(Span::new(id, 0, 0), "empty").render(&map, false);
        assert_eq!(rendered, "error: empty\n --> empty.ray:1:1\n  |\n1 |\n  | ^\n");
        let (map, id) = map_with("a.ray", "é", 0);
        let rendered = Diagnostic::error(Span::new(id, 1, 40), "inside a character").render(&map, false);
        assert!(rendered.contains("a.ray:1:"), "{rendered}");
    }

    #[test]
    fn control_characters_are_not_sent_to_the_terminal() {
        let (map, id) = map_with("a.ray", "let x = \u{1b}[31m", 0);
        let rendered = Diagnostic::error(Span::new(id, 8, 9), "unexpected character").render(&map, false);
        assert!(!rendered.contains('\u{1b}'));
        assert!(rendered.contains("let x = ?[31m"), "{rendered}");
    }
}
