//! `:help`: a short explanation with an example for every keyword of the
//! language and every command of the session, written for learners.
//!
//! The pages are plain text files under `help_pages/`, shown as written by
//! every front-end. This module holds the language's pages and looks pages
//! up; the commands' pages are in their descriptions (`commands`), which
//! hand the whole list to the functions here.

use crate::lang::suggest::closest;
use crate::lang::words::{self, Kind};

/// The help page in `help_pages/PATH.txt`, as a `&'static str` without
/// the file's last newline.
macro_rules! help_page {
    ($path:literal) => {
        include_str!(concat!("help_pages/", $path, ".txt")).trim_ascii_end()
    };
}
pub(crate) use help_page;

/// One help page.
#[derive(Debug, Clone, Copy)]
pub struct Topic {
    /// The name `:help NAME` finds it by.
    pub name: &'static str,
    /// Other names that lead to the same page (`kd` leads to `texture`). A
    /// command's other names that start with `:` are also typed as the
    /// command (`:q` for `:quit`); the others are only looked up by `:help`.
    pub aliases: &'static [&'static str],
    /// A one-line summary for the overview.
    pub summary: &'static str,
    /// Where the overview lists it.
    pub group: Group,
    /// The page: what it is, then an example.
    pub text: &'static str,
}

/// The groups of the overview.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// The lessons.
    Learning,
    /// The camera, the ambient light and the lights.
    SceneSetUp,
    /// The shapes and their textures.
    Shapes,
    /// Transformations and groups.
    MovingShapes,
    /// Putting, naming, procedures and conditions.
    BuildingTheScene,
    /// Arithmetic, time, functions, comments and printing.
    Numbers,
    /// Rendering, saving and animating, and their settings.
    Pictures,
    /// Loading, watching and writing files.
    Files,
    /// What the session holds.
    LookingInside,
    /// Help, undo, reset, limits and leaving.
    TheSession,
}

impl Group {
    /// Every group, in the order a learner meets them.
    const IN_ORDER: [Group; 10] = [
        Group::Learning,
        Group::SceneSetUp,
        Group::Shapes,
        Group::MovingShapes,
        Group::BuildingTheScene,
        Group::Numbers,
        Group::Pictures,
        Group::Files,
        Group::LookingInside,
        Group::TheSession,
    ];

    /// Its heading in the overview.
    fn title(self) -> &'static str {
        match self {
            Group::Learning => "Learning",
            Group::SceneSetUp => "Scene set-up",
            Group::Shapes => "Shapes",
            Group::MovingShapes => "Moving shapes",
            Group::BuildingTheScene => "Building the scene",
            Group::Numbers => "Numbers",
            Group::Pictures => "Pictures",
            Group::Files => "Files",
            Group::LookingInside => "Looking inside",
            Group::TheSession => "The session",
        }
    }
}

/// What `:help` alone prints before the list of pages.
const OVERVIEW: &str = include_str!("help_pages/overview.txt").trim_ascii_end();

