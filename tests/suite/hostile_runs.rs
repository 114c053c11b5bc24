//! The hostile-input run (issue 35, point 14): mutated programs, run as a
//! scene file, as a piped script and in a typed session on a terminal,
//! under a memory limit. Every run must end with status 0, 1, 2 or 130,
//! with a message when it is not 0; never a panic, an abort, a leftover
//! temporary file or a changed scene file.
//!
//! The programs are the project's own (the scenarios and the test cases)
//! with a few mutations each: tokens deleted, repeated, swapped or
//! inserted (keywords, symbols, extreme numbers, whole items), lines
//! swapped, the text cut short, deep parentheses, bytes that are not UTF-8.
//! The same seed gives the same cases. CI runs a bounded number;
//! `RAYREPL_HOSTILE_CASES=N` runs N per mode (the typed session a tenth of
//! them, being slower), and `RAYREPL_HOSTILE_SEED=S` another series.
//!
//! A failing case is kept in `tests/hostile-regressions/` (named by its
//! mode and its hash), and every file there runs first, every time: once
//! it is fixed, it stays in as a regression test.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use expectrl::process::unix::WaitStatus;
use expectrl::{Any, ControlCode, Eof, Expect, Regex, Session};

use crate::common::interrupt::names_in;

/// Cases per mode in CI (the typed session runs a tenth of them).
const CI_CASES: usize = 80;

/// The series CI runs.
const CI_SEED: u64 = 35;

/// The address space a run may use, in KiB: 2 GiB.
const MEMORY_KIB: u64 = 2 << 20;

/// Primitives a run may make: small, so that a mutation that multiplies
/// the objects reaches the limit in a moment rather than in a minute.
const MAX_PRIMITIVES: &str = "200000";

/// A run that takes longer is stopped and counted as slow (a mutated
/// program may legitimately compute for long), not as a failure.
const TIME_LIMIT: Duration = Duration::from_secs(30);

/// Where failing cases are kept.
const REGRESSIONS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/hostile-regressions");

/// The exit statuses a run may end with: success, an error in the
/// program or its files, a usage error, Ctrl-C.
const STATUSES: [i32; 4] = [0, 1, 2, 130];

// ---- Cases ---------------------------------------------------------------------

/// A small deterministic generator (SplitMix64): the same seed, the same cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number below `n` (which is not 0).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// What mutations insert besides the fuzz test's words
/// ([`crate::fuzz::vocabulary`]): extreme numbers, whole items that stress
/// the renderer or the evaluator, and odd characters.
const INSERTIONS: &[&str] = &[
    "1e308",
    "-1e308",
    "1e-320",
    "-0",
    "1e15",
    "123456789012345678901234567890",
    "0.000000001",
    "n",
    "r",
    "p(1)",
    "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end",
    "put box center 0, 0, 0 length 1e300, 1, 1 kd 1 ks 1 phong 1 color 0, 0, 255 end",
    "put plane normal 0, 1, 0 distance 1e-300 kd 0 ks 1 phong 1 color 1, 1, 1 end",
    "proc p(x) p(x + 1) end",
    "proc q(x) q(x) q(x) end",
    "object o = ",
    "put o",
    "translate 1e300, 0, 0",
    "scale 1e-300",
    "rotate 90, 0, 0",
    "light vector 0, 0, 0 intensity 1e308 end",
    "camera distance 0 angle 0 end",
    "let time = 1",
    "print 1 / 0",
    "sqrt(-1)",
    "\r",
    "\t",
    "\u{0}",
    "\u{feff}",
    "🙂",
];

/// The programs mutations start from: the project's scenarios and valid
/// test cases, then its invalid ones, each sorted by path.
struct Seeds {
    valid: Vec<Vec<u8>>,
    invalid: Vec<Vec<u8>>,
}

impl Seeds {
    fn read() -> Seeds {
        Seeds {
            valid: programs_in(&["scenarios", "tests/cases/valid", "tests/cases/warnings"]),
            invalid: programs_in(&["tests/cases/invalid"]),
        }
    }

