//! Turning source text into tokens with spans (SPEC section 1).
//!
//! The [`Lexer`] is an iterator of `(start, Token, end)` triples, the shape
//! lalrpop's external-lexer interface expects; `start` and `end` are byte
//! offsets into the text. It allocates nothing per token except the first
//! time a name is seen by the process ([`Name`]); a lexer keeps the names it
//! has read, so that each takes the process's table once. Keywords come from
//! the table of [`super::words`].

use std::collections::HashMap;

use unicode_width::UnicodeWidthChar;

use super::diagnostic::Diagnostic;
use super::fast_hash::FastHash;
use super::name::Name;
use super::nesting::Nesting;
use super::source::{SourceId, Span};
use super::token::Token;
use super::words::{self, Word};

/// A token with its byte range: the triple lalrpop consumes.
pub type Spanned = (usize, Token, usize);

/// A token with the row of the words table it comes from, for a keyword.
pub type WordToken = (Spanned, Option<&'static Word>);

/// Splits a text into tokens, skipping blanks and `#` comments (and a
/// byte-order mark at the start, which some editors write).
///
/// Yields `Err` once, at the first character that cannot start a token or
/// at the token that nests too deeply ([`super::nesting`]), and then stops.
#[derive(Debug)]
pub struct Lexer<'a> {
    text: &'a str,
    pos: usize,
    source: SourceId,
    /// The keywords, shared by every lexer of the thread.
    keywords: &'static KeywordTable,
    /// The names read so far, interned.
    names: HashMap<&'a str, Name, FastHash>,
    /// Where the line of the last token starts.
    line_start: usize,
    /// How deeply the tokens read so far nest.
    nesting: Nesting,
    failed: bool,
}

/// The keywords, their tokens and rows of the words table.
type KeywordTable = HashMap<&'static str, (Token, Option<&'static Word>), FastHash>;

thread_local! {
    /// The keywords' table, built once per thread and kept to the end: a
    /// session or a script makes a lexer per input, and neither building
    /// nor copying a table per lexer is needed.
    static KEYWORDS: &'static KeywordTable = Box::leak(Box::new(
        words::keywords().map(|(word, token)| (word.text, (token.clone(), Some(word)))).collect(),
    ));
}

