//! The command registry: every command of the session (`:render`, `:time`,
//! `:save`, ...) defined once, with its name and other names, usage, help
//! page, what files it touches and the function that runs it; and the
//! dispatcher that runs a command line. The handlers live in the modules
//! of their topic, below this one: none of them imports it.

use crate::lang::suggest::closest;

use super::file_commands;
use super::help::{self, Group, Topic, help_page};
use super::inspect;
use super::lesson_commands;
pub(crate) use super::outcome::Flow;
use super::outcome::{CommandError, CommandResult};
use super::outputs::FrontEnd;
use super::picture_commands;
use super::play;
use super::reload;
use super::report::show_printed;
use super::session_commands;
use super::setting_commands;
use super::shell::Shell;
use super::write_back;

/// A command of the session.
pub(crate) struct Command {
    /// Its name (colon included), other names, summary, group and help page.
    pub topic: Topic,
    /// How to call it.
    pub usage: &'static str,
    /// What files its arguments name.
    pub files: Files,
    /// Runs it on its arguments.
    run: fn(&mut Shell, &[String], &mut dyn FrontEnd) -> CommandResult,
}

/// What files a command's arguments name, for file name completion and for
/// a script's check that it wrote a picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Files {
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
pub(crate) const COMMANDS: &[Command] = &[
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
        run: lesson_commands::lesson,
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
        run: lesson_commands::goal,
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
        run: picture_commands::render_command,
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
        run: picture_commands::save,
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
        run: picture_commands::anim,
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
        run: play::play,
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
        run: setting_commands::time,
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
        run: setting_commands::size,
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
        run: setting_commands::depth,
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
        run: setting_commands::samples,
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
        run: picture_commands::preview_command,
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
        run: picture_commands::pick,
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
        run: file_commands::load,
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
        run: reload::reload,
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
        run: file_commands::watch,
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
        run: write_back::write,
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
        run: inspect::env,
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
        run: inspect::scene,
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
        run: inspect::show,
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
        run: inspect::list,
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
        run: inspect::history,
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
        run: help_command,
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
        run: session_commands::undo,
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
        run: session_commands::reset,
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
        run: setting_commands::limits,
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
        run: session_commands::quit,
    },
];

impl Command {
    /// The names it is typed by: its name, and its other names that start
    /// with `:` (the rest are only for `:help`).
    pub(crate) fn typed_names(&self) -> impl Iterator<Item = &'static str> {
        let aliases = self.topic.aliases.iter().copied().filter(|alias| alias.starts_with(':'));
        std::iter::once(self.topic.name).chain(aliases)
    }
}

/// The command typed as `name`.
pub(crate) fn find(name: &str) -> Option<&'static Command> {
    COMMANDS.iter().find(|command| command.typed_names().any(|typed| typed == name))
}

/// Every page `:help` knows: the language's, then the commands'.
pub(crate) fn help_pages() -> Vec<&'static Topic> {
    help::LANGUAGE.iter().chain(COMMANDS.iter().map(|command| &command.topic)).collect()
}

/// Whether `line` is a command rather than program text.
pub(crate) fn is_command(line: &str) -> bool {
    line.trim_start().starts_with(':')
}

/// Whether the command on `line` writes image files (`:save`, `:anim`).
pub(crate) fn writes_pictures(line: &str) -> bool {
    let command = line.split_whitespace().next().and_then(find);
    command.is_some_and(|command| command.files == Files::WritesPictures)
}

/// Runs the command on `line`, reporting any failure on the front.
/// Returns `Err(())` if it failed, so scripts can count errors.
pub(crate) fn execute(shell: &mut Shell, line: &str, front: &mut dyn FrontEnd) -> Result<Flow, ()> {
    let result = split_arguments(line).map_err(CommandError::Failed).and_then(|words| dispatch(shell, &words, front));
    show_printed(&shell.session, front);
    match result {
        Ok(flow) => Ok(flow),
        Err(error) => {
            error.report(&shell.session, front);
            Err(())
        }
    }
}

fn dispatch(shell: &mut Shell, words: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let Some((name, arguments)) = words.split_first().filter(|(name, _)| name.as_str() != ":") else {
        return Err(CommandError::Failed("type a command name after `:`, for example `:help`".to_string()));
    };
    let Some(command) = find(name) else {
        return Err(unknown_command(name));
    };
    (command.run)(shell, arguments, front).map_err(|error| match error {
        CommandError::Usage(problem) => CommandError::Usage(format!("{problem}\nusage: {}", command.usage)),
        other => other,
    })
}

fn unknown_command(name: &str) -> CommandError {
    let names = COMMANDS.iter().flat_map(Command::typed_names);
    let mut message = format!("there is no command `{name}`");
    if let Some(close) = closest(name, names) {
        message.push_str(&format!("; did you mean `{close}`?"));
    }
    message.push_str("\n`:help` lists the commands");
    CommandError::Failed(message)
}

/// Splits a command line into words. Double quotes keep spaces in a word,
/// and (except on Windows, where it separates folders) a backslash keeps the
/// next character as it is, as file name completion writes `my\ scene.ray`.
pub(crate) fn split_arguments(line: &str) -> Result<Vec<String>, String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quoted = false;
    let mut chars = line.trim().chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                quoted = !quoted;
                word.get_or_insert_with(String::new);
            }
            '\\' if cfg!(not(windows)) && !quoted => {
                let escaped = chars.next().unwrap_or('\\');
                word.get_or_insert_with(String::new).push(escaped);
            }
            c if c.is_whitespace() && !quoted => words.extend(word.take()),
            c => word.get_or_insert_with(String::new).push(c),
        }
    }
    if quoted {
        return Err("a `\"` is not closed".to_string());
    }
    words.extend(word);
    Ok(words)
}

/// `:help [NAME]`: the overview, or the page about one name.
fn help_command(_shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let pages = help_pages();
    match arguments {
        [] => front.say(help::overview(&pages)),
        [name] => match help::find(name, &pages) {
            Some(topic) => front.say(topic.text),
            None => {
                let hint = help::suggestion(name, &pages).map(|s| format!("; did you mean `{s}`?")).unwrap_or_default();
                return Err(CommandError::Failed(format!(
                    "no help about `{name}`{hint}\n`:help` lists what it explains"
                )));
            }
        },
        _ => {
            return Err(CommandError::Usage("ask about one name at a time".to_string()));
        }
    }
    Ok(Flow::Continue)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::words;

    #[test]
    fn arguments_split_on_spaces_and_keep_quoted_ones() {
        assert_eq!(split_arguments(" :save  a.png 10 20 ").unwrap(), vec![":save", "a.png", "10", "20"]);
        assert_eq!(split_arguments(":load \"my scene.ray\"").unwrap(), vec![":load", "my scene.ray"]);
        assert_eq!(split_arguments(":load \"\"").unwrap(), vec![":load", ""]);
        assert!(split_arguments(":load \"oops").is_err());
        if cfg!(not(windows)) {
            assert_eq!(split_arguments(r":load my\ scene.ray").unwrap(), vec![":load", "my scene.ray"]);
        }
    }

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