    /// A valid program three times in four: most mutations of an invalid
    /// one stop at its error.
    fn pick(&self, rng: &mut Rng) -> &[u8] {
        let programs = if rng.below(4) == 0 { &self.invalid } else { &self.valid };
        rng.pick(programs).as_slice()
    }
}

/// The `.ray` programs in `folders` of the project, sorted by path.
fn programs_in(folders: &[&str]) -> Vec<Vec<u8>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths: Vec<PathBuf> = folders
        .iter()
        .flat_map(|folder| std::fs::read_dir(root.join(folder)).expect("the folder is readable"))
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.extension().is_some_and(|extension| extension == "ray"))
        .collect();
    paths.sort();
    paths.iter().map(|path| std::fs::read(path).expect("a seed program")).collect()
}

/// Cuts `text` into tokens: runs of word characters, runs of spaces, and
/// single other characters, so that joining them gives `text` again.
fn tokens(text: &str) -> Vec<String> {
    #[derive(PartialEq, Clone, Copy)]
    enum Class {
        Word,
        Space,
        Other,
    }
    let class = |c: char| match c {
        c if c.is_alphanumeric() || c == '_' || c == '.' => Class::Word,
        c if c.is_whitespace() => Class::Space,
        _ => Class::Other,
    };
    let mut out: Vec<String> = Vec::new();
    let mut last = None;
    for c in text.chars() {
        let now = class(c);
        match out.last_mut() {
            Some(token) if last == Some(now) && now != Class::Other => token.push(c),
            _ => out.push(c.to_string()),
        }
        last = Some(now);
    }
    out
}

/// Numbers that mutations put in place of others.
const EXTREME_NUMBERS: &[&str] = &["0", "1e308", "1e-308", "5e-324", "1e30", "1e-30", "100000", "0.5", "360"];

/// A seed with one to four mutations: half the time only ones that keep
/// a valid program valid (a number replaced, a line repeated), so that
/// the cases reach evaluation and rendering, not only the parser.
fn mutated(rng: &mut Rng, seed: &[u8]) -> Vec<u8> {
    let mut words = tokens(&String::from_utf8_lossy(seed));
    let mut not_utf8_at = None;
    let gentle = rng.below(2) == 0;
    for _ in 0..=rng.below(4) {
        if words.is_empty() {
            words.push(String::new());
        }
        let at = rng.below(words.len());
        if gentle {
            let numbers: Vec<usize> =
                (0..words.len()).filter(|&i| words[i].starts_with(|c: char| c.is_ascii_digit())).collect();
            if rng.below(3) > 0 && !numbers.is_empty() {
                let number = *rng.pick(&numbers);
                words[number] = rng.pick(EXTREME_NUMBERS).to_string();
            } else {
                let mut lines: Vec<String> = words.concat().split('\n').map(str::to_string).collect();
                let line = rng.below(lines.len());
                let copy = lines[line].clone();
                lines.insert(line, copy);
                words = tokens(&lines.join("\n"));
            }
            continue;
        }
        match rng.below(9) {
            0 => {
                words.remove(at);
            }
            1 => {
                let end = (at + 1 + rng.below(12)).min(words.len());
                let copy: Vec<String> = words[at..end].to_vec();
                let times = 1 + rng.below(3);
                for _ in 0..times {
                    words.splice(at..at, copy.iter().cloned());
                }
            }
            2 => {
                let other = rng.below(words.len());
                words.swap(at, other);
            }
            3 => words.insert(at, format!(" {} ", rng.pick(&crate::fuzz::vocabulary()))),
            4 => words.insert(at, format!(" {} ", rng.pick(INSERTIONS))),
            5 => {
                let lines: Vec<String> = words.concat().split('\n').map(str::to_string).collect();
                let mut lines = lines;
                let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
                lines.swap(a, b);
                words = tokens(&lines.join("\n"));
            }
            6 => words.truncate(at),
            7 => {
                let depth = 1 + rng.below(3000);
                let close = at + rng.below(words.len() - at + 1);
                words.insert(close, ")".repeat(depth));
                words.insert(at, "(".repeat(depth));
            }
            _ => not_utf8_at = Some(at),
        }
    }
    let mut bytes = Vec::new();
    for (i, word) in words.iter().enumerate() {
        if not_utf8_at == Some(i) {
            bytes.push(0xff);
        }
        bytes.extend_from_slice(word.as_bytes());
    }
    bytes
}

