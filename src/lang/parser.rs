//! Parsing: tokens to AST, with learner-friendly syntax errors.
//!
//! The grammar lives in `grammar/scene.lalrpop`; lalrpop turns it into an
//! LR(1) table parser, which runs in a loop over an explicit stack, so deeply
//! nested input cannot overflow the call stack while parsing. lalrpop's
//! errors name grammar terminals; the `errors` submodule turns them into sentences.

// The public functions return the `Diagnostic` itself (the signatures are
// shared with the rest of the crate); a syntax error happens once per parse,
// so its size costs nothing that matters.

mod context;
mod errors;
mod order;

use lalrpop_util::{ParseError, lalrpop_mod};

use super::ast::{Instr, InstrKind, Item, Program};
use super::diagnostic::Diagnostic;
use super::lexer::{Lexer, Token};
use super::source::{SourceId, Span};
use context::{Read, Tracked};
use errors::Mode;

lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications)]
    grammar,
    "/scene.rs"
);

/// Parses a whole `.ray` file: camera, ambient, lights, procedures, then
/// instructions, in the order SPEC 2 gives.
pub fn parse_file(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    let program = parse(source, text, Mode::File)?;
    order::check(source, text, &program)?;
    Ok(program)
}

/// Parses one input of the interactive session: any items, in any order (SPEC 7).
pub fn parse_items(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    parse(source, text, Mode::Session)
}

/// Runs the generated parser over the tokens, recording what they open so
/// that a syntax error can say what is not closed.
fn parse(source: SourceId, text: &str, mode: Mode) -> Result<Program, Diagnostic> {
    parse_tokens(source, text, mode, Tracked::new(source, text))
}

/// Parses `text` from `tokens`, its tokens.
fn parse_tokens(source: SourceId, text: &str, mode: Mode, mut tokens: Tracked) -> Result<Program, Diagnostic> {
    let parsed = grammar::ItemsParser::new().parse(source, &mut tokens);
    match parsed {
        Ok(items) => Ok(Program { items }),
        Err(error) => Err(errors::syntax_error(source, text, mode, tokens.context(), error)),
    }
}

/// Appends the instruction of `kind` spanning `span` to `items` (the
/// grammar's action for a top-level instruction).
pub(crate) fn push_instr(mut items: Vec<Item>, kind: InstrKind, span: Span) -> Vec<Item> {
    items.push(Item::Instr(Instr { kind, span }));
    items
}

/// Appends the instruction of `kind` spanning `span` to a block.
pub(crate) fn push(mut instrs: Vec<Instr>, kind: InstrKind, span: Span) -> Vec<Instr> {
    instrs.push(Instr { kind, span });
    instrs
}

/// What a typed entry of the session is, so far.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntryState {
    /// It parses: submit it.
    Complete,
    /// Everything typed so far starts a valid input: read another line.
    Unfinished,
    /// No continuation can make it valid: report the error now, at the line
    /// that went wrong, instead of after the closing `end`.
    Broken,
}

/// Where the session's entry `text` stands. The grammar is LR(1), so it
/// stops at the first token that no valid input can have there: an error
/// at the end of the text means only that more is needed.
pub fn entry_state(text: &str) -> EntryState {
    let source = SourceId::default();
    match grammar::ItemsParser::new().parse(source, Lexer::new(source, text)) {
        Ok(_) => EntryState::Complete,
        Err(ParseError::UnrecognizedEof { .. }) => EntryState::Unfinished,
        Err(_) => EntryState::Broken,
    }
}

/// Whether `text` is an unfinished input that the session should continue on
/// the next line: a construct opened and not yet closed by `end`, or a line
/// ending in a binary operator or a comma.
///
/// More precisely: a construct (`camera`, `light`, `proc`, `sphere`, `plane`,
/// `box`, `translate`, `rotate`, `scale`, `group`, `if`) is still open, or a
/// `(` is, or the last token cannot end an input (an operator, `,`, `=`, `(`,
/// or a keyword that needs what follows, like `let` or `put`). Text with a
/// lexing error, or with an `end` or `)` that closes nothing, is complete:
/// submitting it shows the error at once instead of waiting for more lines.
pub fn is_incomplete(text: &str) -> bool {
    Entry::read(text).is_incomplete()
}

