//! Scripts on standard input: `cat script | rayrepl` runs items and commands
//! line by line, without prompts or previews. Lines accumulate while an input
//! is unfinished; diagnostics carry the script's own line numbers. Finished
//! inputs whose lines are already in the reader's buffer are parsed together,
//! then run and answered one by one; the script never waits for a line
//! before it has answered every input read.

use std::io::BufRead;

use anstream::stream::RawStream;

use crate::lang::ast::Program;
use crate::lang::{Diagnostic, Entry, EntryState, SourceId, parse_entries};

use super::cancel::{ArmedSwitch, CancelSwitch};
use super::commands::{self, Flow, is_command};
use super::console::Console;
use super::file_commands::load_reporting;
use super::inputs::report_input;
use super::lessons;
use super::options::{SessionOptions, new_session};
use super::outputs::FrontEnd;
use super::session::Session;
use super::shell::Shell;
use crate::interruption::Signal;
use crate::output::INTERRUPTED_EXIT_CODE;
use lines::{LineError, MOST_LINE_BYTES, ScriptLine, ScriptLines};

mod lines;

/// The name scripts' diagnostics show.
const SCRIPT_NAME: &str = "<stdin>";

/// How many finished inputs a script reads ahead before running them.
const MOST_READ_AHEAD: usize = 256;

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
    let cancel = console.cancel;
    let named = Named { name: SCRIPT_NAME, noun: "script" };
    let mut script = Script::new(shell, console, cancel, named, options.keep_going);
    if let Some(path) = &options.initial_file {
        let loaded = load_reporting(script.shell, path, script.front);
        if script.after(loaded.is_ok()) == Step::Stop {
            return Ended::Status(1);
        }
    }
    if let Some(lesson) = &options.lesson {
        let started = lessons::start_reporting(script.shell, lesson, script.front);
        if script.after(started.is_ok()) == Step::Stop {
            return Ended::Status(1);
        }
    }
    script.run(input);
    if script.interrupted {
        Ended::Status(INTERRUPTED_EXIT_CODE)
    } else if script.errors > 0 {
        Ended::Status(1)
    } else if script.wrote {
        Ended::Status(0)
    } else {
        Ended::WithoutPicture
    }
}

/// How the text of a cell ran (see [`run_text`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TextRan {
    /// Every input and command succeeded.
    Done,
    /// One failed, and the text stopped there.
    Failed,
    /// Ctrl-C (the switch of `front`) stopped it.
    Interrupted,
    /// `:quit` ended it.
    Quit,
}

/// Runs `text` in `shell` as a script is run, its diagnostics and messages
/// naming it as `named` says: for a notebook's cell, whose inputs and
/// commands run in order until the first that fails. Raising `cancel`
/// stops it.
pub(crate) fn run_text(
    shell: &mut Shell,
    front: &mut dyn FrontEnd,
    cancel: Option<&'static CancelSwitch>,
    named: Named,
    text: &str,
) -> TextRan {
    let mut script = Script::new(shell, front, cancel, named, false);
    script.run(text.as_bytes());
    if script.interrupted {
        TextRan::Interrupted
    } else if script.errors > 0 {
        TextRan::Failed
    } else if script.quit {
        TextRan::Quit
    } else {
        TextRan::Done
    }
}

/// Who a script is: the name its diagnostics show (`<stdin>`, `<cell 3>`)
/// and the word its messages use for it ("script", "cell").
#[derive(Debug, Clone, Copy)]
pub(crate) struct Named<'n> {
    /// The name diagnostics show, before the line and column.
    pub name: &'n str,
    /// What it is, in messages ("the script stopped at line 3").
    pub noun: &'static str,
}

/// Finished inputs read ahead of the one running, with their first lines.
#[derive(Default)]
struct ReadAhead {
    entries: Vec<Entry>,
    first_lines: Vec<usize>,
}

impl ReadAhead {
    fn push(&mut self, entry: Entry, first_line: usize) {
        self.entries.push(entry);
        self.first_lines.push(first_line);
    }

