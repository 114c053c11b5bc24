//! The `.ray` language: source texts, parsing into an AST, diagnostics, and
//! evaluation into a [`crate::scene::Scene`].

pub mod ast;
pub mod degrees;
pub mod diagnostic;
pub mod eval;
pub(crate) mod fast_hash;
pub mod format;
pub mod lexer;
pub mod name;
pub mod names;
pub mod nesting;
pub mod number;
pub mod parser;
pub mod source;
pub mod suggest;
pub mod token;
pub mod walk;
pub mod words;

pub use diagnostic::{Diagnostic, Note, Severity};
pub use eval::{Interpreter, Limits, RaisedWith};
pub use nesting::MAX_NESTING;
pub use parser::{Entry, EntryState, entry_state, is_incomplete, parse_entries, parse_file, parse_items};
pub(crate) use parser::{parse_file_interruptible, parse_items_apart, stopped_reading};
pub use source::{SourceFile, SourceId, SourceMap, Span};
