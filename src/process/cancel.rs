//! Stopping what an entry does without leaving the session: a switch that
//! is armed while a job runs, and whose flag evaluation and renders poll.
//! The front-end raises it (the terminal's Ctrl-C handler,
//! `crate::process::signals`); at any other time the front-end does what
//! it would do anyway. And work that looks at no flag runs on a thread
//! that a cancelled wait abandons ([`off_thread`]).

use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use crate::process::interruption::Signal;

/// The switch that stops a running job.
#[derive(Debug, Default)]
pub struct CancelSwitch {
    /// Raised by Ctrl-C while armed; polled by evaluation and renders.
    cancel: AtomicBool,
    /// How many cancellable jobs are running (an entry, a render inside it).
    armed: AtomicUsize,
    /// The signal that raised the flag ([`Signal::code`]), 0 before one.
    signal: AtomicU8,
}

impl CancelSwitch {
    /// Raises the flag if a job is running, recording that `signal` asked;
    /// says whether one was.
    pub fn cancel_if_armed(&self, signal: Signal) -> bool {
        let armed = self.is_armed();
        if armed {
            self.signal.store(signal.code(), Ordering::SeqCst);
            self.cancel.store(true, Ordering::SeqCst);
        }
        armed
    }

    /// Whether a cancellable job is running.
    pub fn is_armed(&self) -> bool {
        self.armed.load(Ordering::SeqCst) > 0
    }

    /// Arms the switch for one job; it is disarmed when the guard drops. A
    /// job inside another (a render inside an entry) shares its flag.
    pub(crate) fn arm(&'static self) -> ArmedSwitch {
        if self.armed.fetch_add(1, Ordering::SeqCst) == 0 {
            self.cancel.store(false, Ordering::SeqCst);
        }
        ArmedSwitch { switch: self }
    }

    /// The signal that raised the flag last, if one has: what stopped the
    /// last job stopped, until another signal stops one.
    pub(crate) fn last_signal(&self) -> Option<Signal> {
        Signal::from_code(self.signal.load(Ordering::SeqCst))
    }

    /// The flag Ctrl-C raises while the switch is armed.
    pub(crate) fn flag(&'static self) -> &'static AtomicBool {
        &self.cancel
    }
}

/// The flag Ctrl-C raises while `switch` is armed; without a switch, one
/// never raised (Ctrl-C then ends the process).
pub(crate) fn cancel_flag(switch: Option<&'static CancelSwitch>) -> &'static AtomicBool {
    switch.map_or(&crate::output::NEVER_CANCELLED, CancelSwitch::flag)
}

/// A switch armed for the duration of one job.
#[derive(Debug)]
pub(crate) struct ArmedSwitch {
    switch: &'static CancelSwitch,
}

impl ArmedSwitch {
    /// The flag Ctrl-C raises: the job polls it and stops when it is set.
    pub(crate) fn flag(&self) -> &AtomicBool {
        &self.switch.cancel
    }

    /// Whether Ctrl-C was pressed (or another signal asked to stop) since
    /// the outermost job started.
    pub(crate) fn pressed(&self) -> bool {
        self.switch.cancel.load(Ordering::SeqCst)
    }

    /// The signal that raised the flag since the outermost job started.
    pub(crate) fn signal(&self) -> Option<Signal> {
        self.pressed().then(|| Signal::from_code(self.switch.signal.load(Ordering::SeqCst))).flatten()
    }
}

impl Drop for ArmedSwitch {
    fn drop(&mut self) {
        if self.switch.armed.fetch_sub(1, Ordering::SeqCst) == 1 {
            self.switch.cancel.store(false, Ordering::SeqCst);
        }
    }
}

/// How often a wait that cannot be woken looks at its flag: for work on
/// another thread here, and in the terminal's signal listener and plain
/// prompt.
pub(crate) const LOOK: Duration = Duration::from_millis(5);

/// Why work handed to [`off_thread`] gave no answer.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Stopped {
    /// The cancel flag was raised first.
    Cancelled,
    /// The work's thread ended without an answer (it panicked).
    Failed,
}

/// Runs `work` on a thread named `name` and waits for its answer, unless
/// `cancel` is raised first: then the thread is abandoned, and ends when
/// its work does (or with the process). For work that looks at no flag (a
/// read that blocks: `open` of a FIFO no one writes), and for work whose
/// cleanup is long: what it builds and drops (a large syntax tree) is
/// freed on its thread, not while the session waits. Where no thread can
/// be made (wasm32), `work` runs here.
pub(crate) fn off_thread<T: Send + 'static>(
    name: &str,
    cancel: &AtomicBool,
    work: impl FnOnce() -> T + Send + 'static,
) -> Result<T, Stopped> {
    off_thread_streaming(name, cancel, |_: &Parts<(), T>| work(), |()| {})
}

/// How many parts work on another thread may have sent and the waiting
/// thread not yet taken: past that its [`Parts::send`] waits.
const PARTS_AHEAD: usize = 2;

/// What work on another thread sends to the thread that waits for it.
enum Sent<P, T> {
    /// A part of what it makes, handed over as soon as it is made.
    Part(P),
    /// Its answer, the last thing it sends.
    Answer(T),
}

/// How work given to [`off_thread_streaming`] hands over its parts.
pub(crate) struct Parts<P, T> {
    sent: Sender<Sent<P, T>>,
}

/// A channel bounded to [`PARTS_AHEAD`] parts where the work has a thread
/// of its own; unbounded where it runs on the waiting thread (wasm32),
/// which takes its parts once it is done.
enum Sender<M> {
    Bounded(mpsc::SyncSender<M>),
    Unbounded(mpsc::Sender<M>),
}

