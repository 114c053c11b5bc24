//! Places in a text as editors count them, turned into byte offsets and
//! back: a line and a column in UTF-16 code units (the Language Server
//! Protocol's default encoding, the one every client speaks), or a count
//! of characters (a notebook's cursor). Lines end at `\n`, `\r\n` or a
//! lone `\r`, as in the diagnostics.

/// A place in a text: a line and a column in UTF-16 code units, both from 0.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Utf16Position {
    /// The line, from 0.
    pub line: u32,
    /// The UTF-16 code units before it on its line.
    pub column: u32,
}

/// Where each line of a text starts, to turn positions into byte offsets.
pub struct Lines<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> Lines<'a> {
    /// The lines of `text`.
    pub fn new(text: &'a str) -> Lines<'a> {
        let bytes = text.as_bytes();
        let ends = text
            .match_indices(['\n', '\r'])
            .filter(|&(at, _)| !(bytes[at] == b'\r' && bytes.get(at + 1) == Some(&b'\n')));
        let starts = std::iter::once(0).chain(ends.map(|(at, _)| at + 1)).collect();
        Lines { text, starts }
    }

    /// The position just after the text's last character.
    pub fn end(&self) -> Utf16Position {
        let last = self.starts.len() - 1;
        let column: usize = self.text[self.starts[last]..].chars().map(char::len_utf16).sum();
        Utf16Position { line: last as u32, column: column as u32 }
    }

    /// The byte offset of `position`: a column past the end of its line is
    /// the line's end, a line past the last is the text's end, and a
    /// column inside a character two code units wide is that character's start.
    pub fn offset(&self, position: Utf16Position) -> usize {
        let Some(&start) = self.starts.get(position.line as usize) else { return self.text.len() };
        let line = &self.text[start..];
        let line = &line[..line.find(['\n', '\r']).unwrap_or(line.len())];
        let mut units = 0;
        for (at, c) in line.char_indices() {
            units += c.len_utf16();
            if units > position.column as usize {
                return start + at;
            }
        }
        start + line.len()
    }
}

/// Replaces the part of `text` between `start` and `end` with `new` (an
/// end before the start is the start: the change inserts).
pub fn replace(text: &mut String, start: Utf16Position, end: Utf16Position, new: &str) {
    let lines = Lines::new(text);
    let (start, end) = (lines.offset(start), lines.offset(end));
    text.replace_range(start..end.max(start), new);
}

/// The largest character boundary of `text` at or before byte `at`.
pub fn floor_char_boundary(text: &str, at: usize) -> usize {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// The byte offset of character `chars` of `text` (its end past the last).
pub fn byte_of_char(text: &str, chars: usize) -> usize {
    text.char_indices().nth(chars).map_or(text.len(), |(at, _)| at)
}

/// How many characters come before byte `bytes` of `text`.
pub fn chars_before(text: &str, bytes: usize) -> usize {
    text[..bytes.min(text.len())].chars().count()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(line: u32, column: u32) -> Utf16Position {
        Utf16Position { line, column }
    }

    #[test]
    fn columns_count_utf16_code_units() {
        // `é` is one code unit (two bytes), `🎨` two (four bytes).
        let text = "# é🎨 x\r\nlet a = 1\rlet b";
        let lines = Lines::new(text);
        let x = text.find('x').unwrap();
        assert_eq!(lines.offset(at(0, 6)), x);
        assert_eq!(lines.offset(at(0, 3)), text.find('🎨').unwrap(), "after the two-byte character");
        assert_eq!(lines.offset(at(0, 4)), text.find('🎨').unwrap(), "inside the pair");
        assert_eq!(lines.offset(at(0, 5)), text.find('🎨').unwrap() + '🎨'.len_utf8(), "after the astral character");
        assert_eq!(lines.offset(at(0, 99)), text.find('\r').unwrap());
        assert_eq!(lines.offset(at(2, 4)), text.find('b').unwrap(), "a lone CR ends a line");
        assert_eq!(lines.offset(at(9, 0)), text.len());
        assert_eq!(lines.end(), at(2, 5));
        assert_eq!(Lines::new("a\n").end(), at(1, 0));
        assert_eq!(Lines::new("🎨").end(), at(0, 2), "an astral character is two units");
    }

    #[test]
    fn a_replacement_counts_its_columns_in_utf16() {
        let mut text = "let é = 1\nlet 🎨b = 2\n".to_string();
        replace(&mut text, at(0, 8), at(0, 9), "42");
        assert_eq!(text, "let é = 42\nlet 🎨b = 2\n");
        replace(&mut text, at(1, 6), at(1, 7), "c");
        assert_eq!(text, "let é = 42\nlet 🎨c = 2\n");
        replace(&mut text, at(0, 10), at(1, 0), " ");
        assert_eq!(text, "let é = 42 let 🎨c = 2\n");
    }

    #[test]
    fn cursor_positions_count_characters() {
        let text = "let é = 1";
        assert_eq!(byte_of_char(text, 5), 6);
        assert_eq!(chars_before(text, 6), 5);
        assert_eq!(byte_of_char(text, 99), text.len());
    }

    #[test]
    fn characters_and_bytes_convert_both_ways() {
        let text = "é🎨x";
        assert_eq!(byte_of_char(text, 2), text.find('x').unwrap());
        assert_eq!(byte_of_char(text, 9), text.len());
        assert_eq!(chars_before(text, text.find('x').unwrap()), 2);
        assert_eq!(chars_before(text, 99), 3);
        assert_eq!(floor_char_boundary(text, 3), 2, "inside the astral character: its start");
        assert_eq!(floor_char_boundary(text, 1), 0, "inside the two-byte character: its start");
        assert_eq!(floor_char_boundary(text, 99), text.len());
    }
}
