//! Source texts and positions in them.
//!
//! Spans name their source by [`SourceId`], so that an error raised while
//! running a procedure defined in an earlier input of the session still points
//! at the right text.

use std::sync::{Arc, OnceLock};

/// Identifies one source text inside a [`SourceMap`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SourceId(pub u32);

/// A range of bytes `start..end` in one source text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// Which source text.
    pub source: SourceId,
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
}

impl Span {
    /// A span of `start..end` in `source`.
    pub fn new(source: SourceId, start: usize, end: usize) -> Span {
        Span { source, start: start as u32, end: end as u32 }
    }

    /// The smallest span covering both `self` and `other` (same source).
    pub fn to(self, other: Span) -> Span {
        Span { source: self.source, start: self.start.min(other.start), end: self.end.max(other.end) }
    }
}

/// One source text: a file, standard input, or one input of the session.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// The name shown in diagnostics (a path, `<stdin>`, `<input>`).
    pub name: String,
    /// The text itself.
    pub text: Arc<str>,
    /// Line number of the text's first line, minus one: a piece of a script
    /// that starts at line 17 has `line_offset` 16, so diagnostics show the
    /// script's own line numbers.
    pub line_offset: usize,
    /// Where each line of `text` starts, found on the first question (a
    /// text without diagnostics never needs it): a file with many warnings
    /// is not scanned from its start for each. Shared by the clones of the
    /// file, and with the thread [`SourceFile::find_lines_apart`] starts.
    line_starts: Arc<OnceLock<Vec<usize>>>,
}

impl SourceFile {
    /// The 1-based (line, column) of byte `offset`, columns counted in characters.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let (line, line_start) = self.line_of(offset);
        let column = self.text[line_start..offset].chars().count();
        (line + 1 + self.line_offset, column + 1)
    }

    /// The 0-based index in `text` of the line holding byte `offset` (a
    /// line's `\n` is its last byte), and where that line starts.
    pub(crate) fn line_of(&self, offset: usize) -> (usize, usize) {
        let starts = self.line_starts.get_or_init(|| line_starts(&self.text));
        let line = starts.partition_point(|&start| start <= offset) - 1;
        (line, starts[line])
    }

    /// Starts finding where the lines of the text start on a thread of its
    /// own, for a large text about to be parsed and run: the first
    /// diagnostic about it (the error of a Ctrl-C that stops it) then finds
    /// them ready, where scanning 100 MB would take it 30 ms. Where no
    /// thread can be made (wasm32), they are found on the first question.
    pub(crate) fn find_lines_apart(&self) {
        let (text, starts) = (Arc::clone(&self.text), Arc::clone(&self.line_starts));
        let _ = std::thread::Builder::new().name("lines".to_string()).spawn(move || {
            starts.get_or_init(|| line_starts(&text));
        });
    }
}

/// Where each line of `text` starts.
fn line_starts(text: &str) -> Vec<usize> {
    std::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i + 1)).collect()
}

/// All the source texts a run or a session has seen.
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    pub const fn new() -> SourceMap {
        SourceMap { files: Vec::new() }
    }

    /// Adds a text and returns its id. A line that ends with `\r` alone
    /// (old Mac files) ends there, as one ending with `\n` or `\r\n`: the
    /// text is kept with that `\r` read as `\n`, so every byte stays where
    /// it was.
    pub fn add(&mut self, name: impl Into<String>, text: impl Into<Arc<str>>, line_offset: usize) -> SourceId {
        let text = with_lone_returns_as_newlines(text.into());
        self.files.push(SourceFile { name: name.into(), text, line_offset, line_starts: Arc::default() });
        SourceId((self.files.len() - 1) as u32)
    }

    /// The text with this id.
    pub fn get(&self, id: SourceId) -> &SourceFile {
        &self.files[id.0 as usize]
    }
}

/// `text` with every `\r` not followed by `\n` made a `\n` (the same
/// length); `text` itself when it has none.
fn with_lone_returns_as_newlines(text: Arc<str>) -> Arc<str> {
    let bytes = text.as_bytes();
    let lone = |at: usize| bytes[at] == b'\r' && bytes.get(at + 1) != Some(&b'\n');
    // Most texts have no `\r` at all: one fast search says so.
    if !text.contains('\r') || !(0..bytes.len()).any(lone) {
        return text;
    }
    let fixed: Vec<u8> = (0..bytes.len()).map(|at| if lone(at) { b'\n' } else { bytes[at] }).collect();
    // Only ASCII bytes changed, into ASCII bytes: still UTF-8.
    Arc::from(String::from_utf8(fixed).expect("an ASCII byte for an ASCII byte keeps UTF-8"))
}

/// `bytes` as text, or where its first byte that is not UTF-8 is, in
/// words: "line 3, column 5 is not UTF-8 text".
pub fn text_of(bytes: Vec<u8>) -> Result<String, String> {
    String::from_utf8(bytes).map_err(|error| {
        let valid = &error.as_bytes()[..error.utf8_error().valid_up_to()];
        // The valid part is UTF-8: its lines and characters count.
        let before = std::str::from_utf8(valid).unwrap_or_default();
        let line = before.matches(['\n', '\r']).count() - before.matches("\r\n").count() + 1;
        let line_start = before.rfind(['\n', '\r']).map_or(0, |at| at + 1);
        let column = before[line_start..].chars().count() + 1;
        format!("line {line}, column {column} is not UTF-8 text")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lone_return_ends_a_line_and_keeps_the_bytes_in_place() {
        let mut sources = SourceMap::new();
        let id = sources.add("mac.ray", "a\rb\r\nc\r", 0);
        assert_eq!(&*sources.get(id).text, "a\nb\r\nc\n");
    }

    #[test]
    fn text_that_is_not_utf8_says_where() {
        assert_eq!(text_of(b"ok\n".to_vec()).as_deref(), Ok("ok\n"));
        assert_eq!(text_of(b"ab\r\n\xc3\xa9x\xff".to_vec()), Err("line 2, column 3 is not UTF-8 text".to_string()));
        assert_eq!(text_of(b"\xff".to_vec()), Err("line 1, column 1 is not UTF-8 text".to_string()));
    }

    #[test]
    fn line_col_counts_from_one_and_honours_the_offset() {
        let mut map = SourceMap::new();
        let id = map.add("a.ray", "ab\ncd\n", 0);
        assert_eq!(map.get(id).line_col(0), (1, 1));
        assert_eq!(map.get(id).line_col(4), (2, 2));
        let id = map.add("b.ray", "x\ny", 16);
        assert_eq!(map.get(id).line_col(2), (18, 1));
    }

    #[test]
    fn lines_found_apart_are_the_lines_found_on_the_first_question() {
        let mut map = SourceMap::new();
        let text = "ab\n\ncd\n".repeat(1000);
        let (apart, asked) = (map.add("a.ray", text.as_str(), 0), map.add("b.ray", text.as_str(), 0));
        map.get(apart).find_lines_apart();
        for offset in [0, 3, 4, 5, 4000, text.len()] {
            assert_eq!(map.get(apart).line_col(offset), map.get(asked).line_col(offset));
        }
    }

    #[test]
    fn a_line_ends_with_its_newline() {
        let mut map = SourceMap::new();
        let id = map.add("a.ray", "ab\n\ncd", 0);
        let file = map.get(id);
        let lines: Vec<_> = (0..=6).map(|offset| file.line_of(offset)).collect();
        assert_eq!(lines, [(0, 0), (0, 0), (0, 0), (1, 3), (2, 4), (2, 4), (2, 4)]);
        assert_eq!(file.line_col(6), (3, 3));
    }
}