/// One entry of the session whose tokens were read to see whether it is
/// finished ([`is_incomplete`]), and kept for the parser: a script's input
/// is lexed once.
pub struct Entry<'t> {
    text: &'t str,
    incomplete: bool,
    /// The tokens of the whole text, unless reading stopped early (a lexing
    /// error, a stray closer): the parser then reads the text itself.
    tokens: Option<Vec<Read>>,
}

impl<'t> Entry<'t> {
    /// Reads the tokens of `text`.
    pub fn read(text: &'t str) -> Entry<'t> {
        let complete = Entry { text, incomplete: false, tokens: None };
        let mut tokens = Tracked::new(SourceId::default(), text);
        // Tokens take a few bytes each: one allocation instead of growing.
        let mut read = Vec::with_capacity(text.len() / 2);
        while let Some(token) = tokens.next_read() {
            let Ok(token) = token else {
                return complete;
            };
            if tokens.context().stray_closer {
                return complete;
            }
            read.push(token);
        }
        let context = tokens.context();
        let last = read.last().map(|(((_, token, _), _), _)| token);
        let incomplete = !context.stray_closer
            && (!context.open.is_empty() || !context.parens.is_empty() || last.is_some_and(needs_more));
        Entry { text, incomplete, tokens: Some(read) }
    }

    /// The entry's text.
    pub fn text(&self) -> &'t str {
        self.text
    }

    /// Whether the entry is unfinished, as [`is_incomplete`] says.
    pub fn is_incomplete(&self) -> bool {
        self.incomplete
    }

    /// Parses the entry as [`parse_items`] does, from the tokens read.
    pub fn parse(self, source: SourceId) -> Result<Program, Diagnostic> {
        match self.tokens {
            Some(read) => parse_tokens(source, self.text, Mode::Session, Tracked::replay(source, read)),
            None => parse_items(source, self.text),
        }
    }
}

/// Whether an input cannot end with `token`.
fn needs_more(token: &Token) -> bool {
    match token {
        Token::Number(_) | Token::Ident(_) | Token::End | Token::Pi | Token::RParen => false,
        // Every other keyword and symbol expects something after it.
        _ => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_constructs_are_incomplete() {
        assert!(is_incomplete("proc p()"));
        assert!(is_incomplete("put sphere center 0, 0, 0 radius 1"));
        assert!(is_incomplete("if a < 1 then\n  put s\nelse"));
        assert!(!is_incomplete("proc p() put s end"));
    }

    #[test]
    fn trailing_operators_and_parens_are_incomplete() {
        for text in ["let x = 1 +", "let x =", "p(1,", "let x = (1", "let x = sin(", "ambient"] {
            assert!(is_incomplete(text), "{text}");
        }
        assert!(!is_incomplete("let x = (1)"));
        assert!(!is_incomplete("let x = 1 # +"));
    }

    #[test]
    fn entries_are_broken_as_soon_as_no_continuation_can_fix_them() {
        assert_eq!(entry_state("proc p()\n  put ball"), EntryState::Unfinished);
        assert_eq!(entry_state("proc p()\n  put ball\nend"), EntryState::Complete);
        assert_eq!(entry_state("proc p()\n  put sphre radius 1"), EntryState::Broken);
        assert_eq!(entry_state("let x = 1 +"), EntryState::Unfinished);
        assert_eq!(entry_state("let x = 1 $"), EntryState::Broken);
        assert_eq!(entry_state("end"), EntryState::Broken);
        assert_eq!(entry_state(""), EntryState::Complete);
    }

    #[test]
    fn an_entry_parses_from_its_tokens_as_its_text_does() {
        let texts = [
            "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end",
            "let x = (1 +\n 2) let y = x",
            "proc p(a)\n  put a\n",
            "proc p(a)\n  if a < 1 then\n    put b\n  end\nend end",
            "let = 2",
            "let x = 1 $",
            "end",
        ];
        for text in texts {
            let parsed = Entry::read(text).parse(SourceId(3));
            assert_eq!(format!("{parsed:?}"), format!("{:?}", parse_items(SourceId(3), text)), "{text}");
        }
    }

    #[test]
    fn stray_closers_and_bad_characters_are_complete() {
        assert!(!is_incomplete("end"));
        assert!(!is_incomplete("let x = 1) + ("));
        assert!(!is_incomplete("proc p() $"));
        assert!(!is_incomplete(""));
    }
}
