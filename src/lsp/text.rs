//! An open document's text, and the protocol's positions in it: a line and
//! a column counted in UTF-16 code units, as the Language Server Protocol
//! requires (its default encoding, the one every client speaks). Lines end
//! at `\n`, `\r\n` or a lone `\r`, for the protocol as for the diagnostics.

use lsp_types::{Position, Range, TextDocumentContentChangeEvent};

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

/// Where each line of a text starts, to turn positions into byte offsets.
pub(crate) struct Lines<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> Lines<'a> {
    /// The lines of `text`.
    pub(crate) fn new(text: &'a str) -> Lines<'a> {
        let bytes = text.as_bytes();
        let ends = text
            .match_indices(['\n', '\r'])
            .filter(|&(at, _)| !(bytes[at] == b'\r' && bytes.get(at + 1) == Some(&b'\n')));
        let starts = std::iter::once(0).chain(ends.map(|(at, _)| at + 1)).collect();
        Lines { text, starts }
    }

    /// The position just after the text's last character.
    pub(crate) fn end(&self) -> Position {
        let last = self.starts.len() - 1;
        let column: usize = self.text[self.starts[last]..].chars().map(char::len_utf16).sum();
        Position { line: last as u32, character: column as u32 }
    }

    /// The byte offset of `position`: a column past the end of its line is
    /// the line's end, a line past the last is the text's end, and a
    /// column inside a character two code units wide is that character's start.
    pub(crate) fn offset(&self, position: Position) -> usize {
        let Some(&start) = self.starts.get(position.line as usize) else { return self.text.len() };
        let line = &self.text[start..];
        let line = &line[..line.find(['\n', '\r']).unwrap_or(line.len())];
        let mut units = 0;
        for (at, c) in line.char_indices() {
            units += c.len_utf16();
            if units > position.character as usize {
                return start + at;
            }
        }
        start + line.len()
    }
}

/// `text` after one change the client sent: a range replaced, or the
/// whole text when the change has no range.
pub(crate) fn apply(text: &mut String, change: TextDocumentContentChangeEvent) {
    match change.range {
        Some(range) => {
            let lines = Lines::new(text);
            let (start, end) = (lines.offset(range.start), lines.offset(range.end));
            text.replace_range(start..end.max(start), &change.text);
        }
        None => *text = change.text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_utf16_code_units() {
        // `é` is one code unit (two bytes), `🎨` two (four bytes).
        let text = "# é🎨 x\r\nlet a = 1\rlet b";
        let lines = Lines::new(text);
        let at = |line, character| Position { line, character };
        let x = text.find('x').unwrap();
        assert_eq!(lines.offset(at(0, 6)), x);
        assert_eq!(lines.offset(at(0, 4)), text.find('🎨').unwrap(), "inside the pair");
        assert_eq!(lines.offset(at(0, 99)), text.find('\r').unwrap());
        assert_eq!(lines.offset(at(2, 4)), text.find('b').unwrap(), "a lone CR ends a line");
        assert_eq!(lines.offset(at(9, 0)), text.len());
        assert_eq!(lines.end(), at(2, 5));
        assert_eq!(Lines::new("a\n").end(), at(1, 0));
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
