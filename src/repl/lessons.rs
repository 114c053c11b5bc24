//! Guided lessons (`:lesson`): each step says what to build, shows the goal
//! picture beside the learner's render, and checks the learner's scene after
//! every accepted input: a hint after a wrong try, the next step on success.
//! Progress is kept between sessions ([`progress`]).

mod content;
mod progress;
pub(crate) mod tutor;

use std::sync::atomic::AtomicBool;

use image::RgbImage;

use crate::lang::{Diagnostic, Limits};

use super::outcome::{CommandError, CommandResult, Flow};
use super::outputs::{FrontEnd, LessonStep, LessonVerdict, Output, Picture, side_by_side};
use super::rendering::{RenderError, Size, render_image};
use super::session::Session;
use super::shell::Shell;
use crate::render::SceneGeometry;
use content::{LESSONS, Lesson, Step};
use progress::Progress;
use tutor::Tutor;

/// Wrong tries of a step after which its example is shown with the hint.
const TRIES_BEFORE_EXAMPLE: u32 = 2;
/// Columns of background between the goal picture and the learner's.
const PICTURE_GAP: u32 = 4;

/// `:lesson` lists the lessons; `:lesson N` starts (or resumes) lesson N;
/// `:lesson stop` leaves the lesson.
pub(crate) fn lesson(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    match arguments {
        [] => list(shell, front),
        [word] if word == "stop" => {
            shell.tutor = Tutor::default();
            front.say("left the lesson; `:lesson` lists them all");
        }
        [number] => {
            let index = number
                .parse::<usize>()
                .ok()
                .filter(|n| (1..=LESSONS.len()).contains(n))
                .ok_or_else(|| CommandError::Usage(format!("the lessons are numbered 1 to {}", LESSONS.len())))?;
            start(shell, index - 1, front)?;
        }
        _ => return Err(CommandError::Usage("give one lesson number, or nothing to list them".to_string())),
    }
    Ok(Flow::Continue)
}

/// After an accepted input: checks the scene against the current step, and
/// moves on or gives the hint.
pub(crate) fn check_input(shell: &mut Shell, front: &mut dyn FrontEnd) {
    let Some((lesson, step)) = shell.tutor.place else {
        return;
    };
    let current = &LESSONS[lesson].steps[step];
    match (current.check)(&shell.session) {
        Ok(()) => {
            let _ = front.present(Output::LessonVerdict(LessonVerdict::Done { number: step + 1, already: false }));
            advance(shell, front, lesson, step);
        }
        Err(missing) => {
            show_pictures(&shell.session, front, lesson, step);
            shell.tutor.wrong_tries += 1;
            let show_example = shell.tutor.wrong_tries >= TRIES_BEFORE_EXAMPLE && !current.example_up_front;
            let example = show_example.then(|| current.example.to_string());
            let verdict = LessonVerdict::NotYet { missing, hint: current.hint.to_string(), example };
            let _ = front.present(Output::LessonVerdict(verdict));
        }
    }
}

fn list(shell: &Shell, front: &mut dyn FrontEnd) {
    let progress = Progress::load();
    front.say("lessons (`:lesson N` starts one):");
    for (index, lesson) in LESSONS.iter().enumerate() {
        let number = index + 1;
        let mark = if progress.done.contains(&number) { "✓" } else { " " };
        front.say(format!("  {mark} {number}. {} ({} steps)", lesson.title, lesson.steps.len()));
    }
    match (shell.tutor.place, progress.at) {
        (Some((lesson, step)), _) => {
            front.say(format!("you are at lesson {} step {}:", lesson + 1, step + 1));
            say_step(front, &LESSONS[lesson].steps[step], step, LESSONS[lesson].steps.len());
        }
        (None, Some((lesson, step))) => {
            front.say(format!("you stopped at lesson {lesson} step {step}: `:lesson {lesson}` goes on from there"))
        }
        (None, None) => {}
    }
}

