//! The notebook kernel (`rayrepl jupyter --connection-file FILE`, started
//! by Jupyter from the kernelspec `rayrepl jupyter install` writes).
//!
//! Each cell runs in one session core ([`CellSession`]), on the thread
//! that started the kernel, as a piped script runs its lines: definitions
//! accumulate across cells, a cell stops at its first error, which names
//! the cell as the notebook shows it (`<cell 3>:2:5`). What a cell shows
//! goes out as it comes (`front`); the sockets are served on a thread of
//! their own (`sockets`), which answers the control channel at once, so
//! that an interrupt (a message, or SIGINT: both modes of the kernelspec
//! work) stops a running cell and leaves the session as before it.

mod front;
pub mod install;
mod sockets;

use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

use jupyter_protocol::{
    CodeMirrorMode, CommInfoReply, CompleteReply, CompleteRequest, ConnectionInfo, ExecuteInput, ExecuteReply,
    ExecuteRequest, ExecutionCount, HistoryEntry, HistoryReply, HistoryRequest, InspectReply, InspectRequest,
    InterruptReply, IsCompleteReply, IsCompleteRequest, JupyterMessage, JupyterMessageContent, KernelInfoReply,
    LanguageInfo, Media, MediaType, ReplyError, ReplyStatus, ShutdownReply, ShutdownRequest, Status,
};

use crate::clock::Stopwatch;
use crate::ide::offsets::{byte_of_char, chars_before};
use crate::process::interruption::Signal;
use crate::session::{CancelSwitch, CellEnd, CellSession, Completeness, FrontEnd, SessionOptions};
use front::KernelFront;
use sockets::{Control, Outgoing};

pub use install::{KernelPrefix, install};

/// The language's name, as notebooks and their exporters know it (the
/// kernelspec's `language`, the Pygments lexer's and CodeMirror mode's name).
pub const LANGUAGE: &str = "ray";

/// Serves the kernel whose sockets `connection_file` describes, until a
/// shutdown request ends the process; the kernel's interrupt (SIGINT) stops
/// the cell that runs. Fails with the reason when the file cannot be read,
/// a socket cannot be bound or the signals cannot be heard.
pub fn serve(connection_file: &Path) -> Result<(), String> {
    let switch = crate::process::signals::install().ok_or("Ctrl-C cannot be handled here")?;
    let text = std::fs::read_to_string(connection_file).map_err(|error| {
        format!(
            "the connection file {} cannot be read: {}",
            connection_file.display(),
            crate::output::io_reason(&error)
        )
    })?;
    let info: ConnectionInfo = serde_json::from_str(&text)
        .map_err(|error| format!("the connection file {} is not one: {error}", connection_file.display()))?;
    crate::process::signals::ignore_idle_interrupts();
    let session_id = uuid::Uuid::new_v4().to_string();
    let (requests, outgoing) =
        sockets::start(info, session_id, Box::new(move |request, outgoing| control(request, outgoing, switch)))?;
    let mut kernel = Kernel {
        cells: CellSession::new(&SessionOptions::default()).with_cancel(switch),
        switch,
        outgoing,
        count: 0,
        history: Vec::new(),
    };
    kernel.outgoing.iopub(JupyterMessage::new(Status::starting(), None));
    while let Ok(request) = requests.recv() {
        kernel.handle(&request, &requests);
    }
    Ok(())
}

/// Answers a request on the control channel, on the sockets' thread: at
/// once, even while a cell runs.
fn control(request: &JupyterMessage, outgoing: &Outgoing, switch: &'static CancelSwitch) -> Control {
    let reply = |content: JupyterMessageContent| JupyterMessage::new(content, Some(request));
    outgoing.iopub(JupyterMessage::new(Status::busy(), Some(request)));
    let answer = match &request.content {
        JupyterMessageContent::InterruptRequest(_) => {
            switch.cancel_if_armed(Signal::Interrupt);
            Control::Reply(reply(InterruptReply::new().into()))
        }
        JupyterMessageContent::ShutdownRequest(shutdown) => {
            Control::ReplyAndEnd(shutdown_reply(shutdown, request, outgoing))
        }
        JupyterMessageContent::KernelInfoRequest(_) => Control::Reply(reply(kernel_info().into())),
        other => {
            sockets_ignored(other.message_type());
            Control::Ignore
        }
    };
    outgoing.iopub(JupyterMessage::new(Status::idle(), Some(request)));
    answer
}

