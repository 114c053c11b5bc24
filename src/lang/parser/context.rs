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

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::lang::diagnostic::Diagnostic;
use crate::lang::lexer::{Lexer, Spanned};
use crate::lang::source::{SourceId, Span};
use crate::lang::token::Token;
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
    /// For an `if` with an `else if`: the `end` that closed the inner
    /// `if`, after which this one's own `end` most likely belongs.
    pub else_if_end: Option<Span>,
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

/// A token handed to the parser, as the bookkeeping needs it: plain data,
/// cheap to keep for every token (the text at `span` tells the token).
#[derive(Debug, Clone, Copy)]
struct Handed {
    span: Span,
    class: Class,
    /// Its row of the words table, for a keyword.
    word: Option<&'static Word>,
    /// Where its line starts.
    line_start: usize,
}

/// What the bookkeeping does with a token, copied out of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    End,
    Else,
    If,
    Proc,
    By,
    LParen,
    RParen,
    Ident,
    /// A keyword followed by a triple, with the triple's name.
    Triple(&'static str),
    Other,
}

impl Class {
    fn of(token: &Token) -> Class {
        match token {
            Token::End => Class::End,
            Token::Else => Class::Else,
            Token::If => Class::If,
            Token::Proc => Class::Proc,
            Token::By => Class::By,
            Token::LParen => Class::LParen,
            Token::RParen => Class::RParen,
            Token::Ident(_) => Class::Ident,
            Token::Center => Class::Triple("the centre"),
            Token::Length => Class::Triple("the lengths"),
            Token::Rotation | Token::Vector => Class::Triple("the rotation"),
            Token::Color => Class::Triple("the colour"),
            _ => Class::Other,
        }
    }
}

/// How many of the last tokens are kept: the one the parser stopped at, the
/// two before it, and one more for a round number.
const RECENT: usize = 4;

/// What the tokens before the current one leave open.
#[derive(Debug, Default)]
pub(super) struct Context {
    /// Constructs opened and not yet closed, innermost last.
    pub open: Vec<Open>,
    /// Parentheses opened and not yet closed, innermost last, each with the
    /// keyword before it (`sqrt` in `sqrt(`).
    pub parens: Vec<(Span, Option<&'static Word>)>,
    /// The name of the triple being read, if any ("the centre").
    pub triple: Option<&'static str>,
    /// The first `end`s that lined up with an outer construct.
    pub misclosed: Vec<Misclosed>,
    /// Whether an `end` or a `)` closed nothing.
    pub stray_closer: bool,
    /// The last tokens handed to the parser: token number `n` in slot `n % RECENT`.
    recent: [Option<Handed>; RECENT],
    /// How many tokens were handed to the parser, and how many of them are
    /// taken into account (all but the last, or all at the end of the text).
    handed: usize,
    counted: usize,
    /// Where the line of the last token counted starts, and its indentation
    /// (the column of its first token).
    line_start: usize,
    line_indent: usize,
}

impl Context {
    /// Where the last token taken into account is.
    pub(super) fn previous(&self) -> Option<Span> {
        self.counted_back(1).map(|handed| handed.span)
    }

    /// Where the token before [`Context::previous`] is.
    pub(super) fn before_previous(&self) -> Option<Span> {
        self.counted_back(2).map(|handed| handed.span)
    }

    /// The token `back` places before the next one to take into account.
    fn counted_back(&self, back: usize) -> Option<Handed> {
        let number = self.counted.checked_sub(back)?;
        self.recent[number % RECENT]
    }

    /// Keeps the token just handed to the parser, to take into account when
    /// the next one is.
    fn hand(&mut self, handed: Handed) {
        self.recent[self.handed % RECENT] = Some(handed);
        self.handed += 1;
    }

    /// Takes the tokens handed to the parser into account.
    fn count_handed(&mut self) {
        while self.counted < self.handed {
            self.count_next();
        }
    }

