//! Lessons as text files: Markdown with a title, an optional setup program,
//! then one `##` section a step, each with its task, example, hint, checks
//! and the answers the lesson promises to accept and to refuse. The built-in
//! lessons are such files (`lessons/*.md`), and a teacher writes new ones
//! without recompiling; docs/lessons.md documents the format.
//!
//! [`Lesson::read`] reads a file and then proves it: every step's checks
//! must not hold before the step, its example and every `passes` answer
//! must pass, every `fails` answer must not (with the words of its
//! `Says:`). A mistake is a [`Diagnostic`] pointing at the file's line.

use crate::lang::{Diagnostic, SourceId, Span};
use crate::settings::RenderSettings;

use super::check::{Check, Shortfall, holds, no_degrees, parse};
use super::learner::Learner;
use super::lesson_scene::LessonScene;

/// A lesson: a title, the scene it starts from, its steps.
#[derive(Debug)]
pub(crate) struct Lesson {
    /// What it teaches, in a few words.
    pub title: String,
    /// Program text run when the lesson starts (a camera, a light, a
    /// floor), so that each lesson practises one thing.
    pub setup: String,
    pub steps: Vec<Step>,
}

/// One step of a lesson.
#[derive(Debug)]
pub(crate) struct Step {
    /// What to do, in plain words.
    pub task: String,
    /// A program that does it: shown with the task (`example_up_front`) or
    /// after wrong tries, run for the goal picture.
    pub example: String,
    pub example_up_front: bool,
    /// Where the example is in the file: where a mistake of the step is shown.
    pub example_at: Span,
    /// What to think of when a check fails.
    pub hint: String,
    /// What the scene must hold, all of it.
    pub checks: Vec<Check>,
    /// Answers that must pass, each with its place in the file.
    pub passes: Vec<(String, Span)>,
    /// Answers that must not, with the words the "not yet" must say.
    pub fails: Vec<Refused>,
}

/// An answer a step must refuse.
#[derive(Debug)]
pub(crate) struct Refused {
    pub program: String,
    pub place: Span,
    /// Words the shortfall must contain (`Says:`), if given.
    pub says: Option<String>,
}

/// A fenced block being read: its kind, where it opened, its lines.
struct Block {
    kind: BlockKind,
    opened: Span,
    text: String,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BlockKind {
    Setup,
    Example { shown: bool },
    Passes,
    Fails,
}

/// The block kinds, as written after "```ray ".
const BLOCK_KINDS: &[(&str, BlockKind)] = &[
    ("setup", BlockKind::Setup),
    ("example", BlockKind::Example { shown: false }),
    ("example shown", BlockKind::Example { shown: true }),
    ("passes", BlockKind::Passes),
    ("fails", BlockKind::Fails),
];

/// A step as it is read, before its example is known to be there.
struct StepDraft {
    heading: Span,
    task: Vec<String>,
    example: Option<(String, bool, Span)>,
    hint: Vec<String>,
    checks: Vec<Check>,
    passes: Vec<(String, Span)>,
    fails: Vec<Refused>,
    /// Whether the lines read last continue the hint.
    in_hint: bool,
}

impl Lesson {
    /// The lesson written `text` (the file `source`), read and proved.
    pub(crate) fn read(text: &str, source: SourceId) -> Result<Lesson, Diagnostic> {
        let lesson = Lesson::parse(text, source)?;
        lesson.prove()?;
        Ok(lesson)
    }

    /// The lesson written `text` (the file `source`), read without running
    /// anything: for lessons proved already (the built-in ones, by the tests).
    pub(crate) fn parse(text: &str, source: SourceId) -> Result<Lesson, Diagnostic> {
        read_format(text, source)
    }

    /// The program the lesson's scene holds at step `step` (from 0): its
    /// setup, then the examples of the steps before.
    pub(crate) fn scene_at(&self, step: usize) -> String {
        let mut text = self.setup.clone();
        for earlier in &self.steps[..step] {
            text.push('\n');
            text.push_str(&earlier.example);
        }
        text
    }

    /// The lesson's scene at `step` (from 0), evaluated with `time` at the
    /// value `time`;
    /// `None` if its program fails.
    pub(crate) fn evaluate_at(&self, step: usize, time: f64) -> Option<LessonScene> {
        let mut evaluation = LessonScene::new(time);
        evaluation.run("<goal>", &self.scene_at(step)).ok()?;
        Some(evaluation)
    }

