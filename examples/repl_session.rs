//! The session entry point as `main` will call it, for trying the session
//! before the binary is wired: `cargo run --example repl_session -- [-i FILE]
//! [--no-preview] [--keep-going]`.

use std::process::ExitCode;

use rayrepl::repl::{SessionOptions, run};

fn main() -> ExitCode {
    let mut options = SessionOptions::default();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--no-preview" => options.no_preview = true,
            "--keep-going" => options.keep_going = true,
            "-i" => options.initial_file = args.next().map(Into::into),
            other => {
                eprintln!("unknown argument `{other}`");
                return ExitCode::FAILURE;
            }
        }
    }
    run(&options)
}