/// How a case is run.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    /// `rayrepl scene.ray -o out.png`.
    File,
    /// `rayrepl < script`, the program followed by a render.
    Script,
    /// The session on a terminal, the program typed line by line.
    Typed,
}

impl Mode {
    const ALL: [Mode; 3] = [Mode::File, Mode::Script, Mode::Typed];

    fn name(self) -> &'static str {
        match self {
            Mode::File => "file",
            Mode::Script => "script",
            Mode::Typed => "typed",
        }
    }
}

// ---- Runs ----------------------------------------------------------------------

/// How a run ended, if it was not a failure.
#[derive(Debug, PartialEq)]
enum Ended {
    Status(i32),
    /// Stopped at [`TIME_LIMIT`].
    Slow,
}

/// The binary under the memory limit, with `args`.
fn limited(args: &[&str]) -> Command {
    let mut command = Command::new("sh");
    command
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_KIB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_rayrepl"))
        .args(args)
        .env("NO_COLOR", "1");
    command
}

/// Runs `command` with `stdin` until it ends or [`TIME_LIMIT`] passes:
/// its status (`None` if it was stopped) and its stderr.
fn run_until_limit(mut command: Command, stdin: Vec<u8>) -> (Option<ExitStatus>, String) {
    let mut child =
        command.stdin(Stdio::piped()).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().expect("the binary starts");
    let mut input = child.stdin.take().expect("stdin is piped");
    // Fed and read from other threads, so that neither pipe can block the run.
    std::thread::spawn(move || {
        let _ = input.write_all(&stdin);
    });
    let mut stderr = child.stderr.take().expect("stderr is piped");
    let reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = stderr.read_to_end(&mut text);
        String::from_utf8_lossy(&text).into_owned()
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("the run can be waited for") {
            break Some(status);
        }
        if start.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    (status, reader.join().expect("stderr is read"))
}

/// Judges a run that exited with `status` and said `said`.
fn judge(status: Option<ExitStatus>, said: &str) -> Result<Ended, String> {
    let Some(status) = status else { return Ok(Ended::Slow) };
    if said.contains("panicked") || said.contains("internal error") {
        return Err(format!("it panicked:\n{said}"));
    }
    let Some(code) = status.code() else { return Err(format!("it was ended by a signal ({status}):\n{said}")) };
    if !STATUSES.contains(&code) {
        return Err(format!("it exited with status {code}:\n{said}"));
    }
    if code != 0 && said.trim().is_empty() {
        return Err(format!("it exited with status {code} and said nothing"));
    }
    Ok(Ended::Status(code))
}

/// Runs `program` in `mode`, in a folder of its own, and checks what the
/// folder holds afterwards.
fn run_case(mode: Mode, program: &[u8]) -> Result<Ended, String> {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = folder.path().join("scene.ray");
    std::fs::write(&scene, program).expect("the scene is written");
    let out = folder.path().join("out.png");
    let ended = match mode {
        Mode::File => {
            let (scene, out) = (scene.to_str().expect("a UTF-8 path"), out.to_str().expect("a UTF-8 path"));
            let args = [scene, "--width", "16", "--height", "12", "--max-primitives", MAX_PRIMITIVES, "-o", out];
            let (status, said) = run_until_limit(limited(&args), Vec::new());
            judge(status, &said)?
        }
        Mode::Script => {
            let mut script = b":size 16 12\n".to_vec();
            script.extend_from_slice(program);
            script.extend_from_slice(format!("\n:render\n:save {}\n", out.display()).as_bytes());
            let (status, said) = run_until_limit(limited(&["--max-primitives", MAX_PRIMITIVES]), script);
            judge(status, &said)?
        }
        Mode::Typed => typed(folder.path(), program)?,
    };
    if std::fs::read(&scene).ok().as_deref() != Some(program) {
        return Err("the scene file was changed".to_string());
    }
    let left: Vec<String> = names_in(folder.path())
        .into_iter()
        .filter(|name| !["scene.ray", "out.png", "data"].contains(&&**name))
        .collect();
    if !left.is_empty() {
        return Err(format!("it left {left:?}"));
    }
    if ended == Ended::Status(0) && mode == Mode::File {
        image::open(&out).map_err(|error| format!("it succeeded but its picture is unreadable: {error}"))?;
    }
    Ok(ended)
}

