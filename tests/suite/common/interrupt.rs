//! Interrupting the binary with a real SIGINT at a known moment, and
//! looking at what it left in a folder.

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// How long a wait for the binary to reach a point may take before the
/// test fails instead of hanging (the binary may have stopped early).
const GIVE_UP: Duration = Duration::from_secs(300);

/// Polls `reached` every `every` until it holds; panics, saying `what`
/// was awaited, after [`GIVE_UP`].
fn wait_until(what: &str, every: Duration, reached: impl Fn() -> bool) {
    let start = Instant::now();
    while !reached() {
        assert!(start.elapsed() < GIVE_UP, "gave up waiting for {what}");
        std::thread::sleep(every);
    }
}

/// The names in `dir`, sorted.
pub fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("the folder is readable")
        .map(|entry| entry.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Whether `name` is one of the temporary files that writes go through.
pub fn is_temporary(name: &str) -> bool {
    name.starts_with(".rayrepl-") && name.ends_with(".tmp")
}

/// Waits until a file is being written in `dir`: a temporary file with
/// bytes in it (the check before a render makes an empty one).
pub fn wait_for_a_write(dir: &Path) {
    let written = |name: &String| std::fs::metadata(dir.join(name)).is_ok_and(|m| m.len() > 0);
    let writing = || names_in(dir).iter().any(|name| is_temporary(name) && written(name));
    wait_until("a file being written", Duration::from_millis(1), writing);
}

/// Waits until `dir` holds at least `count` files ending in `suffix`.
pub fn wait_for_files(dir: &Path, suffix: &str, count: usize) {
    let present = || names_in(dir).iter().filter(|name| name.ends_with(suffix)).count() >= count;
    wait_until(&format!("{count} {suffix} files"), Duration::from_millis(5), present);
}

/// Sends SIGINT (what Ctrl-C sends) to the process `pid`.
pub fn interrupt(pid: u32) {
    let sent = Command::new("kill").args(["-INT", &pid.to_string()]).status().expect("kill runs");
    assert!(sent.success(), "the signal is sent");
}
