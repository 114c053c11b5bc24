//! The `rayrepl` binary: parses the command line and hands over to the
//! library. Nothing in the library depends on the size of this thread's
//! stack: deep programs are evaluated on stacks grown on demand and dropped
//! without recursion.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::process::ExitCode;

use clap::Parser;
use rayrepl::cli::{Cli, translate_legacy_args};
use rayrepl::process::failure::{report_failure, unwritten_messages};

fn main() -> ExitCode {
    keep_freed_memory();
    let cli = Cli::parse_from(translate_legacy_args(std::env::args_os()));
    match catch_unwind(AssertUnwindSafe(|| rayrepl::app::run(cli))) {
        // A message lost on a full disk fails the run (failure.rs).
        Ok(code) if code == ExitCode::SUCCESS && unwritten_messages() => ExitCode::FAILURE,
        Ok(code) => code,
        Err(_) => {
            report_failure("internal error (please report it with the input that caused it)");
            ExitCode::from(2)
        }
    }
}

/// Has glibc's allocator keep and reuse freed memory: by default it gives
/// every block from 128 KiB up pages of its own, fresh from the kernel, and
/// returns them when freed, so a big scene's tree build (whose lists come
/// and go) spent a quarter of its time in the kernel clearing new pages.
/// Blocks from 64 MiB up still get their own pages, and at most 128 MiB of
/// freed memory is kept.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn keep_freed_memory() {
    // SAFETY: `mallopt` only sets two thresholds of the allocator; it is
    // called first thing, before any other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 64 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 128 << 20);
    }
}

/// Other allocators keep their own policy.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn keep_freed_memory() {}