/// The program typed line by line into a session on a terminal (typed
/// ahead: each line is sent without waiting for the answer before it),
/// then a size and a render, Ctrl-C (dropping an unfinished entry) at the
/// prompt and Ctrl-D twice (the first may warn that inputs are not written).
fn typed(folder: &Path, program: &[u8]) -> Result<Ended, String> {
    let mut command = limited(&["--no-preview", "--max-primitives", MAX_PRIMITIVES]);
    command.env("XDG_DATA_HOME", folder.join("data")).env("TERM", "xterm-256color");
    let mut session = Session::spawn(command).expect("the session starts");
    session.set_expect_timeout(Some(TIME_LIMIT));
    let mut seen = String::new();
    // Waits for `what`; `Ok(false)` if it takes longer than the time limit.
    let mut wait = |session: &mut expectrl::session::OsSession, what: &str| -> Result<bool, String> {
        match session.expect(Regex(what)) {
            Ok(found) => {
                seen.push_str(&String::from_utf8_lossy(found.before()));
                seen.push_str(&String::from_utf8_lossy(&found[0]));
                if seen.contains("panicked") || seen.contains("internal error") {
                    return Err(format!("it panicked:\n{seen}"));
                }
                Ok(true)
            }
            Err(expectrl::Error::ExpectTimeout) => Ok(false),
            Err(error) => Err(format!("the session ended early ({error}); it showed:\n{seen}")),
        }
    };
    // A prompt: `[3] ray> ` for a new entry, `...sphere> ` for the rest of one.
    const PROMPT: &str = r"(\[\d+\] ray|\.\.\.[a-z]+)> ";
    let text = String::from_utf8_lossy(program).replace(['\u{0}', '\r'], " ");
    let send = |session: &mut expectrl::session::OsSession, keys: &str| {
        session.send(keys).map_err(|error| format!("cannot type: {error}"))
    };
    if !wait(&mut session, PROMPT)? {
        return Err("no first prompt".to_string());
    }
    for line in text.split('\n') {
        send(&mut session, &format!("{line}\r"))?;
    }
    // Keys typed while an entry runs reach the terminal in its normal mode,
    // where Ctrl-C and Ctrl-D mean something else: they are sent only once
    // the answer to a command typed after everything else has come, and
    // then a prompt. (A command works in the middle of an unfinished entry.)
    let mut settle = |session: &mut expectrl::session::OsSession| -> Result<bool, String> {
        send(session, ":size 16 12\r")?;
        Ok(wait(session, "size = 16×12")? && wait(session, PROMPT)?)
    };
    if !settle(&mut session)? {
        return Ok(Ended::Slow);
    }
    send(&mut session, &(ControlCode::EndOfText as u8 as char).to_string())?;
    send(&mut session, ":render\r")?;
    if !settle(&mut session)? {
        return Ok(Ended::Slow);
    }
    let ctrl_d = (ControlCode::EndOfTransmission as u8 as char).to_string();
    send(&mut session, &ctrl_d)?;
    const NOTE: &str = "not written to a file";
    let found = session.expect(Any::boxed(vec![Box::new(NOTE), Box::new(Eof)]));
    if found.is_ok_and(|found| found.get(0) == Some(NOTE.as_bytes())) {
        session.expect(Regex(PROMPT)).map_err(|error| format!("no prompt after the note ({error})"))?;
        send(&mut session, &ctrl_d)?;
    }
    session.expect(Eof).map_err(|error| format!("the session does not end ({error}); it showed:\n{seen}"))?;
    match session.get_process().wait().map_err(|error| error.to_string())? {
        WaitStatus::Exited(_, 0) => Ok(Ended::Status(0)),
        other => Err(format!("the session ended with {other:?}; it showed:\n{seen}")),
    }
}

// ---- The run -------------------------------------------------------------------

