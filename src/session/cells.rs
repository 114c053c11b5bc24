//! A session driven by cells of text: a notebook's kernel, a web page.
//! Each cell is run as a piped script is (items and `:` commands mixed,
//! accumulating into one session, stopping at the first error), its
//! diagnostics naming it (`<cell 3>:2:5`); a cell stopped by an interrupt
//! leaves the session as it was before the cell. What a cell shows comes
//! back as [`Output`](super::Output) values to the front-end that runs it.
//! Beside running, the questions an editor of cells asks: whether a cell
//! is complete, what may be typed at a place, what the word at a place is.

use std::ops::Range;
use std::path::Path;

use image::RgbImage;

use crate::ide::commands::is_command;
use crate::ide::completion::{self, Candidate};
use crate::ide::hover::{Pages, Subject, hover};
use crate::ide::offsets::floor_char_boundary;
use crate::ide::scanner::open_constructs;
use crate::lang::{Entry, EntryState, SourceId, SourceMap, parse_items};
use crate::pipeline::{PictureError, render_picture};
use crate::render::{OutOfMemory, Region, RenderControl};

use super::commands;
use super::file_commands::load_text_reporting;
use super::lesson_commands::check_scene;
use super::options::{SessionOptions, new_session};
use super::outputs::{Collected, FrontEnd, Output};
use super::render_steps::notes_before_rendering;
use super::rendering::{Size, render_options};
use super::report::show_printed;
use super::script::{Named, TextRan, run_text};
use super::shell::Shell;
use crate::process::cancel::CancelSwitch;

/// How a cell ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellEnd {
    /// Every input and command in it succeeded.
    Done,
    /// One failed (its diagnostic was shown); the cell stopped there, and
    /// what ran before it in the cell stays.
    Failed,
    /// The interrupt stopped it; the session is as it was before the cell.
    Interrupted,
    /// `:quit` ended it.
    Quit,
}

/// Whether a cell's text is ready to run, as the parser reads it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Completeness {
    /// It is: every input in it is finished.
    Complete,
    /// Its last input waits for more lines (an `end`): the next line's
    /// indent, one level per construct left open.
    Incomplete {
        /// The spaces to start the next line with.
        indent: String,
    },
    /// No line can mend it: running it shows the error.
    Invalid,
}

/// The completions of the word at a place in a cell.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Completions {
    /// Where the word being typed starts, in bytes from the cell's start.
    pub start: usize,
    /// Where it ends (the place asked about).
    pub end: usize,
    /// What may replace it, sorted.
    pub candidates: Vec<String>,
}

/// Spaces per open construct in an indent.
const INDENT: &str = "  ";

/// A session whose inputs come in cells.
#[derive(Debug)]
pub struct CellSession {
    shell: Shell,
    /// The switch that stops a cell, if there is one.
    cancel: Option<&'static CancelSwitch>,
}

impl CellSession {
    /// A session set up with `options`' settings, limits and allowed
    /// warnings (its file and lesson are not started: run `:load` or
    /// `:lesson` in a cell).
    pub fn new(options: &SessionOptions) -> CellSession {
        CellSession { shell: Shell::new(new_session(options, None)), cancel: None }
    }

    /// The same session, its cells stopped when `switch` is raised (the
    /// front-end running them gives the same switch to renders and reads,
    /// from [`FrontEnd::cancel`]).
    pub fn with_cancel(self, switch: &'static CancelSwitch) -> CellSession {
        let mut shell = self.shell;
        shell.session = shell.session.interruptible(switch.flag());
        CellSession { shell, cancel: Some(switch) }
    }

    /// Runs the text of a cell, its diagnostics naming it `name`
    /// (`<cell 3>`), showing what it does on `front`.
    pub fn run(&mut self, name: &str, text: &str, front: &mut dyn FrontEnd) -> CellEnd {
        let before = self.shell.session.checkpoint();
        match run_text(&mut self.shell, front, self.cancel, Named { name, noun: "cell" }, text) {
            TextRan::Done => CellEnd::Done,
            TextRan::Failed => CellEnd::Failed,
            TextRan::Quit => CellEnd::Quit,
            TextRan::Interrupted => {
                if let Err(error) = self.shell.session.restore(before) {
                    front.diagnostic(&error, self.shell.session.sources());
                }
                CellEnd::Interrupted
            }
        }
    }

