//! The `.ray` language: source texts, parsing into an AST, diagnostics, and
//! evaluation into a [`crate::scene::Scene`].

pub mod ast;
pub mod diagnostic;
pub mod eval;
pub mod lexer;
pub mod parser;
pub mod source;
pub mod suggest;
pub mod words;

pub use diagnostic::{Diagnostic, Severity};
pub use eval::{Interpreter, Limits};
pub use parser::{is_incomplete, parse_file, parse_items};
pub use source::{SourceFile, SourceId, SourceMap, Span};
