//! Scripts on standard input: `cat script | rayrepl` runs items and commands
//! line by line, without prompts or previews. Lines accumulate while an input
//! is unfinished; diagnostics carry the script's own line numbers. Finished
//! inputs whose lines are already in the reader's buffer are parsed together,
//! then run and answered one by one; the script never waits for a line
//! before it has answered every input read.

use std::io::BufRead;

use crate::ide::commands::{bare_word_command, is_command, writes_pictures};
use crate::lang::ast::Program;
use crate::lang::{Diagnostic, Entry, EntryState, SourceId, parse_entries};

use super::commands::{self, Flow};
use super::file_commands::load_reporting;
use super::inputs::report_input;
use super::lesson_commands;
use super::options::SessionOptions;
use super::outputs::FrontEnd;
use super::shell::Shell;
use crate::process::cancel::{ArmedSwitch, CancelSwitch};
use crate::process::interruption::Signal;
use lines::{LineError, MOST_LINE_BYTES, ScriptLine, ScriptLines};

mod lines;

/// How many finished inputs a script reads ahead before running them.
const MOST_READ_AHEAD: usize = 256;

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

/// How a script's lines ran, and whether they wrote a picture (a script
/// that wrote none is told how to).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Ran {
    /// How it ended.
    pub ended: TextRan,
    /// Whether an image or animation file was written.
    pub wrote: bool,
}

/// Runs the lines of `input` in `shell` as a script: `options.initial_file`
/// loaded and `options.lesson` started first, then each input and command
/// in order until the first that fails (or through all of them with
/// `options.keep_going`), their diagnostics and messages naming the script
/// as `named` says. A line that is only one of the
/// [`crate::ide::commands::BARE_WORDS`] fails without stopping it. Raising
/// `cancel` stops it.
pub(crate) fn run_lines(
    shell: &mut Shell,
    front: &mut dyn FrontEnd,
    cancel: Option<&'static CancelSwitch>,
    named: Named,
    options: &SessionOptions,
    input: impl BufRead,
) -> Ran {
    let mut script = Script::new(shell, front, cancel, named, options.keep_going);
    if script.preamble(options) == Step::Next {
        script.run(input);
    }
    let ended = if script.interrupted {
        TextRan::Interrupted
    } else if script.errors > 0 {
        TextRan::Failed
    } else if script.quit {
        TextRan::Quit
    } else {
        TextRan::Done
    };
    Ran { ended, wrote: script.wrote }
}

/// Runs `text` in `shell` as a script is run (see [`run_lines`]), for a
/// notebook's cell or the page's scene.
pub(crate) fn run_text(
    shell: &mut Shell,
    front: &mut dyn FrontEnd,
    cancel: Option<&'static CancelSwitch>,
    named: Named,
    text: &str,
) -> TextRan {
    run_lines(shell, front, cancel, named, &SessionOptions::default(), text.as_bytes()).ended
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
                None if bare_word_command(line).is_some() => {
                    if self.run_ready(&mut ready) == Step::Stop {
                        return;
                    }
                    // Counted for the exit status, but the script goes on.
                    self.front.error(did_you_mean(line, number, self.named.noun));
                    self.errors += 1;
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
            Ok(Flow::Continue | Flow::ClearScreen) => {
                self.wrote |= writes_pictures(line);
                self.after(true)
            }
            Err(()) => self.after(false),
        }
    }

    /// Whether Ctrl-C (or SIGTERM, SIGHUP) stopped the entry at `line`: if
    /// so the script says which and where it stopped, while the switch is
    /// still armed (a signal then ends the process if that message cannot
    /// be written, see `crate::process::interruption`).
    fn stopped_by_ctrl_c(&mut self, armed: Option<ArmedSwitch>, line: usize) -> bool {
        let Some(armed) = armed.filter(ArmedSwitch::pressed) else { return false };
        let signal = armed.signal().unwrap_or(Signal::Interrupt);
        let noun = self.named.noun;
        self.front.error(format!("interrupted by {signal}: the {noun} stopped at line {line}"));
        self.interrupted = true;
        true
    }

    /// Loads the file and starts the lesson `options` ask for; says whether
    /// to go on.
    fn preamble(&mut self, options: &SessionOptions) -> Step {
        if let Some(path) = &options.initial_file {
            let loaded = load_reporting(self.shell, path, self.front);
            if self.after(loaded.is_ok()) == Step::Stop {
                return Step::Stop;
            }
        }
        if let Some(lesson) = &options.lesson {
            let started = lesson_commands::start_reporting(self.shell, lesson, self.front);
            return self.after(started.is_ok());
        }
        Step::Next
    }

    fn after(&mut self, succeeded: bool) -> Step {
        if succeeded {
            return Step::Next;
        }
        self.errors += 1;
        if self.keep_going { Step::Next } else { Step::Stop }
    }
}

/// Why line `number` of the script (or `noun`), one of the bare words
/// people type at prompts (`exit`), did nothing, and the command it means.
fn did_you_mean(line: &str, number: usize, noun: &str) -> String {
    let word = line.trim();
    let command = bare_word_command(word).unwrap_or_default();
    format!("line {number} of the {noun}: `{word}` alone does nothing here; did you mean `{command}`?")
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
