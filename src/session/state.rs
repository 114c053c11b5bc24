//! The state of a session (SPEC 7): one interpreter whose global environment
//! and scene accumulate across inputs, the source texts, and the history of
//! accepted inputs that `:undo` and `:time` replay.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::ide::names::Vocabulary;
use crate::lang::ast::{Item, Program};
use crate::lang::eval::{Origins, PrintLog};
use crate::lang::name::Name;
use crate::lang::{
    Diagnostic, Interpreter, Limits, SourceId, SourceMap, Span, parse_items, parse_items_apart, stopped_reading,
};
use crate::lint::{Allowed, Picture};
use crate::pipeline::evaluation::{Evaluation, Lint, scene_warnings};
use crate::scene::{Counts, Primitive, Scene};

use super::describe::ObjectDescriptions;
use super::rendering::RenderSettings;
use crate::process::cancel::{Stopped, drop_apart, off_thread};

/// The most inputs a session holds (each line of a piped script that is a
/// whole item is one, a `:load`ed file is one): the history keeps every
/// accepted input, for `:undo`, `:write` and the replays of `:time`, and an
/// endless script would otherwise fill the memory. At the limit the
/// history takes about 0.6 GB for the smallest inputs.
pub const MOST_INPUTS: usize = 1_000_000;

/// The most `:reload`s (a `:watch` makes one at each save) and `:reset`s
/// that `:undo` takes back: each keeps what it replaced (the file's last
/// version, the inputs cleared), and a `:watch` of a large file saved all
/// day would otherwise fill the memory. Past it the oldest is forgotten: an
/// older reload is then taken back with the input that loaded the file,
/// and `:undo` goes back no further than an older reset.
pub const MOST_VERSIONS_UNDONE: usize = 10;

/// One accepted input, kept so the session can be rebuilt without it, and
/// written back, listed or shown.
#[derive(Debug, Clone)]
pub(crate) struct Input {
    /// The text as typed (`:load FILE` for a file), for `:undo`'s message;
    /// a typed input shares it with the source map.
    pub text: Arc<str>,
    /// The file it was read from, for an input of `:load`, `:reload` or `:watch`.
    pub loaded_from: Option<PathBuf>,
    /// The parsed items.
    pub program: Arc<Program>,
}

/// What `:undo` takes back.
#[derive(Debug, Clone)]
enum UndoStep {
    /// The last accepted input.
    Input,
    /// A `:reset`, with the history it cleared.
    Reset(Vec<Input>),
    /// A `:reload` of the file, with the history before it.
    Reload(Vec<Input>, PathBuf),
}

/// What a session held at one moment ([`Session::checkpoint`]).
#[derive(Debug)]
pub(crate) struct Checkpoint {
    history: Vec<Input>,
    undo_steps: Vec<UndoStep>,
    settings: RenderSettings,
    limits: Limits,
}

/// What an accepted input did, for the confirmation printed after it.
#[derive(Debug, Clone)]
pub(crate) struct Accepted {
    /// The parsed items.
    pub program: Arc<Program>,
    /// Warnings the interpreter raised (clamped colours, ...).
    pub warnings: Vec<Diagnostic>,
    /// The procedures the input defines that were defined before it (to
    /// tell new from redefined).
    pub redefined: Vec<Name>,
    /// What the scene held before the input.
    pub counts_before: Counts,
}

/// What `:undo` did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Undone {
    /// There was nothing to take back.
    Nothing,
    /// The input with this text was taken back.
    Input(String),
    /// A `:reset` was taken back: this many inputs are back.
    Reset(usize),
    /// The `:reload` of this file was taken back.
    Reload(PathBuf),
}

