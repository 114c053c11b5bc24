//! Which flags of the command line go together, said once: for each flag,
//! the flags clap refuses with it, what else it needs to do something, and
//! whether it does anything in a session, with the words said when it would
//! do nothing.
//!
//! clap's conflicts are made from this table ([`with_conflicts`], applied to
//! every flag of [`Cli`]), and the job step's check of the flags given reads
//! it ([`Flag::misuse`]). A pair refused whatever the values is clap's (it
//! says "cannot be used with"); a flag that lacks what it needs, or is given
//! in a session, is said in the table's words. Rules that depend on values
//! (a pixel outside the image, `-` where a file is needed) stay in `job`.

use clap::Arg;

use super::{Cli, ScreenArg};
use crate::lang::Limits;
use crate::settings::DEFAULTS;

/// One flag of the command line (not of a subcommand) and what it goes with.
#[derive(Debug, Clone, Copy)]
pub struct Flag {
    /// clap's id: the field's name in [`Cli`] (`time_start`).
    pub id: &'static str,
    /// How messages name it (`--time-start`, `-o`).
    pub name: &'static str,
    /// Whether the command line gives it; for a flag with a default, whether
    /// it asks for something else (for `--samples`, more than one sample).
    pub given: fn(&Cli) -> bool,
    /// The flags clap refuses with it whatever their values: a pair is
    /// listed on one of its two flags, the one that would do nothing.
    pub conflicts: &'static [&'static str],
    /// What else it needs to do something.
    pub needs: Needs,
    /// Whether it does nothing in a session.
    pub in_a_session: InASession,
}

/// What else a flag needs to do something, and what is said, after the
/// flag's name, when it lacks it.
#[derive(Debug, Clone, Copy)]
pub enum Needs {
    /// Nothing: it does something with whatever else is given.
    Nothing,
    /// One of `flags`, or (`or_a_session`) a session.
    OneOf {
        /// The flags it goes with, by id.
        flags: &'static [&'static str],
        /// Whether a session does too.
        or_a_session: bool,
        /// What is said without them.
        words: &'static str,
    },
    /// None of `flags`.
    NoneOf {
        /// The flags it does nothing with, by id.
        flags: &'static [&'static str],
        /// What is said with one of them.
        words: &'static str,
    },
}

/// What a flag does in a session (no scene file, or `-i`).
#[derive(Debug, Clone, Copy)]
pub enum InASession {
    /// It is not refused for being in a session: it sets the session up, or
    /// what it needs decides.
    NotRefused,
    /// It does nothing there; `instead` says what does its work in a session
    /// (`; there, ...`), if anything does.
    DoesNothing {
        /// Appended to the message.
        instead: &'static str,
    },
}

/// The modes that render no animation: an animation's flags do nothing with
/// them.
const NO_ANIMATION: &[&str] = &["check", "export_pov", "watch", "explain"];

/// What an animation's flags need.
const AN_ANIMATION: Needs =
    Needs::OneOf { flags: &["anim"], or_a_session: false, words: "is for an animation: give --anim N too" };

