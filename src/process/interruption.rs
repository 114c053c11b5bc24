//! What stops a run from outside: the signal that asked (named in the
//! messages that say where it stopped), and the writes that may block
//! forever (a pipe whose reader does not read), which no flag can stop.
//!
//! The front-end's signal handler (`crate::process::signals`) raises the
//! cancel flag; a job polls it. A write blocked in the kernel polls
//! nothing, so the main thread marks such writes ([`may_block`]) and the
//! handler ends the process when one is still blocked a moment after the
//! signal ([`write_in_progress`]).

use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};

/// A signal that stops a run: Ctrl-C, `kill` or a closed terminal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Signal {
    /// SIGINT: Ctrl-C.
    Interrupt,
    /// SIGTERM: `kill`.
    Terminate,
    /// SIGHUP: the terminal was closed.
    HangUp,
}

impl Signal {
    /// The signal numbered `code` in a one-byte record (see [`Signal::code`]).
    pub(crate) fn from_code(code: u8) -> Option<Signal> {
        [Signal::Interrupt, Signal::Terminate, Signal::HangUp].into_iter().find(|signal| signal.code() == code)
    }

    /// A one-byte record of the signal, never 0 (which records none).
    pub(crate) fn code(self) -> u8 {
        match self {
            Signal::Interrupt => 1,
            Signal::Terminate => 2,
            Signal::HangUp => 3,
        }
    }
}

/// As messages name it: "Ctrl-C" (what sends SIGINT), "SIGTERM", "SIGHUP".
impl fmt::Display for Signal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Signal::Interrupt => "Ctrl-C",
            Signal::Terminate => "SIGTERM",
            Signal::HangUp => "SIGHUP",
        })
    }
}

/// How many writes were marked so far: the number of the last one.
static WRITES: AtomicU64 = AtomicU64::new(0);

/// The number of the marked write in progress, 0 if none.
static IN_PROGRESS: AtomicU64 = AtomicU64::new(0);

/// Does `write`, a write to a stream that may block for as long as its
/// reader does not read, marked as such for the signal handler.
pub(crate) fn may_block<T>(write: impl FnOnce() -> T) -> T {
    let number = WRITES.fetch_add(1, Ordering::SeqCst) + 1;
    let outer = IN_PROGRESS.swap(number, Ordering::SeqCst);
    let result = write();
    IN_PROGRESS.store(outer, Ordering::SeqCst);
    result
}

/// The number of the marked write in progress, if any: the same number
/// some time later means the same write is still not done.
#[cfg(feature = "signals")]
pub(crate) fn write_in_progress() -> Option<u64> {
    Some(IN_PROGRESS.load(Ordering::SeqCst)).filter(|&number| number != 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signals_are_recorded_in_one_byte() {
        for signal in [Signal::Interrupt, Signal::Terminate, Signal::HangUp] {
            assert_eq!(Signal::from_code(signal.code()), Some(signal));
        }
        assert_eq!(Signal::from_code(0), None);
    }
}
