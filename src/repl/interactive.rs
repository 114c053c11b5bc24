//! The interactive session: prompts, the line editor, history on disk,
//! Ctrl-C and Ctrl-D.

use std::io::IsTerminal;
use std::path::PathBuf;

use rustyline::Editor;
use rustyline::config::{ColorMode, CompletionType, Config};
use rustyline::error::ReadlineError;
use rustyline::history::FileHistory;

use crate::lang::{EntryState, Limits, RaisedWith, entry_state};

use super::cancel::CancelSwitch;
use super::commands::{self, Flow, is_command};
use super::console::Console;
use super::editor::RayHelper;
use super::preview::Preview;
use super::report::counted;
use super::session::Session;
use super::syntax::continuation_prompt;
use super::write_back;
use super::{SessionOptions, handle_input, new_session};

/// The prompt for a new input, after its number.
const PROMPT: &str = "ray> ";

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
    let color = std::io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let mut editor = new_editor(color).map_err(ReplError::Terminal)?;
    let history = history_path();
    if let Some(path) = &history {
        let _ = editor.load_history(path);
    }
    let (mut out, mut err) = (std::io::stdout(), std::io::stderr());
    let mut console = Console::plain(&mut out, &mut err);
    console.color = color && std::io::stderr().is_terminal();
    console.preview = Preview::new(options.no_preview);
    console.progress = std::io::stderr().is_terminal();
    console.cancel = CancelSwitch::install();
    // A flag cannot be given any more: errors point to `:limits` instead.
    let limits = Limits { raised_with: RaisedWith::Commands, ..options.limits };
    let mut session = new_session(&SessionOptions { limits, ..options.clone() });
    console.say(format!(
        "rayrepl {}: type items of the .ray language, `:help` to learn, Ctrl-D to leave",
        env!("CARGO_PKG_VERSION")
    ));
    if let Some(path) = &options.initial_file {
        let _ = commands::load_reporting(&mut session, path, &mut console);
    }
    let mut repl = Repl { editor, session, history, inputs: 0 };
    repl.run(&mut console)
}

/// The editor and the session it feeds.
struct Repl {
    editor: Editor<RayHelper, FileHistory>,
    session: Session,
    history: Option<PathBuf>,
    /// Inputs submitted so far, to name each one in diagnostics.
    inputs: usize,
}

impl Repl {
    fn run(&mut self, console: &mut Console) -> Result<(), ReplError> {
        let mut pending = String::new();
        // A broken entry of several lines, given back to the editor to fix.
        let mut to_fix = String::new();
        let mut quit_warned = false;
        loop {
            self.refresh_helper(&pending);
            let prompt = if pending.is_empty() { self.prompt() } else { continuation_prompt(&pending) };
            let fixing = !to_fix.is_empty();
            let read = if fixing {
                self.editor.readline_with_initial(&prompt, (&std::mem::take(&mut to_fix), ""))
            } else {
                self.editor.readline(&prompt)
            };
            match read {
                Ok(line) => {
                    // Commands work in the middle of an unfinished input too,
                    // which then goes on (`:help sphere` while typing one).
                    if is_command(&line) {
                        self.remember(&line);
                        if pending.is_empty() {
                            self.inputs += 1;
                        }
                        let flow = commands::execute(&mut self.session, &line, console);
                        let unwritten = self.session.unwritten();
                        if flow == Ok(Flow::Quit) && leave(&pending, unwritten, &mut quit_warned, ":quit", console) {
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
                            self.submit(&input, console);
                        }
                        EntryState::Broken => {
                            let input = std::mem::take(&mut pending);
                            self.submit(&input, console);
                            if input.contains('\n') {
                                console.note("the entry is back in the editor: fix it, or Ctrl-C to drop it");
                                to_fix = input;
                            }
                        }
                    }
                }
                Err(ReadlineError::Interrupted) => {
                    if !pending.is_empty() || fixing {
                        console.say("(input dropped)");
                    }
                    pending.clear();
                    quit_warned = false;
                }
                Err(ReadlineError::Eof) => {
                    if leave(&pending, self.session.unwritten(), &mut quit_warned, "Ctrl-D", console) {
                        return Ok(());
                    }
                }
                Err(error) => return Err(ReplError::Terminal(error)),
            }
        }
    }

    /// The prompt for a new entry, with the number that names it in
    /// messages (`<input 3>`), as IPython's `In [3]:`.
    fn prompt(&self) -> String {
        format!("[{}] {PROMPT}", self.inputs + 1)
    }

    fn submit(&mut self, input: &str, console: &mut Console) {
        if input.trim().is_empty() {
            return;
        }
        self.remember(input);
        self.inputs += 1;
        let name = format!("<input {}>", self.inputs);
        let _ = handle_input(&mut self.session, console, &name, input, 0);
    }

    /// Adds an input to the history, and to the history file.
    fn remember(&mut self, input: &str) {
        let _ = self.editor.add_history_entry(input);
        if let Some(path) = &self.history {
            let _ = self.editor.append_history(path);
        }
    }

    fn refresh_helper(&mut self, pending: &str) {
        let vocabulary = self.session.vocabulary();
        if let Some(helper) = self.editor.helper_mut() {
            helper.set_pending(pending);
            helper.set_names(&vocabulary);
        }
    }
}

/// Whether the session may end now that `how` (Ctrl-D, `:quit`) asks it
/// to: not at once when an entry is half typed, or `unwritten` inputs were
/// not written to a file, which would be lost; the same request right
/// after the warning ends it.
fn leave(pending: &str, unwritten: usize, warned: &mut bool, how: &str, console: &mut Console) -> bool {
    if *warned || (pending.trim().is_empty() && unwritten == 0) {
        return true;
    }
    *warned = true;
    if pending.trim().is_empty() {
        console.note(write_back::unwritten_note(unwritten, how));
        return false;
    }
    let first = pending.lines().find(|line| !line.trim().is_empty()).unwrap_or_default().trim();
    console.note(format!(
        "the entry you are typing is not finished (`{first}`, {}): {how} again leaves without it, \
         Ctrl-C drops it and stays",
        counted(pending.lines().count(), "line")
    ));
    false
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

/// `rayrepl/history` in the user's data directory, created if missing;
/// `None` if there is no such directory or it cannot be created.
pub(super) fn history_path() -> Option<PathBuf> {
    let directory = dirs::data_dir()?.join("rayrepl");
    std::fs::create_dir_all(&directory).ok()?;
    Some(directory.join("history"))
}