/// The state of the language in an interactive session or a script run:
/// the inputs, the scene they build, the settings, history and undo. What a
/// front-end keeps beside it (the lesson followed, the last picture) is in
/// [`super::shell::Shell`].
#[derive(Debug)]
pub struct Session {
    interpreter: Interpreter,
    /// The time `interpreter` was created with. After a `:time` that needed
    /// no replay (nothing had read `time`) it differs from `settings.time`
    /// until the next input, which first rebuilds the interpreter.
    interpreter_time: f64,
    sources: SourceMap,
    history: Vec<Input>,
    undo_steps: Vec<UndoStep>,
    /// The programs of the inputs the last `:write` wrote.
    written: Vec<Arc<Program>>,
    descriptions: ObjectDescriptions,
    settings: RenderSettings,
    limits: Limits,
    /// Raised by Ctrl-C: evaluation stops at the next procedure call.
    interrupt: Option<&'static AtomicBool>,
    /// The scene's counts, kept up to date input by input (counting the
    /// whole scene each time would make a long script quadratic).
    counts: Counts,
    /// The checks of the scene turned off.
    allowed: Allowed,
    /// What `print` wrote and was not yet shown (also by the frames of an
    /// animation, which only read the session).
    printed: RefCell<PrintLog>,
    /// Every file `:load`, `:reload`, `:watch` or `-i` read, which `:save`
    /// and `:anim` must not write over (`:undo` and `:reset` keep them).
    files_read: Vec<PathBuf>,
    /// The file read last and the source of its text while no input holds
    /// it (it failed, or Ctrl-C stopped it): read again as it was (a
    /// `:load` stopped and typed again), it reuses that source, so that a
    /// session keeps the text of a file once however often its load fails.
    failed_file_text: Option<(PathBuf, SourceId)>,
}

impl Session {
    /// An empty session rendering with `settings`.
    pub fn new(settings: RenderSettings, limits: Limits) -> Session {
        Session {
            interpreter: Evaluation::at(settings.time, limits).interpreter(),
            interpreter_time: settings.time,
            sources: SourceMap::new(),
            history: Vec::new(),
            undo_steps: Vec::new(),
            written: Vec::new(),
            descriptions: ObjectDescriptions::default(),
            settings,
            limits,
            allowed: Allowed::default(),
            printed: RefCell::default(),
            counts: Counts::default(),
            interrupt: None,
            files_read: Vec::new(),
            failed_file_text: None,
        }
    }

    /// Lets Ctrl-C (raising `flag`) stop any evaluation of the session.
    pub(crate) fn interruptible(mut self, flag: &'static AtomicBool) -> Session {
        self.interrupt = Some(flag);
        self.interpreter = self.new_interpreter(self.settings.time);
        self
    }

    /// How the session evaluates its inputs at `time`: within its limits,
    /// stopped by Ctrl-C, its scene judged only when a picture is asked for
    /// ([`Session::scene_warnings`]).
    fn evaluation(&self, time: f64) -> Evaluation {
        Evaluation { cancel: self.interrupt, ..Evaluation::at(time, self.limits) }
    }

    /// An empty interpreter with the session's limits and Ctrl-C.
    fn new_interpreter(&self, time: f64) -> Interpreter {
        self.evaluation(time).interpreter()
    }

    /// The same session with the checks `allowed` turned off.
    pub fn allowing(self, allowed: Allowed) -> Session {
        Session { allowed, ..self }
    }

    /// Parses and runs one input. `name` is shown in diagnostics and
    /// `line_offset` is the number of lines before it in its script. On
    /// error the session is unchanged (SPEC 7).
    pub(crate) fn submit(&mut self, name: &str, text: &str, line_offset: usize) -> Result<Accepted, Diagnostic> {
        let source = self.add_source(name, text, line_offset);
        self.submit_program(source, parse_items(source, text))
    }

    /// Adds the text of an input about to be parsed to the source map, as
    /// [`Session::submit`] does; `name` and `line_offset` as there.
    pub(crate) fn add_source(&mut self, name: &str, text: &str, line_offset: usize) -> SourceId {
        self.sources.add(name, text, line_offset)
    }

    /// Runs one input whose text is `source` (see [`Session::add_source`]),
    /// parsed into `parsed`, as [`Session::submit`] does.
    pub(crate) fn submit_program(
        &mut self,
        source: SourceId,
        parsed: Result<Program, Diagnostic>,
    ) -> Result<Accepted, Diagnostic> {
        let mut program = parsed?;
        // An input holds one item or a few: the room the parser left for
        // more would be most of a long script's memory.
        program.items.shrink_to_fit();
        let text = Arc::clone(&self.sources.get(source).text);
        self.run(Input { text, loaded_from: None, program: Arc::new(program) })
    }

