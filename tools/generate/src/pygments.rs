//! The Pygments lexer of `.ray` files (`editors/pygments/rayrepl_pygments/lexer.py`),
//! made from the words table, so that what Pygments colours colours the
//! words the lexer reads: the HTML nbconvert makes of a notebook (the
//! kernel names the lexer `ray`), Sphinx and MkDocs pages, `pygmentize`. A
//! test checks that the committed file is this text.
//!
//! The token types, per kind of word (the classes of
//! [`Class`], as the TextMate grammar has them):
//!
//! | words | token type |
//! |---|---|
//! | `if`, `then`, `else`, `end`, `proc` | `Keyword` |
//! | definitions: `camera`, `ambient`, `light` | `Keyword.Declaration` |
//! | instructions: `let`, `object`, `put`, `print` | `Keyword.Reserved` |
//! | shapes: `sphere`, `plane`, `box` | `Keyword.Type` |
//! | transformations and `group` | `Keyword.Type.Transformation` |
//! | parts: `center`, `radius`, `by`... | `Name.Attribute` |
//! | texture words: `kd`, `ks`, `phong`, `color` | `Name.Attribute.Texture` |
//! | functions: `sin`, `cos`, `sqrt` | `Name.Builtin` |
//! | `pi` | `Keyword.Constant` |
//! | `time` | `Name.Builtin.Pseudo` |
//! | the name after `proc`, a name before `(` | `Name.Function` |
//! | other names | `Name` |
//!
//! Transformations and texture words get a type of their own below a
//! standard one: a style that does not know it colours them as the standard
//! type (shapes, parts), and the HTML has a class for each (`kt kt-Transformation`).
//! Parts and texture words are attributes rather than keywords: they are
//! most of the words of a scene, and a style's bold keywords everywhere
//! would hide the words that give a scene its shape.
//!
//! Numbers (`Number.Integer` without a point or an exponent, `Number.Float`
//! with), `#` comments (`Comment.Single`), operators and punctuation are
//! read the way the lexer reads them ([`rayrepl::lang::lexer`]); a character
//! the lexer rejects, and `//`, `/*`, is `Error`.

use rayrepl::lang::token::Token;
use rayrepl::lang::words::highlight::{
    self, ARITHMETIC, COMPARISONS, Class, FOREIGN_COMMENT, LOGICAL, NAME, NUMBER, WORD_END,
};
use rayrepl::lang::words::{self, Word};

/// Where the lexer is committed, from the workspace's root.
pub const PATH: &str = "editors/pygments/rayrepl_pygments/lexer.py";

/// The blanks the lexer skips; any other space, such as U+00A0, it rejects.
const BLANK: &str = "[ \\t\\r\\n\\x0b\\x0c]";

/// A number without a point or an exponent: digits not followed by more of
/// a number (`2e` is `2` and the name `e` to the lexer; `2e1` is one number).
const INTEGER: &str = "[0-9]+(?!\\.[0-9]|[eE][+-]?[0-9])";

/// The Pygments token type of a word of the language; `None` for words from
/// elsewhere, which are names to the lexer.
pub fn token_type(word: &Word) -> Option<&'static str> {
    Some(match highlight::class(word)? {
        Class::Control => "Keyword",
        Class::Definition => "Keyword.Declaration",
        Class::Instruction => "Keyword.Reserved",
        Class::Shape => "Keyword.Type",
        Class::Transformation => "Keyword.Type.Transformation",
        Class::Part => "Name.Attribute",
        Class::Texture => "Name.Attribute.Texture",
        Class::Function => "Name.Builtin",
        Class::Constant => "Keyword.Constant",
        Class::Predefined => "Name.Builtin.Pseudo",
    })
}

/// A line that is a command of the session (`:render`, `:size 320 240`):
/// its indent, its name with the colon, the rest of the line.
const COMMAND_LINE: &str = "^([ \\t]*)(:[A-Za-z_]+)([^\\n]*)";

