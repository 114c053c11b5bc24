//! Scripts on standard input, `cat script | rayrepl`: the session core
//! runs their lines (`session::script`) and a [`Console`] writes what they
//! show, messages on standard output and diagnostics on standard error.

use std::io::BufRead;

use anstream::stream::RawStream;

use super::console::Console;
use crate::output::INTERRUPTED_EXIT_CODE;
use crate::process::cancel::CancelSwitch;
use crate::session::options::new_session;
use crate::session::script::{Named, Ran, TextRan, run_lines};
use crate::session::shell::Shell;
use crate::session::{Session, SessionOptions};

/// The name scripts' diagnostics show.
const SCRIPT_NAME: &str = "<stdin>";

/// Runs the script read from `input`, writing messages to `out` and
/// diagnostics to `err` (with colours only where the stream is a terminal
/// that wants them). The first error stops the script unless
/// `options.keep_going`; `options.initial_file` is loaded first. A script
/// that succeeds without writing an image ends with a note on how to write
/// one. Returns the exit status: 0 if everything succeeded, 1 otherwise.
/// Nothing stops it midway (the command line's session stops it with Ctrl-C).
pub fn run_script(
    input: impl BufRead,
    out: &mut (impl RawStream + 'static),
    err: &mut (impl RawStream + 'static),
    options: &SessionOptions,
) -> i32 {
    run_script_keeping_session(input, out, err, options, None).0
}

/// Runs the script as [`run_script`] does, stopped (status 130) when
/// `cancel` is raised, and returns its exit status with the session it
/// built, for a caller that ends the process next and need not free what
/// the session holds.
pub(crate) fn run_script_keeping_session(
    input: impl BufRead,
    out: &mut (impl RawStream + 'static),
    err: &mut (impl RawStream + 'static),
    options: &SessionOptions,
    cancel: Option<&'static CancelSwitch>,
) -> (i32, Session) {
    let mut console = Console::new(out, err);
    console.cancel = cancel;
    let mut shell = Shell::new(new_session(options, console.cancel));
    let mut ended = run_in(&mut shell, &mut console, input, options);
    if let Some(reason) = console.unwritten.take() {
        console.error(format!("some of the script's answers could not be written: {reason}"));
        if !matches!(ended, Ended::Status(code) if code != 0) {
            ended = Ended::Status(1);
        }
    }
    drop(console);
    let code = match ended {
        Ended::Status(code) => code,
        Ended::WithoutPicture => {
            let _ = writeln!(
                err,
                "note: the script wrote no picture: end it with `:save out.png` (or `:anim 100 out.gif`)"
            );
            0
        }
    };
    (code, shell.session)
}

/// How a script ended.
enum Ended {
    /// With this exit status.
    Status(i32),
    /// Successfully, without writing an image file.
    WithoutPicture,
}

/// Runs the script in `shell`, as [`run_script`] says.
fn run_in(shell: &mut Shell, console: &mut Console, input: impl BufRead, options: &SessionOptions) -> Ended {
    let named = Named { name: SCRIPT_NAME, noun: "script" };
    let cancel = console.cancel;
    match run_lines(shell, console, cancel, named, options, input) {
        Ran { ended: TextRan::Interrupted, .. } => Ended::Status(INTERRUPTED_EXIT_CODE),
        Ran { ended: TextRan::Failed, .. } => Ended::Status(1),
        Ran { wrote: true, .. } => Ended::Status(0),
        Ran { wrote: false, .. } => Ended::WithoutPicture,
    }
}