    /// Runs the text of the file at `path`, all of it as one input (its
    /// items in any order).
    pub(crate) fn load(&mut self, path: &Path, text: &str) -> Result<Accepted, Diagnostic> {
        let input = self.parse_file_input(path, text)?;
        let accepted = self.run(input)?;
        self.failed_file_text = None;
        Ok(accepted)
    }

    /// Replaces what the last `:load` of `path` brought by `text`, the
    /// file's new content, where it stood among the inputs, so the inputs
    /// typed after it run again on top of it; loads it if nothing came
    /// from `path` yet. On error the session is unchanged.
    pub(crate) fn reload(&mut self, path: &Path, text: &str) -> Result<(), Diagnostic> {
        let Some(index) = self.history.iter().rposition(|input| input.loaded_from.as_deref() == Some(path)) else {
            return self.load(path, text).map(drop);
        };
        let input = self.parse_file_input(path, text)?;
        let previous = self.history.clone();
        let mut history = previous.clone();
        history[index] = Input { text: Arc::clone(&history[index].text), ..input };
        self.rebuild(history)?;
        self.failed_file_text = None;
        self.push_version(UndoStep::Reload(previous, path.to_path_buf()));
        Ok(())
    }

    /// The file that the last loaded input still in the session came from.
    pub(crate) fn last_loaded(&self) -> Option<&Path> {
        self.history.iter().rev().find_map(|input| input.loaded_from.as_deref())
    }

    /// The files the session read its inputs from, in the order first read.
    pub(crate) fn files_read(&self) -> &[PathBuf] {
        &self.files_read
    }

    /// The input holding the text of the file at `path`, parsed.
    fn parse_file_input(&mut self, path: &Path, text: &str) -> Result<Input, Diagnostic> {
        if !self.files_read.iter().any(|read| read == path) {
            self.files_read.push(path.to_path_buf());
        }
        let name = path.display().to_string();
        let source = match self.failed_file_text.take() {
            Some((read, source)) if read == path && *self.sources.get(source).text == *text => source,
            _ => self.sources.add(name.as_str(), text, 0),
        };
        // Until the input runs: `load` and `reload` forget it then.
        self.failed_file_text = Some((path.to_path_buf(), source));
        let program = match self.interrupt {
            Some(interrupt) => self.parse_apart(source, interrupt)?,
            None => parse_items(source, text)?,
        };
        let text = format!(":load {name}").into();
        Ok(Input { text, loaded_from: Some(path.to_path_buf()), program: Arc::new(program) })
    }

    /// The program of the text `source`, parsed on a thread that
    /// `interrupt` abandons: a parse that Ctrl-C stops frees its partial
    /// tree there (for a file of 100 MB, a tenth of a second or more)
    /// while the session goes on.
    fn parse_apart(&self, source: SourceId, interrupt: &'static AtomicBool) -> Result<Program, Diagnostic> {
        let file = self.sources.get(source);
        file.find_lines_apart();
        let text = Arc::clone(&file.text);
        let (stop, reached) = (Arc::new(AtomicBool::new(false)), Arc::new(AtomicUsize::new(0)));
        let (stopping, reading) = (Arc::clone(&stop), Arc::clone(&reached));
        let parsed = off_thread("parse", interrupt, move || parse_items_apart(source, &text, &stopping, &reading));
        match parsed {
            Ok(parsed) => parsed,
            Err(stopped) => {
                stop.store(true, Ordering::Relaxed);
                let at = reached.load(Ordering::Relaxed);
                Err(match stopped {
                    Stopped::Cancelled => stopped_reading(source, at),
                    Stopped::Failed => Diagnostic::error(Span::new(source, at, at), "internal error while reading")
                        .with_note("the parser stopped here; nothing of this input was kept"),
                })
            }
        }
    }