/// The reply to `shutdown` (the content of `request`, on the control or
/// the shell channel), also published on IOPub, as the protocol asks.
fn shutdown_reply(shutdown: &ShutdownRequest, request: &JupyterMessage, outgoing: &Outgoing) -> JupyterMessage {
    let content = ShutdownReply { restart: shutdown.restart, status: ReplyStatus::Ok, error: None };
    outgoing.iopub(JupyterMessage::new(content.clone(), Some(request)));
    JupyterMessage::new(content, Some(request))
}

/// Logs a request of a type the kernel does not answer.
fn sockets_ignored(message_type: &str) {
    crate::process::failure::report_failure(format!(
        "kernel: a `{message_type}` message was ignored: it is not one this kernel answers"
    ));
}

/// What the kernel says of itself and its language.
fn kernel_info() -> KernelInfoReply {
    KernelInfoReply {
        status: ReplyStatus::Ok,
        protocol_version: "5.3".to_string(),
        implementation: "rayrepl".to_string(),
        implementation_version: env!("CARGO_PKG_VERSION").to_string(),
        language_info: LanguageInfo {
            name: LANGUAGE.to_string(),
            version: env!("CARGO_PKG_VERSION").to_string(),
            mimetype: Some("text/x-ray".to_string()),
            file_extension: Some(".ray".to_string()),
            pygments_lexer: Some(LANGUAGE.to_string()),
            codemirror_mode: Some(CodeMirrorMode::Simple(LANGUAGE.to_string())),
            nbconvert_exporter: None,
        },
        banner: format!(
            "rayrepl {}: the .ray scene language. Cells hold items and `:` commands; `:render` shows the picture, \
             `:help` lists the commands, `:lesson 1` starts the first lesson.",
            env!("CARGO_PKG_VERSION")
        ),
        help_links: Vec::new(),
        debugger: false,
        error: None,
    }
}

/// How long a failed cell waits for the requests its client sent before
/// the failure reached it (a notebook's "Run All" sends every cell at
/// once), to abort them: they are read by the sockets' thread, and may
/// reach the session's thread just after the cell ends. A client that
/// waits for each reply (nbclient) sends nothing in this window.
const QUEUED_WINDOW: Duration = Duration::from_millis(50);

/// The session and what the kernel keeps beside it.
struct Kernel {
    cells: CellSession,
    switch: &'static CancelSwitch,
    outgoing: Outgoing,
    /// The execution count: how many cells were run with `store_history`.
    count: usize,
    /// Those cells, with their counts.
    history: Vec<(usize, String)>,
}

impl Kernel {
    /// Answers one shell request, between a `busy` and an `idle` status.
    /// A cell that fails with `stop_on_error` aborts the cells its client
    /// queued behind it, as IPython's kernel does; the other requests
    /// queued with them are answered in order.
    fn handle(&mut self, request: &JupyterMessage, requests: &mpsc::Receiver<JupyterMessage>) {
        self.outgoing.iopub(JupyterMessage::new(Status::busy(), Some(request)));
        let mut queued = Vec::new();
        let reply: Option<JupyterMessageContent> = match &request.content {
            JupyterMessageContent::ExecuteRequest(execute) => {
                let reply = self.execute(request, execute);
                if reply.status == ReplyStatus::Error && execute.stop_on_error {
                    // Before the reply: what comes after it may follow it.
                    let waited = Stopwatch::start();
                    while let Some(left) = QUEUED_WINDOW.checked_sub(waited.elapsed())
                        && let Ok(next) = requests.recv_timeout(left)
                    {
                        queued.push(next);
                    }
                }
                Some(reply.into())
            }
            JupyterMessageContent::KernelInfoRequest(_) => Some(kernel_info().into()),
            JupyterMessageContent::IsCompleteRequest(IsCompleteRequest { code }) => Some(is_complete(code).into()),
            JupyterMessageContent::CompleteRequest(complete) => Some(self.complete(complete).into()),
            JupyterMessageContent::InspectRequest(inspect) => Some(self.inspect(inspect).into()),
            JupyterMessageContent::HistoryRequest(history) => Some(self.history(history).into()),
            JupyterMessageContent::CommInfoRequest(_) => Some(CommInfoReply::default().into()),
            JupyterMessageContent::ShutdownRequest(shutdown) => {
                self.outgoing.reply(shutdown_reply(shutdown, request, &self.outgoing));
                // The reply goes out before the process ends.
                std::thread::sleep(std::time::Duration::from_millis(100));
                std::process::exit(0);
            }
            other => {
                sockets_ignored(other.message_type());
                None
            }
        };
        if let Some(reply) = reply {
            self.outgoing.reply(JupyterMessage::new(reply, Some(request)));
        }
        self.outgoing.iopub(JupyterMessage::new(Status::idle(), Some(request)));
        for next in queued {
            match &next.content {
                JupyterMessageContent::ExecuteRequest(_) => self.abort(&next),
                _ => self.handle(&next, requests),
            }
        }
    }

