//! Errors and warnings about a program, and how they are shown to people.
//!
//! A [`Diagnostic`] points at a [`Span`]; [`Diagnostic::render`] draws it the
//! way rustc does, with annotate-snippets: the message, ` --> file:line:col`,
//! the source lines in a gutter, `^` under the spot, `-` under related places,
//! then `= note:` and `= help:` lines. Positions are never part of the text:
//! they are read from spans when the diagnostic is rendered, in the
//! coordinates of the source the user sees. [`emit`] is how every mode
//! prints a diagnostic. For tools, [`Diagnostic::to_json`] gives it as data
//! (its code, its [`Place`]s as the rendering shows them, the edits its help
//! proposes).

use std::borrow::Cow;
use std::io::Write;
use std::ops::Range;

use annotate_snippets::{Annotation, AnnotationKind, Level, Renderer, Snippet};
use anstream::AutoStream;
use anstream::stream::RawStream;

use super::source::{SourceId, SourceMap, Span};

mod data;

pub use data::{Place, Position};

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The program cannot go on.
    Error,
    /// Something was adjusted (a clamped colour, ...); the program goes on.
    Warning,
}

/// What the language's messages say stopped a run (`stopped by Ctrl-C`),
/// with the code `interrupted`: what stops a run at a terminal's prompt. A
/// front-end that knows another signal did names it
/// ([`Diagnostic::stopped_by`]).
pub(crate) const STOPPED_BY: &str = "Ctrl-C";

/// One error or warning about the program, with where it happened.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// What kind of diagnostic this is, stable and kebab-case
    /// (`unknown-variable`), for tools that read diagnostics as data
    /// (`--check --json`); docs/guide/errors.md lists them.
    pub code: &'static str,
    /// What is wrong, in plain words ("expected `end` to close the `sphere`").
    pub message: String,
    /// The spot the caret points at.
    pub span: Span,
    /// A short text shown next to the caret, if any.
    pub label: Option<String>,
    /// Other places worth showing (where a `sphere` was opened, where a procedure was called from...).
    pub related: Vec<(Span, String)>,
    /// Extra lines of explanation (a call chain, ...).
    pub notes: Vec<Note>,
    /// An obvious fix ("did you mean `sphere`?").
    pub help: Option<String>,
    /// The edits the help proposes, when it proposes some (`sphere` for
    /// `spehre`): never drawn, for tools that apply them.
    pub replacements: Vec<Replacement>,
}

/// Text the help proposes to put in place of a span.
#[derive(Debug, Clone, PartialEq)]
pub struct Replacement {
    /// What is replaced.
    pub span: Span,
    /// What replaces it.
    pub text: String,
}

impl Diagnostic {
    /// This diagnostic naming `by` as what stopped the run, when it says a
    /// run was stopped (its code is `interrupted`): SIGTERM, SIGHUP or a
    /// notebook's interrupt rather than the [`STOPPED_BY`] it is written
    /// with. Any other diagnostic is left as it is.
    pub fn stopped_by(mut self, by: &str) -> Diagnostic {
        if self.code == "interrupted" {
            self.message = self.message.replacen(STOPPED_BY, by, 1);
        }
        self
    }

