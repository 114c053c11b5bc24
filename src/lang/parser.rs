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

use std::sync::atomic::{AtomicBool, AtomicUsize};

use lalrpop_util::{ParseError, lalrpop_mod};

use super::ast::{Cond, Instr, InstrKind, Item, Program};
use super::diagnostic::{Diagnostic, STOPPED_BY};
use super::lexer::{Lexer, Spanned};
use super::nesting::Nesting;
use super::source::{SourceId, Span};
use super::token::Token;
use super::words::Word;
use context::Tracked;
use errors::Mode;

lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications)]
    grammar,
    "/scene.rs"
);

/// Parses a whole `.ray` file: camera, ambient, lights, procedures, then
/// instructions, in the order SPEC 2 gives.
pub fn parse_file(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    parse_file_interruptible(source, text, None)
}

/// [`parse_file`], stopped with an error once `interrupt` is raised (Ctrl-C).
pub(crate) fn parse_file_interruptible(
    source: SourceId,
    text: &str,
    interrupt: Option<&'static AtomicBool>,
) -> Result<Program, Diagnostic> {
    let program = parse(source, text, Mode::File, interrupt)?;
    order::check(source, text, &program)?;
    Ok(program)
}

/// Parses one input of the interactive session: any items, in any order (SPEC 7).
pub fn parse_items(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    parse(source, text, Mode::Session, None)
}

/// [`parse_items`] of `text`, which `stop` ends once raised: a long `:load`
/// is parsed on a thread that Ctrl-C abandons (a syntax tree can move
/// between threads, its names being [`super::name::Name`]s), so that the
/// partial tree of a parse it stops (seconds of text) is freed there, not
/// while the session waits. `reached` follows where the line being read
/// starts, for the error the waiting thread gives then ([`stopped_reading`]).
pub(crate) fn parse_items_apart(
    source: SourceId,
    text: &str,
    stop: &AtomicBool,
    reached: &AtomicUsize,
) -> Result<Program, Diagnostic> {
    let mut tokens = Tracked::new(source, text);
    tokens.interrupt = Some(stop);
    tokens.reached = Some(reached);
    parse_tracked(source, text, Mode::Session, tokens)
}

/// The error of a parse of `source` stopped by Ctrl-C while it read the
/// line that starts at byte `line_start`.
pub(crate) fn stopped_reading(source: SourceId, line_start: usize) -> Diagnostic {
    let at = Span::new(source, line_start, line_start);
    let stopped = Diagnostic::error(at, format!("stopped by {STOPPED_BY} while reading")).with_code("interrupted");
    stopped.with_note("nothing of this input was kept")
}

/// Runs the generated parser over the tokens, recording what they open so
/// that a syntax error can say what is not closed.
fn parse(
    source: SourceId,
    text: &str,
    mode: Mode,
    interrupt: Option<&'static AtomicBool>,
) -> Result<Program, Diagnostic> {
    let mut tokens = Tracked::new(source, text);
    tokens.interrupt = interrupt;
    parse_tracked(source, text, mode, tokens)
}

/// Runs the generated parser over `tokens`, the tokens of `text`.
fn parse_tracked(source: SourceId, text: &str, mode: Mode, mut tokens: Tracked<'_>) -> Result<Program, Diagnostic> {
    let parsed = grammar::ItemsParser::new().parse(&Sources::One(source), &mut tokens);
    match parsed {
        Ok(items) => Ok(Program { items }),
        Err(error) => Err(errors::syntax_error(source, text, mode, tokens.context(), error)),
    }
}

/// What the byte offsets of a parse point into: one source text, or the
/// texts of several entries read as one, so that every span names its own
/// text.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Sources<'s> {
    /// One text, with its source.
    One(SourceId),
    /// The texts of `sources`, the byte `b` of the text at index `i` read
    /// at the offset `i << shift | b` (every text is shorter than
    /// `1 << shift`): a shift finds the text of an offset.
    Many { sources: &'s [SourceId], shift: u32 },
}

impl Sources<'_> {
    /// The span of the bytes `start..end`, in the text where `start` is (an
    /// `end` in a later text lies past the end of that one).
    pub(crate) fn span(&self, start: usize, end: usize) -> Span {
        match *self {
            Sources::One(source) => Span::new(source, start, end),
            Sources::Many { sources, shift } => {
                let index = start >> shift;
                let base = index << shift;
                Span::new(sources[index], start - base, end - base)
            }
        }
    }
}

