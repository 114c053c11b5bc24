//! Text pasted at the prompt without bracketed paste, read at once.
//!
//! Without bracketed paste a terminal sends pasted text as if it were typed,
//! and rustyline repaints the whole line each time the cursor wraps to a new
//! row: a long pasted line costs the square of its length. So the session
//! waits for the first key itself, the terminal in raw mode as the editor
//! sets it: when more bytes come at once than a person types, it reads them
//! all as a paste; otherwise it leaves them unread, for the line editor.
//! Nothing is read twice or lost, and the order is kept.

use std::io::{self, Write};
use std::os::fd::{AsFd, BorrowedFd};
use std::time::Duration;

use rustix::event::{PollFd, PollFlags, Timespec, poll};
use rustix::io::{Errno, ioctl_fionread, read};
use rustix::termios::{OptionalActions, Termios, tcgetattr, tcsetattr};

/// More bytes than this coming together are not keys pressed by a person
/// (one key sends at most 7: `ESC [ 1 5 ; 5 ~`).
const KEYS_OF_A_PERSON: u64 = 16;

/// How long after the first byte the bytes that came with it are counted:
/// a paste comes in a burst, a person's next key tens of milliseconds later.
const SETTLE: Duration = Duration::from_millis(10);

/// A paste has ended when no byte came for this long.
const PAUSE: Duration = Duration::from_millis(50);

/// What came at the prompt.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Arrival {
    /// Keys for the line editor, left unread; the prompt is erased for the
    /// editor to draw its own.
    Keys,
    /// The text of a paste, read; the prompt stays on the screen.
    Paste(String),
}

/// Shows `prompt` and waits for what the terminal sends next. The terminal
/// is in raw mode from before the prompt shows until this returns, so that
/// keys sent after the prompt are neither echoed nor turned into signals.
pub(crate) fn wait_at_prompt(prompt: &str) -> io::Result<Arrival> {
    let stdin = io::stdin();
    let terminal = stdin.as_fd();
    let _raw = RawMode::enter(terminal)?;
    let mut out = io::stdout();
    out.write_all(prompt.as_bytes())?;
    out.flush()?;
    while !readable_within(terminal, None)? {}
    std::thread::sleep(SETTLE);
    if ioctl_fionread(terminal)? > KEYS_OF_A_PERSON {
        return Ok(Arrival::Paste(pasted_text(&read_burst(terminal)?)));
    }
    erase_prompt()?;
    Ok(Arrival::Keys)
}

/// Erases the prompt [`wait_at_prompt`] showed, for the editor to draw its own.
pub(crate) fn erase_prompt() -> io::Result<()> {
    let mut out = io::stdout();
    out.write_all(b"\r\x1b[K")?;
    out.flush()
}

/// The terminal in raw mode, put back as it was on drop.
struct RawMode<'fd> {
    terminal: BorrowedFd<'fd>,
    original: Termios,
}

impl<'fd> RawMode<'fd> {
    fn enter(terminal: BorrowedFd<'fd>) -> io::Result<RawMode<'fd>> {
        let original = tcgetattr(terminal)?;
        let mut raw = original.clone();
        raw.make_raw();
        tcsetattr(terminal, OptionalActions::Now, &raw)?;
        Ok(RawMode { terminal, original })
    }
}

impl Drop for RawMode<'_> {
    fn drop(&mut self) {
        let _ = tcsetattr(self.terminal, OptionalActions::Now, &self.original);
    }
}

/// Whether a byte can be read within `timeout` (`None`: waits for one).
fn readable_within(terminal: BorrowedFd<'_>, timeout: Option<Duration>) -> io::Result<bool> {
    let timeout = timeout.map(|t| Timespec::try_from(t).expect("a short timeout fits"));
    let mut fds = [PollFd::from_borrowed_fd(terminal, PollFlags::IN)];
    match poll(&mut fds, timeout.as_ref()) {
        Ok(ready) => Ok(ready > 0),
        // A signal (the window resized): the caller asks again.
        Err(Errno::INTR) => Ok(false),
        Err(error) => Err(error.into()),
    }
}

/// The bytes of a burst: all that comes until a pause.
fn read_burst(terminal: BorrowedFd<'_>) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut buffer = vec![0; 1 << 16];
    loop {
        let read = read(terminal, &mut buffer[..])?;
        bytes.extend_from_slice(&buffer[..read]);
        if read == 0 || !readable_within(terminal, Some(PAUSE))? {
            return Ok(bytes);
        }
    }
}

/// The text of pasted bytes: line ends as `\n`, and no control characters
/// but tabs (a terminal in raw mode sends Enter as `\r`).
fn pasted_text(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes).replace("\r\n", "\n").replace('\r', "\n");
    text.chars().filter(|&c| !c.is_control() || c == '\n' || c == '\t').collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pasted_text_has_plain_line_ends_and_no_control_characters() {
        assert_eq!(pasted_text(b"let a = 1\r\nput\tb\rend\x07\x1b"), "let a = 1\nput\tb\nend");
        assert_eq!(pasted_text("couleur é\n".as_bytes()), "couleur é\n");
    }
}
