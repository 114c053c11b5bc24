//! The line editor's helper: when an input goes on to the next line,
//! completion, and colours.
//!
//! rustyline has no continuation prompt, so the session reads an unfinished
//! input one line at a time, each with a prompt naming what is still open
//! (`...sphere> `). The validator handles the other case: a buffer that
//! already holds several lines (recalled from history, or pasted without a
//! line end at its end, to be edited) stays in the editor, and Enter adds a
//! line, until it is complete. A paste that ends with a line end is taken
//! line by line, as typed (`vendor/README.md`).

use std::borrow::Cow;

use rustyline::completion::{Completer, FilenameCompleter, Pair};
use rustyline::highlight::{CmdKind, Highlighter};
use rustyline::hint::{Hinter, HistoryHinter};
use rustyline::validate::{ValidationContext, ValidationResult, Validator};
use rustyline::{Context, Helper};

use crate::ide::commands::{self, is_command};
use crate::ide::completion;
use crate::ide::names::Vocabulary;
use crate::ide::scanner::{PieceKind, pieces};
use crate::lang::{EntryState, entry_state};

/// Lines longer than this are neither coloured nor hinted: either one makes
/// rustyline repaint the whole line at every key, so a long pasted line
/// would take seconds.
const MAX_DECORATED: usize = 1000;

/// The rustyline helper of the session.
pub(crate) struct RayHelper {
    color: bool,
    /// The lines of the current input entered so far (empty at the first line).
    pending: String,
    /// Names defined by the session, for completion.
    vocabulary: Vocabulary,
    files: FilenameCompleter,
}

impl RayHelper {
    /// A helper; `color` turns syntax colouring on.
    pub(crate) fn new(color: bool) -> RayHelper {
        RayHelper { color, pending: String::new(), vocabulary: Vocabulary::default(), files: FilenameCompleter::new() }
    }

    /// Tells the helper the lines of the current input entered so far.
    pub(crate) fn set_pending(&mut self, pending: &str) {
        pending.clone_into(&mut self.pending);
    }

    /// Refreshes the names offered by completion.
    pub(crate) fn set_names(&mut self, vocabulary: &Vocabulary) {
        self.vocabulary.clone_from(vocabulary);
    }

    fn complete_command(&self, line: &str, pos: usize, ctx: &Context<'_>) -> rustyline::Result<(usize, Vec<Pair>)> {
        match completion::complete_command(&line[..pos]) {
            Some((start, candidates)) => Ok((start, candidates.into_iter().map(pair).collect())),
            None => self.files.complete(line, pos, ctx),
        }
    }

    /// Completes the word before `pos` with what may come there
    /// ([`completion::complete`]).
    fn complete_word(&self, line: &str, pos: usize) -> (usize, Vec<Pair>) {
        // A line after the first may be anywhere inside a construct.
        let (start, candidates) = completion::complete(&line[..pos], !self.pending.is_empty(), &self.vocabulary);
        (start, candidates.into_iter().map(pair).collect())
    }
}

/// A completion as the line editor lists it.
fn pair(candidate: completion::Candidate) -> Pair {
    Pair { display: candidate.display, replacement: candidate.replacement }
}

impl Completer for RayHelper {
    type Candidate = Pair;

    fn complete(&self, line: &str, pos: usize, ctx: &Context<'_>) -> rustyline::Result<(usize, Vec<Pair>)> {
        if is_command(line) {
            return self.complete_command(line, pos, ctx);
        }
        Ok(self.complete_word(line, pos))
    }
}

/// Fish-style hints: the rest of the latest history entry that starts with
/// the line typed, in grey after the cursor (→ or End takes it), up to the
/// end of that entry's line; none where line and hint would be longer than
/// [`MAX_DECORATED`] (each key repaints a hinted line).
impl Hinter for RayHelper {
    type Hint = String;

    fn hint(&self, line: &str, pos: usize, ctx: &Context<'_>) -> Option<String> {
        if line.len() > MAX_DECORATED {
            return None;
        }
        let hint = HistoryHinter::new().hint(line, pos, ctx)?;
        let first_line = hint.split('\n').next().unwrap_or_default();
        let fits = !first_line.is_empty() && line.len() + first_line.len() <= MAX_DECORATED;
        fits.then(|| first_line.to_string())
    }
}

