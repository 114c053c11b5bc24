//! The TextMate grammar of `.ray` files (`editors/textmate/ray.tmLanguage.json`),
//! made from the words table, so that an editor colours the words the lexer
//! reads: VS Code, Sublime Text, TextMate, and anything else that takes
//! TextMate grammars. A test checks that the committed file is this text.
//!
//! The scopes, per kind of word (standard TextMate names, which themes colour):
//!
//! | words | scope |
//! |---|---|
//! | `if`, `then`, `else`, `end`, `proc` (the help pages `if`, `end`, `proc`) | `keyword.control.ray` |
//! | definitions: `camera`, `ambient`, `light` | `storage.type.ray` |
//! | instructions: `let`, `object`, `put`, `print` | `keyword.other.instruction.ray` |
//! | shapes: `sphere`, `plane`, `box` | `support.type.shape.ray` |
//! | transformations and `group` | `support.type.transformation.ray` |
//! | parts: `center`, `radius`, `by`... | `keyword.other.part.ray` |
//! | texture words: `kd`, `ks`, `phong`, `color` | `keyword.other.texture.ray` |
//! | functions: `sin`, `cos`, `sqrt` | `support.function.ray` |
//! | `pi` | `constant.language.ray` |
//! | `time` | `variable.language.ray` |
//! | the name after `proc`, a name before `(` | `entity.name.function.ray` |
//! | other names | `variable.other.ray` |
//!
//! Numbers, comments, operators, commas and parentheses are read the way the
//! lexer reads them ([`crate::lang::lexer`]); a character the lexer rejects
//! (and `//`, `/*`) is `invalid.illegal`.

use serde_json::{Map, Value, json};

use super::{Kind, Role, WORDS, Word};
use crate::lang::token::Token;

/// Where the grammar is committed, from the crate's root.
pub const PATH: &str = "editors/textmate/ray.tmLanguage.json";

/// The help pages whose keywords direct the flow of a program: `if`, `then`
/// and `else`; `end`; `proc`.
const CONTROL_TOPICS: [&str; 3] = ["if", "end", "proc"];

/// What a name is made of, as the lexer reads it.
pub(super) const NAME: &str = "[A-Za-z_][A-Za-z0-9_]*";

/// After a word: not more of a name (`spheres` is a name, not `sphere`).
const WORD_END: &str = "(?![A-Za-z0-9_])";

/// The grammar, as the JSON text committed at [`PATH`].
pub fn grammar() -> String {
    let mut text = serde_json::to_string_pretty(&grammar_value()).expect("a JSON value always prints");
    text.push('\n');
    text
}

/// The TextMate scope of a word of the language; `None` for words from
/// elsewhere, which are names to the lexer.
pub fn scope(word: &Word) -> Option<&'static str> {
    let role = match word.kind {
        Kind::Keyword { role, .. } => role,
        Kind::Predefined => return Some("variable.language.ray"),
        Kind::Elsewhere { .. } | Kind::MissingFunction => return None,
    };
    if CONTROL_TOPICS.contains(&word.topic) {
        return Some("keyword.control.ray");
    }
    Some(match role {
        Role::Definition => "storage.type.ray",
        Role::Instruction => "keyword.other.instruction.ray",
        Role::Shape => "support.type.shape.ray",
        Role::Transformation => "support.type.transformation.ray",
        Role::Part => "keyword.other.part.ray",
        Role::Texture => "keyword.other.texture.ray",
        Role::Function => "support.function.ray",
        Role::Constant => "constant.language.ray",
    })
}

/// The whole grammar: the rules in the order they are tried, where two
/// match at the same place (a keyword before a name, `proc f` before `proc`).
fn grammar_value() -> Value {
    let rules = [
        ("comment", comment()),
        ("proc-name", proc_name()),
        ("words", words()),
        ("call", call()),
        ("name", json!({ "name": "variable.other.ray", "match": NAME })),
        ("number", number()),
        ("foreign-comment", json!({ "name": "invalid.illegal.comment.ray", "match": "//|/\\*" })),
        ("operator", operators()),
        ("punctuation", punctuation()),
        ("invalid", json!({ "name": "invalid.illegal.character.ray", "match": "[^\\s]" })),
    ];
    let patterns: Vec<Value> = rules.iter().map(|(key, _)| json!({ "include": format!("#{key}") })).collect();
    let repository: Map<String, Value> = rules.into_iter().map(|(key, rule)| (key.to_string(), rule)).collect();
    json!({
        "$schema": "https://raw.githubusercontent.com/martinring/tmlanguage/master/tmlanguage.json",
        "name": "Ray",
        "scopeName": "source.ray",
        "fileTypes": ["ray"],
        "comment": "Generated from the words table (src/lang/words.rs) by src/lang/words/textmate.rs: do not edit; RAYREPL_BLESS=1 cargo test --release --lib textmate writes it again.",
        "patterns": patterns,
        "repository": repository,
    })
}

/// `#` to the end of the line.
fn comment() -> Value {
    json!({
        "name": "comment.line.number-sign.ray",
        "match": "(#).*$",
        "captures": { "1": { "name": "punctuation.definition.comment.ray" } },
    })
}

/// `proc` and the name of the procedure it defines.
fn proc_name() -> Value {
    let proc = super::lookup("proc").expect("`proc` is in the table");
    json!({
        "match": format!("({})\\s+({NAME})", proc.text),
        "captures": {
            "1": { "name": scope(proc) },
            "2": { "name": "entity.name.function.ray" },
        },
    })
}