    /// An error at `span`.
    #[inline(never)]
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code: "error",
            message: with_names_shortened(message.into()),
            span,
            label: None,
            related: Vec::new(),
            notes: Vec::new(),
            help: None,
            replacements: Vec::new(),
        }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, code: "warning", ..Diagnostic::error(span, message) }
    }

    /// Names the kind of diagnostic (see [`Diagnostic::code`]).
    pub fn with_code(mut self, code: &'static str) -> Diagnostic {
        self.code = code;
        self
    }

    /// Adds an edit that the help proposes: `text` in place of `span`.
    pub fn with_replacement(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.replacements.push(Replacement { span, text: text.into() });
        self
    }

    /// Adds the text shown next to the caret.
    pub fn with_label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = Some(with_names_shortened(label.into()));
        self
    }

    /// Adds another place to show.
    pub fn with_related(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.related.push((span, with_names_shortened(text.into())));
        self
    }

    /// Adds a line of explanation: a text, or a [`Note`] that names places.
    pub fn with_note(mut self, note: impl Into<Note>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// Adds a suggested fix.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(with_names_shortened(help.into()));
        self
    }

    /// The diagnostic drawn for a person, ending with a newline: with ANSI
    /// styles if `color`, in plain text otherwise (the same characters).
    pub fn render(&self, sources: &SourceMap, color: bool) -> String {
        let renderer = if color { Renderer::styled() } else { Renderer::plain() };
        // annotate-snippets makes the message and the source printable, not
        // the other texts: control characters could drive the terminal.
        let notes: Vec<String> =
            self.notes.iter().map(|note| printable(&note.display(sources, self.span.source))).collect();
        let help = self.help.as_deref().map(printable);
        let level = match self.severity {
            Severity::Error => Level::ERROR,
            Severity::Warning => Level::WARNING,
        };
        let group = level
            .primary_title(&self.message)
            .elements(self.snippets(sources))
            .elements(notes.iter().map(|note| Level::NOTE.message(note.as_str())))
            .elements(help.map(|help| Level::HELP.message(help)));
        let rendered = renderer.render(&[group]);
        // annotate-snippets shows C0 controls as symbols but lets C1 ones
        // (U+0080 to U+009F, which some terminals obey) through, counting
        // each one column wide, as `�` is.
        let mut out: String =
            rendered.chars().map(|c| if ('\u{80}'..='\u{9f}').contains(&c) { '\u{fffd}' } else { c }).collect();
        out.push('\n');
        out
    }

    /// One snippet per source the diagnostic points into, the primary
    /// span's first, each with its marks: `^` for the primary span, `-`
    /// for the related places. Each snippet holds only the lines from the
    /// first mark to the last (annotate-snippets would scan the text from
    /// its start to find them, for every diagnostic).
    fn snippets<'a>(&'a self, sources: &'a SourceMap) -> Vec<Snippet<'a, Annotation<'a>>> {
        let primary = (self.span, AnnotationKind::Primary, self.label.as_deref());
        let related = self.related.iter().map(|(span, text)| (*span, AnnotationKind::Context, Some(text.as_str())));
        let mut by_source: Vec<(SourceId, Vec<Mark<'a>>)> = Vec::new();
        for (span, kind, label) in std::iter::once(primary).chain(related) {
            let mark = (shown_range(&sources.get(span.source).text, span), kind, label);
            match by_source.iter_mut().find(|(source, _)| *source == span.source) {
                Some((_, marks)) => marks.push(mark),
                None => by_source.push((span.source, vec![mark])),
            }
        }
        by_source
            .into_iter()
            .map(|(source, marks)| {
                let file = sources.get(source);
                let first = marks.iter().map(|(range, ..)| range.start).min().expect("a source has a mark");
                let last = marks.iter().map(|(range, ..)| range.end).max().expect("a source has a mark");
                let (line, start) = file.line_of(first);
                let end = file.text[last..].find('\n').map_or(file.text.len(), |i| last + i + 1);
                let annotations = marks.into_iter().map(|(range, kind, label)| {
                    kind.span(range.start - start..range.end - start).label(label.map(printable))
                });
                Snippet::source(&file.text[start..end])
                    .path(&file.name)
                    .line_start(file.line_offset + line + 1)
                    .annotations(annotations)
            })
            .collect()
    }
}

/// A place a snippet marks: its bytes in the source, whether it is the
/// primary span or a related one, and its label.
type Mark<'a> = (Range<usize>, AnnotationKind, Option<&'a str>);

/// Prints `diagnostic` on `out`: the one way batch runs, scripts and the
/// session print diagnostics, so that they look the same everywhere. The
/// rendering carries styles; `out`, an anstream stream, keeps or strips
/// them as the terminal and `NO_COLOR` / `CLICOLOR_FORCE` say. Output
/// errors (a closed pipe) are ignored: the exit status tells what happened.
pub fn emit<S: RawStream>(out: &mut AutoStream<S>, diagnostic: &Diagnostic, sources: &SourceMap)
where
    AutoStream<S>: Write,
{
    let _ = out.write_all(diagnostic.render(sources, true).as_bytes());
    let _ = out.flush();
}

/// `text` with its control characters shown as symbols (`␛`), as
/// annotate-snippets shows those of the source.
fn printable(text: &str) -> String {
    annotate_snippets::normalize_untrusted_str(text)
}