    /// Runs a parsed input and records it in the history.
    fn run(&mut self, input: Input) -> Result<Accepted, Diagnostic> {
        if self.is_full()
            && let (Some(first), Some(last)) = (input.program.items.first(), input.program.items.last())
        {
            return Err(too_many_inputs(first.span().to(last.span())));
        }
        if self.interpreter_time != self.settings.time {
            // What the earlier inputs print was shown when they ran.
            self.rebuild(self.history.clone())?;
        }
        let counts_before = self.counts;
        let scene = self.interpreter.scene();
        let mark = (scene.primitives.len(), scene.timed_primitives.len());
        // Only the input's own procedures: listing all of them at every
        // input would make a long script quadratic.
        let redefined = input
            .program
            .items
            .iter()
            .filter_map(|item| match item {
                Item::Proc(def) if self.interpreter.procedure(&def.name.name).is_some() => Some(def.name.name),
                _ => None,
            })
            .collect();
        let result = self.interpreter.run(&input.program);
        self.printed.borrow_mut().absorb(self.interpreter.take_printed());
        if let Err(error) = result {
            self.interpreter.take_warnings();
            if input.loaded_from.is_some() {
                drop_apart(input);
            }
            return Err(error);
        }
        let warnings = self.interpreter.take_warnings();
        let added = self.interpreter.scene().counts_after(mark.0, mark.1);
        self.counts = Counts {
            spheres: counts_before.spheres + added.spheres,
            planes: counts_before.planes + added.planes,
            boxes: counts_before.boxes + added.boxes,
            lights: added.lights,
        };
        self.descriptions.record(&input.program);
        let program = Arc::clone(&input.program);
        if !program.items.is_empty() {
            self.history.push(input);
            self.undo_steps.push(UndoStep::Input);
        }
        Ok(Accepted { program, warnings, redefined, counts_before })
    }

    /// Whether the session holds [`MOST_INPUTS`] inputs: it accepts no more.
    pub(crate) fn is_full(&self) -> bool {
        self.history.len() >= MOST_INPUTS
    }

    /// How many primitives of each kind, and lights, the scene holds.
    pub(crate) fn counts(&self) -> Counts {
        self.counts
    }

    /// The accepted inputs, in the order they ran.
    pub(crate) fn inputs(&self) -> &[Input] {
        &self.history
    }

    /// Records that the inputs the session holds now were written to a file.
    pub(crate) fn mark_written(&mut self) {
        self.written = self.history.iter().map(|input| Arc::clone(&input.program)).collect();
    }

    /// How many typed inputs (not loaded from a file) the last `:write`
    /// did not write: what leaving now would lose.
    pub fn unwritten(&self) -> usize {
        let written = |input: &Input| self.written.iter().any(|program| Arc::ptr_eq(program, &input.program));
        self.history.iter().filter(|input| input.loaded_from.is_none() && !written(input)).count()
    }

    /// The limits on calls and primitives.
    pub(crate) fn limits(&self) -> Limits {
        self.limits
    }

    /// Changes the limits on calls and primitives: every input is evaluated
    /// again under them, and if one fails (a lower limit) nothing changes.
    pub(crate) fn set_limits(&mut self, limits: Limits) -> Result<(), Diagnostic> {
        let previous = std::mem::replace(&mut self.limits, limits);
        if let Err(error) = self.rebuild(self.history.clone()) {
            self.limits = previous;
            return Err(error);
        }
        Ok(())
    }

    /// Takes back the last input, or the last `:reset`.
    pub(crate) fn undo(&mut self) -> Result<Undone, Diagnostic> {
        let Some(step) = self.undo_steps.pop() else {
            return Ok(Undone::Nothing);
        };
        let mut history = self.history.clone();
        let undone = match &step {
            UndoStep::Input => Undone::Input(history.pop().map(|input| input.text.to_string()).unwrap_or_default()),
            UndoStep::Reset(cleared) => {
                history = cleared.clone();
                Undone::Reset(history.len())
            }
            UndoStep::Reload(previous, path) => {
                history = previous.clone();
                Undone::Reload(path.clone())
            }
        };
        // What the inputs kept print was shown when they ran.
        if let Err(error) = self.rebuild(history) {
            self.undo_steps.push(step);
            return Err(error);
        }
        Ok(undone)
    }

