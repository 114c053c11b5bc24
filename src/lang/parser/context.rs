//! What the tokens read so far leave open, recorded as the parser reads them,
//! so that a syntax error can say what is not closed and which construct
//! most plausibly lacks its `end`.
//!
//! [`Tracked`] hands the lexer's tokens to the parser and each one, a token
//! late, to its [`Context`]: when the parser stops at a token, the context
//! describes everything before that token. Indentation is a hint, as rustc
//! uses it for braces: an `end` at the column of an outer construct was
//! probably meant for that one, so the construct it closed instead is the
//! one whose `end` is missing.

use crate::lang::diagnostic::Diagnostic;
use crate::lang::lexer::{Lexer, Spanned, Token};
use crate::lang::source::{SourceId, Span};
use crate::lang::words::{Role, Word};

/// How many misplaced `end`s are remembered: the first ones tell the story.
const MISCLOSED_KEPT: usize = 32;

/// How far down the open constructs an `end` looks for the one it lines up with.
const LOOKBACK: usize = 64;

/// A construct opened and not yet closed by `end`.
#[derive(Debug, Clone)]
pub(super) struct Open {
    /// The keyword that opened it.
    pub word: &'static Word,
    /// Where that keyword is.
    pub span: Span,
    /// The procedure's name, for a `proc`.
    pub name: Option<Span>,
    /// The indentation of the line the construct starts on, in bytes.
    pub indent: usize,
    /// Whether the first line after the opening one is indented more than it.
    pub body_indented: Option<bool>,
    /// The first token starting a later line that is not indented more than
    /// the opening line: where the body seems to end.
    pub dedent: Option<Span>,
    /// For an `if`: the `if` written right after its `else` (`else if`).
    pub else_if: Option<Span>,
    /// Whether this is an `if` written right after `else`.
    pub after_else: bool,
}

/// An `end` that closed one construct while lined up with an outer one.
#[derive(Debug, Clone)]
pub(super) struct Misclosed {
    /// The construct the `end` closed, which probably lacks its own.
    pub construct: Open,
    /// The `end`.
    pub end: Span,
    /// The outer construct the `end` lines up with.
    pub meant_for: Open,
}

