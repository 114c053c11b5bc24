//! The interactive session: prompts, the line editor, history on disk,
//! Ctrl-C and Ctrl-D.

use std::io::IsTerminal;
use std::path::PathBuf;

use rustyline::Editor;
use rustyline::config::{ColorMode, CompletionType, Config};
use rustyline::error::ReadlineError;
use rustyline::history::FileHistory;

use crate::lang::is_incomplete;

use super::cancel::CancelSwitch;
use super::commands::{self, Flow, is_command};
use super::console::Console;
use super::editor::RayHelper;
use super::preview::Preview;
use super::session::Session;
use super::syntax::continuation_prompt;
use super::{SessionOptions, handle_input, new_session};

/// The prompt for a new input.
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
    let mut session = new_session(options);
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
        loop {
            self.refresh_helper(&pending);
            let prompt = if pending.is_empty() { PROMPT.to_string() } else { continuation_prompt(&pending) };
            match self.editor.readline(&prompt) {
                Ok(line) => {
                    // Commands work in the middle of an unfinished input too,
                    // which then goes on (`:help sphere` while typing one).
                    if is_command(&line) {
                        self.remember(&line);
                        if commands::execute(&mut self.session, &line, console) == Ok(Flow::Quit) {
                            return Ok(());
                        }
                        continue;
                    }
                    if !pending.is_empty() {
                        pending.push('\n');
                    }
                    pending.push_str(&line);
                    if !is_incomplete(&pending) {
                        let input = std::mem::take(&mut pending);
                        self.submit(&input, console);
                    }
                }
                Err(ReadlineError::Interrupted) => {
                    if !pending.is_empty() {
                        console.say("(input dropped)");
                    }
                    pending.clear();
                }
                Err(ReadlineError::Eof) => return Ok(()),
                Err(error) => return Err(ReplError::Terminal(error)),
            }
        }
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
fn history_path() -> Option<PathBuf> {
    let directory = dirs::data_dir()?.join("rayrepl");
    std::fs::create_dir_all(&directory).ok()?;
    Some(directory.join("history"))
}
