//! The interactive session: prompts, the line editor, history on disk,
//! Ctrl-C and Ctrl-D.

use std::collections::VecDeque;
use std::io::{BufRead, Write};
use std::path::PathBuf;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::Duration;

use anstream::stream::RawStream;
use anstream::{AutoStream, ColorChoice};
use rustyline::Editor;
use rustyline::config::{ColorMode, CompletionType, Config};
use rustyline::error::ReadlineError;
use rustyline::history::FileHistory;

use crate::clock::Stopwatch;
use crate::ide::commands::{bare_word_command, is_command};
use crate::ide::scanner::open_constructs;
use crate::lang::{EntryState, Limits, RaisedWith, entry_state};

use super::console::Console;
use crate::session::commands::{self, Flow};
use crate::session::file_commands::load_reporting;
use crate::session::inputs::report_input;
use crate::session::lesson_commands;
use crate::session::options::new_session;
use crate::session::report::counted;
use crate::session::shell::Shell;
use crate::session::{FrontEnd, Session, SessionOptions};

use super::editor::RayHelper;
use super::front_end::TerminalFrontEnd;
use super::history::history_path;
use super::preview::Preview;
use crate::process::signals;

/// The prompt for a new input, after its number.
const PROMPT: &str = "ray> ";

/// A line read faster than this was not typed by a person but typed ahead
/// or pasted, so more lines may follow it.
const TYPING: Duration = Duration::from_millis(30);

/// Why the interactive session could not run.
#[derive(Debug)]
pub enum ReplError {
    /// The terminal could not be used for line editing.
    Terminal(ReadlineError),
}

impl std::fmt::Display for ReplError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReplError::Terminal(error) => write!(f, "cannot read from the terminal: {error}"),
        }
    }
}

impl std::error::Error for ReplError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReplError::Terminal(error) => Some(error),
        }
    }
}

/// Runs an interactive session on the terminal until `:quit` or Ctrl-D,
/// after loading `options.initial_file` if there is one. History is kept in
/// the user's data directory (`rayrepl/history`); problems with that file
/// are ignored.
pub fn run_interactive(options: &SessionOptions) -> Result<(), ReplError> {
    let (mut out, mut err) = (std::io::stdout(), std::io::stderr());
    let mut console = Console::new(&mut out, &mut err);
    console.cancel = signals::install();
    let front: &mut dyn FrontEnd = &mut TerminalFrontEnd { console, preview: Preview::new(options.no_preview) };
    if editor_unsupported() {
        greet(front);
        return run_entries(PlainTerminal::start(), front, options);
    }
    // The editor draws prompts and highlighting on standard output.
    let color = AutoStream::choice(&std::io::stdout()) != ColorChoice::Never;
    let mut editor = new_editor(color).map_err(ReplError::Terminal)?;
    let history = history_path();
    if let Some(path) = &history {
        let _ = editor.load_history(path);
    }
    greet(front);
    run_entries(Terminal { editor, history }, front, options)
}

fn greet(front: &mut dyn FrontEnd) {
    front.say(format!(
        "rayrepl {}: type items of the .ray language, `:help` to learn, Ctrl-D to leave",
        env!("CARGO_PKG_VERSION")
    ));
}

/// Whether the line editor leaves this terminal alone (rustyline's list:
/// `TERM=dumb`, as Emacs shells and some IDE consoles set it, `cons25`,
/// `emacs`) and reads lines as the terminal edits them.
fn editor_unsupported() -> bool {
    std::env::var("TERM").is_ok_and(|term| ["dumb", "cons25", "emacs"].iter().any(|t| t.eq_ignore_ascii_case(&term)))
}