impl Validator for RayHelper {
    fn validate(&self, ctx: &mut ValidationContext<'_>) -> rustyline::Result<ValidationResult> {
        let input = ctx.input();
        let several_lines = input.trim_end().contains('\n');
        if !several_lines || is_command(input) {
            return Ok(ValidationResult::Valid(None));
        }
        let whole = if self.pending.is_empty() { input.to_string() } else { format!("{}\n{input}", self.pending) };
        let unfinished = entry_state(&whole) == EntryState::Unfinished;
        Ok(if unfinished { ValidationResult::Incomplete } else { ValidationResult::Valid(None) })
    }
}

impl Highlighter for RayHelper {
    fn highlight<'l>(&self, line: &'l str, _pos: usize) -> Cow<'l, str> {
        if !self.color || line.len() > MAX_DECORATED {
            return Cow::Borrowed(line);
        }
        Cow::Owned(colorize(line))
    }

    fn highlight_prompt<'b, 's: 'b, 'p: 'b>(&'s self, prompt: &'p str, _default: bool) -> Cow<'b, str> {
        if !self.color {
            return Cow::Borrowed(prompt);
        }
        // A continuation prompt (`...sphere> `) in yellow, the first one in green.
        let code = if self.pending.is_empty() { "1;32" } else { "33" };
        Cow::Owned(format!("\x1b[{code}m{prompt}\x1b[0m"))
    }

    fn highlight_hint<'h>(&self, hint: &'h str) -> Cow<'h, str> {
        if self.color { Cow::Owned(format!("\x1b[2m{hint}\x1b[0m")) } else { Cow::Borrowed(hint) }
    }

    /// Whether a key calls for the whole line to be drawn again. Without
    /// that, rustyline writes just the key typed at the end of the line; with
    /// it, a pasted line of n characters costs n repaints of up to n each.
    fn highlight_char(&self, line: &str, _pos: usize, kind: CmdKind) -> bool {
        self.color && line.len() <= MAX_DECORATED && kind != CmdKind::MoveCursor
    }
}

impl Helper for RayHelper {}