    /// What the session holds now, to come back to with [`Session::restore`].
    pub(crate) fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            history: self.history.clone(),
            undo_steps: self.undo_steps.clone(),
            settings: self.settings,
            limits: self.limits,
        }
    }

    /// Comes back to what the session held at `checkpoint`: its inputs,
    /// undo steps, settings and limits (a notebook's cell stopped by an
    /// interrupt leaves the session as it was before the cell). The inputs
    /// are evaluated again only if they or the settings changed, and
    /// without the interrupt, which is still raised then: they ran before,
    /// and end as they did.
    pub(crate) fn restore(&mut self, checkpoint: Checkpoint) -> Result<(), Diagnostic> {
        let Checkpoint { history, undo_steps, settings, limits } = checkpoint;
        let same_inputs = history.len() == self.history.len()
            && history.iter().zip(&self.history).all(|(then, now)| Arc::ptr_eq(&then.program, &now.program));
        let same_settings = settings == self.settings && limits == self.limits;
        if !(same_inputs && same_settings) {
            (self.settings, self.limits) = (settings, limits);
            let interrupt = self.interrupt.take();
            let rebuilt = self.rebuild(history);
            self.interrupt = interrupt;
            if let Some(flag) = interrupt {
                let interpreter = std::mem::replace(&mut self.interpreter, Interpreter::new(settings.time, limits));
                self.interpreter = interpreter.interruptible(flag);
            }
            rebuilt?;
        }
        self.undo_steps = undo_steps;
        Ok(())
    }

    /// Forgets every input, and the undo steps with them: for a front-end
    /// that runs a whole scene again in place of the last at every pause
    /// in typing (`CellSession::run_scene`), which never takes one back,
    /// so that what it keeps does not grow with the pauses.
    pub(crate) fn clear(&mut self) {
        self.reset();
        self.undo_steps.clear();
    }

    /// Forgets every input; `:undo` brings them back.
    pub(crate) fn reset(&mut self) {
        let cleared = std::mem::take(&mut self.history);
        self.interpreter = self.new_interpreter(self.settings.time);
        self.counts = Counts::default();
        self.interpreter_time = self.settings.time;
        self.descriptions = ObjectDescriptions::default();
        self.push_version(UndoStep::Reset(cleared));
    }

    /// Records `step`, a reload or a reset, for `:undo`, forgetting the
    /// oldest of them past [`MOST_VERSIONS_UNDONE`] (in the background: it
    /// may hold the only tree of a large file).
    fn push_version(&mut self, step: UndoStep) {
        self.undo_steps.push(step);
        let is_version = |step: &UndoStep| matches!(step, UndoStep::Reload(..) | UndoStep::Reset(_));
        if self.undo_steps.iter().filter(|step| is_version(step)).count() <= MOST_VERSIONS_UNDONE {
            return;
        }
        let Some(oldest) = self.undo_steps.iter().position(is_version) else { return };
        let forgotten = match self.undo_steps[oldest] {
            // The steps before a reset took back inputs it cleared.
            UndoStep::Reset(_) => self.undo_steps.drain(..=oldest).collect(),
            _ => vec![self.undo_steps.remove(oldest)],
        };
        drop_apart(forgotten);
    }

    /// Sets `time`. If anything read it, every input is evaluated again at
    /// once, and if one of them fails at the new time nothing changes.
    /// Returns whether inputs were evaluated again.
    pub(crate) fn set_time(&mut self, time: f64) -> Result<bool, Diagnostic> {
        let previous = self.settings.time;
        self.settings.time = time;
        if !self.interpreter.has_time_reads() {
            return Ok(false);
        }
        match self.rebuild(self.history.clone()) {
            Ok(printed) => self.printed.borrow_mut().absorb(printed),
            Err(error) => {
                self.settings.time = previous;
                return Err(error);
            }
        }
        Ok(true)
    }

    /// Whether evaluation has read `time`: if not, every time gives the same scene.
    pub(crate) fn depends_on_time(&self) -> bool {
        self.interpreter.has_time_reads()
    }

    /// A fresh interpreter that ran the history at `time`; with
    /// `skip_static`, the scene holds only the primitives that depend on
    /// `time` (the other frames of an animation).
    /// What it prints is kept for [`Session::take_printed`].
    pub(crate) fn replay_at(&self, time: f64, skip_static: bool) -> Result<Interpreter, Diagnostic> {
        let interpreter = Evaluation { skip_static, ..self.evaluation(time) }.interpreter();
        let mut interpreter = self.replay(interpreter, &self.history)?;
        self.printed.borrow_mut().absorb(interpreter.take_printed());
        Ok(interpreter)
    }

    /// A fresh interpreter that ran the history at the current time
    /// recording the calls that led to each `put`, to explain a pixel.
    /// What it prints was shown when the inputs ran.
    pub(crate) fn replay_recording_calls(&self) -> Result<Interpreter, Diagnostic> {
        let interpreter = self.new_interpreter(self.settings.time).recording_calls();
        let mut interpreter = self.replay(interpreter, &self.history)?;
        interpreter.take_printed();
        Ok(interpreter)
    }

    /// Replaces the interpreter by one that ran `history` at the current
    /// time; returns what the replay printed.
    fn rebuild(&mut self, history: Vec<Input>) -> Result<PrintLog, Diagnostic> {
        let time = self.settings.time;
        self.interpreter = match self.replay(self.new_interpreter(time), &history) {
            Ok(interpreter) => interpreter,
            Err(error) => {
                // It may hold the only tree of a file `:reload` read.
                drop_apart(history);
                return Err(error);
            }
        };
        self.counts = self.interpreter.scene().counts();
        self.interpreter_time = time;
        let mut descriptions = ObjectDescriptions::default();
        for input in &history {
            descriptions.record(&input.program);
        }
        self.descriptions = descriptions;
        self.history = history;
        Ok(self.interpreter.take_printed())
    }

    fn replay(&self, mut interpreter: Interpreter, history: &[Input]) -> Result<Interpreter, Diagnostic> {
        for input in history {
            interpreter.run(&input.program)?;
        }
        interpreter.take_warnings();
        Ok(interpreter)
    }

    /// The scene built so far.
    pub fn scene(&self) -> &Scene {
        self.interpreter.scene()
    }

    /// Where the scene's parts come from: each primitive's `put`.
    pub(crate) fn origins(&self) -> &Origins {
        self.interpreter.origins()
    }

    /// What `print` wrote since the last call, at most
    /// [`crate::lang::eval::PRINT_LIMIT`] lines.
    pub(crate) fn take_printed(&self) -> PrintLog {
        self.printed.take()
    }

    /// The warnings about the scene, rendered as `picture` (for the checks
    /// not turned off).
    pub(crate) fn scene_warnings(&self, picture: &Picture) -> Vec<Diagnostic> {
        scene_warnings(&self.interpreter, &Lint { picture: *picture, allowed: self.allowed })
    }

    /// The source texts seen so far, to render diagnostics.
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }

    /// The render settings.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// Sets the size of the images `:save` and `:anim` write.
    pub(crate) fn set_size(&mut self, width: u32, height: u32) {
        self.settings.width = width;
        self.settings.height = height;
    }

    /// Sets how many reflections are followed.
    pub(crate) fn set_depth(&mut self, depth: u32) {
        self.settings.depth = depth;
    }

    /// Sets how many rays each pixel averages.
    pub(crate) fn set_samples(&mut self, samples: u32) {
        self.settings.samples = samples;
    }

    /// Whether a `camera` was given (otherwise the default one is used).
    pub fn has_camera(&self) -> bool {
        self.interpreter.has_camera()
    }

    /// Whether an `ambient` was given (otherwise the default one is used).
    pub fn has_ambient(&self) -> bool {
        self.interpreter.has_ambient()
    }

    /// The value of the global number `name`, if it is one.
    pub fn global_number(&self, name: &str) -> Option<f64> {
        self.interpreter.global_number(name)
    }

    /// The global numbers and their values, by name.
    pub(crate) fn numbers(&self) -> Vec<(Name, f64)> {
        let names = self.interpreter.global_names();
        names.into_iter().filter_map(|name| Some((name, self.number_shown(&name)?))).collect()
    }

    /// The value of the global number `name` as the session shows it: after
    /// a `:time` that needed no replay the interpreter still holds the old
    /// `time` (until the next input rebuilds it), unless a `let` rebound it.
    fn number_shown(&self, name: &str) -> Option<f64> {
        let value = self.global_number(name)?;
        let stale_time = name == "time" && value == self.interpreter_time;
        Some(if stale_time { self.settings.time } else { value })
    }

    /// The global objects and what they are, by name.
    pub(crate) fn objects(&self) -> Vec<(Name, String)> {
        let names = self.interpreter.global_names();
        names.into_iter().filter_map(|name| Some((name, self.describe_object(&name)?))).collect()
    }

    /// What the global object `name` is (`sphere`, `group of 2 objects`,
    /// or its count of primitives), if it is one.
    pub(crate) fn describe_object(&self, name: &str) -> Option<String> {
        let primitives = self.global_object(name)?.len();
        Some(match self.descriptions.get(name) {
            Some(description) => description.to_string(),
            None if primitives == 1 => "1 primitive".to_string(),
            None => format!("{primitives} primitives"),
        })
    }

    /// The text the last accepted input was read from (none for an empty
    /// input), to tell what that input made.
    pub(crate) fn last_input_source(&self) -> Option<SourceId> {
        Some(self.inputs().last()?.program.items.first()?.span().source)
    }

    /// The primitives of the global object `name`, if it is one.
    pub(crate) fn global_object(&self, name: &str) -> Option<&[Primitive]> {
        self.interpreter.global_object(name)
    }

    /// The procedures and their parameters, by name.
    pub(crate) fn procedures(&self) -> Vec<(Name, Vec<Name>)> {
        let names = self.interpreter.procedure_names();
        names
            .into_iter()
            .filter_map(|name| {
                let params = self.interpreter.procedure(&name)?.params.iter().map(|p| p.name).collect();
                Some((name, params))
            })
            .collect()
    }

    /// The names the session defines, for completion and inspection.
    pub(crate) fn vocabulary(&self) -> Vocabulary {
        Vocabulary::of_interpreter(&self.interpreter)
    }
}

