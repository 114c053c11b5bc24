//! The highlight queries of the tree-sitter grammar of `.ray` files
//! (`editors/tree-sitter-ray/queries/highlights.scm`), made from the words
//! table, and the check that the grammar (`editors/tree-sitter-ray/grammar.js`,
//! written by hand like grammar/scene.lalrpop) uses the table's keywords and
//! no others. Tests check both committed files.
//!
//! The captures, per kind of word (the names Neovim, Helix and Zed colour):
//!
//! | words | capture |
//! |---|---|
//! | `proc` | `@keyword.function` |
//! | shapes: `sphere`, `plane`, `box` | `@type` |
//! | functions: `sin`, `cos`, `sqrt` | `@function.builtin` |
//! | `pi` | `@constant.builtin` |
//! | `time` | `@variable.builtin` |
//! | other keywords | `@keyword` |
//! | the name after `proc`, the name called | `@function` |
//! | other names | `@variable` |
//!
//! The patterns are in the order of the tree-sitter command line (0.27),
//! Neovim and Zed, where the last pattern that matches a node gives its
//! capture: the one for any name first.

use rayrepl::lang::token::Token;
use rayrepl::lang::words::{Kind, Role, WORDS, Word, highlight};

/// Where the queries are committed, from the workspace's root.
pub const HIGHLIGHTS_PATH: &str = "editors/tree-sitter-ray/queries/highlights.scm";

/// The capture of a keyword; `None` for the words that are not keywords.
pub fn capture(word: &Word) -> Option<&'static str> {
    let Kind::Keyword { role, .. } = word.kind else { return None };
    Some(match role {
        Role::Definition if word.text == "proc" => "keyword.function",
        Role::Shape => "type",
        Role::Function => "function.builtin",
        Role::Constant => "constant.builtin",
        Role::Definition | Role::Instruction | Role::Transformation | Role::Texture | Role::Part => "keyword",
    })
}

/// The queries, as the text committed at [`HIGHLIGHTS_PATH`].
pub fn highlights() -> String {
    let mut text = String::from(
        "; Generated from the words table (src/lang/words.rs) by tools/generate/src/tree_sitter.rs:\n\
         ; do not edit; cargo run -p generate -- write makes it again.\n\
         ; The last pattern that matches a node gives its capture.\n\n\
         (identifier) @variable\n\n\
         (comment) @comment\n\n\
         (number) @number\n\n",
    );
    for (capture, words) in highlight::grouped(capture) {
        text.push_str(&list(&words, capture));
    }
    for word in WORDS.iter().filter(|word| word.kind == Kind::Predefined) {
        text.push_str(&format!("((identifier) @variable.builtin\n  (#eq? @variable.builtin \"{}\"))\n\n", word.text));
    }
    text.push_str(
        "(procedure\n  name: (identifier) @function)\n\n\
         (call\n  name: (identifier) @function)\n\n\
         (parameters\n  (identifier) @variable.parameter)\n\n",
    );
    let operators = [
        Token::Plus,
        Token::Minus,
        Token::Star,
        Token::Slash,
        Token::Eq,
        Token::Ne,
        Token::Lt,
        Token::Le,
        Token::Gt,
        Token::Ge,
        Token::And,
        Token::Or,
        Token::Bang,
    ];
    text.push_str(&list(&spellings(&operators), "operator"));
    text.push_str(&list(&spellings(&[Token::Comma]), "punctuation.delimiter"));
    text.push_str(&list(&spellings(&[Token::LParen, Token::RParen]), "punctuation.bracket"));
    text
}

/// How `tokens` are written.
fn spellings(tokens: &[Token]) -> Vec<&'static str> {
    tokens.iter().map(|token| token.spelling().expect("a symbol has a spelling")).collect()
}

/// A pattern giving `capture` to each of `nodes`, anonymous nodes spelt as written.
fn list(nodes: &[&str], capture: &str) -> String {
    let mut text = String::from("[\n");
    for node in nodes {
        text.push_str(&format!("  \"{node}\"\n"));
    }
    text.push_str(&format!("] @{capture}\n\n"));
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::committed;
    use rayrepl::lang::words;

    /// Where the grammar is committed, from the workspace's root.
    const GRAMMAR_PATH: &str = "editors/tree-sitter-ray/grammar.js";

    /// The words written between single quotes in `source` that could be
    /// keywords (lower-case letters only, not the name of a `field(...)`): the
    /// keywords of a tree-sitter grammar whose strings are all in single quotes
    /// and whose comments have none.
    fn quoted_words(source: &str) -> Vec<&str> {
        let mut parts = source.split('\'');
        let mut words = Vec::new();
        // The parts alternate: outside quotes, inside, outside...
        while let (Some(before), Some(inside)) = (parts.next(), parts.next()) {
            let keyword = !inside.is_empty() && inside.bytes().all(|b| b.is_ascii_lowercase());
            if keyword && !before.ends_with("field(") {
                words.push(inside);
            }
        }
        words
    }

    /// The grammar's keywords are the table's, each of them and no other.
    #[test]
    fn the_grammar_uses_the_keywords_of_the_table() {
        let grammar = committed(GRAMMAR_PATH);
        let mut in_grammar: Vec<&str> = quoted_words(&grammar);
        // The grammar's own name is not a keyword.
        in_grammar.retain(|word| *word != "ray");
        in_grammar.sort_unstable();
        in_grammar.dedup();
        let mut in_table: Vec<&str> = words::keyword_names().collect();
        in_table.sort_unstable();
        assert_eq!(in_grammar, in_table, "the keywords of {GRAMMAR_PATH} are not the words table's");
    }

    #[test]
    fn captures_by_role() {
        let capture_of = |text| words::lookup(text).and_then(capture);
        assert_eq!(capture_of("proc"), Some("keyword.function"));
        assert_eq!(capture_of("camera"), Some("keyword"));
        assert_eq!(capture_of("end"), Some("keyword"));
        assert_eq!(capture_of("box"), Some("type"));
        assert_eq!(capture_of("sqrt"), Some("function.builtin"));
        assert_eq!(capture_of("pi"), Some("constant.builtin"));
        assert_eq!(capture_of("time"), None);
        assert_eq!(capture_of("colour"), None);
    }

    #[test]
    fn quoted_words_are_found() {
        assert_eq!(quoted_words("seq('let', field('name', $.x), '=', 'end', 'Ab')"), ["let", "end"]);
    }
}
