//! The files rayrepl makes from its own sources and commits, made in one
//! place: the parser from `grammar/scene.lalrpop` (by lalrpop), and from
//! the words table (`rayrepl::lang::words`) the grammars the editors
//! colour `.ray` files with.
//!
//! `cargo run -p generate -- write` writes them all again;
//! `cargo run -p generate -- check` (and `cargo test -p generate`) fails
//! naming each committed file that is not what its source makes now.
//!
//! | file | made by |
//! |---|---|
//! | `src/lang/parser/scene.rs` | [`parser`], lalrpop on `grammar/scene.lalrpop` |
//! | `editors/textmate/ray.tmLanguage.json` | [`textmate`] |
//! | `editors/pygments/rayrepl_pygments/lexer.py` | [`pygments`] |
//! | `editors/tree-sitter-ray/queries/highlights.scm` | [`tree_sitter`] |
//! | `web/src/ray-words.json` | [`codemirror`] |
//!
//! None of this is in the library: a build of rayrepl compiles the
//! committed files and never runs lalrpop or these generators. Without its
//! feature `words` (`--no-default-features`) the tool makes the parser
//! alone and does not build rayrepl, for when rayrepl no longer compiles
//! with the committed parser.

#[cfg(feature = "words")]
mod codemirror;
mod parser;
#[cfg(feature = "words")]
mod pygments;
#[cfg(feature = "words")]
mod textmate;
#[cfg(feature = "words")]
mod tree_sitter;

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// How to write the files again, for the messages of `check` and the tests.
const WRITE: &str = "cargo run -p generate -- write";

/// A file the tool makes: where it goes, from the workspace's root, and what it holds.
struct Output {
    /// The path from the workspace's root.
    path: &'static str,
    /// The whole text of the file.
    text: String,
}

/// The root of the workspace, whose files the tool reads and writes.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every file the tool makes, from the sources under `root`.
fn outputs(root: &Path) -> Result<Vec<Output>, Box<dyn Error>> {
    let mut outputs = vec![Output { path: parser::PATH, text: parser::generate(root)? }];
    outputs.extend(made_from_words());
    Ok(outputs)
}

/// The files made from the words table.
#[cfg(feature = "words")]
fn made_from_words() -> Vec<Output> {
    vec![
        Output { path: textmate::PATH, text: textmate::grammar() },
        Output { path: pygments::PATH, text: pygments::lexer() },
        Output { path: tree_sitter::HIGHLIGHTS_PATH, text: tree_sitter::highlights() },
        Output { path: codemirror::PATH, text: codemirror::words_file() },
    ]
}

/// None: without the feature `words`, the tool makes the parser alone.
#[cfg(not(feature = "words"))]
fn made_from_words() -> Vec<Output> {
    Vec::new()
}

/// The paths of the committed files under `root` that differ from what
/// their sources make (a missing file differs).
fn stale(root: &Path) -> Result<Vec<&'static str>, Box<dyn Error>> {
    let outputs = outputs(root)?;
    let differs = |output: &Output| std::fs::read_to_string(root.join(output.path)).ok().as_ref() != Some(&output.text);
    Ok(outputs.iter().filter(|output| differs(output)).map(|output| output.path).collect())
}

/// Writes every file under `root`, the unchanged ones too.
fn write(root: &Path) -> Result<(), Box<dyn Error>> {
    for output in outputs(root)? {
        std::fs::write(root.join(output.path), &output.text)
            .map_err(|error| format!("cannot write {}: {error}", output.path))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let command = std::env::args().nth(1);
    let result = match command.as_deref() {
        Some("write") => write(&root()).map(|()| true),
        Some("check") => stale(&root()).map(|stale| {
            for path in &stale {
                eprintln!("{path} is not what its source makes now: {WRITE}");
            }
            stale.is_empty()
        }),
        _ => {
            eprintln!("usage: cargo run -p generate -- write|check");
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(error) => {
            eprintln!("generate: {error}");
            ExitCode::FAILURE
        }
    }
}

/// The text of the committed file at `path`, from the workspace's root
/// (empty if it cannot be read), for the tests that check a file written by hand.
#[cfg(all(test, feature = "words"))]
fn committed(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every committed file is what its source makes now.
    #[test]
    fn the_committed_files_are_fresh() {
        let stale = stale(&root()).expect("the sources are read and the parser is generated");
        assert!(stale.is_empty(), "not what their sources make now: {}; {WRITE}", stale.join(", "));
    }

    /// What the TextMate grammar, the Pygments lexer and CodeMirror give a
    /// word of each class; nothing to a word from elsewhere, a name to the lexer.
    #[cfg(feature = "words")]
    #[test]
    fn highlighters_by_class() {
        use rayrepl::lang::words::WORDS;
        use rayrepl::lang::words::highlight::{self, Class::*};
        let rows = [
            (Control, "keyword.control.ray", "Keyword", "controlKeyword"),
            (Definition, "storage.type.ray", "Keyword.Declaration", "definitionKeyword"),
            (Instruction, "keyword.other.instruction.ray", "Keyword.Reserved", "keyword"),
            (Shape, "support.type.shape.ray", "Keyword.Type", "typeName"),
            (Transformation, "support.type.transformation.ray", "Keyword.Type.Transformation", "modifier"),
            (Part, "keyword.other.part.ray", "Name.Attribute", "propertyName"),
            (Texture, "keyword.other.texture.ray", "Name.Attribute.Texture", "attributeName"),
            (Function, "support.function.ray", "Name.Builtin", "variableName.standard"),
            (Constant, "constant.language.ray", "Keyword.Constant", "atom"),
            (Predefined, "variable.language.ray", "Name.Builtin.Pseudo", "variableName.special"),
        ];
        for word in WORDS {
            let given = (textmate::scope(word), pygments::token_type(word), codemirror::tag(word));
            let expected = match highlight::class(word) {
                Some(class) => {
                    let row = rows.iter().find(|row| row.0 == class).expect("a row per class");
                    (Some(row.1), Some(row.2), Some(row.3))
                }
                None => (None, None, None),
            };
            assert_eq!(given, expected, "`{}`", word.text);
        }
    }
}
