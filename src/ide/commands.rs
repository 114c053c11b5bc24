//! The commands of the session (`:render`, `:time`, `:save`, ...) as
//! editors and help know them: each described once, with its name and
//! other names, summary, help page, usage and the files its arguments
//! name. The session's registry (`crate::session`) gives each of them the
//! function that runs it, found by name; completion, highlighting, help
//! and hovers read the descriptions here.

use super::help::{self, Group, Topic, help_page};

/// A command of the session, as described to its users.
#[derive(Debug)]
pub struct Command {
    /// Its name (colon included), other names, summary, group and help page.
    pub topic: Topic,
    /// How to call it.
    pub usage: &'static str,
    /// What files its arguments name.
    pub files: Files,
}

/// What files a command's arguments name, for file name completion and for
/// a script's check that it wrote a picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Files {
    /// None.
    None,
    /// A program file it reads.
    Reads,
    /// A program file it writes.
    WritesScene,
    /// An image or animation file it writes.
    WritesPictures,
}

/// Every command, in the order the help overview lists them.
pub const COMMANDS: &[Command] = &[
    Command {
        topic: Topic {
            name: ":lesson",
            aliases: &["lessons", "learn", "tutorial"],
            summary: "guided lessons, from a first sphere to an animation",
            group: Group::Learning,
            text: help_page!("commands/lesson"),
        },
        usage: ":lesson [NUMBER|FILE|stop]",
        files: Files::Reads,
    },
    Command {
        topic: Topic {
            name: ":goal",
            aliases: &[],
            summary: "show the goal of the lesson's step, or write it to a file",
            group: Group::Learning,
            text: help_page!("commands/goal"),
        },
        usage: ":goal [FILE.png]",
        files: Files::WritesPictures,
    },
    Command {
        topic: Topic {
            name: ":render",
            aliases: &[],
            summary: "draw the scene in the terminal",
            group: Group::Pictures,
            text: help_page!("commands/render"),
        },
        usage: ":render [WIDTH HEIGHT]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":save",
            aliases: &[],
            summary: "write the scene to an image file",
            group: Group::Pictures,
            text: help_page!("commands/save"),
        },
        usage: ":save FILE [WIDTH HEIGHT]",
        files: Files::WritesPictures,
    },
    Command {
        topic: Topic {
            name: ":anim",
            aliases: &["animation"],
            summary: "write an animation, with time = 1, 2, ... N",
            group: Group::Pictures,
            text: help_page!("commands/anim"),
        },
        usage: ":anim FRAMES FILE [--fps F] [--loop N|forever] [--time-start A] [--time-step S] [--apng]",
        files: Files::WritesPictures,
    },
    Command {
        topic: Topic {
            name: ":play",
            aliases: &[],
            summary: "play the animation in the terminal, until a key",
            group: Group::Pictures,
            text: help_page!("commands/play"),
        },
        usage: ":play [FRAMES [FPS]]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":time",
            aliases: &[],
            summary: "set the value of time",
            group: Group::Pictures,
            text: help_page!("commands/time"),
        },
        usage: ":time [NUMBER]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":size",
            aliases: &[],
            summary: "set the image size for :save and :anim",
            group: Group::Pictures,
            text: help_page!("commands/size"),
        },
        usage: ":size [WIDTH HEIGHT]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":depth",
            aliases: &[],
            summary: "set how many mirror reflections are followed",
            group: Group::Pictures,
            text: help_page!("commands/depth"),
        },
        usage: ":depth [REFLECTIONS]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":samples",
            aliases: &[],
            summary: "set how many rays each pixel averages (smoother edges)",
            group: Group::Pictures,
            text: help_page!("commands/samples"),
        },
        usage: ":samples [RAYS PER PIXEL]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":preview",
            aliases: &[],
            summary: "choose how big the picture of `:render` is in the terminal",
            group: Group::Pictures,
            text: help_page!("commands/preview"),
        },
        usage: ":preview [fit|small|off]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":pick",
            aliases: &["why"],
            summary: "why a pixel of the last picture has its colour",
            group: Group::Pictures,
            text: help_page!("commands/pick"),
        },
        usage: ":pick X Y",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":load",
            aliases: &[],
            summary: "run a .ray file into the session",
            group: Group::Files,
            text: help_page!("commands/load"),
        },
        usage: ":load FILE",
        files: Files::Reads,
    },
    Command {
        topic: Topic {
            name: ":reload",
            aliases: &[],
            summary: "run the file of the last :load again, as it is now",
            group: Group::Files,
            text: help_page!("commands/reload"),
        },
        usage: ":reload",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":watch",
            aliases: &[],
            summary: "render a file again every time it is saved",
            group: Group::Files,
            text: help_page!("commands/watch"),
        },
        usage: ":watch FILE",
        files: Files::Reads,
    },
    Command {
        topic: Topic {
            name: ":write",
            aliases: &[],
            summary: "write what the session holds as a .ray file",
            group: Group::Files,
            text: help_page!("commands/write"),
        },
        usage: ":write FILE.ray",
        files: Files::WritesScene,
    },
    Command {
        topic: Topic {
            name: ":env",
            aliases: &[],
            summary: "list the names and procedures defined",
            group: Group::LookingInside,
            text: help_page!("commands/env"),
        },
        usage: ":env",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":scene",
            aliases: &[],
            summary: "show the camera, lights and what was put",
            group: Group::LookingInside,
            text: help_page!("commands/scene"),
        },
        usage: ":scene",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":show",
            aliases: &[],
            summary: "print how a procedure, object or number was defined",
            group: Group::LookingInside,
            text: help_page!("commands/show"),
        },
        usage: ":show NAME",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":list",
            aliases: &[],
            summary: "list the inputs the session holds, in order",
            group: Group::LookingInside,
            text: help_page!("commands/list"),
        },
        usage: ":list",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":history",
            aliases: &[],
            summary: "list the lines you typed (this session and earlier ones)",
            group: Group::LookingInside,
            text: help_page!("commands/history"),
        },
        usage: ":history [LINES]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":help",
            aliases: &[":h", ":?"],
            summary: "this help, or help on one word",
            group: Group::TheSession,
            text: help_page!("commands/help"),
        },
        usage: ":help [NAME]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":undo",
            aliases: &[],
            summary: "take back the last input that changed the session",
            group: Group::TheSession,
            text: help_page!("commands/undo"),
        },
        usage: ":undo",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":reset",
            aliases: &[],
            summary: "start again from an empty session",
            group: Group::TheSession,
            text: help_page!("commands/reset"),
        },
        usage: ":reset",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":limits",
            aliases: &["max-calls", "max-primitives"],
            summary: "raise the limits on recursion and on primitives",
            group: Group::TheSession,
            text: help_page!("commands/limits"),
        },
        usage: ":limits [calls N] [primitives N]",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":clear",
            aliases: &[":cls"],
            summary: "clear the terminal's screen (Ctrl-L does too)",
            group: Group::TheSession,
            text: help_page!("commands/clear"),
        },
        usage: ":clear",
        files: Files::None,
    },
    Command {
        topic: Topic {
            name: ":quit",
            aliases: &[":q", ":exit"],
            summary: "leave (Ctrl-D does too)",
            group: Group::TheSession,
            text: help_page!("commands/quit"),
        },
        usage: ":quit",
        files: Files::None,
    },
];

