//! Diagnostics as data, for tools rather than people: each place as lines
//! and columns (in characters and in UTF-16 code units) and bytes, and the
//! whole diagnostic as one JSON object (`rayrepl --check --json`). The
//! places are those the rendering draws, so that a tool and a person read
//! the same line and column.

use std::ops::Range;

use serde_json::{Value, json};

use super::{Diagnostic, Severity, shown_range};
use crate::lang::source::{SourceFile, SourceMap, Span};

/// Where a span is, as the rendered diagnostic shows it: its source, the
/// bytes marked (inside the text, on character boundaries; a span in the
/// blank end of the text is just after its last character), and the
/// positions of their start and end.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Place {
    /// The source's name, as the rendering shows it (a path, `<stdin>`).
    pub source: String,
    /// The bytes marked, in the source's text.
    pub bytes: Range<usize>,
    /// Where the marked bytes start: the `line:column` of ` --> file:line:column`.
    pub start: Position,
    /// Just after the marked bytes.
    pub end: Position,
}

/// A line and a column, both from 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Position {
    /// The line, as the rendering numbers it (a piece of a script has the script's numbers).
    pub line: usize,
    /// The column, counted in characters (a tab is one).
    pub column: usize,
    /// The column, counted in UTF-16 code units (as editors and the language server protocol count).
    pub column_utf16: usize,
}

impl Place {
    /// The place of `span` in `sources`.
    pub fn of(span: Span, sources: &SourceMap) -> Place {
        let file = sources.get(span.source);
        let bytes = shown_range(&file.text, span);
        Place { source: file.name.clone(), start: position(file, bytes.start), end: position(file, bytes.end), bytes }
    }

    /// The place as a JSON object, with `label` (or `null`).
    fn to_json(&self, label: Option<&str>) -> Value {
        json!({
            "source": self.source,
            "line": self.start.line,
            "column": self.start.column,
            "column_utf16": self.start.column_utf16,
            "end_line": self.end.line,
            "end_column": self.end.column,
            "end_column_utf16": self.end.column_utf16,
            "bytes": [self.bytes.start, self.bytes.end],
            "label": label,
        })
    }
}

/// The position of byte `offset` (a character boundary) of `file`.
fn position(file: &SourceFile, offset: usize) -> Position {
    let (line, start) = file.line_of(offset);
    let before = &file.text[start..offset];
    Position {
        line: file.line_offset + line + 1,
        column: before.chars().count() + 1,
        column_utf16: before.encode_utf16().count() + 1,
    }
}

