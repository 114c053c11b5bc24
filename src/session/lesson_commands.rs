//! The lesson commands (`:lesson`, `:goal`) and what the session does
//! for the lesson followed (`crate::lessons`): after every accepted input,
//! the scene checked against the step, what comes closest and a hint after
//! a wrong try, the next step on success; the goal picture beside the
//! learner's render. The session's state is the learner the checks read.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use image::RgbImage;

use crate::lang::eval::Origins;
use crate::lang::name::Name;
use crate::lang::{SourceMap, Span};
use crate::lessons::{BUILT_IN, Following, Learner, Lesson, Progress, Shortfall};
use crate::output::{self, Content};
use crate::scene::{Primitive, Scene};

use super::outcome::{CommandError, CommandResult, Flow};
use super::outputs::{FrontEnd, LessonStep, LessonVerdict, Output, Picture, side_by_side};
use super::reload;
use super::render_steps::write_failure;
use super::rendering::{RenderSettings, Size, render_image};
use super::shell::Shell;
use super::state::Session;
use crate::process::cancel::cancel_flag;

/// Wrong tries of a step after which its example is shown with the hint.
const TRIES_BEFORE_EXAMPLE: u32 = 2;
/// Columns of background between the goal picture and the learner's.
const PICTURE_GAP: u32 = 4;

/// `:lesson` lists the lessons; `:lesson N` starts (or resumes) lesson N;
/// `:lesson FILE` starts the lesson written in FILE; `:lesson stop` leaves.
pub(crate) fn lesson(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    match arguments {
        [] => list(shell, front),
        [word] if word == "stop" => {
            shell.tutor.following = None;
            front.say("left the lesson; `:lesson` lists them all");
        }
        [number] if number.parse::<usize>().is_ok() => {
            let index = number
                .parse::<usize>()
                .ok()
                .filter(|n| (1..=BUILT_IN.len()).contains(n))
                .ok_or_else(|| CommandError::Usage(format!("the lessons are numbered 1 to {}", BUILT_IN.len())))?;
            start(shell, Arc::clone(&BUILT_IN[index - 1]), Some(index), front)?;
        }
        [file] => {
            let lesson = read_lesson_file(shell, Path::new(file), front)?;
            start(shell, Arc::new(lesson), None, front)?;
        }
        _ => return Err(CommandError::Usage("give one lesson number or file, or nothing to list them".to_string())),
    }
    Ok(Flow::Continue)
}

/// Starts the lesson `--lesson` names (a number or a file), reporting any
/// failure on the front; `Err(())` if it failed.
pub(crate) fn start_reporting(shell: &mut Shell, lesson_or_file: &str, front: &mut dyn FrontEnd) -> Result<(), ()> {
    let started = lesson(shell, &[lesson_or_file.to_string()], front);
    started.map(drop).map_err(|error| error.report(&shell.session, front))
}

/// Reads and proves the lesson in the file at `path`; its mistakes point
/// into the file, which the session's sources then hold.
fn read_lesson_file(shell: &mut Shell, path: &Path, front: &mut dyn FrontEnd) -> Result<Lesson, CommandError> {
    let text = reload::read(path, cancel_flag(front.cancel()))?;
    let id = shell.session.add_source(&path.display().to_string(), &text, 0);
    Lesson::read(&text, id).map_err(|diagnostic| CommandError::Program(Box::new(diagnostic)))
}

/// After an accepted input: checks the scene against the current step, and
/// moves on or says what is missing (and that `:undo` takes the input back
/// if it made the problem). Nothing while checks are held.
pub(crate) fn check_input(shell: &mut Shell, front: &mut dyn FrontEnd) {
    if !shell.tutor.checks_held {
        check(shell, front, true);
    }
}

/// After a whole scene ran in place of the session's program: checks it
/// against the current step once, as [`check_input`] checks an input,
/// one wrong try at most; no `:undo` is offered, the scene being all the
/// learner's text.
pub(crate) fn check_scene(shell: &mut Shell, front: &mut dyn FrontEnd) {
    check(shell, front, false);
}