impl Command {
    /// The names it is typed by: its name, and its other names that start
    /// with `:` (the rest are only for `:help`).
    pub fn typed_names(&self) -> impl Iterator<Item = &'static str> {
        let aliases = self.topic.aliases.iter().copied().filter(|alias| alias.starts_with(':'));
        std::iter::once(self.topic.name).chain(aliases)
    }
}

/// The command typed as `name`.
pub fn find(name: &str) -> Option<&'static Command> {
    COMMANDS.iter().find(|command| command.typed_names().any(|typed| typed == name))
}

/// Every page `:help` knows: the language's, then the commands'.
pub fn help_pages() -> Vec<&'static Topic> {
    help::LANGUAGE.iter().chain(COMMANDS.iter().map(|command| &command.topic)).collect()
}

/// The words people type at prompts out of habit, without the colon, and
/// the command each means. Typed alone at the terminal a word runs its
/// command; alone on a line of a script or a cell it is answered with the
/// command to type. A bare name is never a whole input of the language, so
/// these words alone mean nothing else (`let clear = 2` stays a definition).
pub const BARE_WORDS: &[(&str, &str)] =
    &[("exit", ":quit"), ("quit", ":quit"), ("help", ":help"), ("clear", ":clear"), ("cls", ":clear")];

/// The command meant by `line` when it is one of the [`BARE_WORDS`] alone
/// (blanks around it allowed).
pub fn bare_word_command(line: &str) -> Option<&'static str> {
    let line = line.trim();
    BARE_WORDS.iter().find(|(word, _)| *word == line).map(|(_, command)| *command)
}

/// Whether `line` is a command rather than program text.
pub fn is_command(line: &str) -> bool {
    line.trim_start().starts_with(':')
}