    /// Runs `text` as the whole of the learner's scene, in place of the
    /// session's program (as `:reset` then the cell would, the inputs it
    /// replaces forgotten, not kept for `:undo`), and checks the
    /// lesson followed once, after it, as the terminal checks an input
    /// typed at its prompt: for a front-end whose editor holds the whole
    /// scene and runs it again at each pause in typing (the browser page's
    /// lessons). Checked after each of its inputs, as a cell is, every one
    /// that comes before the step's would count as a wrong try. A scene
    /// that fails or is interrupted is not checked: the terminal checks
    /// only what it accepted.
    pub fn run_scene(&mut self, name: &str, text: &str, front: &mut dyn FrontEnd) -> CellEnd {
        self.shell.session.clear();
        self.shell.tutor.checks_held = true;
        let end = self.run(name, text, front);
        self.shell.tutor.checks_held = false;
        if end == CellEnd::Done {
            check_scene(&mut self.shell, front);
        }
        end
    }

    /// Runs `text` as `:load` runs the file at `path` (all of it one
    /// input, its items in any order), without reading the file: for a
    /// front-end that holds the file's text itself (an editor in a page).
    pub fn load_text(&mut self, path: &Path, text: &str, front: &mut dyn FrontEnd) -> CellEnd {
        let loaded = load_text_reporting(&mut self.shell, path, text, front);
        show_printed(&self.shell.session, front);
        if loaded.is_ok() { CellEnd::Done } else { CellEnd::Failed }
    }

    /// Rows `rows` of the picture `:render` makes of the session's scene
    /// at the session's size and settings, the same bytes, with the notes
    /// `:render` gives before it (the defaults the scene falls back on,
    /// the warnings about it) shown on `front`: for a front-end that
    /// renders the bands of one picture in sessions of its own, one per
    /// worker, each loaded with the same text and settings (the browser
    /// page). Fails, as `:render` does, when the memory the render needs
    /// cannot be had.
    ///
    /// A band is a [`Region`] of the picture on the pipeline's one road
    /// ([`render_picture`]): its bytes are the whole picture's there, at
    /// any number of samples and with adaptive anti-aliasing too.
    pub fn render_rows(&mut self, rows: Range<u32>, front: &mut dyn FrontEnd) -> Result<RgbImage, OutOfMemory> {
        let session = &self.shell.session;
        let settings = session.settings();
        let size = Size { width: settings.width, height: settings.height };
        notes_before_rendering(session, &mut self.shell.warned, front, size, false);
        let options = render_options(size, settings);
        match render_picture(session.scene(), &options, Region::rows(&options, rows), &RenderControl::default()) {
            Ok(rendered) => Ok(rendered.image),
            Err(PictureError::OutOfMemory(error)) => Err(error),
            Err(PictureError::Cancelled) => unreachable!("a render without a cancel flag runs to its end"),
        }
    }

    /// Makes `image` the session's last picture, as if `:render` had
    /// shown it: for a front-end that put it together from bands rendered
    /// in sessions of its own ([`CellSession::render_rows`]), so that
    /// `:pick` explains its pixels without rendering it again (and notes,
    /// as it does for any picture, a pixel the scene no longer gives).
    pub fn adopt_picture(&mut self, image: RgbImage) {
        self.shell.last_picture = Some(image);
    }

    /// The texts the session's diagnostics point into.
    pub fn sources(&self) -> &SourceMap {
        self.shell.session.sources()
    }

    /// Whether `text` is ready to run (every input in it finished and
    /// parsed), or how the next line starts.
    pub fn completeness(text: &str) -> Completeness {
        let mut pending: Option<Entry> = None;
        for line in text.lines() {
            let entry = match pending.take() {
                Some(mut entry) => {
                    entry.add_line(line);
                    entry
                }
                None if is_command(line) => continue,
                None => Entry::read(line.to_string()),
            };
            match entry.state() {
                EntryState::Unfinished => pending = Some(entry),
                EntryState::Broken | EntryState::BrokenBeforeLastLine => return Completeness::Invalid,
                EntryState::Complete if parse_items(SourceId::default(), entry.text()).is_err() => {
                    return Completeness::Invalid;
                }
                EntryState::Complete => {}
            }
        }
        match pending {
            Some(entry) => Completeness::Incomplete { indent: INDENT.repeat(open_constructs(entry.text()).len()) },
            None => Completeness::Complete,
        }
    }

