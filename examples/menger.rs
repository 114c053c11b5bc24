//! Times the evaluation of a Menger sponge and reports peak memory.
//!
//! `cargo run --release --example menger [DEPTH]` (default depth 5: 3.2
//! million boxes from 3,368,421 procedure calls). Prints the evaluation time
//! and the process's peak resident memory (VmHWM, Linux only).

use std::time::Instant;

use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};

/// The sponge scene; its last line calls `menger(0, 0, 0, 3, 5)`.
const SCENE: &str = include_str!("menger.ray");

fn main() {
    let depth: u32 = std::env::args().nth(1).and_then(|d| d.parse().ok()).unwrap_or(5);
    let text = SCENE.replace("menger(0, 0, 0, 3, 5)", &format!("menger(0, 0, 0, 3, {depth})"));
    let mut sources = SourceMap::new();
    let id = sources.add("menger.ray", text.clone(), 0);
    let program = match parse_file(id, &text) {
        Ok(program) => program,
        Err(d) => {
            eprintln!("syntax error: {}", d.message);
            std::process::exit(1);
        }
    };
    let start = Instant::now();
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    if let Err(d) = interpreter.run(&program) {
        eprintln!("error: {}", d.message);
        std::process::exit(1);
    }
    let elapsed = start.elapsed();
    let counts = interpreter.scene().counts();
    println!("depth {depth}: {} boxes in {:.3} s", counts.boxes, elapsed.as_secs_f64());
    match peak_memory() {
        Some(peak) => println!("peak resident memory: {peak}"),
        None => println!("peak resident memory: unknown (no /proc/self/status)"),
    }
}

/// The `VmHWM` line of `/proc/self/status`: the peak resident set size.
fn peak_memory() -> Option<String> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    Some(line.trim_start_matches("VmHWM:").trim().to_string())
}