    /// Reads `entry` (starting at line `first_line`, in `state`) ahead if
    /// it is finished, or broken so that no line can mend it (its error is
    /// then reported at once, and the script goes on after it with
    /// `--keep-going`); gives it back if it waits for more lines.
    fn place(&mut self, entry: Entry, state: EntryState, first_line: usize) -> Option<Entry> {
        if state == EntryState::Unfinished {
            return Some(entry);
        }
        if !entry.text().trim().is_empty() {
            self.push(entry, first_line);
        }
        None
    }
}

/// Whether the script goes on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Next,
    Stop,
}

/// A script (or a notebook's cell) being run.
struct Script<'s> {
    shell: &'s mut Shell,
    front: &'s mut dyn FrontEnd,
    /// The switch Ctrl-C raises, if the front-end has one.
    cancel: Option<&'static CancelSwitch>,
    /// Who the script is, in its diagnostics and messages.
    named: Named<'s>,
    keep_going: bool,
    errors: usize,
    /// Whether `:quit` ended it.
    quit: bool,
    /// Whether a command wrote an image file.
    wrote: bool,
    /// Whether Ctrl-C stopped the script.
    interrupted: bool,
}

impl<'s> Script<'s> {
    fn new(
        shell: &'s mut Shell,
        front: &'s mut dyn FrontEnd,
        cancel: Option<&'static CancelSwitch>,
        named: Named<'s>,
        keep_going: bool,
    ) -> Script<'s> {
        Script { shell, front, cancel, named, keep_going, errors: 0, quit: false, wrote: false, interrupted: false }
    }

    fn run(&mut self, input: impl BufRead) {
        let mut lines = ScriptLines::new(input);
        let mut ready = ReadAhead::default();
        let mut pending: Option<Entry> = None;
        let mut first_line = 0;
        let mut number = 0;
        while let Some(line) = lines.next_line() {
            number += 1;
            let ScriptLine { text: line, next_ready } = match line {
                Ok(line) => line,
                Err(error) => {
                    if self.run_ready(&mut ready) == Step::Next {
                        self.front.error(line_error(&error, number, self.named.noun));
                        self.errors += 1;
                    }
                    return;
                }
            };
            let line = line.strip_suffix('\r').unwrap_or(line);
            // Ctrl-C while a long line is lexed stops the script here.
            let armed = self.cancel.map(|switch| switch.arm());
            let entry = match pending.take() {
                Some(mut entry) => {
                    if entry.text().len() + line.len() > MOST_LINE_BYTES {
                        // An input that never ends (a line ending in `+`,
                        // again and again) must not fill the memory either.
                        if self.run_ready(&mut ready) == Step::Next {
                            self.front.error(input_too_long(first_line, self.named.noun));
                            self.errors += 1;
                        }
                        return;
                    }
                    entry.add_line(line);
                    entry
                }
                None if is_command(line) => {
                    if self.run_ready(&mut ready) == Step::Stop || self.command(line, number) == Step::Stop {
                        return;
                    }
                    continue;
                }
                None => {
                    first_line = number;
                    Entry::read(line.to_string())
                }
            };
            if self.stopped_by_ctrl_c(armed, number) {
                return;
            }
            pending = match entry.state() {
                EntryState::BrokenBeforeLastLine => {
                    // Reported with the line that broke it, which then
                    // starts the next entry, as in the interactive session.
                    ready.push(entry, first_line);
                    first_line = number;
                    let next = Entry::read(line.to_string());
                    let state = next.state();
                    ready.place(next, state, first_line)
                }
                state => ready.place(entry, state, first_line),
            };
            // Run what is finished before a read that may wait for the writer.
            let waits = !next_ready || ready.entries.len() >= MOST_READ_AHEAD;
            if waits && self.run_ready(&mut ready) == Step::Stop {
                return;
            }
        }
        if self.run_ready(&mut ready) == Step::Stop {
            return;
        }
        if let Some(entry) = pending {
            // Unfinished at the end: the parser says what is missing.
            ready.push(entry, first_line);
            self.run_ready(&mut ready);
        }
    }

    /// Runs the finished inputs read ahead, in order, parsed together.
    /// Ctrl-C during the parse stops the script at the first of them.
    fn run_ready(&mut self, ready: &mut ReadAhead) -> Step {
        let Some(&first_line) = ready.first_lines.first() else { return Step::Next };
        let armed = self.cancel.map(|switch| switch.arm());
        let sources: Vec<SourceId> = (ready.entries.iter().zip(&ready.first_lines))
            .map(|(entry, first_line)| {
                self.shell.session.add_source(self.named.name, entry.text(), first_line.saturating_sub(1))
            })
            .collect();
        let parsed = parse_entries(&mut ready.entries, &sources);
        if self.stopped_by_ctrl_c(armed, first_line) {
            return Step::Stop;
        }
        let inputs = ready.entries.drain(..).zip(ready.first_lines.drain(..)).zip(sources.into_iter().zip(parsed));
        for ((entry, first_line), (source, parsed)) in inputs {
            if self.input(entry.text(), source, parsed, first_line) == Step::Stop {
                return Step::Stop;
            }
        }
        Step::Next
    }

    fn input(&mut self, text: &str, source: SourceId, parsed: Result<Program, Diagnostic>, first_line: usize) -> Step {
        let armed = self.cancel.map(|switch| switch.arm());
        let accepted = self.shell.session.submit_program(source, parsed);
        let result = report_input(self.shell, self.front, text, accepted);
        if self.stopped_by_ctrl_c(armed, first_line) {
            return Step::Stop;
        }
        // A full session refuses every input after: even `--keep-going` stops.
        if result.is_err() && self.shell.session.is_full() {
            self.errors += 1;
            return Step::Stop;
        }
        self.after(result.is_ok())
    }

    fn command(&mut self, line: &str, number: usize) -> Step {
        let armed = self.cancel.map(|switch| switch.arm());
        let result = commands::execute(self.shell, line, self.front);
        if self.stopped_by_ctrl_c(armed, number) {
            return Step::Stop;
        }
        match result {
            Ok(Flow::Quit) => {
                self.quit = true;
                Step::Stop
            }
            Ok(Flow::Continue) => {
                self.wrote |= commands::writes_pictures(line);
                self.after(true)
            }
            Err(()) => self.after(false),
        }
    }

    /// Whether Ctrl-C (or SIGTERM, SIGHUP) stopped the entry at `line`: if
    /// so the script says which and where it stopped, while the switch is
    /// still armed (a signal then ends the process if that message cannot
    /// be written, see `crate::interruption`).
    fn stopped_by_ctrl_c(&mut self, armed: Option<ArmedSwitch>, line: usize) -> bool {
        let Some(armed) = armed.filter(ArmedSwitch::pressed) else { return false };
        let signal = armed.signal().unwrap_or(Signal::Interrupt);
        let noun = self.named.noun;
        self.front.error(format!("interrupted by {signal}: the {noun} stopped at line {line}"));
        self.interrupted = true;
        true
    }

    fn after(&mut self, succeeded: bool) -> Step {
        if succeeded {
            return Step::Next;
        }
        self.errors += 1;
        if self.keep_going { Step::Next } else { Step::Stop }
    }
}

/// Why the input starting at line `first_line` of the script (or `noun`) cannot run.
fn input_too_long(first_line: usize, noun: &str) -> String {
    format!(
        "the input starting at line {first_line} of the {noun} is longer than {} MiB, the most an input may be \
         (a long program is better read from a file with `:load`)",
        MOST_LINE_BYTES >> 20
    )
}

/// Why line `number` of the script (or `noun`) cannot run, in words.
fn line_error(error: &LineError, number: usize, noun: &str) -> String {
    match error {
        LineError::NotText => format!("line {number} of the {noun} cannot be read as text"),
        LineError::TooLong => {
            format!("line {number} of the {noun} is longer than {} MiB, the most a line may be", MOST_LINE_BYTES >> 20)
        }
        LineError::Read(error) => {
            format!("line {number} of the {noun} cannot be read: {}", crate::output::io_reason(error))
        }
    }
}
