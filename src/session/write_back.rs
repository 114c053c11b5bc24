//! `:write FILE.ray`: the session written back as a scene file.
//!
//! The session takes items in any order, replaces the camera, redefines
//! procedures and loads files; a file gives its parts in a fixed order
//! (SPEC 2). The file holds the last camera and ambient light, every light
//! in order, the last definition of each procedure and every instruction in
//! order, each as its author wrote it, so that `rayrepl FILE.ray` renders
//! the picture `:save` renders. Where no file can give the session's scene
//! (an instruction ran a procedure redefined after it, a light reads a
//! variable), it says why and writes nothing.

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::lang::ast::{AmbientDef, CameraDef, Instr, Item, LightDef, ProcDef};
use crate::lang::eval::{DEFAULT_AMBIENT, DEFAULT_CAMERA};
use crate::lang::walk::{bound_name, called_name, same_level, variables};
use crate::lang::{Interpreter, Limits, SourceMap, Span, parse_file_interruptible};
use crate::output::{self, OutputError};
use crate::render::Screen;
use crate::scene::{Primitive, Scene};
use crate::settings::RenderSettings;

use super::excerpt::{item_text, location, raw};
use super::outcome::{CommandError, CommandResult, Flow};
use super::outputs::FrontEnd;
use super::render_steps::write_failure;
use super::report::counted;
use super::shell::Shell;
use super::state::{Input, Session};
use crate::process::cancel::{Stopped, cancel_flag, off_thread_streaming};

/// How many instructions are written between two looks at the cancel flag.
const CANCEL_EVERY: usize = 4096;

/// `:write FILE.ray`.
pub(crate) fn write(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let [file] = arguments else {
        return Err(CommandError::Usage("give the name of the .ray file to write".to_string()));
    };
    let path = Path::new(file);
    if path.extension().is_none_or(|extension| extension != "ray") {
        return Err(CommandError::Usage(format!("`{file}` is not a scene file: end its name in .ray")));
    }
    if session.inputs().is_empty() {
        return Err(CommandError::Failed("the session is empty: there is nothing to write yet".to_string()));
    }
    // Ctrl-C stops each step: the file and the session stay as they were.
    let cancel = cancel_flag(front.cancel());
    let cancelled = || write_failure(OutputError::Cancelled { path: path.to_owned() });
    let parts = Parts::of(session.inputs());
    parts.check(session.sources()).map_err(|inexact| CommandError::Failed(inexact.to_string()))?;
    let command = batch_command(path, session.settings(), session.limits());
    let text = Arc::new(parts.file_text(session, &command, cancel).ok_or_else(cancelled)?);
    match gives_the_scene(&text, session, cancel) {
        Err(Stopped::Cancelled) => return Err(cancelled()),
        _ if cancel.load(Ordering::SeqCst) => return Err(cancelled()),
        Ok(true) => {}
        Ok(false) | Err(Stopped::Failed) => {
            let bug = "the file would not give the session's scene (a bug of rayrepl: please report it)";
            return Err(CommandError::Failed(format!("{bug}; nothing was written")));
        }
    }
    output::write_text(path, &text, cancel).map_err(write_failure)?;
    let summary = parts.summary();
    session.mark_written();
    front.say(format!("wrote {} ({summary})", path.display()));
    front.say(format!("`{command}` renders the picture `:save` renders"));
    Ok(Flow::Continue)
}

/// A camera, ambient light or light, with whether `time` was rebound
/// (`let time = ...`) before it, and where.
struct Header<'s, T> {
    def: &'s T,
    span: Span,
    time_bound_at: Option<Span>,
}

/// The session's items sorted into the parts of a file, in its order.
struct Parts<'s> {
    camera: Option<Header<'s, CameraDef>>,
    ambient: Option<Header<'s, AmbientDef>>,
    lights: Vec<Header<'s, LightDef>>,
    /// The last definition of each procedure, in the order they were first defined.
    procs: Vec<&'s Arc<ProcDef>>,
    /// Every item in the order it ran, to follow calls through redefinitions.
    items: Vec<&'s Item>,
}