    /// Takes the next token handed to the parser into account.
    fn count_next(&mut self) {
        let Some(Handed { span, class, word, line_start }) = self.recent[self.counted % RECENT] else { return };
        let before = self.counted_back(1);
        let word_before = before.and_then(|handed| handed.word);
        let before = before.map(|handed| handed.class);
        self.counted += 1;
        let first_on_line = line_start != self.line_start || before.is_none();
        self.line_start = line_start;
        let column = first_on_line.then(|| (span.start as usize).saturating_sub(line_start));
        if let Some(column) = column {
            self.line_indent = column;
            self.new_line(class, span, column);
        }
        match class {
            Class::End => self.close(span, column),
            Class::LParen => self.parens.push((span, word_before)),
            Class::RParen => self.stray_closer |= self.parens.pop().is_none(),
            Class::Ident if before == Some(Class::Proc) => {
                if let Some(open) = self.open.last_mut() {
                    open.name = Some(span);
                }
            }
            _ => {}
        }
        let Some(word) = word else { return };
        if word.opens() {
            self.open(word, class == Class::If && before == Some(Class::Else), span);
        }
        self.triple = match class {
            Class::Triple(name) => Some(name),
            Class::By => match self.open.last().map(|open| open.word.text) {
                Some("translate") => Some("the vector"),
                Some("rotate") => Some("the rotation"),
                _ => None,
            },
            _ if matches!(word.role(), Some(Role::Function | Role::Constant)) => self.triple,
            _ => None,
        };
    }

    /// Notes, for the open constructs, the first token of a new line at `column`.
    fn new_line(&mut self, class: Class, span: Span, column: usize) {
        for open in self.open.iter_mut().rev() {
            if open.body_indented.is_some() {
                break;
            }
            open.body_indented = Some(column > open.indent);
        }
        if matches!(class, Class::End | Class::Else) {
            return;
        }
        for open in self.open.iter_mut().rev() {
            if open.dedent.is_some() || open.indent < column {
                break;
            }
            open.dedent = Some(span);
        }
    }

    /// Opens the construct of `word` at `span`; `after_else` for an `if`
    /// written right after `else`.
    fn open(&mut self, word: &'static Word, after_else: bool, span: Span) {
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
            else_if_end: None,
        });
    }

    /// Closes the innermost construct with the `end` at `span`, which starts
    /// its line at `column` if it starts one.
    fn close(&mut self, span: Span, column: Option<usize>) {
        let Some(closed) = self.open.pop() else {
            self.stray_closer = true;
            return;
        };
        if closed.after_else
            && let Some(outer) = self.open.last_mut()
        {
            outer.else_if_end = Some(span);
        }
        let Some(column) = column.filter(|column| *column < closed.indent) else { return };
        let Some(outer) = self.open.iter().rev().take(LOOKBACK).find(|open| open.indent == column) else { return };
        let repeated = self.misclosed.last().is_some_and(|last| last.meant_for.span == outer.span);
        if !repeated && self.misclosed.len() < MISCLOSED_KEPT {
            self.misclosed.push(Misclosed { construct: closed, end: span, meant_for: outer.clone() });
        }
    }

    /// The construct that most plausibly lacks its `end`: the innermost open
    /// one, unless an `end` lined up with it closed an inner construct
    /// instead; then that inner one.
    pub(super) fn blame(&self) -> Option<Blame<'_>> {
        let innermost = self.open.last()?;
        let misclosed = self.misclosed.iter().find(|misclosed| misclosed.meant_for.span == innermost.span);
        Some(misclosed.map_or(Blame::Unclosed(innermost), Blame::Misclosed))
    }
}

/// The lexer's tokens, as the parser reads them, recorded in a [`Context`].
pub(super) struct Tracked<'t> {
    lexer: Lexer<'t>,
    source: SourceId,
    context: Context,
    /// Raised by Ctrl-C: the tokens end in an error (a long file stops).
    pub(super) interrupt: Option<&'t AtomicBool>,
    /// Where the line of the last token starts, for a thread that waits
    /// for this parse ([`super::parse_items_apart`]).
    pub(super) reached: Option<&'t AtomicUsize>,
}