/// Appends the instruction of `kind` spanning `span` to `items` (the
/// grammar's action for a top-level instruction).
pub(crate) fn push_instr(mut items: Vec<Item>, kind: InstrKind, span: Span) -> Vec<Item> {
    items.push(Item::Instr(Instr { kind, span }));
    items
}

/// The `if` of `cond` with its branches, without the room their lists kept
/// for more instructions: deeply nested `if`s would take four times the
/// memory (docs/language.md, section 10).
pub(crate) fn if_instr(cond: Cond, mut then: Vec<Instr>, mut otherwise: Option<Vec<Instr>>) -> InstrKind {
    then.shrink_to_fit();
    if let Some(otherwise) = &mut otherwise {
        otherwise.shrink_to_fit();
    }
    InstrKind::If(cond, then, otherwise)
}

/// Appends the instruction of `kind` spanning `span` to a block.
pub(crate) fn push(mut instrs: Vec<Instr>, kind: InstrKind, span: Span) -> Vec<Instr> {
    instrs.push(Instr { kind, span });
    instrs
}

/// What an entry of the session or of a script is, so far.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntryState {
    /// It parses: submit it.
    Complete,
    /// Everything typed so far starts a valid input: read another line.
    Unfinished,
    /// No continuation can make it valid: report the error now, at the line
    /// that went wrong, instead of after the closing `end`.
    Broken,
    /// Broken by the first token of its last line where an `end` was
    /// wanted, that line being one that can start an entry of its own (`put
    /// sphere ...` after a sphere left without its `end`): the error is
    /// reported with that line, as [`Broken`] is, then the line is read
    /// again as the first line of the next entry.
    ///
    /// [`Broken`]: EntryState::Broken
    BrokenBeforeLastLine,
}