/// Starts lesson `lesson` (from 0) on a scene of its own, at the step the
/// learner last reached in it.
fn start(shell: &mut Shell, lesson: usize, front: &mut dyn FrontEnd) -> Result<(), CommandError> {
    let progress = Progress::load();
    let step = match progress.at {
        Some((at, step)) if at == lesson + 1 && (1..=LESSONS[lesson].steps.len()).contains(&step) => step - 1,
        _ => 0,
    };
    let setup = lesson_scene(&LESSONS[lesson], step);
    shell.session.reset();
    let mut undo = "`:undo` brings yours back";
    if !setup.trim().is_empty() {
        if let Err(error) = shell.session.submit(&format!("<lesson {}>", lesson + 1), &setup, 0) {
            // Low `:limits` can stop the lesson's own program: leave the session as it was.
            let _ = shell.session.undo();
            return Err(CommandError::Program(Box::new(error)));
        }
        undo = "`:undo` twice brings yours back";
    }
    front.say(format!("lesson {} of {}: {}", lesson + 1, LESSONS.len(), LESSONS[lesson].title));
    let holds = shell.session.counts();
    let lights = super::report::counted(holds.lights, "light");
    front.say(format!("starting scene: {}, {lights} (`:list` shows it; {undo})", holds.primitives_in_words()));
    if step > 0 {
        front.say(format!("going on at step {}, where you stopped", step + 1));
    }
    begin_step(shell, front, lesson, step);
    Ok(())
}

/// The program a lesson's scene starts from at `step`: its setup, then the
/// examples of the steps before.
fn lesson_scene(lesson: &Lesson, step: usize) -> String {
    let mut text = lesson.setup.to_string();
    for earlier in &lesson.steps[..step] {
        text.push('\n');
        text.push_str(earlier.example);
    }
    text
}

/// Says what step `step` asks, shows its goal, and remembers where the
/// learner is.
fn begin_step(shell: &mut Shell, front: &mut dyn FrontEnd, lesson: usize, step: usize) {
    shell.tutor = Tutor { place: Some((lesson, step)), wrong_tries: 0 };
    let steps = LESSONS[lesson].steps;
    say_step(front, &steps[step], step, steps.len());
    let mut progress = Progress::load();
    progress.at = Some((lesson + 1, step + 1));
    save(&progress, front);
    if (steps[step].check)(&shell.session).is_ok() {
        let _ = front.present(Output::LessonVerdict(LessonVerdict::Done { number: step + 1, already: true }));
        advance(shell, front, lesson, step);
        return;
    }
    show_pictures(&shell.session, front, lesson, step);
}

fn say_step(front: &mut dyn FrontEnd, step: &Step, index: usize, steps: usize) {
    let example = step.example_up_front.then(|| step.example.to_string());
    let step = LessonStep { number: index + 1, steps, task: step.task.to_string(), example };
    let _ = front.present(Output::LessonStep(step));
}

/// Moves past step `step` of `lesson`: to the next step, or to the end of
/// the lesson, which is then remembered as done.
fn advance(shell: &mut Shell, front: &mut dyn FrontEnd, lesson: usize, step: usize) {
    if step + 1 < LESSONS[lesson].steps.len() {
        begin_step(shell, front, lesson, step + 1);
        return;
    }
    show_pictures(&shell.session, front, lesson, step);
    shell.tutor = Tutor::default();
    let mut progress = Progress::load();
    progress.done.insert(lesson + 1);
    progress.at = None;
    save(&progress, front);
    front.say(format!("✓ lesson {} done: {}", lesson + 1, LESSONS[lesson].title));
    match LESSONS.get(lesson + 1) {
        Some(next) => front.say(format!("next: `:lesson {}` ({})", lesson + 2, next.title)),
        None => front.say("that was the last lesson: `:help` lists everything the language has"),
    }
}