fn check(shell: &mut Shell, front: &mut dyn FrontEnd, undo_offered: bool) {
    let Some(following) = shell.tutor.following.clone() else {
        return;
    };
    let step = &following.lesson.steps[following.step];
    match holds(&following, &shell.session) {
        Ok(()) => {
            let number = following.step + 1;
            let _ = front.present(Output::LessonVerdict(LessonVerdict::Done { number, already: false }));
            advance(shell, front, following);
        }
        Err(shortfall) => {
            if show_pictures(&shell.session, front, &following) {
                // The pictures push the task up: say it again under them.
                say_step(front, &following);
            }
            let wrong_tries = following.wrong_tries + 1;
            let show_example = wrong_tries >= TRIES_BEFORE_EXAMPLE && !step.example_up_front;
            let newest = shell.session.last_input_source();
            let verdict = LessonVerdict::NotYet {
                missing: shortfall.text,
                undo: undo_offered && shortfall.made_at.is_some_and(|span: Span| Some(span.source) == newest),
                hint: step.hint.clone(),
                example: show_example.then(|| step.example.clone()),
            };
            let _ = front.present(Output::LessonVerdict(verdict));
            shell.tutor.following = Some(Following { wrong_tries, ..following });
        }
    }
}

/// Whether the learner's scene does what the step followed asks.
fn holds(following: &Following, session: &Session) -> Result<(), Shortfall> {
    following.lesson.holds(following.step, session, session.settings().time)
}

fn list(shell: &Shell, front: &mut dyn FrontEnd) {
    let progress = Progress::load();
    front.say("lessons (`:lesson N` starts one, `:lesson FILE` one from a file):");
    for (index, lesson) in BUILT_IN.iter().enumerate() {
        let number = index + 1;
        let mark = if progress.done.contains(&number) { "✓" } else { " " };
        front.say(format!("  {mark} {number}. {} ({} steps)", lesson.title, lesson.steps.len()));
    }
    match (&shell.tutor.following, progress.at) {
        (Some(following), _) => {
            front.say(format!("you are at step {} of \"{}\":", following.step + 1, following.lesson.title));
            say_step(front, following);
        }
        (None, Some((lesson, step))) => {
            front.say(format!("you stopped at lesson {lesson} step {step}: `:lesson {lesson}` goes on from there"))
        }
        (None, None) => {}
    }
}

/// Starts `lesson` (built-in lesson `number`, or one from a file) on a
/// scene of its own, at the step the learner last reached in it.
fn start(
    shell: &mut Shell,
    lesson: Arc<Lesson>,
    number: Option<usize>,
    front: &mut dyn FrontEnd,
) -> Result<(), CommandError> {
    let progress = Progress::load();
    let step = match (progress.at, number) {
        (Some((at, step)), Some(number)) if at == number && (1..=lesson.steps.len()).contains(&step) => step - 1,
        _ => 0,
    };
    let setup = lesson.scene_at(step);
    shell.session.reset();
    let mut undo = "`:undo` brings yours back";
    let name = match number {
        Some(number) => format!("<lesson {number}>"),
        None => "<lesson>".to_string(),
    };
    if !setup.trim().is_empty() {
        if let Err(error) = shell.session.submit(&name, &setup, 0) {
            // Low `:limits` can stop the lesson's own program: leave the session as it was.
            let _ = shell.session.undo();
            return Err(CommandError::Program(Box::new(error)));
        }
        undo = "`:undo` twice brings yours back";
    }
    match number {
        Some(number) => front.say(format!("lesson {number} of {}: {}", BUILT_IN.len(), lesson.title)),
        None => front.say(format!("lesson: {}", lesson.title)),
    }
    let holds = shell.session.counts();
    let lights = super::report::counted(holds.lights, "light");
    front.say(format!("starting scene: {}, {lights} (`:list` shows it; {undo})", holds.primitives_in_words()));
    if step > 0 {
        front.say(format!("going on at step {}, where you stopped", step + 1));
    }
    begin_step(shell, front, Following { lesson, number, step, wrong_tries: 0 });
    Ok(())
}

