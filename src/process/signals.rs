//! Ctrl-C, SIGTERM and SIGHUP.
//!
//! At the line editor's prompt the terminal is in raw mode and rustyline
//! reads Ctrl-C as a key. While an entry runs (evaluation, a render, the
//! writing of a file) it is not, so Ctrl-C raises SIGINT; `kill` sends
//! SIGTERM, a closed terminal SIGHUP. One listener is installed per
//! process; while the session's switch is armed a signal raises the cancel
//! flag that evaluation, reads and renders poll (recording which signal it
//! was, for the messages), and at any other time it does what the signal
//! does by default: end the program (status 130 for all three, as the
//! guide says, with no temporary file left).
//!
//! Two waits poll no flag. A write to a pipe whose reader does not read
//! blocks in the kernel: if one marked by [`crate::process::interruption::may_block`]
//! is still blocked [`STUCK`] after the signal, the process ends at once,
//! discarding unfinished files. And a prompt read without the line editor
//! (a terminal it does not support: `TERM=dumb`) sees Ctrl-C as SIGINT:
//! while [`at_plain_prompt`] waits, SIGINT drops the line, as the key does
//! in the editor.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crate::clock::Stopwatch;
use crate::output::{INTERRUPTED_EXIT_CODE, discarding_unfinished, exit_discarding_unfinished};
use crate::process::cancel::{CancelSwitch, LOOK};
use crate::process::interruption::{Signal, write_in_progress};

/// The switch, once the listener is installed; `None` inside if installing failed.
static SWITCH: OnceLock<Option<CancelSwitch>> = OnceLock::new();

/// How long a marked write may stay blocked after a signal before the
/// process ends (a terminal write returns well within it).
const STUCK: Duration = Duration::from_millis(50);

/// How long the listener waits for its last message before ending the
/// process (standard error may be the stream that blocks).
const LAST_WORDS: Duration = Duration::from_millis(20);

/// The switch the signals raise, with its listener installed on first use.
/// `None` if the listener could not be installed.
pub fn install() -> Option<&'static CancelSwitch> {
    SWITCH.get_or_init(|| listen().then(CancelSwitch::default)).as_ref()
}

/// Starts a thread that hands each SIGINT, SIGTERM and SIGHUP to
/// [`on_signal`]; says whether it runs.
#[cfg(unix)]
fn listen() -> bool {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else { return false };
    let listener = std::thread::Builder::new().name("signals".to_string()).spawn(move || {
        for number in signals.forever() {
            on_signal(match number {
                SIGTERM => Signal::Terminate,
                SIGHUP => Signal::HangUp,
                _ => Signal::Interrupt,
            });
        }
    });
    listener.is_ok()
}

/// Hands each Ctrl-C (or the console's closing) to [`on_signal`]; says
/// whether the handler is installed.
#[cfg(not(unix))]
fn listen() -> bool {
    ctrlc::set_handler(|| on_signal(Signal::Interrupt)).is_ok()
}

fn on_signal(signal: Signal) {
    if signal == Signal::Interrupt && PLAIN_PROMPT_WAITING.load(Ordering::SeqCst) {
        PLAIN_PROMPT_INTERRUPTED.store(true, Ordering::SeqCst);
        return;
    }
    match SWITCH.get() {
        Some(Some(switch)) if switch.cancel_if_armed(signal) => end_if_stuck(switch, signal),
        _ if signal == Signal::Interrupt && IDLE_INTERRUPTS_IGNORED.load(Ordering::SeqCst) => {}
        _ => exit_discarding_unfinished(INTERRUPTED_EXIT_CODE),
    }
}

/// Whether SIGINT while nothing runs is ignored ([`ignore_idle_interrupts`]).
static IDLE_INTERRUPTS_IGNORED: AtomicBool = AtomicBool::new(false);

/// From now on SIGINT while no job runs does nothing, rather than end the
/// process: a notebook's kernel, which Jupyter interrupts with SIGINT
/// whether a cell runs or not (SIGTERM and SIGHUP still end it).
pub fn ignore_idle_interrupts() {
    IDLE_INTERRUPTS_IGNORED.store(true, Ordering::SeqCst);
}

/// Watches the job `signal` stopped until its switch is disarmed: if a
/// marked write stays blocked for [`STUCK`] meanwhile, ends the process.
fn end_if_stuck(switch: &CancelSwitch, signal: Signal) {
    let mut watched: Option<(u64, Stopwatch)> = None;
    loop {
        match (write_in_progress(), watched) {
            (Some(write), Some((seen, since))) if write == seen => {
                if since.elapsed() >= STUCK {
                    end_stuck(signal);
                }
            }
            (Some(write), _) => watched = Some((write, Stopwatch::start())),
            (None, _) if !switch.is_armed() => return,
            (None, _) => watched = None,
        }
        std::thread::sleep(LOOK);
    }
}

/// Ends the process, whose main thread is stuck in a write, saying so if
/// standard error takes it soon, with no temporary file left.
fn end_stuck(signal: Signal) -> ! {
    let (said, saying) = std::sync::mpsc::channel();
    let message = format!("interrupted by {signal}: the output was not being read, so it stops here");
    let speaker = std::thread::Builder::new().spawn(move || {
        crate::process::failure::report_failure(message);
        let _ = said.send(());
    });
    if speaker.is_ok() {
        let _ = saying.recv_timeout(LAST_WORDS);
    }
    discarding_unfinished(INTERRUPTED_EXIT_CODE, exit_at_once)
}

/// Ends the process with `code` without flushing standard output, whose
/// lock the stuck main thread may hold.
#[cfg(unix)]
fn exit_at_once(code: i32) -> ! {
    signal_hook::low_level::exit(code)
}

#[cfg(not(unix))]
fn exit_at_once(code: i32) -> ! {
    std::process::exit(code)
}

/// Whether a plain prompt waits for a line (SIGINT then drops it).
static PLAIN_PROMPT_WAITING: AtomicBool = AtomicBool::new(false);

/// Raised by SIGINT while a plain prompt waits.
static PLAIN_PROMPT_INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// A prompt read without the line editor, waiting: SIGINT drops the line
/// rather than ending the session (SIGTERM and SIGHUP still end it).
pub struct PlainPrompt(());

/// Starts a wait at a plain prompt, until the guard drops.
pub fn at_plain_prompt() -> PlainPrompt {
    PLAIN_PROMPT_INTERRUPTED.store(false, Ordering::SeqCst);
    PLAIN_PROMPT_WAITING.store(true, Ordering::SeqCst);
    PlainPrompt(())
}

impl PlainPrompt {
    /// Whether Ctrl-C was pressed since the wait started.
    pub fn interrupted(&self) -> bool {
        PLAIN_PROMPT_INTERRUPTED.load(Ordering::SeqCst)
    }
}

impl Drop for PlainPrompt {
    fn drop(&mut self) {
        PLAIN_PROMPT_WAITING.store(false, Ordering::SeqCst);
    }
}
