//! What the word at a place is, for every front-end that asks: the
//! language server's hover and a notebook's inspection are this one
//! function, and each only translates its answer into its protocol.

use std::ops::Range;

use crate::lang::words;

use super::commands::{self, help_pages};
use super::help::{self, Topic};
use super::names::Vocabulary;
use super::offsets::floor_char_boundary;
use super::scanner::word_at;

/// The word at a place, and what it is.
#[derive(Debug, Clone)]
pub struct Hover {
    /// Its bytes in the text.
    pub range: Range<usize>,
    /// What it is.
    pub subject: Subject,
}

/// What a word at a place is.
#[derive(Debug, Clone, Copy)]
pub enum Subject {
    /// A name defined there (the word itself): what it holds and where it
    /// is bound are for the front-end that holds the program to say.
    Name,
    /// A word of the language or a command, with its help page.
    Page(&'static Topic),
}

/// Which help pages a word that names nothing defined may lead to: where
/// the front-ends differ on purpose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pages {
    /// The pages of the language's words and of the commands only: a
    /// document holds a program, whose other words are names (the language
    /// server).
    OfWords,
    /// Any page, by its name or another name, as `:help WORD` finds it
    /// (`render`, `numbers`, `learn`): a notebook's inspection, where a
    /// learner asks about what they read in the help.
    AnyTopic,
}

/// What the word around byte `offset` of `text` is, `names` being the names
/// defined there: one of them, or a word with its help page, which `pages`
/// says where to look for. `None` for anything else (an unknown name, a
/// number, a sign).
pub fn hover(text: &str, offset: usize, names: &Vocabulary, pages: Pages) -> Option<Hover> {
    let range = word_at(text, floor_char_boundary(text, offset))?;
    let word = &text[range.clone()];
    let subject = if names.defines(word) { Subject::Name } else { Subject::Page(page(word, pages)?) };
    Some(Hover { range, subject })
}

/// The help page of `word` in `pages`.
fn page(word: &str, pages: Pages) -> Option<&'static Topic> {
    let known = match pages {
        Pages::AnyTopic => true,
        Pages::OfWords if word.starts_with(':') => commands::find(word).is_some(),
        Pages::OfWords => words::lookup(word).is_some(),
    };
    known.then(|| help::find(word, &help_pages())).flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Vocabulary {
        Vocabulary {
            variables: vec!["size".to_string()],
            objects: Vec::new(),
            procedures: vec![("ball".to_string(), vec!["r".to_string()])],
        }
    }

    /// The page's name, or `Name` for a name defined, and the word's bytes.
    fn hovered(text: &str, offset: usize) -> Option<(&'static str, Range<usize>)> {
        let hover = hover(text, offset, &names(), Pages::OfWords)?;
        let what = match hover.subject {
            Subject::Name => "Name",
            Subject::Page(page) => page.name,
        };
        Some((what, hover.range))
    }

    #[test]
    fn a_defined_procedure_is_a_name() {
        assert_eq!(hovered("ball(2)", 1), Some(("Name", 0..4)));
        assert_eq!(hovered("ball(2)", 4), Some(("Name", 0..4)), "just after it");
    }

    #[test]
    fn a_number_variable_is_a_name() {
        assert_eq!(hovered("let a = size * 2", 10), Some(("Name", 8..12)));
    }

    #[test]
    fn a_keyword_has_its_page() {
        assert_eq!(hovered("put sphere end", 6), Some(("sphere", 4..10)));
        assert_eq!(hovered("kd 1", 0), Some(("texture", 0..2)));
        assert_eq!(hovered("rayon 2", 1), Some(("sphere", 0..5)), "a word from elsewhere");
        assert_eq!(hovered("time", 1), Some(("time", 0..4)), "predefined, not defined here");
    }

    #[test]
    fn a_command_has_its_page() {
        assert_eq!(hovered(":render 80 60", 3), Some((":render", 0..7)));
        assert_eq!(hovered(":q", 1), Some((":quit", 0..2)), "by another name");
        assert_eq!(hovered(":nothing", 1), None);
    }

    #[test]
    fn an_unknown_word_is_nothing() {
        assert_eq!(hovered("put blob", 6), None);
        assert_eq!(hovered("render", 2), None, "a command's name without its colon is a name");
        assert_eq!(hovered("let a = 12", 9), None, "a number");
        assert_eq!(hovered("   ", 1), None);
        assert_eq!(hovered("é🎨", 3), None, "a place inside a character");
    }

    #[test]
    fn any_topic_is_found_by_its_names_where_asked() {
        let page = |word: &str| hover(word, 1, &names(), Pages::AnyTopic).map(|hover| hover.subject);
        assert!(matches!(page("render"), Some(Subject::Page(topic)) if topic.name == ":render"));
        assert!(matches!(page("learn"), Some(Subject::Page(topic)) if topic.name == ":lesson"));
        assert!(matches!(page("size"), Some(Subject::Name)), "a defined name first");
        assert!(page("blob").is_none());
    }
}