    /// `Ok` when the `learner`'s scene does everything step `step` (from 0)
    /// asks; the step's goal, for a check that compares with it, is
    /// evaluated with `time`.
    pub(crate) fn holds(&self, step: usize, learner: &dyn Learner, time: f64) -> Result<(), Shortfall> {
        no_degrees(learner)?;
        let checks = &self.steps[step].checks;
        let goal = checks.contains(&Check::MatchesGoal).then(|| self.evaluate_at(step + 1, time)).flatten();
        let goal = goal.as_ref().map(|goal| goal as &dyn Learner);
        checks.iter().try_for_each(|check| holds(check, learner, goal))
    }

    /// Runs every step's answers and example: a lesson whose checks hold
    /// before its step, refuse its own example or its `passes` answers, or
    /// accept its `fails` answers, is wrong.
    fn prove(&self) -> Result<(), Diagnostic> {
        let time = RenderSettings::default().time;
        let mut evaluation = LessonScene::new(time);
        for (index, step) in self.steps.iter().enumerate() {
            let number = index + 1;
            let place = step.example_at;
            if index == 0 {
                run(&mut evaluation, &self.setup, place, "the setup")?;
            }
            if self.holds(index, &evaluation, time).is_ok() {
                let message = format!("step {number}'s checks hold before it starts: they ask for nothing new");
                return Err(Diagnostic::error(place, message));
            }
            for (answer, at) in &step.passes {
                run(&mut evaluation, answer, *at, "this answer")?;
                let verdict = self.holds(index, &evaluation, time);
                evaluation.undo().map_err(|_| Diagnostic::error(*at, "this answer cannot be taken back"))?;
                if let Err(shortfall) = verdict {
                    let message = format!("step {number} refuses this answer: {}", shortfall.text);
                    return Err(Diagnostic::error(*at, message));
                }
            }
            for refused in &step.fails {
                run(&mut evaluation, &refused.program, refused.place, "this answer")?;
                let verdict = self.holds(index, &evaluation, time);
                evaluation.undo().map_err(|_| Diagnostic::error(refused.place, "this answer cannot be taken back"))?;
                match (verdict, &refused.says) {
                    (Ok(()), _) => {
                        let message = format!("step {number} accepts this answer, which it must refuse");
                        return Err(Diagnostic::error(refused.place, message));
                    }
                    (Err(shortfall), Some(says)) if !shortfall.text.contains(says.as_str()) => {
                        let message = format!("step {number} says \"{}\", not \"{says}\"", shortfall.text);
                        return Err(Diagnostic::error(refused.place, message));
                    }
                    (Err(_), _) => {}
                }
            }
            run(&mut evaluation, &step.example, place, "the example")?;
            if let Err(shortfall) = self.holds(index, &evaluation, time) {
                let message = format!("step {number} refuses its own example: {}", shortfall.text);
                return Err(Diagnostic::error(place, message));
            }
        }
        Ok(())
    }
}

/// Runs `program` into `evaluation`; a program that fails is a mistake of
/// the lesson at `place`.
fn run(evaluation: &mut LessonScene, program: &str, place: Span, what: &str) -> Result<(), Diagnostic> {
    let failed = |failure: Diagnostic| Diagnostic::error(place, format!("{what} does not run: {}", failure.message));
    evaluation.run("<lesson>", program).map_err(failed)
}

/// Reads the format, without running anything.
fn read_format(text: &str, source: SourceId) -> Result<Lesson, Diagnostic> {
    let mut title: Option<String> = None;
    let mut setup: Option<String> = None;
    let mut drafts: Vec<StepDraft> = Vec::new();
    let mut block: Option<Block> = None;
    let mut in_comment = false;
    let mut offset = 0;
    let mut last_refused = false;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let line = line.trim_end_matches(['\n', '\r']);
        let span = Span::new(source, start, start + line.len());
        if let Some(open) = block.as_mut() {
            if line.trim_start().starts_with("```") {
                let Block { kind, opened, text } = block.take().expect("a block is open");
                last_refused = kind == BlockKind::Fails;
                place_block(kind, opened, text, &mut setup, &mut drafts)?;
            } else {
                open.text.push_str(line);
                open.text.push('\n');
            }
            continue;
        }
        if in_comment || line.trim_start().starts_with("<!--") {
            in_comment = !line.contains("-->");
            continue;
        }
        let trimmed = line.trim();
        if let Some(fence) = trimmed.strip_prefix("```") {
            let name = fence.strip_prefix("ray").map(str::trim);
            let Some(&(_, kind)) = name.and_then(|name| BLOCK_KINDS.iter().find(|(known, _)| *known == name)) else {
                let kinds: Vec<String> = BLOCK_KINDS.iter().map(|(name, _)| format!("```ray {name}")).collect();
                let message = format!("a lesson's blocks are {}", kinds.join(", "));
                return Err(Diagnostic::error(span, message));
            };
            block = Some(Block { kind, opened: span, text: String::new() });
            continue;
        }
        let refused_before = std::mem::take(&mut last_refused);
        if let Some(heading) = trimmed.strip_prefix("# ") {
            if title.is_some() {
                return Err(Diagnostic::error(span, "a lesson has one title (`# ...`); steps start with `## `"));
            }
            title = Some(heading.trim().to_string());
            continue;
        }
        if title.is_none() && !trimmed.is_empty() {
            return Err(Diagnostic::error(span, "a lesson starts with its title: `# what it teaches`"));
        }
        if trimmed.starts_with("## ") {
            drafts.push(StepDraft {
                heading: span,
                task: Vec::new(),
                example: None,
                hint: Vec::new(),
                checks: Vec::new(),
                passes: Vec::new(),
                fails: Vec::new(),
                in_hint: false,
            });
            continue;
        }
        let Some(draft) = drafts.last_mut() else {
            // Before the first step: the lesson's introduction, not shown in the session.
            continue;
        };
        if trimmed.is_empty() {
            draft.in_hint = false;
        } else if let Some(hint) = trimmed.strip_prefix("Hint:") {
            draft.hint.push(hint.trim().to_string());
            draft.in_hint = true;
        } else if let Some(check) = trimmed.strip_prefix("Check:") {
            let at = start + (line.len() - line.trim_start().len()) + "Check:".len();
            let check_span = Span::new(source, at, start + line.trim_end().len());
            draft.checks.push(parse(check).map_err(|problem| Diagnostic::error(check_span, problem))?);
            draft.in_hint = false;
        } else if let Some(says) = trimmed.strip_prefix("Says:") {
            let refused = draft.fails.last_mut().filter(|_| refused_before);
            let Some(refused) = refused else {
                return Err(Diagnostic::error(span, "`Says:` follows a ```ray fails block"));
            };
            refused.says = Some(says.trim().to_string());
        } else if draft.in_hint {
            draft.hint.push(trimmed.to_string());
        } else {
            draft.task.push(trimmed.to_string());
        }
    }
    if let Some(open) = block {
        return Err(Diagnostic::error(open.opened, "this block is never closed with ```"));
    }
    let end = Span::new(source, text.len(), text.len());
    let title = title.ok_or_else(|| Diagnostic::error(end, "a lesson starts with its title: `# what it teaches`"))?;
    if drafts.is_empty() {
        return Err(Diagnostic::error(end, "a lesson has steps: a `## ` heading for each"));
    }
    let steps = drafts.into_iter().map(finish_step).collect::<Result<_, _>>()?;
    Ok(Lesson { title, setup: setup.unwrap_or_default(), steps })
}