/// The number in environment variable `name`, or `default`.
fn from_environment(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(value) => value.parse().unwrap_or_else(|_| panic!("{name} is not a number: {value}")),
        Err(_) => default,
    }
}

/// Keeps a failing case in [`REGRESSIONS`]; its path.
fn keep(mode: Mode, program: &[u8]) -> PathBuf {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    program.hash(&mut hasher);
    let path = Path::new(REGRESSIONS).join(format!("{}-{:016x}.ray", mode.name(), hasher.finish()));
    std::fs::create_dir_all(REGRESSIONS).expect("the regressions folder can be made");
    std::fs::write(&path, program).expect("the case is kept");
    path
}

/// The kept cases: each file's mode is the start of its name.
fn regressions() -> Vec<(Mode, Vec<u8>)> {
    let Ok(entries) = std::fs::read_dir(REGRESSIONS) else { return Vec::new() };
    let mut paths: Vec<PathBuf> = entries.map(|entry| entry.expect("an entry").path()).collect();
    paths.sort();
    paths
        .iter()
        .filter_map(|path| {
            let name = path.file_name()?.to_str()?;
            let mode = Mode::ALL.into_iter().find(|mode| name.starts_with(&format!("{}-", mode.name())))?;
            Some((mode, std::fs::read(path).expect("a kept case")))
        })
        .collect()
}

#[test]
fn mutated_programs_end_with_a_status_and_a_message_in_every_mode() {
    let cases = from_environment("RAYREPL_HOSTILE_CASES", CI_CASES as u64) as usize;
    let seed = from_environment("RAYREPL_HOSTILE_SEED", CI_SEED);
    let seeds = Seeds::read();
    let mut rng = Rng(seed);
    let mut all: Vec<(Mode, Vec<u8>)> = regressions();
    for mode in Mode::ALL {
        let count = if mode == Mode::Typed { cases.div_ceil(10) } else { cases };
        for _ in 0..count {
            let start = seeds.pick(&mut rng).to_vec();
            all.push((mode, mutated(&mut rng, &start)));
        }
    }
    let mut failures = Vec::new();
    let mut tally = std::collections::BTreeMap::new();
    for (mode, program) in &all {
        match run_case(*mode, program) {
            Ok(ended) => *tally.entry((mode.name(), format!("{ended:?}"))).or_insert(0) += 1,
            Err(why) => failures.push(format!("{}: {why}", keep(*mode, program).display())),
        }
    }
    // What the cases did, for whoever reads the log.
    eprintln!("hostile runs (seed {seed}): {tally:?}");
    assert!(failures.is_empty(), "{} failing cases, kept:\n{}", failures.len(), failures.join("\n\n"));
}

#[test]
fn mutations_change_programs_and_the_seed_decides_them() {
    let seeds = Seeds::read();
    assert!(seeds.valid.len() > 40 && seeds.invalid.len() > 100, "the seed programs are found");
    let start = &seeds.valid[7];
    let series = |seed| {
        let mut rng = Rng(seed);
        (0..50).map(|_| mutated(&mut rng, start)).collect::<Vec<_>>()
    };
    assert_eq!(series(1), series(1));
    assert_ne!(series(1), series(2));
    assert!(series(1).iter().filter(|program| program != &start).count() > 40);
    assert_eq!(tokens("put sphere(1,  2)").concat(), "put sphere(1,  2)");
}

#[test]
fn a_panic_an_abort_or_a_silent_failure_fails_the_run() {
    use std::os::unix::process::ExitStatusExt;
    let exited = |code: i32| Some(ExitStatus::from_raw(code << 8));
    assert_eq!(judge(exited(0), ""), Ok(Ended::Status(0)));
    assert_eq!(judge(exited(1), "error: expected `end`"), Ok(Ended::Status(1)));
    assert_eq!(judge(None, ""), Ok(Ended::Slow));
    assert!(judge(exited(1), "").is_err(), "a failure says why");
    assert!(judge(exited(101), "thread 'main' panicked at src/x.rs").is_err());
    assert!(judge(exited(1), "internal error: index out of bounds").is_err());
    assert!(judge(Some(ExitStatus::from_raw(6)), "").is_err(), "an abort (SIGABRT)");
}