impl<'a> Lexer<'a> {
    /// A lexer over `text`, whose spans in diagnostics name `source`.
    pub fn new(source: SourceId, text: &'a str) -> Lexer<'a> {
        let pos = if text.starts_with(BYTE_ORDER_MARK) { BYTE_ORDER_MARK.len_utf8() } else { 0 };
        let keywords = KEYWORDS.with(|keywords| *keywords);
        Lexer {
            text,
            pos,
            source,
            keywords,
            names: HashMap::default(),
            line_start: 0,
            nesting: Nesting::default(),
            failed: false,
        }
    }

    /// A lexer over `text` from byte `start`, where a line starts, on, the
    /// tokens before leaving `nesting` open: the tokens from there that
    /// [`Lexer::new`] would read.
    pub fn from_line(source: SourceId, text: &'a str, start: usize, nesting: Nesting) -> Lexer<'a> {
        if start == 0 {
            return Lexer { nesting, ..Lexer::new(source, text) };
        }
        Lexer { pos: start, line_start: start, nesting, ..Lexer::new(source, text) }
    }

    /// How deeply the tokens read so far nest.
    pub fn nesting(&self) -> &Nesting {
        &self.nesting
    }

    /// How deeply the tokens read so far nest, taken to go on reading with
    /// [`Lexer::from_line`].
    pub fn take_nesting(&mut self) -> Nesting {
        std::mem::take(&mut self.nesting)
    }

    /// Where the line of the last token read starts, as a byte offset.
    pub fn line_start(&self) -> usize {
        self.line_start
    }

    /// The next token, with its row of the words table if it is a keyword.
    pub fn next_word(&mut self) -> Option<Result<WordToken, Box<Diagnostic>>> {
        if self.failed {
            return None;
        }
        self.skip_trivia();
        if self.pos >= self.text.len() {
            return None;
        }
        let result = self.token().and_then(|(spanned, word)| {
            let (start, token, end) = &spanned;
            self.nesting.count(token, word, Span::new(self.source, *start, *end))?;
            Ok((spanned, word))
        });
        self.failed = result.is_err();
        Some(result)
    }

    /// Moves past blanks and comments.
    fn skip_trivia(&mut self) {
        let bytes = self.text.as_bytes();
        while let Some(&byte) = bytes.get(self.pos) {
            match byte {
                b' ' | b'\t' | b'\r' | b'\x0b' | b'\x0c' => self.pos += 1,
                b'\n' => {
                    self.pos += 1;
                    self.line_start = self.pos;
                }
                b'#' => {
                    self.pos = match bytes[self.pos..].iter().position(|&b| b == b'\n') {
                        Some(newline) => self.pos + newline,
                        None => bytes.len(),
                    };
                }
                _ => break,
            }
        }
    }

    /// Reads the token starting at the current position, which is not blank.
    fn token(&mut self) -> Result<WordToken, Box<Diagnostic>> {
        let bytes = self.text.as_bytes();
        let start = self.pos;
        let first = bytes[start];
        let next = bytes.get(start + 1).copied();
        let (token, len) = match first {
            b'0'..=b'9' => return Ok((self.number()?, None)),
            b'.' if next.is_some_and(|b| b.is_ascii_digit()) => return Ok((self.number()?, None)),
            b'A'..=b'Z' | b'a'..=b'z' | b'_' => return Ok(self.word()),
            b'/' if matches!(next, Some(b'/' | b'*')) => return Err(self.foreign_comment()),
            b'+' => (Token::Plus, 1),
            b'-' => (Token::Minus, 1),
            b'*' => (Token::Star, 1),
            b'/' => (Token::Slash, 1),
            b'(' => (Token::LParen, 1),
            b')' => (Token::RParen, 1),
            b',' => (Token::Comma, 1),
            b'=' => (Token::Eq, 1),
            b'&' => (Token::And, 1),
            b'|' => (Token::Or, 1),
            b'<' if next == Some(b'=') => (Token::Le, 2),
            b'<' => (Token::Lt, 1),
            b'>' if next == Some(b'=') => (Token::Ge, 2),
            b'>' => (Token::Gt, 1),
            b'!' if next == Some(b'=') => (Token::Ne, 2),
            b'!' => (Token::Bang, 1),
            _ => return Err(self.unexpected_character()),
        };
        self.pos += len;
        Ok(((start, token, self.pos), None))
    }

    /// Reads a name or a keyword.
    fn word(&mut self) -> WordToken {
        let start = self.pos;
        let len = self.text.as_bytes()[start..]
            .iter()
            .position(|b| !(b.is_ascii_alphanumeric() || *b == b'_'))
            .unwrap_or(self.text.len() - start);
        self.pos += len;
        let word = &self.text[start..self.pos];
        let (token, row) = match self.keywords.get(word) {
            Some(keyword) => keyword.clone(),
            None => (Token::Ident(*self.names.entry(word).or_insert_with(|| Name::new(word))), None),
        };
        ((start, token, self.pos), row)
    }

    /// Reads `[0-9]*(\.[0-9]+)?([eE][+-]?[0-9]+)?` (at least one digit).
    fn number(&mut self) -> Result<Spanned, Box<Diagnostic>> {
        let bytes = self.text.as_bytes();
        let start = self.pos;
        let digits = |from: usize| bytes[from..].iter().take_while(|b| b.is_ascii_digit()).count();
        let mut end = start + digits(start);
        if bytes.get(end) == Some(&b'.') && bytes.get(end + 1).is_some_and(u8::is_ascii_digit) {
            end += 1 + digits(end + 1);
        }
        if matches!(bytes.get(end), Some(b'e' | b'E')) {
            let sign = usize::from(matches!(bytes.get(end + 1), Some(b'+' | b'-')));
            let exponent = digits(end + 1 + sign);
            if exponent > 0 {
                end += 1 + sign + exponent;
            }
        }
        self.pos = end;
        let literal = &self.text[start..end];
        if let Some(value) = small_integer(literal) {
            return Ok((start, Token::Number(value), end));
        }
        match literal.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok((start, Token::Number(value), end)),
            _ => Err(Box::new(
                Diagnostic::error(Span::new(self.source, start, end), format!("the number `{literal}` is too large"))
                    .with_code("number-too-large")
                    .with_label("too large for a number"),
            )),
        }
    }

    /// The diagnostic for `//` or `/*`, which start comments in other languages.
    fn foreign_comment(&mut self) -> Box<Diagnostic> {
        let start = self.pos;
        self.pos += 2;
        let written = &self.text[start..self.pos];
        Box::new(
            Diagnostic::error(Span::new(self.source, start, self.pos), format!("`{written}` does not start a comment"))
                .with_code("not-a-comment")
                .with_label("not a comment in this language")
                .with_help("comments start with `#` and run to the end of the line"),
        )
    }

    /// The diagnostic for a character that cannot start a token.
    fn unexpected_character(&mut self) -> Box<Diagnostic> {
        let start = self.pos;
        let character = self.text[start..].chars().next().unwrap_or('\u{fffd}');
        let end = start + character.len_utf8();
        self.pos = end;
        let span = Span::new(self.source, start, end);
        if is_invisible(character) {
            let help = if character.is_whitespace() {
                "replace it with an ordinary space"
            } else {
                "delete it: such characters come with text copied from web pages and documents"
            };
            return Box::new(
                Diagnostic::error(span, format!("invisible character U+{:04X}", u32::from(character)))
                    .with_code("invisible-character")
                    .with_label("an invisible character is here")
                    .with_help(help),
            );
        }
        let diagnostic = Diagnostic::error(span, format!("unexpected character `{character}`"))
            .with_code("unexpected-character")
            .with_label("this character is not part of the language");
        let (help, replacement) = if character.is_alphabetic() {
            (Some(self.accented_word_help(start, end)), None)
        } else {
            character_help(character).map_or((None, None), |(help, replacement)| (Some(help.to_string()), replacement))
        };
        let diagnostic = match help {
            Some(help) => diagnostic.with_help(help),
            None => diagnostic,
        };
        let diagnostic = match replacement {
            Some(replacement) => diagnostic.with_replacement(span, replacement),
            None => diagnostic,
        };
        let (word, word_span) = self.word_around(start, end);
        Box::new(match words::keyword_meant(word).filter(|_| character.is_alphabetic()) {
            Some(keyword) => diagnostic.with_replacement(word_span, keyword),
            None => diagnostic,
        })
    }

    /// The word (letters, digits and `_`) around the character at
    /// `start..end`, and its span.
    fn word_around(&self, start: usize, end: usize) -> (&str, Span) {
        let is_letter = |c: char| c.is_alphanumeric() || c == '_';
        let before = self.text[..start].trim_end_matches(is_letter);
        let after = self.text[end..].trim_start_matches(is_letter);
        let (first, last) = (before.len(), self.text.len() - after.len());
        (&self.text[first..last], Span::new(self.source, first, last))
    }

    /// The help for a letter outside a to z at `start..end`: what the whole
    /// word around it means if it is a French keyword (`sphère`), otherwise
    /// which letters names may use.
    fn accented_word_help(&self, start: usize, end: usize) -> String {
        let (word, _) = self.word_around(start, end);
        words::hint_for_name(word)
            .unwrap_or_else(|| "names use only the letters a to z without accents, digits and `_`".to_string())
    }
}

/// U+FEFF, which some editors write at the start of a file.
pub(super) const BYTE_ORDER_MARK: char = '\u{feff}';

/// Whether `character` shows as nothing, or as a blank, on screen: a
/// control character, a zero-width one (U+200B) or an unusual space (U+00A0).
fn is_invisible(character: char) -> bool {
    character.is_whitespace() || matches!(character.width(), None | Some(0))
}

/// The value of `literal` if it is a plain integer of at most 15 digits,
/// which converts to `f64` exactly; most literals are, and this is much
/// quicker than the general float parser.
fn small_integer(literal: &str) -> Option<f64> {
    let bytes = literal.as_bytes();
    if bytes.len() > 15 || !bytes.iter().all(u8::is_ascii_digit) {
        return None;
    }
    let value = bytes.iter().fold(0u64, |value, digit| value * 10 + u64::from(digit - b'0'));
    // At most 15 digits: below 2^53, so the conversion is exact.
    Some(value as f64)
}

/// A hint for characters learners often type by habit from other languages,
/// or that a word processor puts in their place, and the text to type
/// instead where it is plain (a quick fix).
fn character_help(character: char) -> Option<(&'static str, Option<&'static str>)> {
    Some(match character {
        '\u{2212}' => ("this is a Unicode minus sign; type `-`", Some("-")),
        '\u{2010}'..='\u{2015}' | '\u{fe63}' | '\u{ff0d}' => ("this is a Unicode dash; type `-`", Some("-")),
        '\u{d7}' => ("to multiply, type `*`", Some("*")),
        '\u{f7}' => ("to divide, type `/`", Some("/")),
        '\u{2018}'..='\u{201f}' => ("the language has no strings: names are written without quotes", None),
        ';' => ("instructions need no separator: remove the `;`", Some("")),
        '{' | '}' => ("blocks are closed with `end`, not with braces", None),
        '"' | '\'' => ("the language has no strings: names are written without quotes", None),
        '.' => ("write decimals with digits on both sides of the point, like `0.5`", None),
        '^' => ("there is no power operator: multiply, like `x * x`", None),
        '[' | ']' => ("use `(` and `)` for grouping", None),
        _ => return None,
    })
}

impl Iterator for Lexer<'_> {
    type Item = Result<Spanned, Box<Diagnostic>>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_word().map(|result| result.map(|(token, _)| token))
    }
}

