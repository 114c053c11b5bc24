//! The limit on how deeply a program nests (docs/language.md, section 10).
//!
//! The parser keeps what a construct holds open on its heap stack until the
//! construct closes, and evaluation walks the tree with a stack that grows
//! with its depth: a program nested millions of levels deep would take
//! gigabytes before either said anything. The lexer counts the open levels
//! as it reads the tokens, so the error comes at the construct that went
//! one level too deep, before the parser has grown.

use super::diagnostic::Diagnostic;
use super::source::Span;
use super::token::Token;
use super::words::Word;

/// The deepest nesting a program may have: constructs closed by `end`,
/// parentheses, and `-` or `!` written before an operand, counted together.
/// Well above what a program written by a person or generated for a test
/// needs (the deep-nesting tests use 100,000), and low enough that the
/// costliest construct at the limit (an `else if` chain with a `put` in each
/// branch, about 3 KB a level) parses and runs in under a gigabyte.
pub const MAX_NESTING: usize = 250_000;

/// How deeply the tokens read so far nest, as the lexer counts them. A
/// prefix operator opens a level that the operand after it closes; before a
/// `(`, it stays open until the matching `)`.
#[derive(Debug, Clone, Default)]
pub struct Nesting {
    /// The levels open now.
    depth: usize,
    /// The prefix operators read since the last operand.
    prefixes: usize,
    /// For each open parenthesis, the prefix operators written before it.
    before_parens: Vec<usize>,
    /// Whether the last token ends an operand, so that a `-` after it
    /// subtracts rather than negates.
    after_operand: bool,
}

impl Nesting {
    /// Counts `token` (with its row of the words table, for a keyword) at
    /// `span`; the error if it opens a level past [`MAX_NESTING`].
    pub fn count(&mut self, token: &Token, word: Option<&'static Word>, span: Span) -> Result<(), Box<Diagnostic>> {
        let ends_operand = matches!(token, Token::Number(_) | Token::Ident(_) | Token::Pi | Token::RParen);
        let after_operand = std::mem::replace(&mut self.after_operand, ends_operand);
        let opens = match token {
            Token::Minus if !after_operand => {
                self.prefixes += 1;
                true
            }
            Token::Bang => {
                self.prefixes += 1;
                true
            }
            Token::LParen => {
                self.before_parens.push(std::mem::take(&mut self.prefixes));
                true
            }
            Token::RParen => {
                let before = self.before_parens.pop().unwrap_or(0);
                self.depth = self.depth.saturating_sub(1 + before);
                false
            }
            // A function's name waits for its `(`.
            Token::Sin | Token::Cos | Token::Sqrt => false,
            _ => {
                // The prefix operators before an operand end with it.
                self.depth = self.depth.saturating_sub(std::mem::take(&mut self.prefixes));
                if matches!(token, Token::End) {
                    self.depth = self.depth.saturating_sub(1);
                }
                word.is_some_and(Word::opens)
            }
        };
        if !opens {
            return Ok(());
        }
        self.depth += 1;
        if self.depth > MAX_NESTING { Err(Box::new(too_deep(token, span))) } else { Ok(()) }
    }
}

/// The error at the token that opened one level too many.
#[cold]
#[inline(never)]
fn too_deep(token: &Token, span: Span) -> Diagnostic {
    let what = token.spelling().map_or_else(|| "this".to_string(), |spelling| format!("this `{spelling}`"));
    Diagnostic::error(span, format!("nesting deeper than {MAX_NESTING} levels"))
        .with_code("nesting-too-deep")
        .with_label(format!("{what} is one level too deep"))
        .with_note("constructs closed by `end`, parentheses, and `-` or `!` before an operand count as levels")
        .with_help("nest less: an `object` variable or a procedure can hold part of the construct")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::lexer::Lexer;
    use crate::lang::source::SourceId;

    /// The deepest nesting the lexer counts in `text`, and its error.
    fn deepest(text: &str) -> (usize, Option<Box<Diagnostic>>) {
        let mut lexer = Lexer::new(SourceId(0), text);
        let mut deepest = 0;
        while let Some(token) = lexer.next_word() {
            if let Err(error) = token {
                return (deepest, Some(error));
            }
            deepest = deepest.max(lexer.nesting().depth);
        }
        (deepest, None)
    }

    #[test]
    fn levels_are_counted_as_the_tree_nests() {
        assert_eq!(deepest("let x = 1 - 2 - -3").0, 1);
        assert_eq!(deepest("let x = - - -(- -(1))").0, 7);
        assert_eq!(deepest("let x = sin(-sin(1)) let y = 1").0, 3);
        assert_eq!(deepest("if !(a < 1) & !b < 2 then put group s end end").0, 3);
        assert_eq!(deepest("proc p() if a < 1 then put scale s by 2 end end end p()").0, 3);
        // Operands close the levels of their prefixes: a long sum stays flat.
        assert_eq!(deepest(&"1 - -1 ".repeat(1000)).0, 1);
    }

    #[test]
    fn one_level_past_the_limit_is_an_error_at_its_construct() {
        let text = format!("put {}s", "group ".repeat(MAX_NESTING + 1));
        let (deepest, error) = deepest(&text);
        let error = error.expect("too deep");
        assert_eq!(deepest, MAX_NESTING);
        assert_eq!(error.message, format!("nesting deeper than {MAX_NESTING} levels"));
        assert_eq!(error.span.start as usize, 4 + 6 * MAX_NESTING);
    }
}
