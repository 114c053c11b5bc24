//! Parsing: tokens to AST, with learner-friendly syntax errors.

use super::ast::Program;
use super::diagnostic::Diagnostic;
use super::source::SourceId;

/// Parses a whole `.ray` file: camera, ambient, lights, procedures, then
/// instructions, in the order SPEC 2 gives.
pub fn parse_file(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    let _ = (source, text);
    todo!()
}

/// Parses one input of the interactive session: any items, in any order (SPEC 7).
pub fn parse_items(source: SourceId, text: &str) -> Result<Program, Diagnostic> {
    let _ = (source, text);
    todo!()
}

/// Whether `text` is an unfinished input that the session should continue on
/// the next line: a construct opened and not yet closed by `end`, or a line
/// ending in a binary operator or a comma.
pub fn is_incomplete(text: &str) -> bool {
    let _ = text;
    todo!()
}
