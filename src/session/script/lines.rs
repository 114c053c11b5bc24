//! A script's lines, each told whether the whole next line is already in
//! the reader's buffer: the script may then read it ahead without waiting
//! for whoever writes the script (who may be waiting for an answer).

use std::io::{self, BufRead};

/// The longest line a script may have, in bytes: a line is read whole
/// before it runs, and one without an end (a stream with no newline) must
/// not fill the memory. A scene's longest lines are a few hundred bytes.
pub(crate) const MOST_LINE_BYTES: usize = 64 << 20;

/// Why a line of the script cannot be run.
#[derive(Debug)]
pub(super) enum LineError {
    /// It could not be read.
    Read(io::Error),
    /// It is not UTF-8 text.
    NotText,
    /// It is longer than [`MOST_LINE_BYTES`].
    TooLong,
}

/// One line of the script.
pub(super) struct ScriptLine<'l> {
    /// Its text, without `\n` or `\r\n`, as [`BufRead::lines`] gives it.
    pub text: &'l str,
    /// Whether the whole next line is in the reader's buffer already.
    pub next_ready: bool,
}

/// The lines of a reader, as [`BufRead::lines`] reads them.
pub(super) struct ScriptLines<R> {
    input: R,
    bytes: Vec<u8>,
}

impl<R: BufRead> ScriptLines<R> {
    pub(super) fn new(input: R) -> ScriptLines<R> {
        ScriptLines { input, bytes: Vec::new() }
    }

    /// The next line, `None` at the end of the input; an error if it cannot
    /// be read, is not UTF-8 or is too long.
    pub(super) fn next_line(&mut self) -> Option<Result<ScriptLine<'_>, LineError>> {
        self.bytes.clear();
        let mut next_ready = false;
        loop {
            let buffer = match self.input.fill_buf() {
                Ok(buffer) => buffer,
                Err(error) if error.kind() == io::ErrorKind::Interrupted => continue,
                Err(error) => return Some(Err(LineError::Read(error))),
            };
            if buffer.is_empty() {
                if self.bytes.is_empty() {
                    return None;
                }
                break;
            }
            let Some(newline) = buffer.iter().position(|&byte| byte == b'\n') else {
                let read = buffer.len();
                if self.bytes.len() + read > MOST_LINE_BYTES {
                    return Some(Err(LineError::TooLong));
                }
                self.bytes.extend_from_slice(buffer);
                self.input.consume(read);
                continue;
            };
            if self.bytes.len() + newline > MOST_LINE_BYTES {
                return Some(Err(LineError::TooLong));
            }
            self.bytes.extend_from_slice(&buffer[..newline]);
            next_ready = buffer[newline + 1..].contains(&b'\n');
            self.input.consume(newline + 1);
            if self.bytes.last() == Some(&b'\r') {
                self.bytes.pop();
            }
            break;
        }
        let text = std::str::from_utf8(&self.bytes).map_err(|_| LineError::NotText);
        Some(text.map(|text| ScriptLine { text, next_ready }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each line with whether the next was ready, reading `text` through a
    /// buffer of `capacity` bytes.
    fn lines(text: &str, capacity: usize) -> Vec<(String, bool)> {
        let mut lines = ScriptLines::new(io::BufReader::with_capacity(capacity, text.as_bytes()));
        let mut read = Vec::new();
        while let Some(line) = lines.next_line() {
            let line = line.expect("the text is UTF-8");
            read.push((line.text.to_string(), line.next_ready));
        }
        read
    }

    #[test]
    fn lines_are_split_as_bufread_splits_them() {
        let text = "a\r\nb\n\nc\r\r\nd";
        let expected: Vec<String> = text.as_bytes().lines().map(Result::unwrap).collect();
        for capacity in [1, 2, 3, 5, 64] {
            let read: Vec<String> = lines(text, capacity).into_iter().map(|(text, _)| text).collect();
            assert_eq!(read, expected, "capacity {capacity}");
        }
    }

    #[test]
    fn the_next_line_is_ready_only_if_wholly_buffered() {
        assert_eq!(lines("ab\ncd\nef", 64), [("ab".into(), true), ("cd".into(), false), ("ef".into(), false)]);
        // The buffer holds "ab\nc": the rest of the second line is not read yet.
        assert_eq!(lines("ab\ncd\n", 4)[0], ("ab".into(), false));
        assert_eq!(lines("ab\ncd\n", 6)[0], ("ab".into(), true));
    }

    #[test]
    fn text_that_is_not_utf8_is_an_error() {
        let mut lines = ScriptLines::new(&b"ok\n\xff\n"[..]);
        assert!(lines.next_line().is_some_and(|line| line.is_ok()));
        assert!(matches!(lines.next_line(), Some(Err(LineError::NotText))));
    }

    #[test]
    fn a_line_longer_than_the_limit_is_an_error_before_it_is_all_read() {
        // An endless line: only a little past the limit is ever read.
        let endless = io::BufReader::new(io::repeat(b'a'));
        assert!(matches!(ScriptLines::new(endless).next_line(), Some(Err(LineError::TooLong))));
        let mut text = vec![b'a'; MOST_LINE_BYTES];
        text.extend_from_slice(b"\nb\n");
        let mut lines = ScriptLines::new(&text[..]);
        assert!(lines.next_line().is_some_and(|line| line.is_ok_and(|line| line.text.len() == MOST_LINE_BYTES)));
    }
}
