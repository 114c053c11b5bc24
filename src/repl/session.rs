//! The state of a session (SPEC 7): one interpreter whose global environment
//! and scene accumulate across inputs, the source texts, and the history of
//! accepted inputs that `:undo` and `:time` replay.

use std::cell::RefCell;
use std::collections::HashSet;
use std::rc::Rc;

use crate::lang::ast::Program;
use crate::lang::eval::PrintLog;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceMap, Span, parse_items};
use crate::lint::{Allowed, Check, Picture, check_scene};
use crate::scene::{Counts, Scene};

use super::describe::ObjectDescriptions;
use super::rendering::RenderSettings;

/// One accepted input, kept so the session can be rebuilt without it.
#[derive(Debug, Clone)]
struct Input {
    /// The text as typed (`:load FILE` for a file), for `:undo`'s message.
    text: String,
    /// The parsed items.
    program: Rc<Program>,
}

/// What `:undo` takes back.
#[derive(Debug, Clone)]
enum UndoStep {
    /// The last accepted input.
    Input,
    /// A `:reset`, with the history it cleared.
    Reset(Vec<Input>),
}

/// What an accepted input did, for the confirmation printed after it.
#[derive(Debug, Clone)]
pub(crate) struct Accepted {
    /// The parsed items.
    pub program: Rc<Program>,
    /// Warnings the interpreter raised (clamped colours, ...).
    pub warnings: Vec<Diagnostic>,
    /// The procedures defined before the input (to tell new from redefined).
    pub procedures_before: Vec<Rc<str>>,
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
}

/// Names defined by the session, for completion.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct Vocabulary {
    /// Global numbers and objects.
    pub variables: Vec<String>,
    /// Procedures with their parameters.
    pub procedures: Vec<(String, Vec<String>)>,
}

/// An interactive session or a script run: everything that accumulates.
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
    descriptions: ObjectDescriptions,
    settings: RenderSettings,
    limits: Limits,
    /// The checks of the scene turned off.
    allowed: Allowed,
    /// The warnings about the scene already shown, by check and place: a
    /// cause is warned about once, not at every render.
    warned: HashSet<(Check, Span)>,
    /// What `print` wrote and was not yet shown (also by the frames of an
    /// animation, which only read the session).
    printed: RefCell<PrintLog>,
}

impl Session {
    /// An empty session rendering with `settings`.
    pub fn new(settings: RenderSettings, limits: Limits) -> Session {
        Session {
            interpreter: Interpreter::new(settings.time, limits),
            interpreter_time: settings.time,
            sources: SourceMap::new(),
            history: Vec::new(),
            undo_steps: Vec::new(),
            descriptions: ObjectDescriptions::default(),
            settings,
            limits,
            allowed: Allowed::default(),
            warned: HashSet::new(),
            printed: RefCell::default(),
        }
    }

    /// The same session with the checks `allowed` turned off.
    pub fn allowing(self, allowed: Allowed) -> Session {
        Session { allowed, ..self }
    }

    /// Parses and runs one input. `name` is shown in diagnostics and
    /// `line_offset` is the number of lines before it in its script. On
    /// error the session is unchanged (SPEC 7).
    pub(crate) fn submit(&mut self, name: &str, text: &str, line_offset: usize) -> Result<Accepted, Diagnostic> {
        let source = self.sources.add(name, text, line_offset);
        let program = parse_items(source, text)?;
        self.run(text.to_string(), program)
    }

    /// Runs the text of a file, all of it as one input (its items in any order).
    pub(crate) fn load(&mut self, name: &str, text: &str) -> Result<Accepted, Diagnostic> {
        let source = self.sources.add(name, text, 0);
        let program = parse_items(source, text)?;
        self.run(format!(":load {name}"), program)
    }

    /// Runs an already parsed input and records it in the history.
    fn run(&mut self, text: String, program: Program) -> Result<Accepted, Diagnostic> {
        if self.interpreter_time != self.settings.time {
            // What the earlier inputs print was shown when they ran.
            self.rebuild(self.history.clone())?;
        }
        let counts_before = self.interpreter.scene().counts();
        let procedures_before = self.interpreter.procedure_names();
        let result = self.interpreter.run_with_sources(&program, &self.sources);
        self.printed.borrow_mut().absorb(self.interpreter.take_printed());
        if let Err(error) = result {
            self.interpreter.take_warnings();
            return Err(error);
        }
        let warnings = self.interpreter.take_warnings();
        self.descriptions.record(&program);
        let program = Rc::new(program);
        if !program.items.is_empty() {
            self.history.push(Input { text, program: Rc::clone(&program) });
            self.undo_steps.push(UndoStep::Input);
        }
        Ok(Accepted { program, warnings, procedures_before, counts_before })
    }