impl<P, T> Parts<P, T> {
    /// Hands `part` to the waiting thread, waiting while it has
    /// [`PARTS_AHEAD`] parts not yet taken; `false` once the wait is over
    /// (Ctrl-C): nothing more needs to be made.
    pub(crate) fn send(&self, part: P) -> bool {
        self.send_message(Sent::Part(part))
    }

    fn send_message(&self, message: Sent<P, T>) -> bool {
        match &self.sent {
            Sender::Bounded(sent) => sent.send(message).is_ok(),
            Sender::Unbounded(sent) => sent.send(message).is_ok(),
        }
    }
}

impl<P, T> Clone for Parts<P, T> {
    fn clone(&self) -> Self {
        let sent = match &self.sent {
            Sender::Bounded(sent) => Sender::Bounded(sent.clone()),
            Sender::Unbounded(sent) => Sender::Unbounded(sent.clone()),
        };
        Parts { sent }
    }
}

/// [`off_thread`] for work that makes its result in parts: each part it
/// sends (with [`Parts::send`]) is given to `take` here as it comes, at
/// most [`PARTS_AHEAD`] waiting, so what the two threads hold at once stays
/// bounded whatever the size of the whole.
pub(crate) fn off_thread_streaming<P: Send + 'static, T: Send + 'static>(
    name: &str,
    cancel: &AtomicBool,
    work: impl FnOnce(&Parts<P, T>) -> T + Send + 'static,
    mut take: impl FnMut(P),
) -> Result<T, Stopped> {
    let (sent, received) = mpsc::sync_channel(PARTS_AHEAD);
    let parts = Parts { sent: Sender::Bounded(sent) };
    let work = Arc::new(Mutex::new(Some(work)));
    let take_work = |work: &Mutex<Option<_>>| work.lock().unwrap_or_else(PoisonError::into_inner).take();
    let on_thread = Arc::clone(&work);
    let spawned = std::thread::Builder::new().name(name.to_string()).spawn(move || {
        if let Some(work) = take_work(&on_thread) {
            let answer = work(&parts);
            parts.send_message(Sent::Answer(answer));
        }
    });
    if spawned.is_err() {
        let work = take_work(&work).ok_or(Stopped::Failed)?;
        let (sent, received) = mpsc::channel();
        let answer = work(&Parts { sent: Sender::Unbounded(sent) });
        for message in received.try_iter() {
            if let Sent::Part(part) = message {
                take(part);
            }
        }
        return Ok(answer);
    }
    loop {
        let message = received.recv_timeout(LOOK);
        if cancel.load(Ordering::SeqCst) {
            // What came with the Ctrl-C or waits behind it (a whole syntax
            // tree) is freed elsewhere, as what comes after it is, by the
            // work's thread.
            drop_apart((message, received));
            return Err(Stopped::Cancelled);
        }
        match message {
            Ok(Sent::Part(part)) => take(part),
            Ok(Sent::Answer(answer)) => return Ok(answer),
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => return Err(Stopped::Failed),
        }
    }
}

/// Drops `value` on a thread of its own, for a value whose freeing is long
/// (the syntax tree of a large file whose run failed or was stopped: a
/// tenth of a second and more for 100 MB of text), so that the session
/// does not wait for it. Where no thread can be made (wasm32), it is
/// dropped here.
pub(crate) fn drop_apart<T: Send + 'static>(value: T) {
    // A spawn that fails drops its closure, and `value` with it, here.
    let _ = std::thread::Builder::new().name("free".to_string()).spawn(move || drop(value));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value that says on which thread it is dropped.
    struct Noted(mpsc::Sender<std::thread::ThreadId>);

    impl Drop for Noted {
        fn drop(&mut self) {
            self.0.send(std::thread::current().id()).expect("the test waits");
        }
    }

    /// The thread the [`Noted`] whose messages `received` takes was dropped on.
    fn dropped_on(received: &mpsc::Receiver<std::thread::ThreadId>) -> std::thread::ThreadId {
        received.recv_timeout(Duration::from_secs(10)).expect("dropped")
    }

    /// What [`drop_apart`] is given is dropped, on another thread.
    #[test]
    fn a_value_dropped_apart_is_dropped_on_a_thread_of_its_own() {
        let (sent, received) = mpsc::channel();
        drop_apart(Noted(sent));
        assert_ne!(dropped_on(&received), std::thread::current().id());
    }

    /// An answer that comes with the Ctrl-C is not freed by the thread
    /// that waited for it (a large syntax tree would hold it up).
    #[test]
    fn an_answer_cancelled_is_not_dropped_by_the_waiting_thread() {
        static RAISED: AtomicBool = AtomicBool::new(true);
        let (sent, received) = mpsc::channel();
        assert_eq!(off_thread("noted", &RAISED, move || Noted(sent)).err(), Some(Stopped::Cancelled));
        assert_ne!(dropped_on(&received), std::thread::current().id());
    }

    #[test]
    fn work_off_the_thread_answers_or_is_abandoned_when_cancelled() {
        assert_eq!(off_thread("sum", &AtomicBool::new(false), || 6 * 7), Ok(42));
        let never = off_thread("wait", &AtomicBool::new(true), || std::thread::sleep(Duration::from_secs(600)));
        assert_eq!(never, Err(Stopped::Cancelled));
        let panicked = off_thread("panic", &AtomicBool::new(false), || -> u8 { panic!("on purpose") });
        assert_eq!(panicked, Err(Stopped::Failed));
    }
}