/// The byte range drawn for `span` in `text`: inside the text and on
/// character boundaries. A span in the blank end of the text (where "the
/// file ends here" points) is drawn just after its last character.
fn shown_range(text: &str, span: Span) -> Range<usize> {
    let content_end = text.trim_end().len();
    let start = floor_boundary(text, span.start as usize);
    if start >= content_end {
        return content_end..content_end;
    }
    start..ceil_boundary(text, (span.end as usize).clamp(start, text.len()))
}

/// The largest character boundary at or before `offset` (and at most the
/// text's length).
fn floor_boundary(text: &str, offset: usize) -> usize {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// The smallest character boundary at or after `offset` (at most the text's length).
fn ceil_boundary(text: &str, offset: usize) -> usize {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset += 1;
    }
    offset
}

/// A line of explanation that may name places: text and spans, each span
/// shown as `line 12` when it is in the file of the diagnostic's primary
/// span and as `<input 3>:2` when it is in another, computed only when the
/// diagnostic is rendered.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Note {
    pieces: Vec<NotePiece>,
}

/// A part of a [`Note`].
#[derive(Debug, Clone, PartialEq)]
enum NotePiece {
    Text(String),
    Place(Span),
}

impl Note {
    /// Adds text at the end.
    pub fn text(mut self, text: impl Into<String>) -> Note {
        self.pieces.push(NotePiece::Text(with_names_shortened(text.into())));
        self
    }

    /// Adds the place of `span` at the end (`line 12` or `<input 3>:2`).
    pub fn place(mut self, span: Span) -> Note {
        self.pieces.push(NotePiece::Place(span));
        self
    }

    /// Adds another note's pieces at the end.
    pub fn then(mut self, other: Note) -> Note {
        self.pieces.extend(other.pieces);
        self
    }

    /// The notes one after the other, with `separator` between them.
    pub fn joined(notes: impl IntoIterator<Item = Note>, separator: &str) -> Note {
        let mut joined = Note::default();
        for (index, note) in notes.into_iter().enumerate() {
            if index > 0 {
                joined = joined.text(separator);
            }
            joined = joined.then(note);
        }
        joined
    }

    /// The note as the user reads it in a diagnostic whose primary span is
    /// in `primary`: places in a file of the same name (one text, or pieces
    /// of one script) are `line N`, others `name:N`.
    pub fn display(&self, sources: &SourceMap, primary: SourceId) -> String {
        let primary_name = &sources.get(primary).name;
        self.pieces
            .iter()
            .map(|piece| match piece {
                NotePiece::Text(text) => text.clone(),
                NotePiece::Place(span) => {
                    let file = sources.get(span.source);
                    let (line, _) = file.line_col(floor_boundary(&file.text, span.start as usize));
                    if file.name == *primary_name { format!("line {line}") } else { format!("{}:{line}", file.name) }
                }
            })
            .collect()
    }
}

/// Names longer than this many characters are shortened in messages.
const LONGEST_NAME_SHOWN: usize = 48;

/// How many of a shortened name's first characters a message shows.
const NAME_START_SHOWN: usize = 40;

/// `name` as a message shows it: whole up to [`LONGEST_NAME_SHOWN`]
/// characters, otherwise its first [`NAME_START_SHOWN`], `…` and its length
/// (`aaaa…` (1000000 characters)): a name a megabyte long is not echoed whole.
pub fn shown_name(name: &str) -> Cow<'_, str> {
    // A name has at most as many characters as bytes.
    if name.len() <= LONGEST_NAME_SHOWN {
        return Cow::Borrowed(name);
    }
    let characters = name.chars().count();
    if characters <= LONGEST_NAME_SHOWN {
        return Cow::Borrowed(name);
    }
    let start: String = name.chars().take(NAME_START_SHOWN).collect();
    Cow::Owned(format!("{start}… ({characters} characters)"))
}

/// Whether the text between two backquotes is a name too long to show whole.
fn is_long_name(quoted: &str) -> bool {
    quoted.len() > LONGEST_NAME_SHOWN
        && quoted.chars().all(|c| c.is_alphanumeric() || c == '_')
        && quoted.chars().count() > LONGEST_NAME_SHOWN
}