    /// Takes back the last input, or the last `:reset`.
    pub(crate) fn undo(&mut self) -> Result<Undone, Diagnostic> {
        let Some(step) = self.undo_steps.pop() else {
            return Ok(Undone::Nothing);
        };
        let mut history = self.history.clone();
        let undone = match &step {
            UndoStep::Input => Undone::Input(history.pop().map(|input| input.text).unwrap_or_default()),
            UndoStep::Reset(cleared) => {
                history = cleared.clone();
                Undone::Reset(history.len())
            }
        };
        // What the inputs kept print was shown when they ran.
        if let Err(error) = self.rebuild(history) {
            self.undo_steps.push(step);
            return Err(error);
        }
        Ok(undone)
    }

    /// Forgets every input; `:undo` brings them back.
    pub(crate) fn reset(&mut self) {
        let cleared = std::mem::take(&mut self.history);
        self.interpreter = Interpreter::new(self.settings.time, self.limits);
        self.interpreter_time = self.settings.time;
        self.descriptions = ObjectDescriptions::default();
        self.undo_steps.push(UndoStep::Reset(cleared));
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
        let interpreter = Interpreter::new(time, self.limits).skip_static(skip_static);
        let mut interpreter = self.replay(interpreter, &self.history)?;
        self.printed.borrow_mut().absorb(interpreter.take_printed());
        Ok(interpreter)
    }

    /// Replaces the interpreter by one that ran `history` at the current
    /// time; returns what the replay printed.
    fn rebuild(&mut self, history: Vec<Input>) -> Result<PrintLog, Diagnostic> {
        let time = self.settings.time;
        self.interpreter = self.replay(Interpreter::new(time, self.limits), &history)?;
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
            interpreter.run_with_sources(&input.program, &self.sources)?;
        }
        interpreter.take_warnings();
        Ok(interpreter)
    }

    /// The scene built so far.
    pub fn scene(&self) -> &Scene {
        self.interpreter.scene()
    }

    /// What `print` wrote since the last call, at most
    /// [`crate::lang::eval::PRINT_LIMIT`] lines.
    pub(crate) fn take_printed(&self) -> PrintLog {
        self.printed.take()
    }

    /// The warnings about the scene, rendered as `picture`, that were not
    /// shown before (for the checks not turned off).
    pub(crate) fn scene_warnings(&mut self, picture: &Picture) -> Vec<Diagnostic> {
        let warnings = check_scene(self.scene(), self.interpreter.origins(), picture, self.allowed);
        warnings
            .into_iter()
            .filter(|warning| self.warned.insert((warning.check, warning.diagnostic.span)))
            .map(|warning| warning.diagnostic)
            .collect()
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

    /// How many accepted inputs the session holds.
    pub fn history_len(&self) -> usize {
        self.history.len()
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
    pub(crate) fn numbers(&self) -> Vec<(Rc<str>, f64)> {
        let names = self.interpreter.global_names();
        names.into_iter().filter_map(|name| Some((Rc::clone(&name), self.number_shown(&name)?))).collect()
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
    pub(crate) fn objects(&self) -> Vec<(Rc<str>, String)> {
        let names = self.interpreter.global_names();
        names.into_iter().filter_map(|name| Some((Rc::clone(&name), self.describe_object(&name)?))).collect()
    }

    /// What the global object `name` is (`sphere`, `group of 2 objects`,
    /// or its count of primitives), if it is one.
    pub(crate) fn describe_object(&self, name: &str) -> Option<String> {
        let primitives = self.interpreter.global_object_size(name)?;
        Some(match self.descriptions.get(name) {
            Some(description) => description.to_string(),
            None if primitives == 1 => "1 primitive".to_string(),
            None => format!("{primitives} primitives"),
        })
    }

    /// The procedures and their parameters, by name.
    pub(crate) fn procedures(&self) -> Vec<(Rc<str>, Vec<Rc<str>>)> {
        let names = self.interpreter.procedure_names();
        names
            .into_iter()
            .filter_map(|name| {
                let params = self.interpreter.procedure(&name)?.params.iter().map(|p| Rc::clone(&p.name)).collect();
                Some((name, params))
            })
            .collect()
    }

    /// The names completion offers.
    pub(crate) fn vocabulary(&self) -> Vocabulary {
        Vocabulary {
            variables: self.interpreter.global_names().iter().map(|name| name.to_string()).collect(),
            procedures: self
                .procedures()
                .into_iter()
                .map(|(name, params)| (name.to_string(), params.iter().map(|p| p.to_string()).collect()))
                .collect(),
        }
    }
}
