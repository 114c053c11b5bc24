//! The parser of `.ray` files (`src/lang/parser/scene.rs`), made by
//! lalrpop from `grammar/scene.lalrpop`: an LR(1) table parser that
//! `rayrepl::lang::parser` runs. It is committed so that building rayrepl
//! does not build and run lalrpop; lalrpop writes the hash of the grammar
//! at its top, which a test of rayrepl compares with the grammar's.

use std::error::Error;
use std::path::Path;

/// Where the parser is committed, from the workspace's root.
pub const PATH: &str = "src/lang/parser/scene.rs";

/// The grammar, from the workspace's root.
const GRAMMAR: &str = "grammar/scene.lalrpop";

/// The parser lalrpop makes from the grammar under `root`, as the text
/// committed at [`PATH`].
pub fn generate(root: &Path) -> Result<String, Box<dyn Error>> {
    let out = tempfile::tempdir()?;
    let grammar = root.join(GRAMMAR);
    let grammar_dir = grammar.parent().expect("the grammar is in a folder");
    lalrpop::Configuration::new()
        .set_out_dir(out.path())
        // No cargo features: the grammar has no conditions, and the header
        // (`// features: ...`) is then the same wherever the tool runs.
        .set_features(Vec::<String>::new())
        .force_build(true)
        .log_quiet()
        .process_dir(grammar_dir)
        .map_err(|error| format!("lalrpop cannot make a parser of {GRAMMAR}: {error}"))?;
    let file_name = grammar.with_extension("rs");
    let file_name = file_name.file_name().expect("the grammar's path names a file");
    Ok(std::fs::read_to_string(out.path().join(file_name))?)
}
