//! The `rayrepl` binary: parses the command line and hands over to the
//! library. Nothing in the library depends on the size of this thread's
//! stack: deep programs are evaluated on stacks grown on demand and dropped
//! without recursion.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::process::ExitCode;

use clap::Parser;
use rayrepl::cli::{Cli, translate_legacy_args};

fn main() -> ExitCode {
    let cli = Cli::parse_from(translate_legacy_args(std::env::args_os()));
    match catch_unwind(AssertUnwindSafe(|| rayrepl::app::run(cli))) {
        Ok(code) => code,
        Err(_) => {
            eprintln!("rayrepl: internal error (please report it with the input that caused it)");
            ExitCode::from(2)
        }
    }
}
