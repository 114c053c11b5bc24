//! Batch work from the command line: checking, rendering still images and
//! animations of a scene file.

use std::io::{IsTerminal, Read};
use std::path::Path;
use std::process::ExitCode;

use crate::cli::Cli;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceId, SourceMap, parse_file};
use crate::scene::Scene;

/// Runs what the command line asks for and returns the process's exit code.
pub fn run(cli: Cli) -> ExitCode {
    let Some(path) = cli.scene.clone() else {
        eprintln!("rayrepl: the interactive session is not built yet; give a scene file");
        return ExitCode::FAILURE;
    };
    match run_file(&cli, &path) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            if !message.is_empty() {
                eprintln!("{message}");
            }
            ExitCode::FAILURE
        }
    }
}

/// Checks or renders one scene file.
fn run_file(cli: &Cli, path: &Path) -> Result<(), String> {
    let mut sources = SourceMap::new();
    let id = load(&mut sources, path)?;
    let limits = Limits { max_call_depth: cli.max_calls, max_primitives: cli.max_primitives };
    let scene = evaluate(&sources, id, cli.time, limits)?;
    if cli.check {
        println!("{}: {}", sources.get(id).name, summary(&scene));
        return Ok(());
    }
    Err("rayrepl: rendering is not built yet".into())
}

/// Reads a scene file (or standard input for `-`) into `sources`.
pub fn load(sources: &mut SourceMap, path: &Path) -> Result<SourceId, String> {
    if path == Path::new("-") {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| format!("rayrepl: cannot read the scene from standard input: {e}"))?;
        return Ok(sources.add("<stdin>", text, 0));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("rayrepl: cannot read `{}`: {}", path.display(), io_reason(&e)))?;
    Ok(sources.add(path.display().to_string(), text, 0))
}

/// An I/O error in plain words, without Rust's `(os error 2)` suffix.
pub fn io_reason(error: &std::io::Error) -> String {
    match error.kind() {
        std::io::ErrorKind::NotFound => "no such file".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        std::io::ErrorKind::IsADirectory => "it is a directory".into(),
        std::io::ErrorKind::InvalidData => "it is not UTF-8 text".into(),
        _ => error.to_string(),
    }
}

/// Parses and evaluates a whole file at `time`, printing warnings on stderr.
fn evaluate(sources: &SourceMap, id: SourceId, time: f64, limits: Limits) -> Result<Scene, String> {
    let color = std::io::stderr().is_terminal();
    let show = |d: &Diagnostic| d.render(sources, color);
    let program = parse_file(id, &sources.get(id).text).map_err(|d| show(&d))?;
    let mut interpreter = Interpreter::new(time, limits);
    let result = interpreter.run(&program);
    for warning in interpreter.take_warnings() {
        eprint!("{}", show(&warning));
    }
    result.map_err(|d| show(&d))?;
    Ok(interpreter.into_scene())
}

/// "3 spheres, 1 plane, 0 boxes, 2 lights".
fn summary(scene: &Scene) -> String {
    let counts = scene.counts();
    let plural = |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    format!(
        "{}, {}, {}, {}",
        plural(counts.spheres, "sphere", "spheres"),
        plural(counts.planes, "plane", "planes"),
        plural(counts.boxes, "box", "boxes"),
        plural(counts.lights, "light", "lights"),
    )
}