/// Puts a block that just closed where it belongs.
fn place_block(
    kind: BlockKind,
    opened: Span,
    text: String,
    setup: &mut Option<String>,
    drafts: &mut [StepDraft],
) -> Result<(), Diagnostic> {
    let text = text.trim_end().to_string();
    let Some(draft) = drafts.last_mut() else {
        if kind != BlockKind::Setup {
            return Err(Diagnostic::error(opened, "this block belongs in a step: put a `## ` heading before it"));
        }
        if setup.replace(text).is_some() {
            return Err(Diagnostic::error(opened, "a lesson has one setup block"));
        }
        return Ok(());
    };
    match kind {
        BlockKind::Setup => {
            return Err(Diagnostic::error(opened, "the setup block comes before the first step"));
        }
        BlockKind::Example { shown } => {
            if draft.example.replace((text, shown, opened)).is_some() {
                return Err(Diagnostic::error(opened, "a step has one example"));
            }
        }
        BlockKind::Passes => draft.passes.push((text, opened)),
        BlockKind::Fails => draft.fails.push(Refused { program: text, place: opened, says: None }),
    }
    draft.in_hint = false;
    Ok(())
}

fn finish_step(draft: StepDraft) -> Result<Step, Diagnostic> {
    let Some((example, example_up_front, example_at)) = draft.example else {
        return Err(Diagnostic::error(draft.heading, "this step has no ```ray example block"));
    };
    if draft.checks.is_empty() {
        return Err(Diagnostic::error(draft.heading, "this step has no `Check:` line"));
    }
    if draft.task.is_empty() {
        return Err(Diagnostic::error(draft.heading, "this step says no task: write it under the heading"));
    }
    Ok(Step {
        task: draft.task.join(" "),
        example,
        example_up_front,
        example_at,
        hint: draft.hint.join(" "),
        checks: draft.checks,
        passes: draft.passes,
        fails: draft.fails,
    })
}
