//! A forgiving word scanner for editors: it splits text that is still
//! being typed into pieces to colour, finds the constructs left open and
//! the word at a place.
//!
//! The language's own lexer reports errors; this one never fails, because the
//! line being edited is usually not a valid program yet.

use std::ops::Range;

use crate::lang::words::{self, Kind, Role};

/// What a piece of text is, for colouring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PieceKind {
    /// A reserved word such as `sphere` or `end`.
    Keyword,
    /// `time`, `sin`, `cos`, `sqrt`, `pi`.
    Builtin,
    /// A name chosen by the user.
    Ident,
    /// A numeric literal.
    Number,
    /// `#` to the end of the line.
    Comment,
    /// A session command such as `:render` (first word of a line only).
    Command,
    /// Anything else: operators, punctuation, spaces, stray characters.
    Other,
}

/// One piece of the scanned text: `text[start..end]` is of kind `kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Piece {
    /// Its kind.
    pub kind: PieceKind,
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

/// Splits `text` into pieces covering every byte, in order.
pub fn pieces(text: &str) -> Vec<Piece> {
    let mut pieces = Vec::new();
    let mut rest = text.char_indices().peekable();
    let mut at_line_start = true;
    while let Some(&(start, c)) = rest.peek() {
        let kind = if c == '#' {
            take_while(&mut rest, |c| c != '\n');
            PieceKind::Comment
        } else if c == ':' && at_line_start {
            rest.next();
            take_while(&mut rest, is_word_char);
            PieceKind::Command
        } else if c.is_ascii_digit() || (c == '.' && next_is_digit(text, start)) {
            take_while(&mut rest, |c| c.is_ascii_digit() || c == '.');
            PieceKind::Number
        } else if c.is_ascii_alphabetic() || c == '_' {
            take_while(&mut rest, is_word_char);
            PieceKind::Ident
        } else {
            rest.next();
            PieceKind::Other
        };
        let end = rest.peek().map_or(text.len(), |&(i, _)| i);
        let kind = if kind == PieceKind::Ident { classify_word(&text[start..end]) } else { kind };
        at_line_start = match kind {
            PieceKind::Other => c == '\n' || (at_line_start && c.is_whitespace()),
            _ => false,
        };
        pieces.push(Piece { kind, start, end });
    }
    pieces
}

/// Whether `c` can be part of a name.
pub fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// Where the name that ends at the end of `before` starts.
pub fn word_start(before: &str) -> usize {
    before.char_indices().rev().take_while(|(_, c)| is_word_char(*c)).last().map_or(before.len(), |(i, _)| i)
}

/// The bytes of the word around byte `at` of `text` (or just before it): a
/// name, a word of the language, or a command with its colon.
pub fn word_at(text: &str, at: usize) -> Option<Range<usize>> {
    let is_part = |c: char| is_word_char(c) || c == ':';
    let start = text[..at].char_indices().rev().take_while(|(_, c)| is_part(*c)).last().map_or(at, |(i, _)| i);
    let end = text[at..].char_indices().find(|(_, c)| !is_part(*c)).map_or(text.len(), |(i, _)| at + i);
    (start < end).then_some(start..end)
}

/// The constructs opened in `text` and not yet closed by `end`, outermost
/// first: for `proc p() put sphere` it is `["proc", "sphere"]`.
pub fn open_constructs(text: &str) -> Vec<&'static str> {
    let mut open = Vec::new();
    for piece in pieces(text) {
        if piece.kind != PieceKind::Keyword {
            continue;
        }
        let word = &text[piece.start..piece.end];
        if word == "end" {
            open.pop();
        } else if let Some(opener) = words::lookup(word).filter(|word| word.opens()) {
            open.push(opener.text);
        }
    }
    open
}

/// The colour of a word: the built-in functions, `pi` and `time` apart from
/// the other keywords.
fn classify_word(word: &str) -> PieceKind {
    match words::lookup(word).map(|word| &word.kind) {
        Some(Kind::Keyword { role: Role::Function | Role::Constant, .. } | Kind::Predefined) => PieceKind::Builtin,
        Some(Kind::Keyword { .. }) => PieceKind::Keyword,
        _ => PieceKind::Ident,
    }
}

fn next_is_digit(text: &str, at: usize) -> bool {
    text[at..].chars().nth(1).is_some_and(|c| c.is_ascii_digit())
}

fn take_while(chars: &mut std::iter::Peekable<std::str::CharIndices<'_>>, keep: impl Fn(char) -> bool) {
    while chars.peek().is_some_and(|&(_, c)| keep(c)) {
        chars.next();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<(PieceKind, &str)> {
        pieces(text)
            .into_iter()
            .filter(|t| !text[t.start..t.end].trim().is_empty())
            .map(|t| (t.kind, &text[t.start..t.end]))
            .collect()
    }

    #[test]
    fn tokens_cover_every_byte_in_order() {
        let text = "put sphere center 1.5,0,-2 # a ball\n  radius r*2 é end";
        let all = pieces(text);
        let mut at = 0;
        for piece in &all {
            assert_eq!(piece.start, at);
            at = piece.end;
        }
        assert_eq!(at, text.len());
    }

    #[test]
    fn words_numbers_comments_and_commands_are_told_apart() {
        use PieceKind::*;
        assert_eq!(
            kinds("let r = sqrt(2) * time # half"),
            vec![
                (Keyword, "let"),
                (Ident, "r"),
                (Other, "="),
                (Builtin, "sqrt"),
                (Other, "("),
                (Number, "2"),
                (Other, ")"),
                (Other, "*"),
                (Builtin, "time"),
                (Comment, "# half"),
            ]
        );
        assert_eq!(kinds("  :render 80 40"), vec![(Command, ":render"), (Number, "80"), (Number, "40")]);
        assert_eq!(
            kinds("let a = b :c"),
            vec![(Keyword, "let"), (Ident, "a"), (Other, "="), (Ident, "b"), (Other, ":"), (Ident, "c")]
        );
    }

    #[test]
    fn the_word_at_a_place_takes_a_commands_colon() {
        let text = "put sphere :render é";
        assert_eq!(word_at(text, 5), Some(4..10));
        assert_eq!(word_at(text, 10), Some(4..10), "just after the word");
        assert_eq!(word_at(text, 13), Some(11..18));
        assert_eq!(word_at(text, text.len()), None, "after a character that is no part of a word");
        assert_eq!(word_start("let ab"), 4);
    }

    #[test]
    fn open_constructs_follow_end() {
        assert_eq!(open_constructs("proc p(n)\n put sphere center 0,0,0"), vec!["proc", "sphere"]);
        assert_eq!(
            open_constructs("put sphere center 0,0,0 radius 1 kd 1 ks 0 phong 1 color 1,1,1 end"),
            Vec::<&str>::new()
        );
        assert_eq!(open_constructs("if x < 1 then # sphere end\n"), vec!["if"]);
        assert_eq!(open_constructs("put group translate"), vec!["group", "translate"]);
    }
}