    /// Answers a queued cell without running it: a cell before it failed.
    fn abort(&self, request: &JupyterMessage) {
        self.outgoing.iopub(JupyterMessage::new(Status::busy(), Some(request)));
        let reply = ExecuteReply {
            status: ReplyStatus::Aborted,
            execution_count: ExecutionCount::new(self.count),
            payload: Vec::new(),
            user_expressions: Some(std::collections::HashMap::new()),
            error: None,
        };
        self.outgoing.reply(JupyterMessage::new(reply, Some(request)));
        self.outgoing.iopub(JupyterMessage::new(Status::idle(), Some(request)));
    }

    /// Runs a cell: its outputs go out as they come, its first error is
    /// the reply's.
    fn execute(&mut self, request: &JupyterMessage, execute: &ExecuteRequest) -> ExecuteReply {
        let stored = execute.store_history && !execute.silent;
        if stored {
            self.count += 1;
        }
        let count = ExecutionCount::new(self.count);
        if !execute.silent {
            let input = ExecuteInput { code: execute.code.clone(), execution_count: count };
            self.outgoing.iopub(JupyterMessage::new(input, Some(request)));
        }
        let name = if stored { format!("<cell {}>", self.count) } else { "<cell>".to_string() };
        let mut front = KernelFront {
            outgoing: &self.outgoing,
            parent: request,
            silent: execute.silent,
            switch: self.switch,
            history: self.history.iter().map(|(_, code)| code.clone()).collect(),
            first_error: None,
            pending: String::new(),
        };
        // Armed for the whole cell: an interrupt between two of its inputs stops it too.
        let armed = self.switch.arm();
        let ended = self.cells.run(&name, &execute.code, &mut front);
        drop(armed);
        front.flush();
        let first_error = front.first_error.take();
        if stored {
            self.history.push((self.count, execute.code.clone()));
        }
        let error = match ended {
            CellEnd::Done => None,
            CellEnd::Quit => {
                let note = "a notebook's kernel keeps running after `:quit`: Kernel > Shut Down ends it";
                self.outgoing.iopub(JupyterMessage::new(
                    jupyter_protocol::StreamContent::stdout(&format!("{note}\n")),
                    Some(request),
                ));
                None
            }
            CellEnd::Failed | CellEnd::Interrupted => Some(first_error.unwrap_or_else(|| ReplyError {
                ename: "error".to_string(),
                evalue: "the cell failed".to_string(),
                traceback: Vec::new(),
            })),
        };
        ExecuteReply {
            status: if error.is_some() { ReplyStatus::Error } else { ReplyStatus::Ok },
            execution_count: count,
            payload: Vec::new(),
            // Expressions are not asked for by name here: none are evaluated.
            user_expressions: Some(std::collections::HashMap::new()),
            error: error.map(Box::new),
        }
    }