/// Runs the interactive session's entry loop on `lines` as if each was
/// typed at the prompt and ended with Enter, then Ctrl-D: messages go to
/// `out` and diagnostics to `err`, as on a terminal (without prompts,
/// previews or progress bars). It shows what a person at the terminal sees
/// without needing one: the tests of the session's messages use it.
pub fn run_typed(
    lines: impl IntoIterator<Item = String>,
    out: &mut (impl RawStream + 'static),
    err: &mut (impl RawStream + 'static),
    options: &SessionOptions,
) {
    let mut console = Console::new(out, err);
    let ended = run_entries(Typed(lines.into_iter()), &mut console, options);
    ended.expect("typed lines never fail to be read");
}

/// Loads `options.initial_file`, then runs the session on what is typed.
fn run_entries(lines: impl LineSource, front: &mut dyn FrontEnd, options: &SessionOptions) -> Result<(), ReplError> {
    // A flag cannot be given any more: errors point to `:limits` instead.
    let limits = Limits { raised_with: RaisedWith::Commands, ..options.limits };
    let mut shell = Shell::new(new_session(&SessionOptions { limits, ..options.clone() }, front.cancel()));
    if let Some(path) = &options.initial_file {
        let _ = load_reporting(&mut shell, path, front);
    }
    if let Some(lesson) = &options.lesson {
        let _ = lesson_commands::start_reporting(&mut shell, lesson, front);
    }
    Repl { lines, shell, inputs: 0, queued: VecDeque::new(), several_lines_read: false }.run(front)
}

/// Where the session's lines come from: the line editor, or lines given in
/// advance.
trait LineSource {
    /// The next line typed after `prompt`, starting from `initial` (an entry
    /// given back to fix), and whether a person typed it (rather than typed
    /// it ahead or pasted it). `pending` (the unfinished input) and `session`
    /// feed the editor's highlighting and completion.
    fn read(
        &mut self,
        prompt: &str,
        initial: &str,
        pending: &str,
        session: &Session,
    ) -> Result<EnteredLine, ReadlineError>;

    /// Keeps an entry in the history.
    fn remember(&mut self, entry: &str);

    /// Clears the screen, where the lines are typed on one.
    fn clear_screen(&mut self) {}
}

/// The line editor on the terminal, with its history file.
struct Terminal {
    editor: Editor<RayHelper, FileHistory>,
    history: Option<PathBuf>,
}

/// A line read, and whether a person typed it.
struct EnteredLine {
    text: String,
    typed: bool,
}

impl LineSource for Terminal {
    fn read(
        &mut self,
        prompt: &str,
        initial: &str,
        pending: &str,
        session: &Session,
    ) -> Result<EnteredLine, ReadlineError> {
        let vocabulary = session.vocabulary();
        if let Some(helper) = self.editor.helper_mut() {
            helper.set_pending(pending);
            helper.set_names(&vocabulary);
        }
        let started = Stopwatch::start();
        let text = self.editor.readline_with_initial(prompt, (initial, ""))?;
        Ok(EnteredLine { text, typed: started.elapsed() >= TYPING })
    }

    /// Adds an entry to the history, and to the history file.
    fn remember(&mut self, entry: &str) {
        let _ = self.editor.add_history_entry(entry);
        if let Some(path) = &self.history {
            let _ = self.editor.append_history(path);
        }
    }

    fn clear_screen(&mut self) {
        let _ = self.editor.clear_screen();
    }
}

/// Lines as a terminal the editor does not support edits them, read on a
/// thread of their own. There Ctrl-C is no key but SIGINT (the terminal
/// drops the line being typed): while a prompt waits it drops the entry,
/// as the editor's Ctrl-C does, instead of ending the session.
struct PlainTerminal {
    lines: Receiver<std::io::Result<String>>,
}

impl PlainTerminal {
    fn start() -> PlainTerminal {
        let (sent, lines) = mpsc::sync_channel(0);
        let reader = std::thread::Builder::new().name("lines".to_string()).spawn(move || {
            let mut stdin = std::io::stdin().lock();
            loop {
                let mut line = String::new();
                match stdin.read_line(&mut line) {
                    Ok(0) => break,
                    read => {
                        let failed = read.is_err();
                        if sent.send(read.map(|_| line)).is_err() || failed {
                            break;
                        }
                    }
                }
            }
        });
        // Without the thread, the channel is closed: the session ends as at Ctrl-D.
        drop(reader);
        PlainTerminal { lines }
    }
}

impl LineSource for PlainTerminal {
    fn read(&mut self, prompt: &str, initial: &str, _: &str, _: &Session) -> Result<EnteredLine, ReadlineError> {
        let mut stdout = std::io::stdout();
        // An entry given back to fix cannot be edited here: it is shown again.
        let shown = if initial.is_empty() { String::new() } else { format!("{initial}\n") };
        let _ = write!(stdout, "{shown}{prompt}").and_then(|()| stdout.flush());
        let started = Stopwatch::start();
        let waiting = signals::at_plain_prompt();
        loop {
            match self.lines.recv_timeout(crate::process::cancel::LOOK) {
                Ok(Ok(mut text)) => {
                    let end = text.trim_end_matches(['\n', '\r']).len();
                    text.truncate(end);
                    return Ok(EnteredLine { text, typed: started.elapsed() >= TYPING });
                }
                Ok(Err(error)) => return Err(ReadlineError::Io(error)),
                Err(RecvTimeoutError::Timeout) if waiting.interrupted() => {
                    let _ = writeln!(stdout);
                    return Err(ReadlineError::Interrupted);
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => return Err(ReadlineError::Eof),
            }
        }
    }

    fn remember(&mut self, _entry: &str) {}
}

/// Lines given in advance, typed one after the other; Ctrl-D after the last.
struct Typed<I>(I);

impl<I: Iterator<Item = String>> LineSource for Typed<I> {
    fn read(&mut self, _: &str, _: &str, _: &str, _: &Session) -> Result<EnteredLine, ReadlineError> {
        self.0.next().map(|text| EnteredLine { text, typed: true }).ok_or(ReadlineError::Eof)
    }

    fn remember(&mut self, _entry: &str) {}
}

/// The session and the lines that feed it.
struct Repl<L> {
    lines: L,
    shell: Shell,
    /// Inputs submitted so far, to name each one in diagnostics.
    inputs: usize,
    /// The lines of one read not handled yet: the lines of a paste (or of
    /// an entry recalled from history) are handled one at a time, as typed.
    queued: VecDeque<EnteredLine>,
    /// Whether the last read gave several lines (a paste, an entry from
    /// history): if they leave the entry open, a note says what is open
    /// before the next prompt, since nobody typed those lines one by one.
    several_lines_read: bool,
}

impl<L: LineSource> Repl<L> {
    fn run(&mut self, front: &mut dyn FrontEnd) -> Result<(), ReplError> {
        let mut pending = String::new();
        // A broken entry of several lines, given back to the editor to fix.
        let mut to_fix = String::new();
        let mut quit_warned = false;
        loop {
            let prompt = if pending.is_empty() { self.prompt() } else { continuation_prompt(&pending) };
            let fixing = !to_fix.is_empty();
            let read = match self.queued.pop_front() {
                Some(line) => Ok(line),
                None => {
                    if std::mem::take(&mut self.several_lines_read) && !pending.is_empty() {
                        front.note(still_open_note(&pending));
                    }
                    self.read(&prompt, &std::mem::take(&mut to_fix), &pending)
                }
            };
            match read {
                Ok(EnteredLine { text: line, typed }) => {
                    // A word such as `exit` alone runs the command it means,
                    // rather than start an input that waits for more.
                    let meant = bare_word_command(&line).filter(|_| pending.is_empty());
                    // Commands work in the middle of an unfinished input too,
                    // which then goes on (`:help sphere` while typing one).
                    if is_command(&line) || meant.is_some() {
                        self.lines.remember(&line);
                        if pending.is_empty() {
                            self.inputs += 1;
                        }
                        let armed = front.cancel().map(|switch| switch.arm());
                        let flow = commands::execute(&mut self.shell, meant.unwrap_or(&line), front);
                        self.drop_queued_if(armed.as_ref().is_some_and(|armed| armed.pressed()), front);
                        drop(armed);
                        if flow == Ok(Flow::ClearScreen) {
                            self.lines.clear_screen();
                        }
                        let unwritten = self.shell.session.unwritten();
                        if flow == Ok(Flow::Quit) && leave(&pending, unwritten, &mut quit_warned, ":quit", front) {
                            return Ok(());
                        }
                        continue;
                    }
                    quit_warned = false;
                    if !pending.is_empty() {
                        pending.push('\n');
                    }
                    pending.push_str(&line);
                    match entry_state(&pending) {
                        EntryState::Unfinished => {}
                        EntryState::Complete => {
                            let input = std::mem::take(&mut pending);
                            self.submit(&input, &input, front);
                        }
                        EntryState::BrokenBeforeLastLine => {
                            let input = std::mem::take(&mut pending);
                            let (broken, last) = input.rsplit_once('\n').unwrap_or((&input, ""));
                            // Reported with the line that broke it, which then
                            // starts the next entry, as in a script; the entry
                            // without it is in the history, to fix.
                            self.submit(broken, &input, front);
                            self.queued.push_front(EnteredLine { text: last.to_string(), typed });
                        }
                        EntryState::Broken => {
                            let input = std::mem::take(&mut pending);
                            self.submit(&input, &input, front);
                            if input.contains('\n') && typed {
                                front.note("the entry is back in the editor: fix it, or Ctrl-C to drop it");
                                to_fix = input;
                            } else if input.contains('\n') {
                                // Typed ahead or pasted: what follows must not land in it.
                                front.note("the arrow key up brings the entry back to fix it");
                            }
                        }
                    }
                }
                Err(ReadlineError::Interrupted) => {
                    if !pending.is_empty() || fixing {
                        front.say("(input dropped)");
                    }
                    pending.clear();
                    quit_warned = false;
                }
                Err(ReadlineError::Eof) => {
                    if leave(&pending, self.shell.session.unwritten(), &mut quit_warned, "Ctrl-D", front) {
                        return Ok(());
                    }
                }
                Err(error) => return Err(ReplError::Terminal(error)),
            }
        }
    }

    /// The next line from the editor; a read of several lines gives the
    /// first, and queues the others.
    fn read(&mut self, prompt: &str, initial: &str, pending: &str) -> Result<EnteredLine, ReadlineError> {
        let EnteredLine { text, typed } = self.lines.read(prompt, initial, pending, &self.shell.session)?;
        let mut lines: VecDeque<EnteredLine> =
            text.split('\n').map(|line| EnteredLine { text: line.to_string(), typed: false }).collect();
        // Only the last line was ended by a person's Enter, if any.
        if let Some(last) = lines.back_mut() {
            last.typed = typed;
        }
        let first = lines.pop_front();
        self.several_lines_read = !lines.is_empty();
        self.queued = lines;
        // `split` gives at least one line: the text itself if it has no line end.
        Ok(first.unwrap_or(EnteredLine { text: String::new(), typed }))
    }

    /// Drops the lines still queued if Ctrl-C was `pressed` during the
    /// entry before them: it stops a paste as it stops a script.
    fn drop_queued_if(&mut self, pressed: bool, front: &mut dyn FrontEnd) {
        if pressed && !self.queued.is_empty() {
            front.say(format!("(the rest of the paste dropped: {})", counted(self.queued.len(), "line")));
            self.queued.clear();
        }
    }

    /// The prompt for a new entry, with the number that names it in
    /// messages (`<input 3>`), as IPython's `In [3]:`.
    fn prompt(&self) -> String {
        format!("[{}] {PROMPT}", self.inputs + 1)
    }

    /// Runs `input` as the next input, kept in the history as `entry` (the
    /// lines of `input` that belong to it).
    fn submit(&mut self, entry: &str, input: &str, front: &mut dyn FrontEnd) {
        if input.trim().is_empty() {
            return;
        }
        self.lines.remember(entry);
        self.inputs += 1;
        let name = format!("<input {}>", self.inputs);
        let armed = front.cancel().map(|switch| switch.arm());
        let _ = handle_input(&mut self.shell, front, &name, input, 0);
        self.drop_queued_if(armed.as_ref().is_some_and(|armed| armed.pressed()), front);
    }
}

/// Whether the session may end now that `how` (Ctrl-D, `:quit`) asks it
/// to: not at once when an entry is half typed, or `unwritten` inputs were
/// not written to a file, which would be lost; the same request right
/// after the warning ends it.
fn leave(pending: &str, unwritten: usize, warned: &mut bool, how: &str, front: &mut dyn FrontEnd) -> bool {
    if *warned || (pending.trim().is_empty() && unwritten == 0) {
        return true;
    }
    *warned = true;
    if pending.trim().is_empty() {
        front.note(unwritten_note(unwritten, how));
        return false;
    }
    let first = pending.lines().find(|line| !line.trim().is_empty()).unwrap_or_default().trim();
    front.note(format!(
        "the entry you are typing is not finished (`{first}`, {}): {how} again leaves without it, \
         Ctrl-C drops it and stays",
        counted(pending.lines().count(), "line")
    ));
    false
}

/// What a paste left open in the `pending` entry, and how to go on.
fn still_open_note(pending: &str) -> String {
    let lines = counted(pending.lines().count(), "line");
    let open = open_constructs(pending);
    let what = match open.as_slice() {
        [] => "ends in the middle of an item".to_string(),
        [one] => format!("leaves `{one}` open, waiting for its `end`"),
        several => {
            let names: Vec<String> = several.iter().map(|word| format!("`{word}`")).collect();
            format!("leaves {} open, each waiting for its `end`", names.join(", "))
        }
    };
    format!("the entry ({lines} so far) {what}: type the rest, or Ctrl-C to drop it")
}

fn new_editor(color: bool) -> rustyline::Result<Editor<RayHelper, FileHistory>> {
    let config = Config::builder()
        .auto_add_history(false)
        .history_ignore_dups(true)?
        .history_ignore_space(true)
        .completion_type(CompletionType::List)
        .color_mode(if color { ColorMode::Enabled } else { ColorMode::Disabled })
        .build();
    let mut editor = Editor::with_config(config)?;
    editor.set_helper(Some(RayHelper::new(color)));
    Ok(editor)
}

/// Runs one input of program text and prints what it did, or its error.
/// `Err(())` tells the caller it failed (the session is unchanged).
fn handle_input(
    shell: &mut Shell,
    front: &mut dyn FrontEnd,
    name: &str,
    text: &str,
    line_offset: usize,
) -> Result<(), ()> {
    let result = shell.session.submit(name, text, line_offset);
    report_input(shell, front, text, result)
}

/// The prompt shown while an input continues on a new line: `...sphere> `
/// names the innermost construct still open, `...> ` when none is (a line
/// that ended with an operator or a comma).
fn continuation_prompt(pending: &str) -> String {
    match open_constructs(pending).last() {
        Some(open) => format!("...{open}> "),
        None => "...> ".to_string(),
    }
}

/// The note for leaving with `unwritten` typed inputs not written to a
/// file, when `how` (Ctrl-D, `:quit`) asked to leave.
fn unwritten_note(unwritten: usize, how: &str) -> String {
    let (inputs, them) =
        if unwritten == 1 { ("1 input is".to_string(), "it") } else { (format!("{unwritten} inputs are"), "them") };
    format!("{inputs} not written to a file: `:write FILE.ray` keeps {them}; {how} again leaves without {them}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn continuation_prompt_names_the_innermost_open_construct() {
        assert_eq!(continuation_prompt("put group sphere"), "...sphere> ");
        assert_eq!(continuation_prompt("let x = 1 +"), "...> ");
    }
}