/// Says what the step followed asks, shows its goal, and remembers where
/// the learner is.
fn begin_step(shell: &mut Shell, front: &mut dyn FrontEnd, following: Following) {
    shell.tutor.following = Some(following.clone());
    say_step(front, &following);
    if let Some(number) = following.number {
        let mut progress = Progress::load();
        progress.at = Some((number, following.step + 1));
        save(&progress, front);
    }
    if holds(&following, &shell.session).is_ok() {
        let number = following.step + 1;
        let _ = front.present(Output::LessonVerdict(LessonVerdict::Done { number, already: true }));
        advance(shell, front, following);
        return;
    }
    show_pictures(&shell.session, front, &following);
}

fn say_step(front: &mut dyn FrontEnd, following: &Following) {
    let steps = &following.lesson.steps;
    let step = &steps[following.step];
    let example = step.example_up_front.then(|| step.example.clone());
    let shown = LessonStep { number: following.step + 1, steps: steps.len(), task: step.task.clone(), example };
    let _ = front.present(Output::LessonStep(shown));
}

/// Moves past the step followed: to the next step, or to the end of the
/// lesson, which is then remembered as done.
fn advance(shell: &mut Shell, front: &mut dyn FrontEnd, following: Following) {
    if following.step + 1 < following.lesson.steps.len() {
        begin_step(shell, front, Following { step: following.step + 1, wrong_tries: 0, ..following });
        return;
    }
    show_pictures(&shell.session, front, &following);
    shell.tutor.following = None;
    let Some(number) = following.number else {
        front.say(format!("✓ lesson done: {}", following.lesson.title));
        return;
    };
    let mut progress = Progress::load();
    progress.done.insert(number);
    progress.at = None;
    save(&progress, front);
    front.say(format!("✓ lesson {number} done: {}", following.lesson.title));
    match BUILT_IN.get(number) {
        Some(next) => front.say(format!("next: `:lesson {}` ({})", number + 1, next.title)),
        None => front.say("that was the last lesson: `:help` lists everything the language has"),
    }
}

fn save(progress: &Progress, front: &mut dyn FrontEnd) {
    if let Err(problem) = progress.save() {
        front.note(format!("cannot keep your progress: {problem}"));
    }
}

/// Shows the goal picture of the step followed beside the learner's
/// render, where the front-end shows pictures; whether it did.
fn show_pictures(session: &Session, front: &mut dyn FrontEnd, following: &Following) -> bool {
    let settings = session.settings();
    // Two pictures of the configured shape, side by side, fitted together.
    let shape = Size { width: settings.width.saturating_mul(2), height: settings.height };
    let Some(pair) = front.lesson_picture_size(shape) else {
        return false;
    };
    let half = Size { width: (pair.width.saturating_sub(PICTURE_GAP) / 2).max(1), height: pair.height };
    let pictures = goal_picture(session, following, half)
        .and_then(|goal| Ok(side_by_side(&goal, &render(session.scene(), settings, half)?, PICTURE_GAP)));
    match pictures {
        Ok(image) => {
            front.say("goal (left) and yours (right):");
            if let Err(problem) = front.present(Output::LessonPictures(image)) {
                front.note(format!("cannot show the pictures here: {problem}"));
            }
            true
        }
        Err(problem) => {
            front.note(format!("cannot show the pictures: {problem}"));
            false
        }
    }
}

/// `scene` rendered at `size`, with `settings`.
fn render(scene: &Scene, settings: &RenderSettings, size: Size) -> Result<RgbImage, String> {
    let never = AtomicBool::new(false);
    render_image(scene, size, settings, &never, &|_| {}).map_err(|error| error.to_string())
}

/// The goal of the step followed, rendered at `size` with the session's
/// settings.
fn goal_picture(session: &Session, following: &Following, size: Size) -> Result<RgbImage, String> {
    let settings = session.settings();
    let goal = following.lesson.evaluate_at(following.step + 1, settings.time);
    render(goal.ok_or("the lesson's example fails")?.scene(), settings, size)
}