/// The pages about the language, in the order the overview lists them.
pub const LANGUAGE: &[Topic] = &[
    Topic {
        name: "camera",
        aliases: &[],
        summary: "where the eye is and how wide it sees",
        group: Group::SceneSetUp,
        text: help_page!("language/camera"),
    },
    Topic {
        name: "ambient",
        aliases: &[],
        summary: "light that reaches every surface, even in shadow",
        group: Group::SceneSetUp,
        text: help_page!("language/ambient"),
    },
    Topic {
        name: "light",
        aliases: &[],
        summary: "a far away light shining from one direction",
        group: Group::SceneSetUp,
        text: help_page!("language/light"),
    },
    Topic {
        name: "sphere",
        aliases: &[],
        summary: "a ball: center and radius",
        group: Group::Shapes,
        text: help_page!("language/sphere"),
    },
    Topic {
        name: "plane",
        aliases: &[],
        summary: "a flat floor, wall or ceiling that goes on forever",
        group: Group::Shapes,
        text: help_page!("language/plane"),
    },
    Topic {
        name: "box",
        aliases: &[],
        summary: "a box: center and sizes along x, y and z",
        group: Group::Shapes,
        text: help_page!("language/box"),
    },
    Topic {
        name: "texture",
        aliases: &[],
        summary: "how a surface looks: kd ks phong color",
        group: Group::Shapes,
        text: help_page!("language/texture"),
    },
    Topic {
        name: "translate",
        aliases: &[],
        summary: "move an object",
        group: Group::MovingShapes,
        text: help_page!("language/translate"),
    },
    Topic {
        name: "rotate",
        aliases: &[],
        summary: "turn an object about the origin",
        group: Group::MovingShapes,
        text: help_page!("language/rotate"),
    },
    Topic {
        name: "scale",
        aliases: &[],
        summary: "make an object bigger or smaller",
        group: Group::MovingShapes,
        text: help_page!("language/scale"),
    },
    Topic {
        name: "group",
        aliases: &[],
        summary: "several objects treated as one",
        group: Group::MovingShapes,
        text: help_page!("language/group"),
    },
    Topic {
        name: "by",
        aliases: &[],
        summary: "how much translate, rotate and scale change an object",
        group: Group::MovingShapes,
        text: help_page!("language/by"),
    },
    Topic {
        name: "rotation",
        aliases: &[],
        summary: "three angles: about x, then y, then z",
        group: Group::MovingShapes,
        text: help_page!("language/rotation"),
    },
    Topic {
        name: "put",
        aliases: &[],
        summary: "add an object to the scene",
        group: Group::BuildingTheScene,
        text: help_page!("language/put"),
    },
    Topic {
        name: "object",
        aliases: &[],
        summary: "give an object a name (without putting it)",
        group: Group::BuildingTheScene,
        text: help_page!("language/object"),
    },
    Topic {
        name: "let",
        aliases: &[],
        summary: "give a number a name",
        group: Group::BuildingTheScene,
        text: help_page!("language/let"),
    },
    Topic {
        name: "proc",
        aliases: &[],
        summary: "a procedure: instructions to run again with other numbers",
        group: Group::BuildingTheScene,
        text: help_page!("language/proc"),
    },
    Topic {
        name: "if",
        aliases: &[],
        summary: "do something only when a condition holds",
        group: Group::BuildingTheScene,
        text: help_page!("language/if"),
    },
    Topic {
        name: "conditions",
        aliases: &["=", "<", "&", "|", "!", "condition"],
        summary: "comparisons and & | ! in an if",
        group: Group::BuildingTheScene,
        text: help_page!("language/conditions"),
    },
    Topic {
        name: "end",
        aliases: &[],
        summary: "closes what camera, light, shapes, transformations, group, proc and if open",
        group: Group::BuildingTheScene,
        text: help_page!("language/end"),
    },
    Topic {
        name: "numbers",
        aliases: &["+", "-", "*", "/", "arithmetic", "expressions"],
        summary: "arithmetic: + - * / and parentheses",
        group: Group::Numbers,
        text: help_page!("language/numbers"),
    },
    Topic {
        name: "time",
        aliases: &[],
        summary: "the frame number of an animation",
        group: Group::Numbers,
        text: help_page!("language/time"),
    },
    Topic {
        name: "functions",
        aliases: &[],
        summary: "sin, cos and sqrt",
        group: Group::Numbers,
        text: help_page!("language/functions"),
    },
    Topic {
        name: "pi",
        aliases: &[],
        summary: "the number pi, half a turn in radians",
        group: Group::Numbers,
        text: help_page!("language/pi"),
    },
    Topic {
        name: "comments",
        aliases: &["#", "comment"],
        summary: "# starts a note to the end of the line",
        group: Group::Numbers,
        text: help_page!("language/comments"),
    },
    Topic {
        name: "print",
        aliases: &[],
        summary: "show values while the program runs",
        group: Group::Numbers,
        text: help_page!("language/print"),
    },
];

/// The page in `pages` for `name` (a page's name or one of its aliases, a
/// word of the language, or a word from elsewhere that means one), if any.
pub fn find(name: &str, pages: &[&'static Topic]) -> Option<&'static Topic> {
    let page = |wanted: &str| pages.iter().copied().find(|page| page.name == wanted || page.aliases.contains(&wanted));
    page(name).or_else(|| page(word_topic(name)?)).or_else(|| {
        // `:help :sphere` or `:help help`: try with and without the colon.
        match name.strip_prefix(':') {
            Some(bare) => page(bare),
            None => page(&format!(":{name}")),
        }
    })
}

/// The page the words table gives for `name`, or for the word of the
/// language that `name` means (`rayon` leads to the page of `radius`).
fn word_topic(name: &str) -> Option<&'static str> {
    let word = words::lookup(name)?;
    match word.kind {
        Kind::Elsewhere { means } => words::lookup(means).map(|meant| meant.topic),
        _ => Some(word.topic).filter(|topic| !topic.is_empty()),
    }
}

/// Every name `:help` knows in `pages`, for completion and suggestions: the
/// pages and their aliases, and the words of the language.
pub fn all_names<'a>(pages: &'a [&'static Topic]) -> impl Iterator<Item = &'static str> + 'a {
    let names = pages.iter().flat_map(|page| std::iter::once(page.name).chain(page.aliases.iter().copied()));
    names.chain(words::language().map(|word| word.text))
}

/// The known name closest to a misspelt one.
pub fn suggestion(name: &str, pages: &[&'static Topic]) -> Option<&'static str> {
    closest(name, all_names(pages))
}

/// The overview: how to start, then every page by group with its summary.
pub fn overview(pages: &[&'static Topic]) -> String {
    let mut text = String::from(OVERVIEW);
    for group in Group::IN_ORDER {
        text.push_str(&format!("\n  {}:\n", group.title()));
        for page in pages.iter().filter(|page| page.group == group) {
            text.push_str(&format!("    {:<12} {}\n", page.name, page.summary));
        }
    }
    text
}
