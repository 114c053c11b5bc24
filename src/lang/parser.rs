//! Parsing: tokens to AST, with learner-friendly syntax errors.
//!
//! The grammar lives in `grammar/scene.lalrpop`; lalrpop turns it into an
//! LR(1) table parser, which runs in a loop over an explicit stack, so deeply
//! nested input cannot overflow the call stack while parsing. lalrpop's
//! errors name grammar terminals; the `errors` submodule turns them into sentences.

// The public functions return the `Diagnostic` itself (the signatures are
// shared with the rest of the crate); a syntax error happens once per parse,
// so its size costs nothing that matters.

mod errors;
mod order;

use lalrpop_util::{ParseError, lalrpop_mod};

use super::ast::{Instr, InstrKind, Item, Program};
use super::diagnostic::Diagnostic;
use super::lexer::{Lexer, Token};
use super::source::{SourceId, Span};

pub(crate) use order::ItemOrder;

lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications)]
    grammar,
    "/scene.rs"
);

/// Parses a whole `.ray` file: camera, ambient, lights, procedures, then
/// instructions, in the order SPEC 2 gives.
pub fn parse_file(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    parse_file_with_line_offset(source, text, 0)
}

/// Parses one input of the interactive session: any items, in any order (SPEC 7).
pub fn parse_items(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    parse_items_with_line_offset(source, text, 0)
}

/// Like [`parse_file`], for a text whose first line is line `line_offset + 1`
/// of what the user sees (see [`super::source::SourceFile::line_offset`]), so
/// that messages such as "opened at line 12" give the user's line numbers.
pub fn parse_file_with_line_offset(source: SourceId, text: &str, line_offset: usize) -> Result<Program, Diagnostic> {
    parse(source, text, &ItemOrder::file(source, text), line_offset)
}

/// Like [`parse_items`], for a text whose first line is line `line_offset + 1`.
pub fn parse_items_with_line_offset(source: SourceId, text: &str, line_offset: usize) -> Result<Program, Diagnostic> {
    parse(source, text, &ItemOrder::any(), line_offset)
}

/// Runs the generated parser over the lexer, then the end-of-file order check.
fn parse(source: SourceId, text: &str, order: &ItemOrder, line_offset: usize) -> Result<Program, Diagnostic> {
    let tokens = Lexer::new(source, text);
    match grammar::ItemsParser::new().parse(source, order, tokens) {
        Ok(items) => {
            order.check_end(text)?;
            Ok(Program { items })
        }
        Err(error) => Err(errors::syntax_error(source, text, line_offset, order, error)),
    }
}

/// Appends `item`, spanning `span`, to `items` if the file order allows it
/// here (the grammar's action for each completed item).
pub(crate) fn push_item(
    mut items: Vec<Item>,
    item: Item,
    order: &ItemOrder<'_>,
    span: Span,
) -> Result<Vec<Item>, ParseError<usize, Token, Box<Diagnostic>>> {
    order.check(&item, span).map_err(|error| ParseError::User { error })?;
    items.push(item);
    Ok(items)
}

/// Appends the instruction of `kind` spanning `span` to `items` (the
/// grammar's action for a top-level instruction).
pub(crate) fn push_instr(
    items: Vec<Item>,
    kind: InstrKind,
    order: &ItemOrder<'_>,
    span: Span,
) -> Result<Vec<Item>, ParseError<usize, Token, Box<Diagnostic>>> {
    push_item(items, Item::Instr(Instr { kind, span }), order, span)
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
    match grammar::ItemsParser::new().parse(source, &ItemOrder::any(), Lexer::new(source, text)) {
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
    let mut open_constructs = 0usize;
    let mut open_parens = 0usize;
    let mut last = None;
    for token in Lexer::new(SourceId::default(), text) {
        let Ok((_, token, _)) = token else {
            return false;
        };
        if opens_construct(&token) {
            open_constructs += 1;
        }
        match token {
            Token::End => match open_constructs.checked_sub(1) {
                Some(depth) => open_constructs = depth,
                None => return false,
            },
            Token::LParen => open_parens += 1,
            Token::RParen => match open_parens.checked_sub(1) {
                Some(depth) => open_parens = depth,
                None => return false,
            },
            _ => {}
        }
        last = Some(token);
    }
    open_constructs > 0 || open_parens > 0 || last.is_some_and(|token| needs_more(&token))
}

/// Whether `token` opens a construct that `end` closes.
pub(crate) fn opens_construct(token: &Token) -> bool {
    matches!(
        token,
        Token::Camera
            | Token::Light
            | Token::Proc
            | Token::Sphere
            | Token::Plane
            | Token::Box
            | Token::Translate
            | Token::Rotate
            | Token::Scale
            | Token::Group
            | Token::If
    )
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
    fn stray_closers_and_bad_characters_are_complete() {
        assert!(!is_incomplete("end"));
        assert!(!is_incomplete("let x = 1) + ("));
        assert!(!is_incomplete("proc p() $"));
        assert!(!is_incomplete(""));
    }
}
