//! The protocol's positions and changes in a document's text, translated
//! to and from the editor services' places ([`crate::ide::offsets`]: lines
//! and columns in UTF-16 code units).

use lsp_types::{Position, Range, TextDocumentContentChangeEvent};

use crate::ide::offsets::{self, Lines, Utf16Position};
use crate::lang::diagnostic::Place;
use crate::lang::{SourceMap, Span};

/// The range of `span`, with the lines and columns its diagnostics show.
pub(crate) fn range(span: Span, sources: &SourceMap) -> Range {
    let place = Place::of(span, sources);
    let position = |at: crate::lang::diagnostic::Position| Position {
        line: (at.line - 1) as u32,
        character: (at.column_utf16 - 1) as u32,
    };
    Range { start: position(place.start), end: position(place.end) }
}

/// The byte offset of `position` in `text` (see [`Lines::offset`]).
pub(crate) fn offset(text: &str, position: Position) -> usize {
    Lines::new(text).offset(place(position))
}

/// The position just after the last character of `text`.
pub(crate) fn end(text: &str) -> Position {
    let end = Lines::new(text).end();
    Position { line: end.line, character: end.column }
}

/// `text` after one change the client sent: a range replaced, or the
/// whole text when the change has no range.
pub(crate) fn apply(text: &mut String, change: TextDocumentContentChangeEvent) {
    match change.range {
        Some(range) => offsets::replace(text, place(range.start), place(range.end), &change.text),
        None => *text = change.text,
    }
}

/// The place the protocol's `position` names.
fn place(position: Position) -> Utf16Position {
    Utf16Position { line: position.line, column: position.character }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_utf16_code_units() {
        // `é` is one code unit (two bytes), `🎨` two (four bytes).
        let text = "# é🎨 x\r\nlet a = 1\rlet b";
        let at = |line, character| Position { line, character };
        let x = text.find('x').unwrap();
        assert_eq!(offset(text, at(0, 6)), x);
        assert_eq!(offset(text, at(0, 4)), text.find('🎨').unwrap(), "inside the pair");
        assert_eq!(end(text), at(2, 5));
        let mut sources = SourceMap::new();
        let id = sources.add("a.ray", text, 0);
        let span = Span::new(id, x, x + 1);
        assert_eq!(range(span, &sources), Range { start: at(0, 6), end: at(0, 7) });
        let b = text.find('b').unwrap();
        assert_eq!(range(Span::new(id, b, b + 1), &sources).start, at(2, 4));
    }

    #[test]
    fn changes_replace_their_range() {
        let mut text = "let é = 1\nlet b = 2\n".to_string();
        let at = |line, character| Position { line, character };
        let change = |range, text: &str| TextDocumentContentChangeEvent {
            range: Some(range),
            range_length: None,
            text: text.to_string(),
        };
        apply(&mut text, change(Range { start: at(0, 8), end: at(0, 9) }, "42"));
        assert_eq!(text, "let é = 42\nlet b = 2\n");
        apply(&mut text, change(Range { start: at(0, 10), end: at(1, 0) }, " "));
        assert_eq!(text, "let é = 42 let b = 2\n");
        apply(&mut text, TextDocumentContentChangeEvent { range: None, range_length: None, text: "new".into() });
        assert_eq!(text, "new");
    }
}
