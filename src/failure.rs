//! How the program says that it, rather than a scene, failed: one line on
//! standard error after its name (`rayrepl: cannot read ...`). Every such
//! line is written here, so the name is written in one place.

use std::fmt::Display;

/// The name in front of the program's own failures.
const PROGRAM: &str = "rayrepl";

/// Writes `message` on standard error as a failure of the program.
pub fn report_failure(message: impl Display) {
    eprintln!("{PROGRAM}: {}", message.to_string().trim_end());
}
