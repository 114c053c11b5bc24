//! Running the binary with a cap on its memory, for the inputs that would
//! otherwise exhaust it.

use std::io::Write;
use std::process::{Command, Output, Stdio};

/// The address space the binary may use, in KiB (`ulimit -v`): room for
/// a scene at the default primitive limit and for the stack of the main
/// thread, far from what an unbounded program would take.
pub const MEMORY_KIB: u64 = 6 << 20;

/// Runs `rayrepl ARGS` with its memory capped at [`MEMORY_KIB`] and `stdin`
/// on its standard input; a failed allocation would end it by an abort.
pub fn run_limited(args: &[&str], stdin: &str) -> Output {
    run_limited_to(MEMORY_KIB, args, stdin)
}

/// Runs `rayrepl ARGS` as [`run_limited`] does, its memory capped at
/// `memory_kib` KiB.
pub fn run_limited_to(memory_kib: u64, args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {memory_kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_rayrepl"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the shell starts");
    let mut input = child.stdin.take().expect("stdin is piped");
    let stdin = stdin.to_string();
    // Written from another thread, so that a long message on stderr cannot
    // block the binary while this one waits for it to read; the binary may
    // stop before reading everything, so a closed pipe is fine.
    let writer = std::thread::spawn(move || {
        let _ = input.write_all(stdin.as_bytes());
    });
    let output = child.wait_with_output().expect("the binary runs");
    writer.join().expect("the writer does not panic");
    output
}
