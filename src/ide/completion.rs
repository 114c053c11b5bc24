//! What may be typed where a word is being typed, for every editor of the
//! language (the session's line editor, the language server): the words
//! the grammar lets come there and the names defined, judged from the text
//! before the word.

use crate::lang::words::{self, Role};

use super::commands::{self, COMMANDS, Files, help_pages};
use super::help;
use super::names::Vocabulary;
use super::scanner::{is_word_char, word_start};

/// What the grammar lets come where a word is being typed, judged from the
/// word or sign just before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Slot {
    /// An object: after `put`, a transformation, `group`, `object NAME =`.
    Object,
    /// A number: after an operator, a comma, `(`, `let NAME =` or a part
    /// that takes numbers (`center`, `color`, ...).
    Number,
    /// A new name: after `let`, `object` or `proc`; nothing to complete.
    NewName,
    /// The start of an item: at the start of an entry, after `then` or
    /// `else`. Only what starts one (`put`, `light`, a call...).
    Start,
    /// Anything else.
    Any,
}

/// What a candidate is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CandidateKind {
    /// A word of the language (`sphere`, `put`).
    Keyword,
    /// A function of the language (`sin`), with its parenthesis.
    Function,
    /// A number defined by the program.
    Number,
    /// An object defined by the program.
    Object,
    /// A procedure defined by the program, with its parenthesis.
    Procedure,
    /// A command, or a help page's name after `:help`.
    Command,
}

/// One completion: what the list shows, and what replaces the word typed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Candidate {
    /// Shown in the list (`spiral(n, r)`).
    pub display: String,
    /// Put in place of the word typed (`spiral(`).
    pub replacement: String,
    /// What it is.
    pub kind: CandidateKind,
}

/// The slot of the word being typed after `before`.
fn slot(before: &str) -> Slot {
    let before = before.trim_end();
    let Some(last) = before.chars().next_back() else { return Slot::Start };
    if !is_word_char(last) {
        let head = &before[..before.len() - last.len_utf8()];
        let defines_object = last == '=' && head.split_whitespace().rev().nth(1) == Some("object");
        return match last {
            '=' if defines_object => Slot::Object,
            ')' => Slot::Any,
            _ => Slot::Number,
        };
    }
    let word = &before[word_start(before)..];
    match (word, words::lookup(word).and_then(words::Word::role)) {
        ("let" | "object" | "proc", _) => Slot::NewName,
        ("put", _) | (_, Some(Role::Transformation)) => Slot::Object,
        ("then" | "else", _) => Slot::Start,
        ("end", _) => Slot::Any,
        ("if" | "print", _) | (_, Some(Role::Part | Role::Texture)) => Slot::Number,
        _ => Slot::Any,
    }
}

/// The completions of the word that ends `before` (where it starts, and
/// the candidates, sorted): after `put` only objects, after `color` only
/// numbers, and so on. With nothing typed yet, it lists them where they
/// are few enough to read (an object or a number), and nothing elsewhere.
/// `inside` says that `before` is a line inside an unfinished construct
/// whose start is not in it: there, a line's start is not an item's.
pub fn complete(before: &str, inside: bool, vocabulary: &Vocabulary) -> (usize, Vec<Candidate>) {
    let start = word_start(before);
    let typed = &before[start..];
    let slot = match slot(&before[..start]) {
        Slot::Start if before[..start].trim().is_empty() && inside => Slot::Any,
        slot => slot,
    };
    if typed.is_empty() && !matches!(slot, Slot::Object | Slot::Number) {
        return (start, Vec::new());
    }
    let is_object = |name: &String| vocabulary.objects.contains(name);
    let named = |name: &String, kind| Candidate { display: name.clone(), replacement: name.clone(), kind };
    let objects =
        vocabulary.variables.iter().filter(|name| is_object(name)).map(|name| named(name, CandidateKind::Object));
    let numbers =
        vocabulary.variables.iter().filter(|name| !is_object(name)).map(|name| named(name, CandidateKind::Number));
    let procedures = vocabulary.procedures.iter().map(|(name, params)| Candidate {
        display: format!("{name}({})", params.join(", ")),
        replacement: format!("{name}("),
        kind: CandidateKind::Procedure,
    });
    let language = words::language();
    let candidates: Vec<Candidate> = match slot {
        Slot::NewName => Vec::new(),
        Slot::Start => {
            let starts = language.filter(|word| matches!(word.role(), Some(Role::Definition | Role::Instruction)));
            starts.map(keyword_candidate).chain(procedures).collect()
        }
        Slot::Object => {
            let shapes = language.filter(|word| matches!(word.role(), Some(Role::Shape | Role::Transformation)));
            shapes.map(keyword_candidate).chain(objects).collect()
        }
        Slot::Number => {
            let values = language.filter(|word| matches!(word.role(), Some(Role::Function | Role::Constant) | None));
            values.map(keyword_candidate).chain(numbers).collect()
        }
        Slot::Any => language.map(keyword_candidate).chain(objects).chain(numbers).chain(procedures).collect(),
    };
    let mut candidates: Vec<Candidate> =
        candidates.into_iter().filter(|candidate| candidate.replacement.starts_with(typed)).collect();
    candidates.sort_by(|a, b| a.display.cmp(&b.display));
    candidates.dedup_by(|a, b| a.display == b.display);
    (start, candidates)
}

/// The completions on a command's line, `before` being the line up to the
/// place asked about: the commands' names while the first word is typed,
/// the help pages' names after `:help`, nothing after the other commands;
/// `None` after a command that takes a file (the front-end lists files).
pub fn complete_command(before: &str) -> Option<(usize, Vec<Candidate>)> {
    let start = before.len() - before.trim_start().len();
    let command = |display: &str, replacement: String| Candidate {
        display: display.to_string(),
        replacement,
        kind: CandidateKind::Command,
    };
    let Some(command_end) = before[start..].find(char::is_whitespace).map(|i| start + i) else {
        let typed = &before[start..];
        let names = COMMANDS.iter().map(|command| command.topic.name).filter(|name| name.starts_with(typed));
        return Some((start, names.map(|name| command(name, format!("{name} "))).collect()));
    };
    match commands::find(&before[start..command_end]) {
        Some(found) if found.files != Files::None => None,
        Some(found) if found.topic.name == ":help" => {
            let word_start = word_start(before);
            let typed = &before[word_start..];
            let mut topics: Vec<&str> = help::all_names(&help_pages()).filter(|name| name.starts_with(typed)).collect();
            topics.sort_unstable();
            topics.dedup();
            Some((word_start, topics.into_iter().map(|name| command(name, name.to_string())).collect()))
        }
        _ => Some((before.len(), Vec::new())),
    }
}

/// A word of the language followed by a space, or a function with its parenthesis.
fn keyword_candidate(word: &words::Word) -> Candidate {
    let text = word.text;
    if word.role() == Some(Role::Function) {
        Candidate { display: format!("{text}(x)"), replacement: format!("{text}("), kind: CandidateKind::Function }
    } else {
        Candidate { display: text.to_string(), replacement: format!("{text} "), kind: CandidateKind::Keyword }
    }
}