    /// What may replace the word that ends at byte `cursor` of the cell
    /// `text`: commands and help topics on a command's line, elsewhere the
    /// words the grammar lets come there and the names the session defines.
    pub fn complete(&self, text: &str, cursor: usize) -> Completions {
        let cursor = floor_char_boundary(text, cursor);
        let line_start = text[..cursor].rfind('\n').map_or(0, |at| at + 1);
        let before = &text[line_start..cursor];
        let (start, candidates) = if is_command(before) {
            completion::complete_command(before).unwrap_or((before.len(), Vec::new()))
        } else {
            let inside = matches!(CellSession::completeness(&text[..line_start]), Completeness::Incomplete { .. });
            completion::complete(before, inside, &self.shell.session.vocabulary())
        };
        let candidates = candidates.into_iter().map(|Candidate { replacement, .. }| replacement).collect();
        Completions { start: line_start + start, end: cursor, candidates }
    }

    /// What the word at byte `cursor` of `text` is, as the session says it
    /// ([`hover`]): the definition `:show` gives of a name the session
    /// defines (a procedure's source, a number's value), else the page
    /// `:help WORD` gives. `None` for anything else.
    pub fn inspect(&mut self, text: &str, cursor: usize) -> Option<String> {
        let hovered = hover(text, cursor, &self.shell.session.vocabulary(), Pages::AnyTopic)?;
        let name = match hovered.subject {
            Subject::Page(page) => return Some(page.text.to_string()),
            Subject::Name => &text[hovered.range],
        };
        let mut said = Collected::default();
        commands::execute(&mut self.shell, &format!(":show {name}"), &mut said).ok()?;
        let texts: Vec<String> = said
            .outputs
            .into_iter()
            .filter_map(|output| match output {
                Output::Text { text, .. } => Some(text),
                _ => None,
            })
            .collect();
        (!texts.is_empty()).then(|| texts.join("\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::{LessonVerdict, TextRole};

    fn session() -> CellSession {
        CellSession::new(&SessionOptions::default())
    }

    fn messages(front: &Collected) -> Vec<&str> {
        let texts = front.outputs.iter().filter_map(|output| match output {
            Output::Text { role: TextRole::Message, text } => Some(text.as_str()),
            _ => None,
        });
        texts.collect()
    }

    #[test]
    fn a_cell_mixes_items_and_commands_and_stops_at_its_first_error() {
        let mut cells = session();
        let mut front = Collected::default();
        let cell = "let r = 2\n:size 40 30\nput sphere center 0, 0, 0 radius r kd 1 ks 0 phong 1 color 9, 9, 9 end\nput box end\nlet after = 1";
        assert_eq!(cells.run("<cell 1>", cell, &mut front), CellEnd::Failed);
        assert_eq!(cells.shell.session.global_number("r"), Some(2.0));
        assert_eq!(cells.shell.session.global_number("after"), None, "the cell stopped at `put box end`");
        assert_eq!(cells.shell.session.settings().width, 40);
        let Some(Output::Diagnostic(diagnostic)) = front.outputs.last() else { panic!("{:?}", front.outputs) };
        let place = diagnostic.render(cells.sources(), false);
        assert!(place.contains("<cell 1>:4:"), "{place}");
    }

    #[test]
    fn a_word_typed_at_other_prompts_is_an_error_that_does_not_stop_the_cell() {
        let mut cells = session();
        let mut front = Collected::default();
        assert_eq!(cells.run("<cell 1>", "exit\nlet after = 1", &mut front), CellEnd::Failed);
        assert_eq!(cells.shell.session.global_number("after"), Some(1.0));
        let error = Output::Text {
            role: TextRole::Error,
            text: "line 1 of the cell: `exit` alone does nothing here; did you mean `:quit`?".to_string(),
        };
        assert!(front.outputs.contains(&error), "{:?}", front.outputs);
    }

    #[test]
    fn definitions_accumulate_across_cells() {
        let mut cells = session();
        let mut front = Collected::default();
        assert_eq!(
            cells.run(
                "<cell 1>",
                "proc ball(r)\n  put sphere center 0, 0, 0 radius r kd 1 ks 0 phong 1 color 9, 9, 9 end\nend",
                &mut front
            ),
            CellEnd::Done
        );
        assert_eq!(cells.run("<cell 2>", "ball(3)", &mut front), CellEnd::Done);
        assert_eq!(messages(&front).last(), Some(&"put 1 sphere (1 object in the scene)"));
    }

    /// The bands a front-end renders in sessions of its own, put together,
    /// are the picture `:render` shows, with the notes it gives first.
    #[test]
    fn bands_of_rows_are_the_picture_render_shows_with_its_notes() {
        let scene = ":size 40 30\nput sphere center 0, 0, 0 radius 2 kd 1 ks 0 phong 1 color 9, 9, 9 end";
        let notes = |front: &Collected| -> Vec<String> {
            let texts = front.outputs.iter().filter_map(|output| match output {
                Output::Text { role: TextRole::Note, text } => Some(text.clone()),
                _ => None,
            });
            texts.collect()
        };
        let mut whole = session();
        let mut rendered = Collected::default();
        assert_eq!(whole.run("<cell 1>", &format!("{scene}\n:render"), &mut rendered), CellEnd::Done);
        let Some(Output::Picture(picture)) =
            rendered.outputs.iter().find(|output| matches!(output, Output::Picture(_)))
        else {
            panic!("{:?}", rendered.outputs)
        };
        let mut bands = Vec::new();
        let mut band_notes = Vec::new();
        for rows in [0..1, 1..17, 17..30] {
            let mut cells = session();
            let mut front = Collected::default();
            assert_eq!(cells.run("<cell 1>", scene, &mut front), CellEnd::Done);
            let mut shown = Collected::default();
            bands.extend_from_slice(&cells.render_rows(rows, &mut shown).expect("memory"));
            band_notes = notes(&shown);
        }
        assert!(bands == *picture.image.as_raw());
        assert_eq!(band_notes, notes(&rendered));
        assert!(band_notes.iter().any(|note| note.contains("no light yet")), "{band_notes:?}");
    }

    /// A whole scene run again in place of the last is one try of the
    /// lesson's step, however many inputs come before the step's, and it
    /// offers no `:undo`; the step done moves the lesson on.
    #[test]
    fn a_whole_scene_is_checked_once_against_the_lessons_step() {
        let folder = tempfile::tempdir().expect("a temporary folder");
        let path = folder.path().join("first-sphere.md");
        std::fs::write(&path, include_str!("../../lessons/1-first-sphere.md")).expect("written");
        let mut cells = session();
        assert_eq!(
            cells.run("<cell 1>", &format!(":lesson {}", path.display()), &mut Collected::default()),
            CellEnd::Done
        );
        let verdicts = |front: &Collected| -> Vec<LessonVerdict> {
            let verdicts = front.outputs.iter().filter_map(|output| match output {
                Output::LessonVerdict(verdict) => Some(verdict.clone()),
                _ => None,
            });
            verdicts.collect()
        };
        let wrong_tries = |cells: &CellSession| cells.shell.tutor.following.as_ref().map(|f| (f.step, f.wrong_tries));
        let mut front = Collected::default();
        let short = "let a = 1\nlet b = 2\ncamera distance 8 angle 0.8 end";
        assert_eq!(cells.run_scene("<scene 1>", short, &mut front), CellEnd::Done);
        let [LessonVerdict::NotYet { missing, undo: false, .. }] = &verdicts(&front)[..] else {
            panic!("{:?}", front.outputs)
        };
        assert!(missing.contains("distance 8"), "{missing}");
        assert_eq!(wrong_tries(&cells), Some((0, 1)));
        let mut front = Collected::default();
        assert_eq!(cells.run_scene("<scene 2>", "let d = 5\nput box", &mut front), CellEnd::Failed);
        assert!(verdicts(&front).is_empty(), "a scene with an error is not a try");
        assert_eq!(wrong_tries(&cells), Some((0, 1)));
        let mut front = Collected::default();
        let camera = "let d = 5\ncamera distance 2 * d angle 0.8 end";
        assert_eq!(cells.run_scene("<scene 3>", camera, &mut front), CellEnd::Done);
        assert!(
            matches!(verdicts(&front)[..], [LessonVerdict::Done { number: 1, already: false }]),
            "{:?}",
            front.outputs
        );
        assert_eq!(wrong_tries(&cells), Some((1, 0)));
        assert_eq!(cells.shell.session.global_number("a"), None, "the scene replaced the last one");
        // The scenes it replaced are forgotten: `:undo` reaches back to the start of the last.
        let mut front = Collected::default();
        assert_eq!(cells.run("<cell 2>", ":undo\n:undo\n:undo", &mut front), CellEnd::Done);
        let said = messages(&front);
        assert_eq!(said.iter().filter(|text| text.starts_with("took back")).count(), 2, "{said:?}");
        assert!(said.contains(&"nothing to undo"), "{said:?}");
        assert_eq!(cells.shell.session.global_number("d"), None);
    }

    #[test]
    fn a_cell_is_complete_incomplete_with_its_indent_or_invalid() {
        assert_eq!(CellSession::completeness("let a = 1\n:render"), Completeness::Complete);
        assert_eq!(
            CellSession::completeness("proc p()\n  if 1 < 2 then"),
            Completeness::Incomplete { indent: "    ".to_string() }
        );
        assert_eq!(CellSession::completeness("put sphere radius 1 radius end )"), Completeness::Invalid);
        assert_eq!(CellSession::completeness("let = 3"), Completeness::Invalid);
        assert_eq!(CellSession::completeness(""), Completeness::Complete);
    }

    #[test]
    fn completion_follows_the_grammar_and_the_session() {
        let mut cells = session();
        cells.run(
            "<cell 1>",
            "let radius_big = 3\nobject ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end",
            &mut Collected::default(),
        );
        let text = "put sph";
        let completions = cells.complete(text, text.len());
        assert_eq!((completions.start, completions.candidates), (4, vec!["sphere ".to_string()]));
        let text = "let a = 1\nput b";
        assert_eq!(cells.complete(text, text.len()).candidates, ["ball", "box "]);
        let text = ":ren";
        assert_eq!(cells.complete(text, text.len()).candidates, [":render "]);
    }

    #[test]
    fn inspecting_a_word_gives_its_definition_or_its_help_page() {
        let mut cells = session();
        cells.run(
            "<cell 1>",
            "let size = 4\nproc ball(r)\n  put sphere center 0, 0, 0 radius r kd 1 ks 0 phong 1 color 9, 9, 9 end\nend",
            &mut Collected::default(),
        );
        let ball = cells.inspect("ball(2)", 1).expect("a procedure");
        assert!(ball.contains("proc ball(r)"), "{ball}");
        assert!(cells.inspect("size", 2).expect("a number").contains("size = 4 now"));
        assert!(cells.inspect("put sphere end", 6).expect("a word").contains("sphere"));
        assert!(cells.inspect(":render", 3).expect("a command").contains(":render"));
        assert_eq!(cells.inspect("   ", 1), None);
    }

    #[test]
    fn an_interrupted_cell_leaves_the_session_as_before_it() {
        let switch: &'static CancelSwitch = Box::leak(Box::default());
        let mut cells = session().with_cancel(switch);
        let mut front = Collected::default();
        cells.run("<cell 1>", "let a = 1", &mut front);
        // As a kernel does: armed for the whole cell, interrupted from another thread.
        let armed = switch.arm();
        let interrupter = std::thread::spawn(|| {
            std::thread::sleep(std::time::Duration::from_millis(100));
            switch.cancel_if_armed(crate::process::interruption::Signal::Interrupt)
        });
        let runaway =
            "let b = 2\n:size 10 10\nproc f(n)\n  if n > 0 then\n    f(n - 1)\n    f(n - 1)\n  end\nend\nf(60)";
        let ended = cells.run("<cell 2>", runaway, &mut front);
        assert!(interrupter.join().expect("it raises the flag"));
        drop(armed);
        assert_eq!(ended, CellEnd::Interrupted, "{:?}", front.outputs);
        assert_eq!(cells.shell.session.global_number("a"), Some(1.0));
        assert_eq!(cells.shell.session.global_number("b"), None);
        assert_eq!(cells.shell.session.settings().width, SessionOptions::default().settings.width);
        assert_eq!(cells.run("<cell 3>", "let c = a + 1", &mut front), CellEnd::Done, "the session goes on");
    }
}