/// Where the entry `text` stands, its last line having just been added;
/// the interactive session and scripts cut their entries by it. The
/// grammar is LR(1), so it stops at the first token that no valid input
/// can have there: an error at the end of the text means only that more is
/// needed.
pub fn entry_state(text: &str) -> EntryState {
    let source = SourceId::default();
    let refused = match grammar::ItemsParser::new().parse(&Sources::One(source), Lexer::new(source, text)) {
        Ok(_) => return EntryState::Complete,
        Err(ParseError::UnrecognizedEof { .. }) => return EntryState::Unfinished,
        // Only a forgotten `end` is cut off: where `end` was wanted, the
        // construct before could have been over (a `then` forgotten is not).
        Err(ParseError::UnrecognizedToken { token: (start, ..), expected })
            if expected.iter().any(|name| name == "\"end\"") =>
        {
            start
        }
        Err(_) => return EntryState::Broken,
    };
    let Some(last_line) = text.rfind('\n').map(|newline| newline + 1) else { return EntryState::Broken };
    let starts_last_line = refused >= last_line && text[last_line..refused].trim().is_empty();
    if starts_last_line && entry_state(&text[last_line..]) != EntryState::Broken {
        EntryState::BrokenBeforeLastLine
    } else {
        EntryState::Broken
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
    Entry::read(text.to_string()).is_incomplete()
}

/// The longest entry whose every line is parsed again to see whether it
/// is broken ([`Entry::state`]): a longer one would cost time quadratic in
/// its length (a procedure of 20,000 lines, minutes).
pub const MOST_CHECKED_BYTES: usize = 64 << 10;

/// One entry of the session whose tokens were read to see whether it is
/// finished ([`is_incomplete`]), and kept for the parser: a script's input
/// is lexed once, and a line added to it is lexed alone.
pub struct Entry {
    text: String,
    /// The tokens of the whole text, unless reading stopped early (a lexing
    /// error, a stray closer): the parser then reads the text itself.
    tokens: Option<Vec<Spanned>>,
    /// How many constructs and parentheses the tokens leave open.
    constructs: usize,
    parens: usize,
    /// How deeply they nest, to go on counting on the next line.
    nesting: Nesting,
}

impl Entry {
    /// Reads the tokens of `text`.
    pub fn read(text: String) -> Entry {
        // About a token for two bytes of text: one allocation instead of growing.
        let tokens = Some(Vec::with_capacity(text.len() / 2));
        let mut entry = Entry { text, tokens, constructs: 0, parens: 0, nesting: Nesting::default() };
        entry.read_from(0);
        entry
    }

    /// Adds `line` to the text and reads its tokens: no token spans two
    /// lines, so those before are the same.
    pub fn add_line(&mut self, line: &str) {
        self.text.push('\n');
        let start = self.text.len();
        self.text.push_str(line);
        self.read_from(start);
    }

    /// The entry's text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Whether the entry is unfinished, as [`is_incomplete`] says.
    pub fn is_incomplete(&self) -> bool {
        let last = self.tokens.as_ref().and_then(|tokens| tokens.last()).map(|(_, token, _)| token);
        self.tokens.is_some() && (self.constructs > 0 || self.parens > 0 || last.is_some_and(needs_more))
    }

    /// Where the entry stands, its last line having just been added, as
    /// [`entry_state`] says. An entry of one line that its tokens close
    /// is not parsed here: finished or broken, it is submitted either way.
    /// Nor is one longer than [`MOST_CHECKED_BYTES`]: it waits for its
    /// tokens to close what they open, as they say.
    pub fn state(&self) -> EntryState {
        let checked = self.text.len() <= MOST_CHECKED_BYTES && self.text.contains('\n');
        if checked {
            entry_state(&self.text)
        } else if self.tokens.is_none() {
            EntryState::Broken
        } else if !self.is_incomplete() {
            EntryState::Complete
        } else if self.text.len() <= MOST_CHECKED_BYTES {
            entry_state(&self.text)
        } else {
            EntryState::Unfinished
        }
    }

    /// Reads the tokens from byte `start` (where a line starts) on, unless
    /// reading stopped before (a lexing error, a stray closer). Counting the
    /// open constructs and parentheses is enough here; the parser's fuller
    /// record of them ([`Tracked`]) serves its errors, and an entry that
    /// does not parse is read again that way.
    fn read_from(&mut self, start: usize) {
        let Some(tokens) = &mut self.tokens else { return };
        let nesting = std::mem::take(&mut self.nesting);
        let mut lexer = Lexer::from_line(SourceId::default(), &self.text, start, nesting);
        while let Some(token) = lexer.next_word() {
            let Ok((spanned, word)) = token else {
                self.tokens = None;
                return;
            };
            let stray_closer = match spanned.1 {
                Token::End => self.constructs.checked_sub(1).map(|left| self.constructs = left).is_none(),
                Token::RParen => self.parens.checked_sub(1).map(|left| self.parens = left).is_none(),
                Token::LParen => {
                    self.parens += 1;
                    false
                }
                _ => {
                    self.constructs += usize::from(word.is_some_and(Word::opens));
                    false
                }
            };
            if stray_closer {
                self.tokens = None;
                return;
            }
            tokens.push(spanned);
        }
        self.nesting = lexer.take_nesting();
    }
}

/// Parses each of the finished `entries`, whose texts are the sources
/// `sources`, as [`parse_items`] does. Entries that came together are
/// parsed in one run of the parser, as one text: a parse has a cost of its
/// own (its stacks start empty). When that fails (a syntax error, or an
/// item reaching from one entry into the next) each is parsed on its own,
/// which says what is wrong where. The entries' tokens are used up.
pub fn parse_entries(entries: &mut [Entry], sources: &[SourceId]) -> Vec<Result<Program, Diagnostic>> {
    match parse_together(entries, sources) {
        Some(programs) => programs.into_iter().map(Ok).collect(),
        None => entries.iter().zip(sources).map(|(entry, &source)| parse_items(source, &entry.text)).collect(),
    }
}

/// The programs of `entries` parsed as one text, the entries one line
/// after the other; `None` if that text does not parse into items that
/// each lie inside one entry.
fn parse_together(entries: &mut [Entry], sources: &[SourceId]) -> Option<Vec<Program>> {
    let longest = entries.iter().map(|entry| entry.text.len()).max()?;
    let shift = (longest + 1).next_power_of_two().trailing_zeros();
    // Every offset, the ends of items across texts too, must fit a span.
    if shift >= u32::BITS || entries.len() > (u32::MAX >> shift) as usize {
        return None;
    }
    let mut tokens = Vec::with_capacity(entries.len());
    for (index, entry) in entries.iter_mut().enumerate() {
        tokens.push((index << shift, entry.tokens.take()?));
    }
    let shifted = tokens.into_iter().flat_map(|(base, read)| {
        read.into_iter().map(move |(start, token, end)| Ok((base + start, token, base + end)))
    });
    let items = grammar::ItemsParser::new().parse(&Sources::Many { sources, shift }, shifted).ok()?;
    // How many items each entry has, the items being in the entries' order.
    let mut counts = vec![0; entries.len()];
    let mut owner = 0;
    for item in &items {
        let span = item.span();
        owner += sources.get(owner..)?.iter().position(|&source| source == span.source)?;
        if span.end as usize > entries[owner].text.len() {
            return None;
        }
        counts[owner] += 1;
    }
    let mut items = items.into_iter();
    let programs = counts.into_iter().map(|count| Program { items: items.by_ref().take(count).collect() }).collect();
    Some(programs)
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

    /// A parse made apart crosses to another thread whole; raised, its
    /// stop flag ends it with the error of Ctrl-C at the line it was
    /// reading, which `reached` follows.
    #[test]
    fn a_parse_made_apart_is_run_elsewhere_or_stopped_at_its_line() {
        let text = "let a = 1\nproc p(x)\n  let y = x\nend\np(a)\n";
        let (stop, reached) = (AtomicBool::new(false), AtomicUsize::new(0));
        let parsed = parse_items_apart(SourceId(0), text, &stop, &reached);
        let program = std::thread::spawn(move || parsed).join().expect("parsed").expect("a program");
        assert_eq!(program, parse_items(SourceId(0), text).expect("a program"));
        assert_eq!(reached.load(std::sync::atomic::Ordering::Relaxed), text.find("p(a)").expect("there"));
        stop.store(true, std::sync::atomic::Ordering::Relaxed);
        let stopped = parse_items_apart(SourceId(0), text, &stop, &reached).expect_err("stopped");
        assert_eq!(stopped.code, "interrupted");
    }

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
    fn a_last_line_that_can_start_an_entry_is_cut_off_a_broken_one() {
        let sphere = "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0";
        assert_eq!(entry_state(&format!("{sphere}\n{sphere} end")), EntryState::BrokenBeforeLastLine);
        assert_eq!(entry_state(&format!("{sphere}\n  {sphere}")), EntryState::BrokenBeforeLastLine);
        // Not a forgotten `end`, but a forgotten `then`, or an operand.
        assert_eq!(entry_state("if 1 < 2\n  put ball"), EntryState::Broken);
        assert_eq!(entry_state("let x = 1 +\nprint 7"), EntryState::Broken);
        // The line cannot start an entry either: the error is in it.
        assert_eq!(entry_state("put sphere center 0, 0, 0\nraduis 1"), EntryState::Broken);
        assert_eq!(entry_state("proc p()\nend end"), EntryState::Broken);
        // The error is in the middle of the line.
        assert_eq!(entry_state("let x = (1 +\n2 let y = 3"), EntryState::Broken);
    }

    /// `parse_entries` of `texts` (ids 3, 4, ...) printed, and the same for
    /// `parse_items` of each text.
    fn together_and_alone(texts: &[&str]) -> (String, String) {
        let sources: Vec<SourceId> = (3..).map(SourceId).take(texts.len()).collect();
        let mut entries: Vec<Entry> = texts.iter().map(|text| Entry::read(text.to_string())).collect();
        let together = parse_entries(&mut entries, &sources);
        let alone: Vec<_> = texts.iter().zip(&sources).map(|(text, &source)| parse_items(source, text)).collect();
        (format!("{together:?}"), format!("{alone:?}"))
    }

    #[test]
    fn entries_parse_together_as_each_alone() {
        let texts = [
            "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end",
            "let x = (1 +\n 2) let y = x",
            "# a comment",
            "proc p(a)\n  if a < 1 then\n    put b\n  end\nend",
            "p(1)",
        ];
        let (together, alone) = together_and_alone(&texts);
        assert_eq!(together, alone);
    }

    #[test]
    fn entries_that_do_not_parse_together_parse_alone() {
        let cases: [&[&str]; 4] = [
            // Each is finished, but together they make one item.
            &["let x = 1", "+ 2"],
            &["let x = 1", "let = 2", "let y = 3"],
            &["let x = 1 $", "let y = 2"],
            &["let x = 1", "end"],
        ];
        for texts in cases {
            let (together, alone) = together_and_alone(texts);
            assert_eq!(together, alone, "{texts:?}");
        }
    }

    #[test]
    fn an_entry_read_line_by_line_reads_as_read_whole() {
        let texts = [
            "proc p(a)\n  put a # (\n  let x = (1 +\n 2)\nend",
            "let x = (\n1 $\n)",
            "proc p()\nend end\nlet y",
            "let x = 1\n\u{feff}let y = 2",
            "let x =\n\n  # nothing yet\n3",
        ];
        for text in texts {
            let mut lines = text.split('\n');
            let mut entry = Entry::read(lines.next().unwrap_or_default().to_string());
            for line in lines {
                entry.add_line(line);
                let whole = Entry::read(entry.text().to_string());
                let read = |entry: &Entry| (entry.is_incomplete(), format!("{:?}", entry.tokens));
                assert_eq!(read(&entry), read(&whole), "{}", entry.text());
            }
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