/// The error of an input that a full session cannot take (the input at `span`).
#[cold]
fn too_many_inputs(span: Span) -> Diagnostic {
    Diagnostic::error(span, format!("the session already holds {MOST_INPUTS} inputs, the most it may"))
        .with_code("too-many-inputs")
        .with_label("this input is one too many")
        .with_note("the session keeps every input it accepted, for `:undo`, `:write` and `:time`")
        .with_help("put the program in a file and `:load` it: a file is one input")
}

#[cfg(test)]
mod tests {
    use super::*;

    const BALL: &str = "put sphere center x, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end";

    /// Every `:undo` until there is nothing left to take back.
    fn undo_all(session: &mut Session) -> Vec<Undone> {
        std::iter::from_fn(|| Some(session.undo().expect("undoes")).filter(|undone| *undone != Undone::Nothing))
            .collect()
    }

    /// A file whose load fails (or Ctrl-C stops) keeps its text once
    /// however often it is loaded again as it was, and no text an input
    /// holds is reused.
    #[test]
    fn a_file_loaded_again_as_it_was_after_a_failure_keeps_one_text() {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        let path = Path::new("part.ray");
        let failed = |session: &mut Session, text: &str| session.load(path, text).expect_err("fails").span.source;
        let first = failed(&mut session, "let a = 1 / 0");
        assert_eq!(failed(&mut session, "let a = 1 / 0"), first);
        assert_ne!(failed(&mut session, "let a = 2 / 0"), first, "another text is another source");
        session.load(path, "let a = 1").expect("loads");
        let held = session.inputs()[0].program.items[0].span().source;
        session.load(path, "let a = 1").expect("loads");
        assert_ne!(session.inputs()[1].program.items[0].span().source, held, "the first load holds its text");
    }

