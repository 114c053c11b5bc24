//! What the highlighters made from the words table share: the class each
//! word is coloured by, the table's words grouped by what a highlighter
//! gives them, and the regular expressions of names, numbers and symbols as
//! the lexer ([`crate::lang::lexer`]) reads them. The editors' grammars are
//! made from them by `tools/generate` (`cargo run -p generate -- write`):
//! the TextMate grammar and the Pygments lexer are regular expressions over
//! the text, and both dialects (Oniguruma, Python's `re`) read these ones
//! alike; the tree-sitter queries and the playground's words list them.

use super::{Kind, Role, WORDS, Word};
use crate::lang::token::Token;

/// What part a word plays, as a highlighter colours it: a keyword's role,
/// except the words that direct the flow of a program, which are one class.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// `if`, `then`, `else`, `end`, `proc`: the keywords of the help pages
    /// in [`CONTROL_TOPICS`].
    Control,
    /// `camera`, `ambient`, `light`.
    Definition,
    /// `let`, `object`, `put`, `print`.
    Instruction,
    /// `sphere`, `plane`, `box`.
    Shape,
    /// `translate`, `rotate`, `scale`, `group`.
    Transformation,
    /// `center`, `radius`, `by`...
    Part,
    /// `kd`, `ks`, `phong`, `color`.
    Texture,
    /// `sin`, `cos`, `sqrt`.
    Function,
    /// `pi`.
    Constant,
    /// `time`, a name the language gives a value without reserving it.
    Predefined,
}

/// The help pages whose keywords direct the flow of a program: `if`, `then`
/// and `else`; `end`; `proc`.
pub const CONTROL_TOPICS: [&str; 3] = ["if", "end", "proc"];

/// What a name is made of, as the lexer reads it.
pub const NAME: &str = "[A-Za-z_][A-Za-z0-9_]*";

/// After a word: not more of a name (`spheres` is a name, not `sphere`).
pub const WORD_END: &str = "(?![A-Za-z0-9_])";

/// `[0-9]*(\.[0-9]+)?([eE][+-]?[0-9]+)?` with at least one digit, as the lexer reads it.
pub const NUMBER: &str = "(?:[0-9]+(?:\\.[0-9]+)?|\\.[0-9]+)(?:[eE][+-]?[0-9]+)?";

/// `//` and `/*`, which start comments in other languages and which the lexer rejects.
pub const FOREIGN_COMMENT: &str = "//|/\\*";

/// The comparisons, two-character ones first (a regular expression tries
/// its alternatives in order).
pub const COMPARISONS: &[Token] = &[Token::Ne, Token::Le, Token::Ge, Token::Eq, Token::Lt, Token::Gt];

/// The arithmetic operators.
pub const ARITHMETIC: &[Token] = &[Token::Plus, Token::Minus, Token::Star, Token::Slash];

/// The logical operators.
pub const LOGICAL: &[Token] = &[Token::And, Token::Or, Token::Bang];

/// The class of a word of the language; `None` for words from elsewhere,
/// which are names to the lexer.
pub fn class(word: &Word) -> Option<Class> {
    let role = match word.kind {
        Kind::Keyword { role, .. } => role,
        Kind::Predefined => return Some(Class::Predefined),
        Kind::Elsewhere { .. } | Kind::MissingFunction => return None,
    };
    if CONTROL_TOPICS.contains(&word.topic) {
        return Some(Class::Control);
    }
    Some(match role {
        Role::Definition => Class::Definition,
        Role::Instruction => Class::Instruction,
        Role::Shape => Class::Shape,
        Role::Transformation => Class::Transformation,
        Role::Part => Class::Part,
        Role::Texture => Class::Texture,
        Role::Function => Class::Function,
        Role::Constant => Class::Constant,
    })
}

/// The words of the table that `highlight` gives something, grouped by
/// what it gives them: the groups in the order of their first word, each
/// with its words in the table's order.
pub fn grouped<T: PartialEq>(highlight: impl Fn(&Word) -> Option<T>) -> Vec<(T, Vec<&'static str>)> {
    let mut groups: Vec<(T, Vec<&'static str>)> = Vec::new();
    for word in WORDS {
        let Some(given) = highlight(word) else { continue };
        match groups.iter_mut().find(|(known, _)| *known == given) {
            Some((_, words)) => words.push(word.text),
            None => groups.push((given, vec![word.text])),
        }
    }
    groups
}

/// A regular expression for any of `tokens`, each as it is spelt.
pub fn alternatives(tokens: &[Token]) -> String {
    let spellings: Vec<String> =
        tokens.iter().map(|token| escape(token.spelling().expect("a symbol has a spelling"))).collect();
    spellings.join("|")
}

/// `text` with the characters regular expressions give a meaning escaped.
fn escape(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let special = "\\^$.|?*+()[]{}".contains(c);
            special.then_some('\\').into_iter().chain([c])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_word_of_the_language_is_in_its_group() {
        let groups = grouped(class);
        for word in WORDS {
            let Some(class) = class(word) else { continue };
            let in_group = groups.iter().any(|(given, words)| *given == class && words.contains(&word.text));
            assert!(in_group, "`{}` is not grouped as {class:?}", word.text);
        }
        assert_eq!(groups.len(), 10, "one group per class");
    }

    #[test]
    fn operators_are_escaped() {
        assert_eq!(escape("*"), "\\*");
        assert_eq!(alternatives(&[Token::Ne, Token::Or, Token::Plus]), "!=|\\||\\+");
    }
}