/// Every flag of [`Cli`], in the order they are checked: of two flags that
/// would do nothing, the first is named.
pub static FLAGS: [Flag; 31] = [
    flag("json", "--json", |cli| cli.json).needs(Needs::OneOf {
        flags: &["check", "explain"],
        or_a_session: false,
        words: "is for --check (the diagnostics) and --explain X,Y (the explanation)",
    }),
    flag("output", "-o", |cli| cli.output.is_some())
        .conflicts(&["check", "export_pov", "explain"])
        .nothing_in_a_session("; there, `:save FILE` and `:anim FRAMES FILE` write images"),
    flag("anim", "--anim", |cli| cli.anim.is_some())
        .conflicts(NO_ANIMATION)
        .nothing_in_a_session("; there, `:anim FRAMES FILE` renders an animation"),
    animation_flag("frames", "--frames", |cli| cli.frames.is_some()),
    animation_flag("time_start", "--time-start", |cli| cli.timeline.time_start.is_some()),
    animation_flag("time_step", "--time-step", |cli| cli.timeline.time_step.is_some()),
    animation_flag("fps", "--fps", |cli| cli.fps.is_some()),
    animation_flag("loops", "--loop", |cli| cli.loops.is_some()),
    animation_flag("apng", "--apng", |cli| cli.apng),
    flag("check", "--check", |cli| cli.check)
        .conflicts(&["export_pov"])
        .nothing_in_a_session("; there, `:scene` tells what the scene holds"),
    flag("export_pov", "--export-pov", |cli| cli.export_pov.is_some()).nothing_in_a_session(""),
    flag("stats", "--stats", |cli| cli.stats).conflicts(&["check", "export_pov", "explain"]).nothing_in_a_session(""),
    flag("reference", "--reference", |cli| cli.reference).conflicts(&["check", "export_pov"]).nothing_in_a_session(""),
    flag("quiet", "--quiet", |cli| cli.quiet).conflicts(&["check", "explain"]).nothing_in_a_session(""),
    flag("watch", "--watch", |cli| cli.watch)
        .conflicts(&["check", "export_pov", "explain"])
        .nothing_in_a_session("; there, `:watch FILE` follows a file"),
    flag("explain", "--explain", |cli| cli.explain.is_some())
        .conflicts(&["check", "export_pov"])
        .nothing_in_a_session("; there, `:pick X Y` explains a pixel of the last picture"),
    flag("adaptive", "--adaptive", |cli| cli.adaptive).conflicts(&["check", "export_pov", "reference"]).needs(
        Needs::OneOf {
            flags: &["samples"],
            or_a_session: true,
            words: "gives more samples to some pixels: give --samples N too, with N > 1",
        },
    ),
    flag("time", "--time", |cli| cli.time.is_some()).needs(Needs::NoneOf {
        flags: &["anim"],
        words: "sets the time of one image; frame k of an animation has time = k, \
                or A + (k - 1) * S with --time-start A --time-step S",
    }),
    flag("no_preview", "--no-preview", |cli| cli.no_preview).needs(Needs::OneOf {
        flags: &["watch"],
        or_a_session: true,
        words: "is for the interactive session (`rayrepl` or `rayrepl -i scene.ray`) and --watch",
    }),
    flag("lesson", "--lesson", |cli| cli.lesson.is_some()).needs(Needs::OneOf {
        flags: &[],
        or_a_session: true,
        words: "is for the session (`rayrepl --lesson 1`, or `rayrepl -i scene.ray --lesson FILE`)",
    }),
    flag("keep_going", "--keep-going", |cli| cli.keep_going).needs(Needs::OneOf {
        flags: &[],
        or_a_session: true,
        words: "is for a script on standard input (`rayrepl --keep-going < script`)",
    }),
    flag("interactive", "-i", |cli| cli.interactive),
    flag("width", "--width", |cli| cli.picture.width != DEFAULTS.width).conflicts(&["check"]),
    flag("height", "--height", |cli| cli.picture.height != DEFAULTS.height).conflicts(&["check"]),
    flag("depth", "--depth", |cli| cli.picture.depth != DEFAULTS.depth).conflicts(&["check"]),
    flag("samples", "--samples", |cli| cli.picture.samples > 1).conflicts(&["check", "export_pov", "reference"]),
    flag("screen", "--screen", |cli| cli.screen != ScreenArg::Centered).conflicts(&["check", "export_pov"]),
    flag("threads", "--threads", |cli| cli.threads.is_some()).conflicts(&["check", "export_pov"]),
    flag("allow", "--allow", |cli| !cli.allow.is_empty()),
    flag("max_calls", "--max-calls", |cli| cli.limits.max_calls != Limits::DEFAULT.max_call_depth),
    flag("max_primitives", "--max-primitives", |cli| cli.limits.max_primitives != Limits::DEFAULT.max_primitives),
];

/// A flag that goes with everything, in a session too; the methods below
/// say what it does not go with.
const fn flag(id: &'static str, name: &'static str, given: fn(&Cli) -> bool) -> Flag {
    Flag { id, name, given, conflicts: &[], needs: Needs::Nothing, in_a_session: InASession::NotRefused }
}

/// A flag of an animation: it needs `--anim`, and goes with no mode that
/// renders something else.
const fn animation_flag(id: &'static str, name: &'static str, given: fn(&Cli) -> bool) -> Flag {
    flag(id, name, given).conflicts(NO_ANIMATION).needs(AN_ANIMATION).nothing_in_a_session("")
}

impl Flag {
    /// This flag, refused by clap with `conflicts`.
    const fn conflicts(self, conflicts: &'static [&'static str]) -> Flag {
        Flag { conflicts, ..self }
    }

    /// This flag, needing `needs`.
    const fn needs(self, needs: Needs) -> Flag {
        Flag { needs, ..self }
    }

    /// This flag, doing nothing in a session (`instead`: what does its work
    /// there).
    const fn nothing_in_a_session(self, instead: &'static str) -> Flag {
        Flag { in_a_session: InASession::DoesNothing { instead }, ..self }
    }

    /// Why this flag would do nothing with the others given, if it is given
    /// and would: `given` says whether a flag is given, by id; `session` is
    /// why the command line starts a session, if it does.
    pub fn misuse(&self, given: &dyn Fn(&str) -> bool, session: Option<&str>) -> Option<String> {
        if !given(self.id) {
            return None;
        }
        if let (Some(why), InASession::DoesNothing { instead }) = (session, self.in_a_session) {
            return Some(format!("{} does nothing in a session ({why}){instead}", self.name));
        }
        let words = match self.needs {
            Needs::Nothing => return None,
            Needs::OneOf { or_a_session: true, .. } if session.is_some() => return None,
            Needs::OneOf { flags, words, .. } if !flags.iter().any(|id| given(id)) => words,
            Needs::NoneOf { flags, words } if flags.iter().any(|id| given(id)) => words,
            Needs::OneOf { .. } | Needs::NoneOf { .. } => return None,
        };
        Some(format!("{} {words}", self.name))
    }
}