    #[test]
    fn undo_takes_back_the_last_reloads_and_an_older_one_with_the_load() {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        let path = Path::new("part.ray");
        session.load(path, "let a = 0").expect("loads");
        let versions = MOST_VERSIONS_UNDONE + 2;
        for version in 1..=versions {
            session.reload(path, &format!("let a = {version}")).expect("reloads");
        }
        for version in (versions - MOST_VERSIONS_UNDONE..versions).rev() {
            assert_eq!(session.undo().ok(), Some(Undone::Reload(path.to_path_buf())));
            assert_eq!(session.interpreter.global_number("a"), Some(version as f64));
        }
        assert_eq!(undo_all(&mut session), [Undone::Input(":load part.ray".to_string())]);
        assert_eq!(session.inputs().len(), 0);
    }

    #[test]
    fn the_help_and_the_docs_give_the_number_of_versions_kept() {
        let undo = include_str!("../ide/help_pages/commands/undo.txt").split_whitespace().collect::<Vec<_>>().join(" ");
        let readme = include_str!("../../docs/guide/terminal.md");
        let language = include_str!("../../docs/language.md").split_whitespace().collect::<Vec<_>>().join(" ");
        let said = format!("the last {MOST_VERSIONS_UNDONE} ");
        for (text, name) in [
            (&undo.to_lowercase(), "the help of :undo"),
            (&readme.to_string(), "docs/guide/terminal.md"),
            (&language, "docs/language.md"),
        ] {
            assert!(text.contains(&said), "{name} does not say {said:?}");
        }
    }