/// Whether the command on `line` writes image files (`:save`, `:anim`).
pub fn writes_pictures(line: &str) -> bool {
    let command = line.split_whitespace().next().and_then(find);
    command.is_some_and(|command| command.files == Files::WritesPictures)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::words;

    #[test]
    fn names_and_other_names_of_commands_are_distinct() {
        let mut seen = std::collections::HashSet::new();
        for command in COMMANDS {
            for name in command.typed_names() {
                assert!(seen.insert(name), "`{name}` names two commands");
                assert_eq!(find(name).map(|found| found.topic.name), Some(command.topic.name));
            }
        }
        assert_eq!(find(":exit").map(|found| found.topic.name), Some(":quit"));
        assert!(writes_pictures(":save a.png") && !writes_pictures(":write a.ray") && !writes_pictures(":load a.ray"));
    }

    #[test]
    fn bare_words_mean_commands_alone_and_are_named_in_the_overview() {
        let overview = help::overview(&help_pages());
        for (word, command) in BARE_WORDS {
            assert!(find(command).is_some(), "`{word}` means `{command}`, which is no command");
            assert_eq!(bare_word_command(&format!("  {word} ")), Some(*command));
            assert!(overview.contains(&format!("`{word}`")), "the overview does not name `{word}`");
        }
        assert_eq!(bare_word_command("let clear = 2"), None);
        assert_eq!(bare_word_command("exit now"), None);
    }

    #[test]
    fn every_word_of_the_language_has_a_page_with_an_example() {
        let pages = help_pages();
        for word in words::language() {
            let topic = help::find(word.text, &pages).unwrap_or_else(|| panic!("no help for `{}`", word.text));
            assert!(topic.text.contains("Example"), "no example for `{}`", word.text);
        }
        for word in ["time", "conditions", "texture"] {
            assert!(help::find(word, &pages).is_some(), "no help for `{word}`");
        }
    }

    #[test]
    fn every_command_has_a_page_with_an_example() {
        for command in COMMANDS {
            assert!(command.topic.text.contains("Example"), "no example for `{}`", command.topic.name);
            assert!(
                command.topic.text.starts_with(command.topic.name),
                "`{}`'s page starts elsewhere",
                command.topic.name
            );
        }
    }

    #[test]
    fn every_page_is_in_the_overview() {
        let pages = help_pages();
        let overview = help::overview(&pages);
        for topic in &pages {
            assert!(
                overview.contains(&format!("    {:<12} ", topic.name)),
                "`{}` missing from the overview",
                topic.name
            );
        }
    }

    /// The program text of a page's example (its command lines left out).
    fn example_program(topic: &Topic) -> String {
        let example = topic.text.split_once("Example").map_or("", |(_, rest)| rest);
        let lines = example.lines().skip(1).filter(|line| !line.trim_start().starts_with(':'));
        lines.collect::<Vec<_>>().join("\n")
    }

    #[test]
    fn every_example_is_valid_syntax() {
        use crate::lang::{SourceId, parse_items};
        for topic in help_pages() {
            let program = example_program(topic);
            if let Err(error) = parse_items(SourceId::default(), &program) {
                panic!("the example of `{}` does not parse: {}\n{program}", topic.name, error.message);
            }
        }
    }

    #[test]
    fn names_are_found_with_or_without_colon() {
        let pages = help_pages();
        let find = |name: &str| help::find(name, &pages).map(|topic| topic.name);
        assert_eq!(find("render"), Some(":render"));
        assert_eq!(find(":render"), Some(":render"));
        assert_eq!(find("time"), Some("time"));
        assert_eq!(find(":time"), Some(":time"));
        assert_eq!(find("kd"), Some("texture"));
        assert_eq!(find("rayon"), Some("sphere"));
        assert_eq!(find("exit"), Some(":quit"));
        assert_eq!(find("why"), Some(":pick"));
        assert_eq!(help::suggestion("spehre", &pages), Some("sphere"));
    }

    /// The guide's table of commands (docs/guide/terminal.md): its first column.
    fn readme_commands() -> Vec<String> {
        let readme = include_str!("../../docs/guide/terminal.md");
        let table =
            readme.split_once("| command | what it does | example |").expect("the guide has a table of commands").1;
        let rows = table.lines().skip(2).take_while(|line| line.starts_with('|'));
        rows.map(|row| row.split(" | ").next().unwrap_or_default().to_string()).collect()
    }

    #[test]
    fn the_readme_table_names_every_command_and_only_commands() {
        let first_column = readme_commands().join(" ");
        for command in COMMANDS {
            assert!(
                first_column.contains(&format!("`{}", command.topic.name)),
                "`{}` missing from the guide's table",
                command.topic.name
            );
        }
        for named in first_column.split('`').skip(1).step_by(2) {
            let name = named.split_whitespace().next().unwrap_or_default();
            assert!(find(name).is_some(), "the guide's table names `{name}`, which is no command");
        }
    }
}
