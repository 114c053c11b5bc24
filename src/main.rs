//! The `rayrepl` binary: parses the command line and hands over to the
//! library. Runs on a thread with a large stack so that very deep programs
//! (long expressions, deep recursion) end in results or clear errors, never
//! in a stack overflow.

use std::process::ExitCode;

use clap::Parser;
use rayrepl::cli::{Cli, translate_legacy_args};

/// Stack for the main work: deep ASTs are dropped and walked recursively.
const STACK_SIZE: usize = 1 << 30;

fn main() -> ExitCode {
    let cli = Cli::parse_from(translate_legacy_args(std::env::args_os()));
    let worker = std::thread::Builder::new().stack_size(STACK_SIZE).spawn(move || rayrepl::app::run(cli));
    match worker.map(|handle| handle.join()) {
        Ok(Ok(code)) => code,
        _ => {
            eprintln!("rayrepl: internal error (please report it with the input that caused it)");
            ExitCode::from(2)
        }
    }
}