    #[test]
    fn undo_goes_back_no_further_than_the_oldest_reset_kept() {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        session.submit("<input 1>", "let a = 0", 0).expect("runs");
        for version in 1..=MOST_VERSIONS_UNDONE + 1 {
            session.reset();
            session.submit("<input>", &format!("let a = {version}"), 0).expect("runs");
        }
        // Each reset kept and the input after it, and the input after the
        // reset forgotten: back to the session that reset left, empty.
        assert_eq!(undo_all(&mut session).len(), 2 * MOST_VERSIONS_UNDONE + 1);
        assert_eq!((session.inputs().len(), session.interpreter.global_number("a")), (0, None));
    }

    #[test]
    fn a_reload_replaces_the_file_where_it_stood_and_keeps_typed_inputs() {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        let path = Path::new("part.ray");
        session.load(path, &format!("proc ball(x) {BALL} end ball(0)")).expect("loads");
        session.submit("<input 2>", "ball(3)", 0).expect("runs");
        assert_eq!(session.scene().counts().spheres, 2);
        // Each ball is now two: the typed call runs again on the new version.
        let two = format!("proc ball(x) {BALL} {BALL} end ball(0)");
        session.reload(path, &two).expect("reloads");
        assert_eq!((session.scene().counts().spheres, session.inputs().len()), (4, 2));
        // A version that fails changes nothing.
        assert!(session.reload(path, "ball(").is_err());
        assert_eq!(session.scene().counts().spheres, 4);
        assert_eq!(session.undo().ok(), Some(Undone::Reload(path.to_path_buf())));
        assert_eq!(session.scene().counts().spheres, 2);
        assert_eq!(session.last_loaded(), Some(path));
    }

    #[test]
    fn typed_inputs_are_unwritten_until_written() {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        session.load(Path::new("part.ray"), "let a = 1").expect("loads");
        assert_eq!(session.unwritten(), 0);
        session.submit("<input 2>", "let b = 2", 0).expect("runs");
        session.submit("<input 3>", "let c = 3", 0).expect("runs");
        assert_eq!(session.unwritten(), 2);
        session.mark_written();
        session.undo().expect("undoes");
        assert_eq!(session.unwritten(), 0);
    }
}