/// `line` with ANSI colours: keywords, built-ins, numbers, comments and
/// commands (those described in [`commands`]: a misspelt one stays plain).
pub(crate) fn colorize(line: &str) -> String {
    let mut out = String::with_capacity(line.len() * 2);
    for piece in pieces(line) {
        let text = &line[piece.start..piece.end];
        let code = match piece.kind {
            PieceKind::Keyword => Some("1;34"),
            PieceKind::Builtin => Some("36"),
            PieceKind::Number => Some("33"),
            PieceKind::Comment => Some("2;37"),
            PieceKind::Command if commands::find(text).is_some() => Some("1;32"),
            PieceKind::Command => None,
            PieceKind::Ident | PieceKind::Other => None,
        };
        match code {
            Some(code) => out.push_str(&format!("\x1b[{code}m{text}\x1b[0m")),
            None => out.push_str(text),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rustyline::history::{DefaultHistory, History};

    fn complete(helper: &RayHelper, line: &str) -> (usize, Vec<String>) {
        let history = DefaultHistory::new();
        let ctx = Context::new(&history);
        let (start, pairs) = helper.complete(line, line.len(), &ctx).expect("completion does not fail");
        (start, pairs.into_iter().map(|p| p.display).collect())
    }

    #[test]
    fn commands_complete_after_a_colon() {
        let helper = RayHelper::new(false);
        let expected = [":render", ":reload", ":reset"].map(String::from).to_vec();
        assert_eq!(complete(&helper, ":re"), (0, expected));
        assert_eq!(complete(&helper, ":help sph"), (6, vec!["sphere".to_string()]));
    }

    #[test]
    fn keywords_and_defined_names_complete_in_program_text() {
        let mut helper = RayHelper::new(false);
        let (start, found) = complete(&helper, "put sph");
        assert_eq!((start, found), (4, vec!["sphere".to_string()]));
        helper.set_names(&Vocabulary {
            variables: vec!["spin".to_string(), "saucer".to_string(), "time".to_string()],
            objects: vec!["saucer".to_string()],
            procedures: vec![("spiral".to_string(), vec!["n".to_string(), "r".to_string()])],
        });
        let found = complete(&helper, "end sp").1;
        assert_eq!(found, ["sphere", "spin", "spiral(n, r)"].map(String::from));
        let found = complete(&helper, "let a = s").1;
        assert_eq!(found, ["sin(x)", "spin", "sqrt(x)"].map(String::from), "a number: no object, no keyword");
        assert_eq!(complete(&helper, "put s").1, ["saucer", "scale", "sphere"].map(String::from));
        assert_eq!(complete(&helper, "object o = translate s").1, ["saucer", "scale", "sphere"].map(String::from));
        assert_eq!(complete(&helper, "put sphere center 1, s").1, ["sin(x)", "spin", "sqrt(x)"].map(String::from));
        assert!(complete(&helper, "let s").1.is_empty(), "a new name");
        assert_eq!(complete(&helper, "let t = ti").1, vec!["time".to_string()]);
        assert_eq!(complete(&helper, "spir").1, vec!["spiral(n, r)".to_string()]);
    }

    #[test]
    fn tab_after_put_lists_shapes_transformations_and_objects() {
        let mut helper = RayHelper::new(false);
        helper.set_names(&Vocabulary {
            variables: vec!["ball".to_string(), "r".to_string()],
            objects: vec!["ball".to_string()],
            procedures: Vec::new(),
        });
        let (start, found) = complete(&helper, "put ");
        assert_eq!(start, 4);
        for expected in ["sphere", "plane", "box", "translate", "rotate", "scale", "group", "ball"] {
            assert!(found.iter().any(|f| f == expected), "{expected} in {found:?}");
        }
        assert!(!found.iter().any(|f| f == "r" || f == "put"), "{found:?}");
        let numbers = complete(&helper, "put sphere center 1, ").1;
        assert!(numbers.iter().any(|f| f == "r") && numbers.iter().any(|f| f == "sin(x)"), "{numbers:?}");
        assert!(complete(&helper, "").1.is_empty(), "no list of everything on an empty line");
    }

    #[test]
    fn the_start_of_an_instruction_offers_only_what_starts_one() {
        let mut helper = RayHelper::new(false);
        helper.set_names(&Vocabulary {
            variables: vec!["grey".to_string()],
            objects: Vec::new(),
            procedures: vec![("grid".to_string(), vec!["n".to_string()])],
        });
        assert_eq!(complete(&helper, "gr").1, ["grid(n)"].map(String::from), "`group` cannot start one");
        assert_eq!(complete(&helper, "  pu").1, ["put"].map(String::from));
        assert_eq!(complete(&helper, "li").1, ["light"].map(String::from));
        assert_eq!(complete(&helper, "if 1 < 2 then gr").1, ["grid(n)"].map(String::from));
        assert_eq!(complete(&helper, "put gr").1, ["group"].map(String::from));
        helper.set_pending("put rotate");
        assert!(complete(&helper, "gr").1.contains(&"group".to_string()), "inside an open construct");
    }

    #[test]
    fn hints_come_from_history_one_line_at_a_time() {
        let helper = RayHelper::new(false);
        let mut history = DefaultHistory::new();
        history.add("put sphere center 0, 0, 0 radius 1\n  kd 1 ks 0 phong 1 color 255, 0, 0 end").unwrap();
        history.add("let radius = 2").unwrap();
        let ctx = Context::new(&history);
        assert_eq!(helper.hint("let r", 5, &ctx).as_deref(), Some("adius = 2"));
        assert_eq!(helper.hint("put s", 5, &ctx).as_deref(), Some("phere center 0, 0, 0 radius 1"));
        assert_eq!(helper.hint("let radius = 2", 14, &ctx), None);
        assert_eq!(helper.hint("let r", 2, &ctx), None, "only at the end of the line");
    }

    #[test]
    fn colours_keep_the_text() {
        let line = "put sphere # ball";
        let painted = colorize(line);
        assert!(painted.contains("\x1b[1;34mput\x1b[0m"));
        let stripped: String =
            painted.split('\x1b').map(|part| part.split_once('m').map_or(part, |(_, rest)| rest)).collect();
        assert_eq!(stripped, line);
    }
}