/// A rule per scope, each with its words in the table's order.
///
/// No `\b` in front: after a number (`2end` is `2` and `end` to the lexer) a
/// keyword starts with no boundary, and inside a name the rule for names
/// has already matched the whole name.
fn words() -> Value {
    let mut scopes: Vec<(&str, Vec<&str>)> = Vec::new();
    for word in WORDS {
        let Some(scope) = scope(word) else { continue };
        match scopes.iter_mut().find(|(known, _)| *known == scope) {
            Some((_, words)) => words.push(word.text),
            None => scopes.push((scope, vec![word.text])),
        }
    }
    let patterns: Vec<Value> = scopes
        .into_iter()
        .map(|(scope, words)| json!({ "name": scope, "match": format!("(?:{}){WORD_END}", words.join("|")) }))
        .collect();
    json!({ "patterns": patterns })
}

/// A name called: `branch(` (`f (x)` too, as the lexer skips the blank).
fn call() -> Value {
    json!({ "name": "entity.name.function.ray", "match": format!("{NAME}(?=\\s*\\()") })
}

/// `[0-9]*(\.[0-9]+)?([eE][+-]?[0-9]+)?` with at least one digit, as the lexer reads it.
pub(super) fn number() -> Value {
    json!({
        "name": "constant.numeric.ray",
        "match": "(?:[0-9]+(?:\\.[0-9]+)?|\\.[0-9]+)(?:[eE][+-]?[0-9]+)?",
    })
}

/// The operators, spelt as the tokens are, two-character ones first.
fn operators() -> Value {
    let kinds = [
        (
            "keyword.operator.comparison.ray",
            [Token::Ne, Token::Le, Token::Ge, Token::Eq, Token::Lt, Token::Gt].as_slice(),
        ),
        ("keyword.operator.arithmetic.ray", &[Token::Plus, Token::Minus, Token::Star, Token::Slash]),
        ("keyword.operator.logical.ray", &[Token::And, Token::Or, Token::Bang]),
    ];
    let patterns: Vec<Value> =
        kinds.iter().map(|(scope, tokens)| json!({ "name": scope, "match": alternatives(tokens) })).collect();
    json!({ "patterns": patterns })
}

/// Commas and parentheses.
fn punctuation() -> Value {
    json!({
        "patterns": [
            { "name": "punctuation.separator.comma.ray", "match": alternatives(&[Token::Comma]) },
            { "name": "punctuation.section.parens.begin.ray", "match": alternatives(&[Token::LParen]) },
            { "name": "punctuation.section.parens.end.ray", "match": alternatives(&[Token::RParen]) },
        ]
    })
}

/// A regular expression for any of `tokens`, each as it is spelt.
fn alternatives(tokens: &[Token]) -> String {
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

    /// The committed grammar is what the table makes now;
    /// `RAYREPL_BLESS=1 cargo test --release --lib textmate` writes it again.
    #[test]
    fn the_committed_grammar_is_made_from_the_table() {
        super::super::assert_generated(PATH, &grammar(), "textmate");
    }

    /// Every word with a role, and `time`, is in the rule of its scope.
    #[test]
    fn every_word_of_the_language_is_in_the_grammar() {
        let value = grammar_value();
        let rules = value["repository"]["words"]["patterns"].as_array().expect("a list of rules");
        for word in WORDS.iter().filter(|word| word.role().is_some() || word.kind == Kind::Predefined) {
            let scope = scope(word).expect("a word of the language has a scope");
            let listed = rules.iter().any(|rule| {
                let words = rule["match"].as_str().unwrap_or_default();
                let words = words.trim_start_matches("(?:").trim_end_matches(WORD_END).trim_end_matches(')');
                rule["name"] == scope && words.split('|').any(|listed| listed == word.text)
            });
            assert!(listed, "`{}` is not in the grammar as {scope}", word.text);
        }
    }

    #[test]
    fn scopes_by_role() {
        let scope_of = |text| super::super::lookup(text).and_then(scope);
        assert_eq!(scope_of("if"), Some("keyword.control.ray"));
        assert_eq!(scope_of("else"), Some("keyword.control.ray"));
        assert_eq!(scope_of("end"), Some("keyword.control.ray"));
        assert_eq!(scope_of("proc"), Some("keyword.control.ray"));
        assert_eq!(scope_of("camera"), Some("storage.type.ray"));
        assert_eq!(scope_of("put"), Some("keyword.other.instruction.ray"));
        assert_eq!(scope_of("box"), Some("support.type.shape.ray"));
        assert_eq!(scope_of("group"), Some("support.type.transformation.ray"));
        assert_eq!(scope_of("radius"), Some("keyword.other.part.ray"));
        assert_eq!(scope_of("phong"), Some("keyword.other.texture.ray"));
        assert_eq!(scope_of("sqrt"), Some("support.function.ray"));
        assert_eq!(scope_of("pi"), Some("constant.language.ray"));
        assert_eq!(scope_of("time"), Some("variable.language.ray"));
        assert_eq!(scope_of("colour"), None);
        for topic in CONTROL_TOPICS {
            assert!(super::super::lookup(topic).is_some_and(|word| word.topic == topic), "`{topic}` is a help page");
        }
    }

    #[test]
    fn operators_are_escaped() {
        assert_eq!(escape("*"), "\\*");
        assert_eq!(alternatives(&[Token::Ne, Token::Or, Token::Plus]), "!=|\\||\\+");
    }
}