/// `text` with every long name it quotes between backquotes shortened as
/// [`shown_name`] does (`aaaa…` (1000000 characters)): the one rule for
/// every message, label, note and help.
#[inline(never)]
pub(crate) fn with_names_shortened(text: String) -> String {
    // Most texts are short, or quote no long name.
    if text.len() <= LONGEST_NAME_SHOWN || !text.split('`').skip(1).step_by(2).any(is_long_name) {
        return text;
    }
    let parts: Vec<&str> = text.split('`').collect();
    let mut shortened = String::with_capacity(text.len().min(1024));
    for (index, part) in parts.iter().enumerate() {
        let quoted = index % 2 == 1;
        let closed = index + 1 < parts.len();
        if quoted {
            shortened.push('`');
        }
        if quoted && closed && is_long_name(part) {
            let start: String = part.chars().take(NAME_START_SHOWN).collect();
            shortened.push_str(&format!("{start}…` ({} characters)", part.chars().count()));
        } else {
            shortened.push_str(part);
            if quoted && closed {
                shortened.push('`');
            }
        }
    }
    shortened
}

impl From<String> for Note {
    fn from(text: String) -> Note {
        Note::default().text(text)
    }
}

impl From<&str> for Note {
    fn from(text: &str) -> Note {
        Note::default().text(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_lines_from_the_first_mark_to_the_last_are_shown() {
        let text = "camera\nput a\n\nput b\nput c\nend\n";
        let (map, id) = map_with("scene.ray", text, 10);
        let (a, b) = (text.find("put a").expect("a") + 4, text.find("put b").expect("b") + 4);
        let diagnostic = Diagnostic::warning(Span::new(id, b, b + 1), "`b` again")
            .with_related(Span::new(id, a, a + 1), "first here");
        let expected = "\
warning: `b` again
  --> scene.ray:14:5
   |
12 | put a
   |     - first here
13 |
14 | put b
   |     ^
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    /// `diagnostic` (its marks all in `file`, no notes) drawn by
    /// annotate-snippets from the whole text: what [`Diagnostic::render`]
    /// must give from its window of lines.
    fn drawn_from_the_whole_text(diagnostic: &Diagnostic, file: &crate::lang::source::SourceFile) -> String {
        let mark = |span, kind: AnnotationKind, label: Option<&str>| {
            kind.span(shown_range(&file.text, span)).label(label.map(printable))
        };
        let related = diagnostic.related.iter().map(|(span, text)| mark(*span, AnnotationKind::Context, Some(text)));
        let annotations =
            std::iter::once(mark(diagnostic.span, AnnotationKind::Primary, diagnostic.label.as_deref())).chain(related);
        let snippet =
            Snippet::source(&*file.text).path(&file.name).line_start(file.line_offset + 1).annotations(annotations);
        let group = Level::WARNING.primary_title(&diagnostic.message).element(snippet);
        format!("{}\n", Renderer::plain().render(&[group]))
    }

    #[test]
    fn the_window_shows_what_the_whole_text_shows() {
        let texts = ["a\nbc\n\ndef\n", "a\r\nbc\r\n\r\nd", "x\n\n\ny\nz", "é\nàb\n\n", "one line"];
        for (text, line_offset) in texts.into_iter().flat_map(|text| [(text, 0), (text, 3)]) {
            let (map, id) = map_with("a.ray", text, line_offset);
            let spans: Vec<Span> = (0..=text.len())
                .flat_map(|start| (start..=text.len()).map(move |end| Span::new(id, start, end)))
                .collect();
            for (k, &primary) in spans.iter().enumerate() {
                let alone = Diagnostic::warning(primary, "here");
                assert_eq!(alone.render(&map, false), drawn_from_the_whole_text(&alone, map.get(id)), "{primary:?}");
                let related = spans[(k * 7) % spans.len()];
                let both = alone.with_label("this").with_related(related, "and that");
                assert_eq!(both.render(&map, false), drawn_from_the_whole_text(&both, map.get(id)), "{related:?}");
            }
        }
    }

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
  |
  = help: did you mean `sphere`?
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
  |
 ::: scene.ray:1:1
  |
1 | proc p(a)
  | --------- `p` is defined here
  |
  = note: called from the top level
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    #[test]
    fn a_line_with_two_marks_is_shown_once() {
        let (map, id) = map_with("a.ray", "put sphere center 0, 0, 0 radius r end", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 33, 34), "unknown variable `r`")
            .with_label("not defined")
            .with_related(Span::new(id, 4, 10), "in this `sphere`");
        let expected = "\
error: unknown variable `r`
 --> a.ray:1:34
  |
1 | put sphere center 0, 0, 0 radius r end
  |     ------ in this `sphere`      ^ not defined
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    #[test]
    fn the_end_of_the_file_is_just_after_its_last_character() {
        let (map, id) = map_with("a.ray", "camera distance 10\n  angle 1\n\n", 0);
        for span in [Span::new(id, 29, 29), Span::new(id, 31, 31), Span::new(id, 30, 31)] {
            let rendered = Diagnostic::error(span, "unexpected end of file").with_label("the file ends here");
            let expected = "\
error: unexpected end of file
 --> a.ray:2:10
  |
2 |   angle 1
  |          ^ the file ends here
";
            assert_eq!(rendered.render(&map, false), expected);
        }
    }

    #[test]
    fn tabs_and_wide_characters_keep_the_caret_under_the_spot() {
        let (map, id) = map_with("a.ray", "let é =\t$", 0);
        let rendered = Diagnostic::error(Span::new(id, 9, 10), "unexpected character `$`").render(&map, false);
        let expected = "\
error: unexpected character `$`
 --> a.ray:1:9
  |
1 | let é =    $
  |            ^
";
        assert_eq!(rendered, expected);
    }

    #[test]
    fn warnings_have_the_same_format() {
        let (map, id) = map_with("a.ray", "color 300, 0, 0", 0);
        let warning = Diagnostic::warning(Span::new(id, 6, 9), "clamped to 255").render(&map, false);
        let error = Diagnostic::error(Span::new(id, 6, 9), "clamped to 255").render(&map, false);
        assert_eq!(warning.strip_prefix("warning"), error.strip_prefix("error"));
    }

    #[test]
    fn colours_only_when_asked_and_the_text_is_the_same() {
        let (map, id) = map_with("a.ray", "let x = $", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 8, 9), "unexpected character `$`").with_help("remove it");
        let plain = diagnostic.render(&map, false);
        assert!(plain.is_ascii() && !plain.contains('\u{1b}'));
        let coloured = diagnostic.render(&map, true);
        assert!(coloured.contains('\u{1b}'));
        let mut stripped = Vec::new();
        anstream::StripStream::new(&mut stripped).write_all(coloured.as_bytes()).expect("writes to memory");
        assert_eq!(String::from_utf8(stripped).expect("text"), plain);
    }

    #[test]
    fn emit_strips_styles_from_a_stream_without_colours() {
        let (map, id) = map_with("a.ray", "let x = $", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 8, 9), "unexpected character `$`");
        let mut out = AutoStream::never(Vec::new());
        emit(&mut out, &diagnostic, &map);
        assert_eq!(String::from_utf8(out.into_inner()).expect("text"), diagnostic.render(&map, false));
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
        let (map, id) = map_with("a.ray", "let x = \u{1b}[31m \u{9b}2J", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 8, 9), "unexpected character `\u{1b}`")
            .with_label("\u{7}")
            .with_related(Span::new(id, 14, 16), "\u{9b}");
        for color in [false, true] {
            let rendered = diagnostic.render(&map, color);
            assert!(!rendered.contains("\u{1b}[31m") && !rendered.contains(['\u{7}', '\u{9b}']), "{rendered}");
        }
        let expected = "\
error: unexpected character `␛`
 --> a.ray:1:9
  |
1 | let x = ␛[31m �2J
  |         ^ ␇   - �
";
        assert_eq!(diagnostic.render(&map, false), expected);
    }

    #[test]
    fn notes_name_places_from_the_sources() {
        let mut map = SourceMap::new();
        let first = map.add("<input 1>", "proc f()\n  f()\nend", 0);
        let second = map.add("<input 2>", "f()", 0);
        let note = Note::from("calls: ").place(Span::new(second, 0, 3)).text(", ").place(Span::new(first, 11, 14));
        assert_eq!(note.display(&map, first), "calls: <input 2>:1, line 2");
        assert_eq!(note.display(&map, second), "calls: line 1, <input 1>:2");
        // Pieces of one script share its name and its line numbers.
        let piece = map.add("<input 1>", "let a = 1", 7);
        assert_eq!(Note::default().place(Span::new(piece, 0, 1)).display(&map, first), "line 8");
    }
}