impl<'s> Parts<'s> {
    fn of(inputs: &'s [Input]) -> Parts<'s> {
        let mut parts = Parts { camera: None, ambient: None, lights: Vec::new(), procs: Vec::new(), items: Vec::new() };
        let mut time_bound_at = None;
        for item in inputs.iter().flat_map(|input| &input.program.items) {
            let span = item.span();
            match item {
                Item::Camera(def) => parts.camera = Some(Header { def, span, time_bound_at }),
                Item::Ambient(def) => parts.ambient = Some(Header { def, span, time_bound_at }),
                Item::Light(def) => parts.lights.push(Header { def, span, time_bound_at }),
                Item::Proc(def) => match parts.procs.iter_mut().find(|known| known.name.name == def.name.name) {
                    Some(known) => *known = def,
                    None => parts.procs.push(def),
                },
                Item::Instr(instr) => {
                    let binds_time = same_level(std::iter::once(instr)).filter_map(bound_name).any(|n| &**n == "time");
                    if binds_time {
                        time_bound_at = Some(instr.span);
                    }
                }
            }
            parts.items.push(item);
        }
        parts
    }

    fn instrs(&self) -> impl Iterator<Item = &'s Instr> + '_ {
        self.items.iter().filter_map(|item| match item {
            Item::Instr(instr) => Some(instr),
            _ => None,
        })
    }

    /// Whether the file gives the session's scene, or why not.
    fn check(&self, sources: &SourceMap) -> Result<(), Inexact> {
        self.check_headers(sources)?;
        self.check_procedures(sources)
    }

    /// At the top of a file, before any `let`, the camera, the ambient
    /// light and the lights can read no variable but `time`, and that one
    /// only as the render sets it.
    fn check_headers(&self, sources: &SourceMap) -> Result<(), Inexact> {
        let camera =
            self.camera.iter().map(|h| ("camera", h.span, h.time_bound_at, vec![&h.def.distance, &h.def.angle]));
        let ambient = self.ambient.iter().map(|h| ("ambient light", h.span, h.time_bound_at, vec![&h.def.intensity]));
        let lights = self.lights.iter().map(|h| {
            let mut exprs: Vec<_> = h.def.rotation.parts.iter().collect();
            exprs.push(&h.def.intensity);
            ("light", h.span, h.time_bound_at, exprs)
        });
        for (what, span, time_bound_at, exprs) in camera.chain(ambient).chain(lights) {
            for name in variables(exprs.into_iter()) {
                let rebound = time_bound_at.filter(|_| &**name == "time").map(|at| location(sources, at));
                if &**name != "time" || rebound.is_some() {
                    let at = location(sources, span);
                    return Err(Inexact::HeaderReads { what, at, name: name.to_string(), rebound });
                }
            }
        }
        Ok(())
    }

    /// A file has one definition of each procedure, the last: every
    /// instruction must have run (directly or through other procedures)
    /// only procedures defined then as they are at the end. A call that
    /// found no procedure did not run, as the input was accepted.
    fn check_procedures(&self, sources: &SourceMap) -> Result<(), Inexact> {
        let last: HashMap<&str, &ProcDef> = self.procs.iter().map(|def| (&*def.name.name, &***def)).collect();
        let same = |a: &ProcDef, b: &ProcDef| std::ptr::eq(a, b) || raw(sources, a.span) == raw(sources, b.span);
        let mut current: HashMap<&str, &ProcDef> = HashMap::new();
        // The procedures whose definition now is not the last one.
        let mut stale: HashSet<&str> = HashSet::new();
        for item in &self.items {
            match item {
                Item::Proc(def) => {
                    let name = &*def.name.name;
                    current.insert(name, def);
                    if same(def, last[name]) {
                        stale.remove(name);
                    } else {
                        stale.insert(name);
                    }
                }
                Item::Instr(instr) if !stale.is_empty() => {
                    let mut visited = HashSet::new();
                    let mut pending: Vec<&Instr> = vec![instr];
                    while let Some(next) = pending.pop() {
                        for name in same_level(std::iter::once(next)).filter_map(called_name) {
                            let Some(&def) = current.get(&**name).filter(|_| visited.insert(&**name)) else {
                                continue;
                            };
                            if stale.contains(&**name) {
                                return Err(Inexact::Redefined {
                                    run_at: location(sources, instr.span),
                                    name: name.to_string(),
                                    old_at: location(sources, def.span),
                                    new_at: location(sources, last[&**name].span),
                                });
                            }
                            pending.extend(&def.body);
                        }
                    }
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The text of the file: a header saying how to render it, then the
    /// parts in a file's order; `None` once `cancel` is raised.
    fn file_text(&self, session: &Session, command: &str, cancel: &AtomicBool) -> Option<String> {
        let sources = session.sources();
        let mut text = format!(
            "# Written by rayrepl's `:write` from a session of {}.\n\
             # `{command}`\n\
             # renders the picture that `:save` gives in the session.\n\n",
            counted(session.inputs().len(), "input")
        );
        let camera = match &self.camera {
            Some(camera) => item_text(sources, camera.span),
            None => format!(
                "camera distance {} angle {} end # the session's default",
                DEFAULT_CAMERA.distance, DEFAULT_CAMERA.angle
            ),
        };
        let ambient = match &self.ambient {
            Some(ambient) => item_text(sources, ambient.span),
            None => format!("ambient {DEFAULT_AMBIENT} # the session's default"),
        };
        let lights: Vec<String> = self.lights.iter().map(|light| item_text(sources, light.span)).collect();
        let procs: Vec<String> = self.procs.iter().map(|def| item_text(sources, def.span)).collect();
        let sections = [vec![camera, ambient], lights, procs];
        let sections: Vec<String> =
            sections.iter().filter(|section| !section.is_empty()).map(|section| section.join("\n")).collect();
        text.push_str(&sections.join("\n\n"));
        // The instructions, the most of a long session, go straight into the text.
        for (k, instr) in self.instrs().enumerate() {
            if k % CANCEL_EVERY == 0 && cancel.load(Ordering::Relaxed) {
                return None;
            }
            text.push_str(if k == 0 { "\n\n" } else { "\n" });
            text.push_str(&item_text(sources, instr.span));
        }
        text.push('\n');
        Some(text)
    }

    /// What the file holds, in words.
    fn summary(&self) -> String {
        let camera = if self.camera.is_some() { "the camera" } else { "the default camera" };
        let ambient = if self.ambient.is_some() { "the ambient light" } else { "the default ambient light" };
        let procs = counted(self.procs.len(), "procedure");
        let instrs = counted(self.instrs().count(), "instruction");
        format!("{camera}, {ambient}, {}, {procs}, {instrs}", counted(self.lights.len(), "light"))
    }
}

/// Why no file gives the session's scene.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Inexact {
    /// A camera, ambient light or light reads a variable, which at the top
    /// of a file has no value, or (`time` after `let time`) another one.
    HeaderReads {
        what: &'static str,
        at: String,
        name: String,
        /// Where `time` was rebound, when that is the variable.
        rebound: Option<String>,
    },
    /// An instruction ran a procedure that was redefined after it.
    Redefined { run_at: String, name: String, old_at: String, new_at: String },
}

impl fmt::Display for Inexact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Inexact::HeaderReads { what, at, name, rebound } => {
                write!(f, "cannot write a file that gives this scene: the {what} at {at} reads `{name}`")?;
                match rebound {
                    Some(let_at) => write!(f, ", as {let_at} set it; at the top of a file `time` is the render's")?,
                    None => write!(f, ", which has no value at the top of a file, where the {what} must stand")?,
                }
                write!(f, "\ngive the {what} again with numbers in place of `{name}`, then `:write` again")
            }
            Inexact::Redefined { run_at, name, old_at, new_at } => write!(
                f,
                "cannot write a file that gives this scene: {run_at} ran `{name}` as {old_at} defined it, \
                 and {new_at} redefined it afterwards; a file has one definition of each procedure\n\
                 run what used the old `{name}` again after the new one (or `:undo` back to before it), \
                 then `:write` again"
            ),
        }
    }
}

/// The command line that renders the file at `path` as `:save` renders the
/// session: its size, depth, samples, time and limits.
fn batch_command(path: &Path, settings: &RenderSettings, limits: Limits) -> String {
    let image = path.with_extension("png");
    let mut command = format!(
        "rayrepl {} -o {} --width {} --height {} --depth {} --samples {}",
        path.display(),
        image.display(),
        settings.width,
        settings.height,
        settings.depth,
        settings.samples
    );
    if settings.adaptive {
        command.push_str(" --adaptive");
    }
    if settings.screen == Screen::Bottom {
        command.push_str(" --screen bottom");
    }
    if settings.time != 0.0 {
        // Rust prints the shortest decimal that reads back as the same number.
        command.push_str(&format!(" --time {}", settings.time));
    }
    if limits.max_call_depth != Limits::DEFAULT.max_call_depth {
        command.push_str(&format!(" --max-calls {}", limits.max_call_depth));
    }
    if limits.max_primitives != Limits::DEFAULT.max_primitives {
        command.push_str(&format!(" --max-primitives {}", limits.max_primitives));
    }
    command
}

/// How many primitives of a kind the check of [`gives_the_scene`] gets from
/// its evaluation at once (some MB).
const CHECK_BATCH: usize = 1 << 15;

/// Whether `text`, read as a file and evaluated as a batch render would,
/// gives the session's scene: the last guard against writing a wrong file.
/// It is read and evaluated on a thread of its own, which Ctrl-C abandons
/// (freeing what it built takes a while for a large session, and is done
/// there); once `cancel` is raised the answer means nothing. The
/// primitives are compared as they are made, a batch at a time, and not
/// kept: the check holds the file's syntax tree, not a second scene.
fn gives_the_scene(text: &Arc<String>, session: &Session, cancel: &'static AtomicBool) -> Result<bool, Stopped> {
    let (text, time, limits) = (Arc::clone(text), session.settings().time, session.limits());
    let expected = session.scene();
    let mut compared = Compared::default();
    let rest = off_thread_streaming(
        "check",
        cancel,
        move |parts| {
            let mut sources = SourceMap::new();
            let id = sources.add("<written>", text.as_str(), 0);
            let program = parse_file_interruptible(id, &text, Some(cancel)).ok()?;
            let parts = parts.clone();
            let mut interpreter =
                Interpreter::new(time, limits).interruptible(cancel).streaming(CHECK_BATCH, move |timed, batch| {
                    parts.send((timed, batch));
                });
            interpreter.run(&program).is_ok().then(|| interpreter.into_scene())
        },
        |(timed, batch)| compared.batch(expected, timed, &batch),
    )?;
    Ok(rest.is_some_and(|rest| compared.ends_as(expected, rest)))
}

/// How far the primitives made by `:write`'s check agree with the
/// session's scene.
#[derive(Debug, Default)]
struct Compared {
    /// How many static primitives, and timed ones, were compared.
    primitives: usize,
    timed: usize,
    /// Whether one differed (or there were more than the scene's).
    differs: bool,
}

impl Compared {
    /// Compares `batch`, the next primitives made (`timed` or static).
    fn batch(&mut self, expected: &Scene, timed: bool, batch: &[Primitive]) {
        let (list, at) = if timed {
            (&expected.timed_primitives, &mut self.timed)
        } else {
            (&expected.primitives, &mut self.primitives)
        };
        self.differs |= list.get(*at..*at + batch.len()) != Some(batch);
        *at += batch.len();
    }