fn save(progress: &Progress, front: &mut dyn FrontEnd) {
    if let Err(problem) = progress.save() {
        front.note(format!("cannot keep your progress: {problem}"));
    }
}

/// Shows the goal picture of `step` beside the learner's render, where the
/// terminal shows pictures.
fn show_pictures(session: &Session, front: &mut dyn FrontEnd, lesson: usize, step: usize) {
    let settings = session.settings();
    // Two pictures of the configured shape, side by side, fitted together.
    let Some(pair) = front.picture_size(Size { width: settings.width.saturating_mul(2), height: settings.height })
    else {
        return;
    };
    match pictures(session, pair, lesson, step) {
        Ok(image) => {
            front.say("goal (left) and yours (right):");
            if let Err(problem) = front.present(Output::Picture(Picture { image, marked: None, saved_to: None })) {
                front.note(format!("cannot show the pictures here: {problem}"));
            }
        }
        Err(problem) => front.note(format!("cannot show the pictures: {problem}")),
    }
}

/// The goal picture of `step` and the learner's, side by side, together
/// of size `pair`.
fn pictures(session: &Session, pair: Size, lesson: usize, step: usize) -> Result<RgbImage, String> {
    let settings = session.settings();
    let half = Size { width: (pair.width.saturating_sub(PICTURE_GAP) / 2).max(1), height: pair.height };
    let goal = goal_session(session, lesson, step).map_err(|_| "the lesson's example fails".to_string())?;
    let render = |scene| {
        let never = AtomicBool::new(false);
        render_image(scene, &SceneGeometry::new(scene), half, settings, &never, &|_| {})
            .map_err(|RenderError::Cancelled| "the render was cancelled".to_string())
    };
    Ok(side_by_side(&render(goal.scene())?, &render(session.scene())?, PICTURE_GAP))
}

/// A session holding what `step` of `lesson` asks for: the setup and the
/// examples up to that step.
fn goal_session(session: &Session, lesson: usize, step: usize) -> Result<Session, Diagnostic> {
    let mut goal = Session::new(*session.settings(), Limits::default());
    let text = lesson_scene(&LESSONS[lesson], step + 1);
    goal.submit("<goal>", &text, 0)?;
    Ok(goal)
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;
    use crate::repl::RenderSettings;

    /// The size and samples of the pictures of docs/learning.md.
    const DOCS_PICTURE: RenderSettings =
        RenderSettings { width: 400, height: 300, samples: 4, ..crate::settings::DEFAULTS };

    fn docs() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs")
    }

    /// The picture of what lesson `index` builds, as docs/learning.md shows it.
    fn lesson_picture(index: usize) -> RgbImage {
        let mut session = Session::new(DOCS_PICTURE, Limits::default());
        let lesson = &LESSONS[index];
        session.submit("<lesson>", &lesson_scene(lesson, lesson.steps.len()), 0).expect("the lesson's examples run");
        let size = Size { width: DOCS_PICTURE.width, height: DOCS_PICTURE.height };
        let scene = session.scene();
        render_image(scene, &SceneGeometry::new(scene), size, &DOCS_PICTURE, &AtomicBool::new(false), &|_| {})
            .expect("nothing cancels it")
    }

    /// docs/learning.md shows every example of every lesson, and the
    /// picture of each lesson is what rayrepl renders of it now.
    /// `RAYREPL_BLESS=1 cargo test --release --lib learning_page` (or
    /// tools/learning-pictures) writes the pictures again.
    #[test]
    fn the_learning_page_shows_every_lesson_as_rendered_now() {
        let page = std::fs::read_to_string(docs().join("learning.md")).expect("docs/learning.md exists");
        let bless = std::env::var_os("RAYREPL_BLESS").is_some();
        for (index, lesson) in LESSONS.iter().enumerate() {
            for step in lesson.steps {
                assert!(page.contains(step.example), "docs/learning.md lacks the example\n{}", step.example);
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