impl Diagnostic {
    /// The diagnostic as one JSON object, its places in `sources` (the
    /// docs/guide/errors.md gives the fields).
    pub fn to_json(&self, sources: &SourceMap) -> Value {
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let related: Vec<Value> =
            self.related.iter().map(|(span, text)| Place::of(*span, sources).to_json(Some(text))).collect();
        let notes: Vec<String> = self.notes.iter().map(|note| note.display(sources, self.span.source)).collect();
        let replacements: Vec<Value> = self
            .replacements
            .iter()
            .map(|replacement| json!({"text": replacement.text, "place": Place::of(replacement.span, sources).to_json(None)}))
            .collect();
        let help: Vec<Value> =
            self.help.iter().map(|help| json!({"message": help, "replacements": replacements})).collect();
        json!({
            "severity": severity,
            "code": self.code,
            "message": self.message,
            "place": Place::of(self.span, sources).to_json(self.label.as_deref()),
            "related": related,
            "notes": notes,
            "help": help,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;
    use crate::lint::Check;
    use crate::source_tree::rust_sources;

    #[test]
    fn columns_count_characters_and_utf16_code_units() {
        let mut map = SourceMap::new();
        // `é` is 2 bytes, 1 UTF-16 unit; `🎨` is 4 bytes, 2 units; the tab is one of each.
        let text = "let é = 1\r\nput 🎨\t$\n";
        let id = map.add("a.ray", text, 4);
        let dollar = text.find('$').expect("a dollar");
        let place = Place::of(Span::new(id, dollar, dollar + 1), &map);
        assert_eq!(place.start, Position { line: 6, column: 7, column_utf16: 8 });
        assert_eq!(place.end, Position { line: 6, column: 8, column_utf16: 9 });
        assert_eq!(place.bytes, 21..22);
        let e = Place::of(Span::new(id, 4, 6), &map);
        assert_eq!(
            (e.start, e.end.column, e.end.column_utf16),
            (Position { line: 5, column: 5, column_utf16: 5 }, 6, 6)
        );
    }

    #[test]
    fn places_are_those_of_the_rendering() {
        let texts = ["a\nbc\n\ndef\n", "a\r\nbc\r\n\r\nd", "x\n\n\ny\nz", "é\nàb\n\n", "\tz🎨y\r\n", "one line", ""];
        for (text, line_offset) in texts.into_iter().flat_map(|text| [(text, 0), (text, 3)]) {
            let mut map = SourceMap::new();
            let id = map.add("a.ray", text, line_offset);
            for start in 0..=text.len() {
                for end in start..=text.len() {
                    let diagnostic = Diagnostic::error(Span::new(id, start, end), "here");
                    let rendered = diagnostic.render(&map, false);
                    let header = rendered.lines().nth(1).expect("a header line");
                    let json = diagnostic.to_json(&map);
                    let place = &json["place"];
                    let expected = format!("a.ray:{}:{}", place["line"], place["column"]);
                    assert_eq!(header.split("--> ").nth(1), Some(expected.as_str()), "{text:?} {start}..{end}");
                }
            }
        }
    }

    /// The codes the sources give to `with_code` as literals, and the
    /// scene checks' names.
    fn codes_in_the_sources() -> BTreeSet<String> {
        let mut codes: BTreeSet<String> = Check::ALL.iter().map(|check| check.name().to_string()).collect();
        for (_, text) in rust_sources() {
            for (at, _) in text.match_indices("with_code(\"") {
                let rest = &text[at + "with_code(\"".len()..];
                codes.insert(rest[..rest.find('"').expect("the literal ends")].to_string());
            }
        }
        codes
    }

    #[test]
    fn the_readme_lists_every_code_and_no_other() {
        let readme = include_str!("../../../docs/guide/errors.md");
        let table = readme.split_once("| from | severity | codes |").expect("the guide has a table of codes").1;
        let rows = table.lines().skip(2).take_while(|line| line.starts_with('|'));
        let listed: BTreeSet<String> = rows
            .flat_map(|row| row.split('|').nth(3).expect("a third column").split(','))
            .map(|code| code.trim().trim_matches('`').to_string())
            .collect();
        assert_eq!(listed, codes_in_the_sources());
        assert!(listed.iter().all(|code| code.chars().all(|c| c.is_ascii_lowercase() || c == '-')), "{listed:?}");
    }

    #[test]
    fn the_json_has_every_part() {
        let mut map = SourceMap::new();
        let id = map.add("a.ray", "put spehre end", 0);
        let diagnostic = Diagnostic::error(Span::new(id, 4, 10), "unknown object `spehre`")
            .with_code("unexpected-token")
            .with_label("not defined")
            .with_related(Span::new(id, 0, 3), "this `put`")
            .with_note("a note")
            .with_help("did you mean `sphere`?")
            .with_replacement(Span::new(id, 4, 10), "sphere");
        let expected = r#"{"severity":"error","code":"unexpected-token","message":"unknown object `spehre`","place":{"source":"a.ray","line":1,"column":5,"column_utf16":5,"end_line":1,"end_column":11,"end_column_utf16":11,"bytes":[4,10],"label":"not defined"},"related":[{"source":"a.ray","line":1,"column":1,"column_utf16":1,"end_line":1,"end_column":4,"end_column_utf16":4,"bytes":[0,3],"label":"this `put`"}],"notes":["a note"],"help":[{"message":"did you mean `sphere`?","replacements":[{"text":"sphere","place":{"source":"a.ray","line":1,"column":5,"column_utf16":5,"end_line":1,"end_column":11,"end_column_utf16":11,"bytes":[4,10],"label":null}}]}]}"#;
        assert_eq!(diagnostic.to_json(&map).to_string(), expected);
    }
}
