//! Parses each file named on the command line with the committed tree-sitter
//! parser of `.ray` files and says where a node is `ERROR` or `MISSING`;
//! fails if any is. What an editor does with the parser, without the
//! tree-sitter command line.

use std::process::ExitCode;

use tree_sitter::{Node, Parser};
use tree_sitter_language::LanguageFn;

unsafe extern "C" {
    fn tree_sitter_ray() -> *const ();
}

/// The language of the parser compiled by build.rs.
const LANGUAGE: LanguageFn = unsafe { LanguageFn::from_raw(tree_sitter_ray) };

fn main() -> ExitCode {
    let mut parser = Parser::new();
    if let Err(error) = parser.set_language(&LANGUAGE.into()) {
        eprintln!("the parser does not fit the runtime: {error}");
        return ExitCode::FAILURE;
    }
    let mut files = 0;
    let mut failed = 0;
    for path in std::env::args().skip(1) {
        let text = match std::fs::read_to_string(&path) {
            Ok(text) => text,
            Err(error) => {
                eprintln!("{path}: {error}");
                return ExitCode::FAILURE;
            }
        };
        files += 1;
        let Some(tree) = parser.parse(&text, None) else {
            eprintln!("{path}: not parsed");
            return ExitCode::FAILURE;
        };
        if let Some(node) = first_error(tree.root_node()) {
            let at = node.start_position();
            let what = if node.is_missing() { "MISSING" } else { "ERROR" };
            eprintln!("{path}:{}:{}: {what} node", at.row + 1, at.column + 1);
            failed += 1;
        }
    }
    if failed > 0 {
        eprintln!("{failed} of {files} files do not parse with the tree-sitter grammar");
        return ExitCode::FAILURE;
    }
    println!("{files} files parsed, no ERROR or MISSING node");
    ExitCode::SUCCESS
}

/// The first node under `node` (itself included) that is an error or missing.
fn first_error(node: Node) -> Option<Node> {
    if !node.has_error() {
        return None;
    }
    if node.is_error() || node.is_missing() {
        return Some(node);
    }
    let mut cursor = node.walk();
    let children: Vec<Node> = node.children(&mut cursor).collect();
    children.into_iter().find_map(first_error)
}