/// The row of the flag with clap's id `id`.
pub fn flag_with_id(id: &str) -> &'static Flag {
    FLAGS.iter().find(|flag| flag.id == id).expect("the table names only its own flags (a test checks)")
}

/// `arg` refused with the flags its row lists: [`Cli`] applies this to
/// each of its flags (`mut_args`), so that clap's conflicts are the table's.
pub fn with_conflicts(arg: Arg) -> Arg {
    match FLAGS.iter().find(|flag| flag.id == arg.get_id()) {
        Some(flag) => arg.conflicts_with_all(flag.conflicts),
        None => arg,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use std::collections::BTreeSet;

    use clap::error::ErrorKind;
    use clap::{CommandFactory, Parser};

    use super::*;

    /// A value for each flag of the table that takes one.
    const VALUES: [(&str, &str); 20] = [
        ("output", "x.png"),
        ("anim", "3"),
        ("frames", "1..2"),
        ("time_start", "2"),
        ("time_step", "2"),
        ("fps", "10"),
        ("loops", "2"),
        ("export_pov", "x.pov"),
        ("explain", "1,1"),
        ("time", "2"),
        ("lesson", "1"),
        ("width", "8"),
        ("height", "8"),
        ("depth", "2"),
        ("samples", "4"),
        ("screen", "bottom"),
        ("threads", "2"),
        ("allow", "colours"),
        ("max_calls", "7"),
        ("max_primitives", "7"),
    ];

    /// `flag` as given on the command line, with a value if it takes one.
    pub(crate) fn example(flag: &Flag) -> Vec<&'static str> {
        let value = VALUES.iter().find(|(id, _)| *id == flag.id).map(|(_, value)| *value);
        [flag.name].into_iter().chain(value).collect()
    }

    /// The command line `rayrepl a.ray` followed by `flags`, as parsed.
    fn parse(flags: &[&Flag]) -> Result<Cli, clap::Error> {
        let args = flags.iter().flat_map(|flag| example(flag));
        Cli::try_parse_from(["rayrepl", "a.ray"].into_iter().chain(args))
    }

    #[test]
    fn every_flag_of_the_command_line_has_one_row_and_its_name() {
        let command = Cli::command();
        let flags: Vec<_> = command.get_arguments().filter(|arg| !arg.is_positional()).collect();
        let ids: BTreeSet<&str> = flags.iter().map(|arg| arg.get_id().as_str()).collect();
        let rows: BTreeSet<&str> = FLAGS.iter().map(|flag| flag.id).collect();
        assert_eq!(rows.len(), FLAGS.len(), "a flag has two rows");
        assert_eq!(rows, ids, "each flag of `Cli` has its row in FLAGS, in the order it is checked");
        for arg in flags {
            let row = flag_with_id(arg.get_id().as_str());
            let long = arg.get_long().map(|long| format!("--{long}"));
            let short = arg.get_short().map(|short| format!("-{short}"));
            assert!([long, short].contains(&Some(row.name.to_string())), "{} is not named {}", row.id, row.name);
        }
        for flag in &FLAGS {
            let named = match flag.needs {
                Needs::Nothing => &[][..],
                Needs::OneOf { flags, .. } | Needs::NoneOf { flags, .. } => flags,
            };
            for id in flag.conflicts.iter().chain(named) {
                assert!(rows.contains(id), "{} names `{id}`, which has no row", flag.id);
            }
        }
    }

    #[test]
    fn given_says_whether_the_command_line_gives_each_flag() {
        let none = parse(&[]).expect("a scene alone parses");
        for flag in &FLAGS {
            let cli = parse(&[flag]).unwrap_or_else(|error| panic!("{}: give it a value in VALUES: {error}", flag.id));
            assert!((flag.given)(&cli), "{} given", flag.id);
            assert!(!(flag.given)(&none), "{} not given", flag.id);
        }
    }

    #[test]
    fn clap_refuses_each_pair_the_table_lists_as_conflicts() {
        for flag in &FLAGS {
            for other in flag.conflicts.iter().map(|id| flag_with_id(id)) {
                for pair in [[flag, other], [other, flag]] {
                    let error = parse(&pair).expect_err("refused");
                    assert_eq!(error.kind(), ErrorKind::ArgumentConflict, "{} {}: {error}", pair[0].id, pair[1].id);
                    assert!(error.to_string().contains("cannot be used with"), "{error}");
                }
            }
        }
    }
}