/// The construct a missing `end` is blamed on.
#[derive(Debug, Clone, Copy)]
pub(super) enum Blame<'c> {
    /// The innermost open construct.
    Unclosed(&'c Open),
    /// A construct that an `end` meant for an outer one closed.
    Misclosed(&'c Misclosed),
}

/// What the tokens before the current one leave open.
#[derive(Debug, Default)]
pub(super) struct Context {
    /// Constructs opened and not yet closed, innermost last.
    pub open: Vec<Open>,
    /// Parentheses opened and not yet closed, innermost last, each with the
    /// token before it (`sqrt` in `sqrt(`).
    pub parens: Vec<(Span, Option<Token>)>,
    /// The last token, and the one before it.
    pub previous: Option<(Token, Span)>,
    pub before_previous: Option<(Token, Span)>,
    /// The name of the triple being read, if any ("the centre").
    pub triple: Option<&'static str>,
    /// The first `end`s that lined up with an outer construct.
    pub misclosed: Vec<Misclosed>,
    /// Whether an `end` or a `)` closed nothing.
    pub stray_closer: bool,
    /// Where the line of the last token starts, its indentation (the
    /// column of its first token), and where the last token ends.
    line_start: usize,
    line_indent: usize,
    last_end: usize,
}

impl Context {
    /// Takes the token `token` at `span` of `text` into account; `word` is
    /// its row of the words table if it is a keyword.
    fn read(&mut self, token: Token, span: Span, word: Option<&'static Word>, text: &str) {
        let start = span.start as usize;
        let gap = text.get(self.last_end..start).unwrap_or("");
        let first_on_line = match gap.rfind('\n') {
            Some(newline) => {
                self.line_start = self.last_end + newline + 1;
                true
            }
            None => self.previous.is_none(),
        };
        self.last_end = span.end as usize;
        let column = first_on_line.then(|| start.saturating_sub(self.line_start));
        if let Some(column) = column {
            self.line_indent = column;
            self.new_line(&token, span, column);
        }
        match &token {
            Token::End => self.close(span, column),
            Token::LParen => {
                let before = self.previous.as_ref().map(|(token, _)| token.clone());
                self.parens.push((span, before));
            }
            Token::RParen => self.stray_closer |= self.parens.pop().is_none(),
            Token::Ident(_) if matches!(self.previous, Some((Token::Proc, _))) => {
                if let Some(open) = self.open.last_mut() {
                    open.name = Some(span);
                }
            }
            _ => {}
        }
        if let Some(word) = word {
            if word.opens() {
                self.open(word, &token, span);
            }
            if !matches!(word.role(), Some(Role::Function | Role::Constant)) {
                self.triple = self.triple_after(&token);
            }
        }
        self.before_previous = self.previous.take();
        self.previous = Some((token, span));
    }

    /// Notes, for the open constructs, the first token of a new line at `column`.
    fn new_line(&mut self, token: &Token, span: Span, column: usize) {
        for open in self.open.iter_mut().rev() {
            if open.body_indented.is_some() {
                break;
            }
            open.body_indented = Some(column > open.indent);
        }
        if matches!(token, Token::End | Token::Else) {
            return;
        }
        for open in self.open.iter_mut().rev() {
            if open.dedent.is_some() || open.indent < column {
                break;
            }
            open.dedent = Some(span);
        }
    }

    /// Opens the construct of `word` (the token `token`) at `span`.
    fn open(&mut self, word: &'static Word, token: &Token, span: Span) {
        let after_else = *token == Token::If && matches!(self.previous, Some((Token::Else, _)));
        if after_else && let Some(parent) = self.open.last_mut() {
            parent.else_if = Some(span);
        }
        self.open.push(Open {
            word,
            span,
            name: None,
            indent: self.line_indent,
            body_indented: None,
            dedent: None,
            else_if: None,
            after_else,
        });
    }

    /// Closes the innermost construct with the `end` at `span`, which starts
    /// its line at `column` if it starts one.
    fn close(&mut self, span: Span, column: Option<usize>) {
        let Some(closed) = self.open.pop() else {
            self.stray_closer = true;
            return;
        };
        let Some(column) = column.filter(|column| *column < closed.indent) else { return };
        let Some(outer) = self.open.iter().rev().take(LOOKBACK).find(|open| open.indent == column) else { return };
        let repeated = self.misclosed.last().is_some_and(|last| last.meant_for.span == outer.span);
        if !repeated && self.misclosed.len() < MISCLOSED_KEPT {
            self.misclosed.push(Misclosed { construct: closed, end: span, meant_for: outer.clone() });
        }
    }

    /// The name of the triple that follows `keyword`, if one does.
    fn triple_after(&self, keyword: &Token) -> Option<&'static str> {
        match keyword {
            Token::Center => Some("the centre"),
            Token::Length => Some("the lengths"),
            Token::Rotation | Token::Vector => Some("the rotation"),
            Token::Color => Some("the colour"),
            Token::By => match self.open.last().map(|open| open.word.text) {
                Some("translate") => Some("the vector"),
                Some("rotate") => Some("the rotation"),
                _ => None,
            },
            _ => None,
        }
    }

    /// The construct that most plausibly lacks its `end`: one closed by an
    /// `end` lined up with an outer construct that is still open, otherwise
    /// the innermost open one.
    pub(super) fn blame(&self) -> Option<Blame<'_>> {
        let still_open = |misclosed: &&Misclosed| self.open.iter().any(|open| open.span == misclosed.meant_for.span);
        match self.misclosed.iter().find(still_open) {
            Some(misclosed) => Some(Blame::Misclosed(misclosed)),
            None => self.open.last().map(Blame::Unclosed),
        }
    }
}

/// The lexer's tokens, as the parser reads them, recorded in a [`Context`].
pub(super) struct Tracked<'t> {
    lexer: Lexer<'t>,
    text: &'t str,
    source: SourceId,
    /// The token handed out last, taken into the context when the next one is asked for.
    pending: Option<(Token, Span, Option<&'static Word>)>,
    context: Context,
}

impl<'t> Tracked<'t> {
    /// The tokens of `text`, whose spans name `source`.
    pub(super) fn new(source: SourceId, text: &'t str) -> Tracked<'t> {
        Tracked { lexer: Lexer::new(source, text), text, source, pending: None, context: Context::default() }
    }

    /// What the tokens before the last one handed out leave open (all of
    /// them once the text is read to its end).
    pub(super) fn context(&self) -> &Context {
        &self.context
    }
}

impl Iterator for Tracked<'_> {
    type Item = Result<Spanned, Box<Diagnostic>>;

    fn next(&mut self) -> Option<Self::Item> {
        if let Some((token, span, word)) = self.pending.take() {
            self.context.read(token, span, word, self.text);
        }
        let result = match self.lexer.next_word()? {
            Ok(((start, token, end), word)) => {
                self.pending = Some((token.clone(), Span::new(self.source, start, end), word));
                Ok((start, token, end))
            }
            Err(error) => Err(error),
        };
        Some(result)
    }
}
