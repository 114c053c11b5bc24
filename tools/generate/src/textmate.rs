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
//! lexer reads them ([`rayrepl::lang::lexer`]); a character the lexer rejects
//! (and `//`, `/*`) is `invalid.illegal`.

use serde_json::{Map, Value, json};

use rayrepl::lang::token::Token;
use rayrepl::lang::words::highlight::{
    self, ARITHMETIC, COMPARISONS, Class, FOREIGN_COMMENT, LOGICAL, NAME, NUMBER, WORD_END,
};
use rayrepl::lang::words::{self, Word};

/// Where the grammar is committed, from the workspace's root.
pub const PATH: &str = "editors/textmate/ray.tmLanguage.json";

/// The grammar, as the JSON text committed at [`PATH`].
pub fn grammar() -> String {
    let mut text = serde_json::to_string_pretty(&grammar_value()).expect("a JSON value always prints");
    text.push('\n');
    text
}

/// The TextMate scope of a word of the language; `None` for words from
/// elsewhere, which are names to the lexer.
pub fn scope(word: &Word) -> Option<&'static str> {
    Some(match highlight::class(word)? {
        Class::Control => "keyword.control.ray",
        Class::Definition => "storage.type.ray",
        Class::Instruction => "keyword.other.instruction.ray",
        Class::Shape => "support.type.shape.ray",
        Class::Transformation => "support.type.transformation.ray",
        Class::Part => "keyword.other.part.ray",
        Class::Texture => "keyword.other.texture.ray",
        Class::Function => "support.function.ray",
        Class::Constant => "constant.language.ray",
        Class::Predefined => "variable.language.ray",
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
        ("foreign-comment", json!({ "name": "invalid.illegal.comment.ray", "match": FOREIGN_COMMENT })),
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
        "comment": "Generated from the words table (src/lang/words.rs) by tools/generate/src/textmate.rs: do not edit; cargo run -p generate -- write makes it again.",
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
    let proc = words::lookup("proc").expect("`proc` is in the table");
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
    let patterns: Vec<Value> = highlight::grouped(scope)
        .into_iter()
        .map(|(scope, words)| json!({ "name": scope, "match": format!("(?:{}){WORD_END}", words.join("|")) }))
        .collect();
    json!({ "patterns": patterns })
}

/// A name called: `branch(` (`f (x)` too, as the lexer skips the blank).
fn call() -> Value {
    json!({ "name": "entity.name.function.ray", "match": format!("{NAME}(?=\\s*\\()") })
}

/// A number, as the lexer reads it.
fn number() -> Value {
    json!({ "name": "constant.numeric.ray", "match": NUMBER })
}

/// The operators, spelt as the tokens are, two-character ones first.
fn operators() -> Value {
    let kinds = [
        ("keyword.operator.comparison.ray", COMPARISONS),
        ("keyword.operator.arithmetic.ray", ARITHMETIC),
        ("keyword.operator.logical.ray", LOGICAL),
    ];
    let patterns: Vec<Value> = kinds
        .iter()
        .map(|(scope, tokens)| json!({ "name": scope, "match": highlight::alternatives(tokens) }))
        .collect();
    json!({ "patterns": patterns })
}

/// Commas and parentheses.
fn punctuation() -> Value {
    json!({
        "patterns": [
            { "name": "punctuation.separator.comma.ray", "match": highlight::alternatives(&[Token::Comma]) },
            { "name": "punctuation.section.parens.begin.ray", "match": highlight::alternatives(&[Token::LParen]) },
            { "name": "punctuation.section.parens.end.ray", "match": highlight::alternatives(&[Token::RParen]) },
        ]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayrepl::lang::words::{Kind, WORDS};

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
}