    /// Whether `rest`, the scene left at the end of the evaluation (the
    /// primitives not yet compared, and the rest of a scene), ends as
    /// `expected` does.
    fn ends_as(mut self, expected: &Scene, rest: Scene) -> bool {
        let Scene { camera, ambient, lights, primitives, timed_primitives, time_use } = rest;
        self.batch(expected, false, &primitives);
        self.batch(expected, true, &timed_primitives);
        !self.differs
            && self.primitives == expected.primitives.len()
            && self.timed == expected.timed_primitives.len()
            && camera == expected.camera
            && ambient == expected.ambient
            && lights == expected.lights
            && time_use == expected.time_use
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::parse_items;

    fn scene_of(text: &str) -> Scene {
        let mut sources = SourceMap::new();
        let program = parse_items(sources.add("<test>", text, 0), text).expect("parses");
        let mut interpreter = Interpreter::new(0.0, Limits::DEFAULT);
        interpreter.run(&program).expect("runs");
        interpreter.into_scene()
    }

    #[test]
    fn the_check_compares_the_primitives_batch_by_batch_and_what_is_left() {
        let ball = |x: u32| format!("put sphere center {x}, 0, 0 radius 1 kd 0.5 ks 0.5 phong 10 color 1, 2, 3 end\n");
        let expected = scene_of(&(1..=5).map(ball).collect::<String>());
        let (first, rest) = expected.primitives.split_at(3);
        let compare = |batches: &[&[Primitive]], rest: &[Primitive]| {
            let mut compared = Compared::default();
            for batch in batches {
                compared.batch(&expected, false, batch);
            }
            compared.ends_as(&expected, Scene { primitives: rest.to_vec(), ..expected.clone() })
        };
        assert!(compare(&[first], rest), "the same primitives in two parts");
        assert!(compare(&[&expected.primitives], &[]), "all in one batch");
        assert!(!compare(&[rest], first), "the same primitives in another order");
        assert!(!compare(&[first], &rest[1..]), "one missing");
        assert!(!compare(&[first, first], rest), "more than the scene's");
        let other = scene_of(&ball(9));
        assert!(!compare(&[&other.primitives, &first[1..]], rest), "one different");
    }
}