/// `:goal` shows the goal of the step followed; `:goal FILE` writes it at
/// the session's size.
pub(crate) fn goal(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let Some(following) = shell.tutor.following.clone() else {
        return Err(CommandError::Failed("no lesson is followed: `:lesson N` starts one".to_string()));
    };
    let settings = shell.session.settings();
    let full = Size { width: settings.width, height: settings.height };
    match arguments {
        [] => {
            let Some(size) = front.picture_size(full) else {
                return Err(CommandError::Failed(
                    "pictures are not shown here: `:goal FILE.png` writes it".to_string(),
                ));
            };
            let image = goal_picture(&shell.session, &following, size).map_err(CommandError::Failed)?;
            front.say(format!("the goal of step {}:", following.step + 1));
            front
                .present(Output::Picture(Picture { image, marked: None, saved_to: None }))
                .map_err(CommandError::Failed)?;
        }
        [file] => {
            let path = PathBuf::from(file);
            output::check_output(&path, Content::Still).map_err(|e| CommandError::Failed(e.to_string()))?;
            let image = goal_picture(&shell.session, &following, full).map_err(CommandError::Failed)?;
            output::write_image_cancellable(&path, &image, cancel_flag(front.cancel())).map_err(write_failure)?;
            let _ = front.present(Output::Picture(Picture { image, marked: None, saved_to: Some(path.clone()) }));
            front.say(format!("saved the goal of step {} to {} ({full})", following.step + 1, path.display()));
        }
        _ => return Err(CommandError::Usage("give one file name, or nothing to see the goal".to_string())),
    }
    Ok(Flow::Continue)
}

/// The learner's state the lessons' checks read: the session's.
impl Learner for Session {
    fn scene(&self) -> &Scene {
        Session::scene(self)
    }

    fn origins(&self) -> &Origins {
        Session::origins(self)
    }

    fn sources(&self) -> &SourceMap {
        Session::sources(self)
    }

    fn has_camera(&self) -> bool {
        Session::has_camera(self)
    }

    fn has_ambient(&self) -> bool {
        Session::has_ambient(self)
    }

    fn numbers(&self) -> Vec<(Name, f64)> {
        Session::numbers(self)
    }

    fn object_names(&self) -> Vec<Name> {
        self.objects().into_iter().map(|(name, _)| name).collect()
    }

    fn object(&self, name: &str) -> Option<&[Primitive]> {
        self.global_object(name)
    }

    fn procedures(&self) -> Vec<(Name, usize)> {
        let procedures = Session::procedures(self);
        procedures.into_iter().map(|(name, parameters)| (name, parameters.len())).collect()
    }
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;

    /// The size and samples of the pictures of docs/learning.md.
    const DOCS_PICTURE: RenderSettings =
        RenderSettings { width: 400, height: 300, samples: 4, ..crate::settings::DEFAULTS };

    fn docs() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs")
    }

    /// The picture of what lesson `index` builds, as docs/learning.md shows it.
    fn lesson_picture(index: usize) -> RgbImage {
        let lesson = &BUILT_IN[index];
        let goal = lesson.evaluate_at(lesson.steps.len(), DOCS_PICTURE.time).expect("the lesson's examples run");
        let size = Size { width: DOCS_PICTURE.width, height: DOCS_PICTURE.height };
        render(goal.scene(), &DOCS_PICTURE, size).expect("nothing cancels it")
    }

    /// docs/learning.md shows every example of every lesson, and the
    /// picture of each lesson is what rayrepl renders of it now.
    /// `RAYREPL_BLESS=1 cargo test --release --lib learning_page` (or
    /// tools/learning-pictures) writes the pictures again.
    #[test]
    fn the_learning_page_shows_every_lesson_as_rendered_now() {
        let page = std::fs::read_to_string(docs().join("learning.md")).expect("docs/learning.md exists");
        let bless = std::env::var_os("RAYREPL_BLESS").is_some();
        for (index, lesson) in BUILT_IN.iter().enumerate() {
            for step in &lesson.steps {
                assert!(page.contains(&step.example), "docs/learning.md lacks the example\n{}", step.example);
            }
            let name = format!("learning/lesson-{}.png", index + 1);
            assert!(page.contains(&name), "docs/learning.md does not show {name}");
            let picture = lesson_picture(index);
            let path = docs().join(&name);
            if bless {
                crate::output::write_image(&path, &picture).expect("the picture is written");
                continue;
            }
            let committed = image::open(&path).map(|image| image.to_rgb8());
            assert!(
                committed.is_ok_and(|committed| committed == picture),
                "{name} is not what lesson {} renders now: RAYREPL_BLESS=1 cargo test --release --lib learning_page",
                index + 1
            );
        }
    }
}