impl<'t> Tracked<'t> {
    /// The tokens of `text`, whose spans name `source`.
    pub(super) fn new(source: SourceId, text: &'t str) -> Tracked<'t> {
        Tracked { lexer: Lexer::new(source, text), source, context: Context::default(), interrupt: None, reached: None }
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
        self.context.count_handed();
        if self.interrupt.is_some_and(|flag| flag.load(Ordering::Relaxed)) {
            return Some(Err(Box::new(super::stopped_reading(self.source, self.lexer.line_start()))));
        }
        if let Some(reached) = self.reached {
            reached.store(self.lexer.line_start(), Ordering::Relaxed);
        }
        let result = match self.lexer.next_word()? {
            Ok(((start, token, end), word)) => {
                let span = Span::new(self.source, start, end);
                let line_start = self.lexer.line_start();
                self.context.hand(Handed { span, class: Class::of(&token), word, line_start });
                Ok((start, token, end))
            }
            Err(error) => Err(error),
        };
        Some(result)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The context after reading all of `text`.
    fn context_of(text: &str) -> Context {
        let mut tokens = Tracked::new(SourceId(0), text);
        while tokens.next().is_some() {}
        tokens.context
    }

    fn at(text: &str, span: Span) -> &str {
        &text[span.start as usize..span.end as usize]
    }

    #[test]
    fn open_constructs_know_their_line_indentation_and_name() {
        let text = "proc ring(n)\n  put group\n    sphere";
        let context = context_of(text);
        let open: Vec<(&str, usize)> = context.open.iter().map(|open| (open.word.text, open.indent)).collect();
        assert_eq!(open, [("proc", 0), ("group", 2), ("sphere", 4)]);
        assert_eq!(context.open[0].name.map(|name| at(text, name)), Some("ring"));
        assert_eq!(context.open[0].body_indented, Some(true));
    }

    #[test]
    fn an_end_lined_up_with_an_outer_construct_blames_the_inner_one() {
        let text = "proc p()\n  if a < 1 then\n    put s\n  put t\nend\n";
        let context = context_of(text);
        let Some(Blame::Misclosed(misclosed)) = context.blame() else { panic!("{:?}", context.blame()) };
        assert_eq!(misclosed.construct.word.text, "if");
        assert_eq!(misclosed.meant_for.word.text, "proc");
        assert_eq!(at(text, misclosed.end), "end");
        assert_eq!(misclosed.construct.dedent.map(|span| at(text, span)), Some("put"));
        assert_eq!(misclosed.construct.dedent.map(|span| span.start), Some(37));
    }

    #[test]
    fn an_end_lined_up_with_its_own_construct_blames_the_innermost() {
        let context = context_of("proc p()\n  if a < 1 then\n    put s\n  end\n");
        assert!(matches!(context.blame(), Some(Blame::Unclosed(open)) if open.word.text == "proc"));
        let context = context_of("put group sphere");
        assert!(matches!(context.blame(), Some(Blame::Unclosed(open)) if open.word.text == "sphere"));
    }

    #[test]
    fn else_if_is_recorded_on_both_ifs() {
        let context = context_of("if a < 1 then\nelse if a < 2 then");
        let [outer, inner] = &context.open[..] else { panic!("two ifs open") };
        assert!(outer.else_if.is_some() && !outer.after_else);
        assert!(inner.after_else);
        let context = context_of("if a < 1 then\nelse if a < 2 then print 1 end\nprint 2");
        let [outer] = &context.open[..] else { panic!("the outer if open") };
        assert_eq!(outer.else_if_end.map(|end| end.start), Some(41), "the inner if's `end`");
    }

    #[test]
    fn stray_closers_are_noticed() {
        assert!(context_of("end").stray_closer);
        assert!(context_of("let x = 1)").stray_closer);
        assert!(!context_of("let x = (1)").stray_closer);
    }

    #[test]
    fn the_last_token_waits_until_the_next_is_asked_for() {
        let mut tokens = Tracked::new(SourceId(0), "let x");
        tokens.next();
        assert_eq!(tokens.context().previous(), None, "`let` is handed out, not yet counted");
        tokens.next();
        assert_eq!(tokens.context().previous().map(|span| span.start), Some(0));
        assert!(tokens.next().is_none());
        assert_eq!(tokens.context().previous().map(|span| span.start), Some(4));
        assert_eq!(tokens.context().before_previous().map(|span| span.start), Some(0));
    }
}