/// The lexer, as the Python source committed at [`PATH`].
pub fn lexer() -> String {
    let mut text = format!(
        r#""""The Pygments lexer of rayrepl's `.ray` scene language.

Generated from the words table (src/lang/words.rs) by tools/generate/src/pygments.rs:
do not edit; cargo run -p generate -- write makes it again.
"""

from pygments.lexer import RegexLexer, bygroups, words
from pygments.token import Comment, Error, Keyword, Name, Number, Operator, Punctuation, Text, Whitespace

__all__ = ["RayLexer"]

# What a name is made of, as rayrepl's lexer reads it.
NAME = {name}
# After a word: not more of a name (`spheres` is a name, not `sphere`).
WORD_END = {word_end}
# The blanks rayrepl's lexer skips; it rejects any other space.
BLANK = {blank}


class RayLexer(RegexLexer):
    """Scenes for rayrepl, a ray tracer with its own small language."""

    name = "Ray"
    aliases = ["ray"]
    filenames = ["*.ray"]
    mimetypes = ["text/x-ray"]

    # Tried in this order at each place: a command's line first (a cell
    # of a notebook holds commands), a keyword before a name, `proc f`
    # before `proc`, a whole integer before a number with a point.
    tokens = {{
        "root": [
"#,
        name = raw(NAME),
        word_end = raw(WORD_END),
        blank = raw(BLANK),
    );
    for (pattern, token_type) in rules() {
        text.push_str(&format!("            ({pattern}, {token_type}),\n"));
    }
    text.push_str("        ],\n    }\n");
    text
}

/// The rules of the root state: a Python expression for each pattern, and
/// the token type it gives.
fn rules() -> Vec<(String, String)> {
    let proc = words::lookup("proc").expect("`proc` is in the table");
    let proc_type = token_type(proc).expect("`proc` is a keyword");
    let mut rules = vec![
        // A session's command, in a notebook's cell or a script: its whole
        // line (files hold none; the lexer rejects the colon there).
        (raw(COMMAND_LINE), "bygroups(Whitespace, Keyword.Pseudo, Text)".to_string()),
        (format!("BLANK + {}", raw("+")), "Whitespace".to_string()),
        (raw("#.*"), "Comment.Single".to_string()),
        (
            format!("{} + BLANK + {} + NAME + {}", raw(&format!("({})(", proc.text)), raw("+)("), raw(")")),
            format!("bygroups({proc_type}, Whitespace, Name.Function)"),
        ),
    ];
    for (token_type, words) in highlight::grouped(token_type) {
        let words: Vec<String> = words.iter().map(|word| format!("\"{word}\"")).collect();
        rules.push((format!("words([{}], suffix=WORD_END)", words.join(", ")), token_type.to_string()));
    }
    let operators = [COMPARISONS, ARITHMETIC, LOGICAL].concat();
    let punctuation = [Token::Comma, Token::LParen, Token::RParen];
    rules.extend([
        (format!("NAME + {} + BLANK + {}", raw("(?="), raw("*\\()")), "Name.Function".to_string()),
        ("NAME".to_string(), "Name".to_string()),
        (raw(INTEGER), "Number.Integer".to_string()),
        (raw(NUMBER), "Number.Float".to_string()),
        (raw(FOREIGN_COMMENT), "Error".to_string()),
        (raw(&highlight::alternatives(&operators)), "Operator".to_string()),
        (raw(&highlight::alternatives(&punctuation)), "Punctuation".to_string()),
        (raw("."), "Error".to_string()),
    ]);
    rules
}

/// `pattern` as a Python raw string literal, which keeps its backslashes.
fn raw(pattern: &str) -> String {
    assert!(
        !pattern.contains('"') && !pattern.ends_with('\\'),
        "`{pattern}` cannot be written as a raw string between double quotes"
    );
    format!("r\"{pattern}\"")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The blanks are those the lexer skips: a text of them has no token.
    #[test]
    fn the_blanks_are_the_lexers() {
        let blanks = " \t\r\n\u{b}\u{c}";
        let class = BLANK.replace("\\t", "\t").replace("\\r", "\r").replace("\\n", "\n");
        let class = class.replace("\\x0b", "\u{b}").replace("\\x0c", "\u{c}");
        assert_eq!(class, format!("[{blanks}]"));
        let source = rayrepl::lang::source::SourceId(0);
        assert_eq!(rayrepl::lang::lexer::tokenize(source, blanks).map(|tokens| tokens.len()).ok(), Some(0));
        assert!(rayrepl::lang::lexer::tokenize(source, "\u{a0}").is_err(), "U+00A0 is not a blank");
    }

    #[test]
    fn patterns_are_raw_strings() {
        assert_eq!(raw("\\(|\\)"), "r\"\\(|\\)\"");
    }
}
