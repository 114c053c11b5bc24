//! The words the browser playground's editor (CodeMirror 6, `web/`)
//! colours, made from the words table: `web/src/ray-words.json`, read by
//! the editor's tokenizer (`web/src/highlight.js`). A test checks that the
//! committed file is this text.
//!
//! Each word gets the CodeMirror highlighting tag of its TextMate scope
//! ([`super::textmate::scope`]), so that the two grammars colour a word by
//! the same part it plays; names and numbers are read with the TextMate
//! grammar's patterns, which are the lexer's.

use serde_json::{Map, Value, json};

use super::textmate::{self, NAME};
use super::{WORDS, Word};
use crate::lang::token::Token;

/// Where the words are committed, from the crate's root.
pub const PATH: &str = "web/src/ray-words.json";

/// The CodeMirror tag (`@lezer/highlight`'s `tags`, modifiers after a dot,
/// as `StreamLanguage` reads token names) of each TextMate scope a word of
/// the language has.
const TAGS: [(&str, &str); 11] = [
    ("keyword.control.ray", "controlKeyword"),
    ("storage.type.ray", "definitionKeyword"),
    ("keyword.other.instruction.ray", "keyword"),
    ("support.type.shape.ray", "typeName"),
    ("support.type.transformation.ray", "modifier"),
    ("keyword.other.part.ray", "propertyName"),
    ("keyword.other.texture.ray", "attributeName"),
    ("support.function.ray", "variableName.standard"),
    ("constant.language.ray", "atom"),
    ("variable.language.ray", "variableName.special"),
    ("entity.name.function.ray", "variableName.function"),
];

/// The CodeMirror tag of a word of the language; `None` for words from
/// elsewhere, which are names to the lexer.
pub fn tag(word: &Word) -> Option<&'static str> {
    textmate::scope(word).map(tag_of_scope)
}

/// The words, as the JSON text committed at [`PATH`].
pub fn words_file() -> String {
    let mut text = serde_json::to_string_pretty(&words_value()).expect("a JSON value always prints");
    text.push('\n');
    text
}

/// Every word with its tag; the patterns of names and numbers; the
/// operators, longest first.
fn words_value() -> Value {
    let words: Map<String, Value> =
        WORDS.iter().filter_map(|word| Some((word.text.to_string(), Value::from(tag(word)?)))).collect();
    let operators = [
        Token::Ne,
        Token::Le,
        Token::Ge,
        Token::Eq,
        Token::Lt,
        Token::Gt,
        Token::Plus,
        Token::Minus,
        Token::Star,
        Token::Slash,
        Token::And,
        Token::Or,
        Token::Bang,
    ];
    let spelt = |tokens: &[Token]| -> Vec<&str> {
        tokens.iter().map(|token| token.spelling().expect("a symbol has a spelling")).collect()
    };
    json!({
        "comment": "Generated from the words table (src/lang/words.rs) by src/lang/words/codemirror.rs: do not edit; RAYREPL_BLESS=1 cargo test --release --lib codemirror writes it again.",
        "words": words,
        "name": NAME,
        "number": textmate::number()["match"],
        "procedure": "proc",
        "call": tag_of_scope("entity.name.function.ray"),
        "operators": spelt(&operators),
        "separators": spelt(&[Token::Comma]),
        "parentheses": spelt(&[Token::LParen, Token::RParen]),
    })
}

/// The tag [`TAGS`] gives `scope`.
fn tag_of_scope(scope: &str) -> &'static str {
    TAGS.iter().find(|(known, _)| *known == scope).map(|(_, tag)| *tag).expect("the scope has a tag")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed words are what the table makes now;
    /// `RAYREPL_BLESS=1 cargo test --release --lib codemirror` writes them again.
    #[test]
    fn the_committed_words_are_made_from_the_table() {
        super::super::assert_generated(PATH, &words_file(), "codemirror");
    }

    #[test]
    fn tags_follow_the_textmate_scopes() {
        let tag_of = |text| super::super::lookup(text).and_then(tag);
        assert_eq!(tag_of("if"), Some("controlKeyword"));
        assert_eq!(tag_of("camera"), Some("definitionKeyword"));
        assert_eq!(tag_of("sphere"), Some("typeName"));
        assert_eq!(tag_of("sqrt"), Some("variableName.standard"));
        assert_eq!(tag_of("time"), Some("variableName.special"));
        assert_eq!(tag_of("colour"), None);
    }

    #[test]
    fn the_operators_are_longest_first() {
        let value = words_value();
        let operators: Vec<&str> =
            value["operators"].as_array().expect("a list").iter().filter_map(Value::as_str).collect();
        for (index, operator) in operators.iter().enumerate() {
            let shadowed = operators[..index].iter().any(|earlier| operator.starts_with(earlier));
            assert!(!shadowed, "`{operator}` comes after an operator it starts with");
        }
    }
}
