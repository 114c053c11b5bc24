//! A quick check of parsing speed; run it in release:
//! `cargo test --release --test speed -- --ignored --nocapture`.

use std::time::{Duration, Instant};

use rayrepl::lang::{SourceId, parse_items};

#[test]
#[ignore = "a timing check, meaningful only in release builds"]
fn a_million_lines_parse_in_under_a_second() {
    let text = "let x = 1 + 2 * y\n".repeat(1_000_000);
    let (cpu, start) = (cpu_time(), Instant::now());
    let program = parse_items(SourceId(0), &text).expect("valid");
    let (parsed, parsed_cpu) = (start.elapsed(), cpu_time().saturating_sub(cpu));
    assert_eq!(program.items.len(), 1_000_000);
    drop(program);
    let total = start.elapsed();
    println!("parsed 1M lines in {parsed:?} wall, {parsed_cpu:?} CPU ({total:?} wall with dropping the AST)");
    // On a busy machine the wall time mostly measures the other processes;
    // the CPU time, where Linux gives it, is the fair measure.
    let measured = if parsed_cpu > Duration::ZERO { parsed_cpu } else { parsed };
    if !cfg!(debug_assertions) {
        assert!(measured.as_secs_f64() < 1.0, "parsing took {measured:?}");
    }
}

/// CPU time this thread has run so far, where Linux tells it (the wall
/// time is unreliable on a busy machine).
fn cpu_time() -> Duration {
    // The first field of schedstat is the time spent on the CPU, in nanoseconds.
    let schedstat = std::fs::read_to_string("/proc/thread-self/schedstat").unwrap_or_default();
    let nanos = schedstat.split_whitespace().next().and_then(|n| n.parse().ok()).unwrap_or(0);
    Duration::from_nanos(nanos)
}

#[test]
#[ignore = "for profiling under valgrind: parses 100k lines once"]
fn probe_100k_lines() {
    let text = "let x = 1 + 2 * y\n".repeat(100_000);
    let program = parse_items(SourceId(0), &text).expect("valid");
    assert_eq!(program.items.len(), 100_000);
}