    /// The session's completions at the cursor (which counts characters).
    fn complete(&self, request: &CompleteRequest) -> CompleteReply {
        let cursor = byte_of_char(&request.code, request.cursor_pos);
        let completions = self.cells.complete(&request.code, cursor);
        CompleteReply {
            matches: completions.candidates,
            cursor_start: chars_before(&request.code, completions.start),
            cursor_end: chars_before(&request.code, completions.end),
            metadata: serde_json::Map::new(),
            status: ReplyStatus::Ok,
            error: None,
        }
    }

    /// What the session says of the word at the cursor.
    fn inspect(&mut self, request: &InspectRequest) -> InspectReply {
        let cursor = byte_of_char(&request.code, request.cursor_pos);
        let text = self.cells.inspect(&request.code, cursor);
        InspectReply {
            found: text.is_some(),
            data: text.map(|text| Media::new(vec![MediaType::Plain(text)])).unwrap_or_default(),
            metadata: serde_json::Map::new(),
            status: ReplyStatus::Ok,
            error: None,
        }
    }

    /// The cells run, as asked: the last `n`, a range of counts, or those
    /// matching a glob pattern (`*` and `?`).
    fn history(&self, request: &HistoryRequest) -> HistoryReply {
        let entry = |(count, code): &(usize, String)| HistoryEntry::Input(0, *count, code.clone());
        let entries: Vec<HistoryEntry> = match request {
            HistoryRequest::Tail { n, .. } => {
                let n = usize::try_from(*n).unwrap_or(0);
                self.history[self.history.len().saturating_sub(n)..].iter().map(entry).collect()
            }
            HistoryRequest::Range { start, stop, .. } => {
                let within = |count: usize| {
                    let count = i64::try_from(count).unwrap_or(i64::MAX);
                    count >= i64::from(*start) && (*stop <= 0 || count < i64::from(*stop))
                };
                self.history.iter().filter(|(count, _)| within(*count)).map(entry).collect()
            }
            HistoryRequest::Search { pattern, unique, n, .. } => {
                let mut found: Vec<&(usize, String)> =
                    self.history.iter().filter(|(_, code)| glob_matches(pattern, code)).collect();
                if *unique {
                    let mut seen = std::collections::HashSet::new();
                    found.retain(|(_, code)| seen.insert(code.as_str()));
                }
                let n = usize::try_from(*n).ok().filter(|n| *n > 0).unwrap_or(found.len());
                found[found.len().saturating_sub(n)..].iter().map(|pair| entry(pair)).collect()
            }
        };
        HistoryReply::new(entries)
    }
}

/// Whether `code` is ready to run, as the parser reads it.
fn is_complete(code: &str) -> IsCompleteReply {
    match CellSession::completeness(code) {
        Completeness::Complete => IsCompleteReply::complete(),
        Completeness::Incomplete { indent } => IsCompleteReply::incomplete(indent),
        Completeness::Invalid => IsCompleteReply::invalid(),
    }
}

/// Whether `text` matches the glob `pattern` (`*` any run, `?` one character).
fn glob_matches(pattern: &str, text: &str) -> bool {
    let (pattern, text): (Vec<char>, Vec<char>) = (pattern.chars().collect(), text.chars().collect());
    // The classic two-pointer match, going back to the last `*`.
    let (mut p, mut t, mut star, mut after_star) = (0, 0, None, 0);
    while t < text.len() {
        if p < pattern.len() && (pattern[p] == '?' || pattern[p] == text[t]) {
            (p, t) = (p + 1, t + 1);
        } else if p < pattern.len() && pattern[p] == '*' {
            (star, after_star, p) = (Some(p), t, p + 1);
        } else if let Some(star) = star {
            after_star += 1;
            (p, t) = (star + 1, after_star);
        } else {
            return false;
        }
    }
    pattern[p..].iter().all(|c| *c == '*')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn globs_match_as_history_searches_expect() {
        assert!(glob_matches("*sphere*", "put sphere end"));
        assert!(glob_matches("let ?=*", "let a=1"));
        assert!(!glob_matches("let ?=*", "let ab=1"));
        assert!(glob_matches("*", ""));
        assert!(!glob_matches("a", ""));
    }
}