/// All tokens of `text`, or the first lexing error.
pub fn tokenize(source: SourceId, text: &str) -> Result<Vec<Spanned>, Box<Diagnostic>> {
    Lexer::new(source, text).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tokens(text: &str) -> Vec<Token> {
        tokenize(SourceId(0), text).expect("valid tokens").into_iter().map(|(_, t, _)| t).collect()
    }

    fn error(text: &str) -> Diagnostic {
        *tokenize(SourceId(0), text).expect_err("a lexing error")
    }

    #[test]
    fn numbers_in_every_accepted_form() {
        assert_eq!(
            tokens("3 0.75 .5 1e3 2.5E-2 7e+1"),
            vec![
                Token::Number(3.0),
                Token::Number(0.75),
                Token::Number(0.5),
                Token::Number(1000.0),
                Token::Number(0.025),
                Token::Number(70.0),
            ]
        );
    }

    #[test]
    fn an_exponent_needs_digits() {
        let expected = vec![Token::Number(2.0), Token::Ident("e".into())];
        assert_eq!(tokens("2e"), expected);
        assert_eq!(tokens("2end"), vec![Token::Number(2.0), Token::End]);
    }

    #[test]
    fn every_keyword_is_its_own_token() {
        for (word, token) in words::keywords() {
            assert_eq!(tokens(word.text), vec![token.clone()], "{}", word.text);
            assert_eq!(token.spelling(), Some(word.text));
            assert!(token.is_keyword());
        }
    }

    #[test]
    fn time_and_near_keywords_are_names() {
        assert_eq!(
            tokens("time spheres Sphere _x1"),
            vec![
                Token::Ident("time".into()),
                Token::Ident("spheres".into()),
                Token::Ident("Sphere".into()),
                Token::Ident("_x1".into()),
            ]
        );
    }

    #[test]
    fn symbols_and_two_character_comparisons() {
        assert_eq!(
            tokens("+-*/(),=<&|! > <= >= !="),
            vec![
                Token::Plus,
                Token::Minus,
                Token::Star,
                Token::Slash,
                Token::LParen,
                Token::RParen,
                Token::Comma,
                Token::Eq,
                Token::Lt,
                Token::And,
                Token::Or,
                Token::Bang,
                Token::Gt,
                Token::Le,
                Token::Ge,
                Token::Ne,
            ]
        );
    }

    #[test]
    fn comments_run_to_the_end_of_the_line() {
        assert_eq!(tokens("a # b ( $\nc # d"), vec![Token::Ident("a".into()), Token::Ident("c".into())]);
    }

    #[test]
    fn spans_are_byte_offsets() {
        let spanned = tokenize(SourceId(0), "let xy = 12.5").expect("valid");
        let ranges: Vec<(usize, usize)> = spanned.iter().map(|(s, _, e)| (*s, *e)).collect();
        assert_eq!(ranges, vec![(0, 3), (4, 6), (7, 8), (9, 13)]);
    }

    #[test]
    fn names_are_interned() {
        let spanned = tokenize(SourceId(0), "abc abc").expect("valid");
        match (&spanned[0].1, &spanned[1].1) {
            (Token::Ident(a), Token::Ident(b)) => assert!(std::ptr::eq(a.as_str(), b.as_str())),
            other => panic!("expected two names, got {other:?}"),
        }
    }

    #[test]
    fn an_unexpected_character_is_reported_at_its_exact_span() {
        let diagnostic = error("let x = 3 $ 4");
        assert_eq!(diagnostic.message, "unexpected character `$`");
        assert_eq!((diagnostic.span.start, diagnostic.span.end), (10, 11));
    }

    #[test]
    fn a_non_ascii_character_is_spanned_whole() {
        let diagnostic = error("é");
        assert_eq!(diagnostic.message, "unexpected character `é`");
        assert_eq!((diagnostic.span.start, diagnostic.span.end), (0, 2));
    }

    #[test]
    fn a_semicolon_gets_a_hint() {
        let diagnostic = error("let x = 1;");
        assert!(diagnostic.help.is_some_and(|h| h.contains("`;`")));
    }

    #[test]
    fn a_byte_order_mark_is_skipped_at_the_start_only() {
        assert_eq!(tokens("\u{feff}let"), vec![Token::Let]);
        assert_eq!(error("let \u{feff}").message, "invisible character U+FEFF");
    }

    #[test]
    fn invisible_characters_are_named_by_their_code() {
        let diagnostic = error("let\u{200b} x");
        assert_eq!(diagnostic.message, "invisible character U+200B");
        assert_eq!((diagnostic.span.start, diagnostic.span.end), (3, 6));
        assert_eq!(error("a\u{1}").message, "invisible character U+0001");
        assert!(error("a\u{a0}b").help.is_some_and(|help| help.contains("ordinary space")));
    }

    #[test]
    fn comments_of_other_languages_are_errors_with_a_hint() {
        for text in ["// note", "x /* note */"] {
            let diagnostic = error(text);
            assert!(diagnostic.message.ends_with("does not start a comment"), "{text}");
            assert_eq!(diagnostic.help.as_deref(), Some("comments start with `#` and run to the end of the line"));
        }
        assert_eq!(tokens("a / b"), vec![Token::Ident("a".into()), Token::Slash, Token::Ident("b".into())]);
    }

    #[test]
    fn typographic_dashes_get_a_hint() {
        assert_eq!(error("\u{2212}1").help.as_deref(), Some("this is a Unicode minus sign; type `-`"));
        assert_eq!(error("\u{2212}1").replacements[0].text, "-", "a quick fix");
        assert_eq!(error("1 \u{2014} 2").help.as_deref(), Some("this is a Unicode dash; type `-`"));
    }

    #[test]
    fn an_accented_letter_names_the_whole_word() {
        assert_eq!(error("put sphère").help.as_deref(), Some("`sphère` is French: the keyword is `sphere`"));
        assert_eq!(
            error("let café = 1").help.as_deref(),
            Some("names use only the letters a to z without accents, digits and `_`")
        );
    }

    #[test]
    fn a_huge_number_is_an_error_not_infinity() {
        assert_eq!(error("1e999").message, "the number `1e999` is too large");
    }

    #[test]
    fn the_lexer_stops_after_an_error() {
        let mut lexer = Lexer::new(SourceId(0), "$ a");
        assert!(matches!(lexer.next(), Some(Err(_))));
        assert!(lexer.next().is_none());
    }
}
