//! The integration tests, in one test binary (one link of the library
//! instead of one per file): each module is the tests of one topic, run
//! alone with `cargo test --release --test suite MODULE::`.

mod common;

mod animation;
mod animation_files;
mod cases;
mod cli;
mod closed_streams;
mod compare;
mod deep;
mod diagnostics;
mod docs;
mod eval;
mod explain;
mod fmt;
mod fuzz;
mod golden;
mod hostile_files;
mod hostile_runs;
mod hostile_scenes;
mod keep_going;
mod language_limits;
mod lesson_papercuts;
mod lessons;
mod memory_limits;
mod parse;
mod pov_export;
mod print;
mod properties;
mod render;
mod repl_interactive;
mod repl_script;
mod scale;
mod scale_out;
mod signals;
mod stability;
mod warnings;
