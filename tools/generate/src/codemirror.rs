//! The words the browser playground's editor (CodeMirror 6, `web/`)
//! colours, made from the words table: `web/src/ray-words.json`, read by
//! the editor's tokenizer (`web/src/highlight.js`). A test checks that the
//! committed file is this text.
//!
//! The tags, per kind of word (the classes of [`Class`],
//! as `@lezer/highlight` names its tags, modifiers after a dot, the way
//! CodeMirror's `StreamLanguage` reads a token's name):
//!
//! | words | tag |
//! |---|---|
//! | `if`, `then`, `else`, `end`, `proc` | `controlKeyword` |
//! | definitions: `camera`, `ambient`, `light` | `definitionKeyword` |
//! | instructions: `let`, `object`, `put`, `print` | `keyword` |
//! | shapes: `sphere`, `plane`, `box` | `typeName` |
//! | transformations and `group` | `modifier` |
//! | parts: `center`, `radius`, `by`... | `propertyName` |
//! | texture words: `kd`, `ks`, `phong`, `color` | `attributeName` |
//! | functions: `sin`, `cos`, `sqrt` | `variableName.standard` |
//! | `pi` | `atom` |
//! | `time` | `variableName.special` |
//! | a name before `(` | `variableName.function`, after `proc` with `.definition` |
//!
//! Names and numbers are read with the regular expressions of
//! [`highlight`], which are the lexer's; the operators are listed
//! longest first, as the tokenizer tries them.

use serde_json::{Map, Value, json};

use rayrepl::lang::token::Token;
use rayrepl::lang::words::highlight::{self, ARITHMETIC, COMPARISONS, Class, LOGICAL, NAME, NUMBER};
use rayrepl::lang::words::{WORDS, Word};

/// Where the words are committed, from the workspace's root.
pub const PATH: &str = "web/src/ray-words.json";

/// The tag of a name called, or defined after `proc` (with `.definition`).
const CALL: &str = "variableName.function";

/// The CodeMirror tag of a word of the language; `None` for words from
/// elsewhere, which are names to the lexer.
pub fn tag(word: &Word) -> Option<&'static str> {
    Some(match highlight::class(word)? {
        Class::Control => "controlKeyword",
        Class::Definition => "definitionKeyword",
        Class::Instruction => "keyword",
        Class::Shape => "typeName",
        Class::Transformation => "modifier",
        Class::Part => "propertyName",
        Class::Texture => "attributeName",
        Class::Function => "variableName.standard",
        Class::Constant => "atom",
        Class::Predefined => "variableName.special",
    })
}

/// The words, as the JSON text committed at [`PATH`].
pub fn words_file() -> String {
    let mut text = serde_json::to_string_pretty(&words_value()).expect("a JSON value always prints");
    text.push('\n');
    text
}

/// Every word with its tag; the patterns of names and numbers; the
/// symbols.
fn words_value() -> Value {
    let words: Map<String, Value> =
        WORDS.iter().filter_map(|word| Some((word.text.to_string(), Value::from(tag(word)?)))).collect();
    let operators: Vec<Token> = [COMPARISONS, ARITHMETIC, LOGICAL].concat();
    let spelt = |tokens: &[Token]| -> Vec<&str> {
        tokens.iter().map(|token| token.spelling().expect("a symbol has a spelling")).collect()
    };
    json!({
        "comment": "Generated from the words table (src/lang/words.rs) by tools/generate/src/codemirror.rs: do not edit; cargo run -p generate -- write makes it again.",
        "words": words,
        "name": NAME,
        "number": NUMBER,
        "procedure": Token::Proc.spelling(),
        "call": CALL,
        "operators": spelt(&operators),
        "separators": spelt(&[Token::Comma]),
        "parentheses": spelt(&[Token::LParen, Token::RParen]),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_operator_comes_after_one_it_starts_with() {
        let value = words_value();
        let operators: Vec<&str> =
            value["operators"].as_array().expect("a list").iter().filter_map(Value::as_str).collect();
        for (index, operator) in operators.iter().enumerate() {
            let shadowed = operators[..index].iter().any(|earlier| operator.starts_with(earlier));
            assert!(!shadowed, "`{operator}` comes after an operator it starts with");
        }
    }
}
