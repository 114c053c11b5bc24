//! Editor services with no I/O, below every front-end that edits the
//! language (the session's line editor and its notebook cells, the
//! language server): completion, the help pages and the commands'
//! descriptions, hovers, the names in scope, the words of text being
//! typed, and places counted as editors count them. Each takes text and
//! what the front-end knows, and returns plain values; the front-ends
//! only translate them into their protocols.

pub mod commands;
pub mod completion;
pub mod help;
pub mod hover;
pub mod names;
pub mod offsets;
pub mod scanner;
