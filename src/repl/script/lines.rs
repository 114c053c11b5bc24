//! A script's lines, each told whether the whole next line is already in
//! the reader's buffer: the script may then read it ahead without waiting
//! for whoever writes the script (who may be waiting for an answer).

use std::io::{self, BufRead};

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
    /// be read or is not UTF-8.
    pub(super) fn next_line(&mut self) -> Option<io::Result<ScriptLine<'_>>> {
        self.bytes.clear();
        let mut next_ready = false;
        loop {
            let buffer = match self.input.fill_buf() {
                Ok(buffer) => buffer,
                Err(error) if error.kind() == io::ErrorKind::Interrupted => continue,
                Err(error) => return Some(Err(error)),
            };
            if buffer.is_empty() {
                if self.bytes.is_empty() {
                    return None;
                }
                break;
            }
            let Some(newline) = buffer.iter().position(|&byte| byte == b'\n') else {
                let read = buffer.len();
                self.bytes.extend_from_slice(buffer);
                self.input.consume(read);
                continue;
            };
            self.bytes.extend_from_slice(&buffer[..newline]);
            next_ready = buffer[newline + 1..].contains(&b'\n');
            self.input.consume(newline + 1);
            if self.bytes.last() == Some(&b'\r') {
                self.bytes.pop();
            }
            break;
        }
        let text = std::str::from_utf8(&self.bytes)
            .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "stream did not contain valid UTF-8"));
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
        assert!(lines.next_line().is_some_and(|line| line.is_err()));
    }
}
