//! Runs every file of `tests/cases/` through `rayrepl --check`.
//!
//! Valid files start with `# expect: spheres=N planes=N boxes=N lights=N`;
//! invalid ones with `# expect-error: line L`. An invalid file must exit with
//! status 1 and a diagnostic that points at line L; no file may panic. The
//! comment lines at the top of an invalid file may add `# expect-help: H`
//! (the diagnostic's `help:` line is H) and `# expect-text: T` (the
//! diagnostic contains T, a label for example).

use std::path::Path;
use std::process::Command;

use crate::common::cases::cases;

/// The value after `prefix` on the file's first line (after a byte-order mark, if any).
fn expectation(path: &Path, prefix: &str) -> String {
    let text = std::fs::read_to_string(path).expect("case is readable");
    let first = text.trim_start_matches('\u{feff}').lines().next().unwrap_or_default();
    first.strip_prefix(prefix).unwrap_or_else(|| panic!("{} lacks `{prefix}`", path.display())).trim().to_owned()
}

/// What the diagnostic must contain, from the `# expect-help:` and
/// `# expect-text:` lines among the comments at the top of the file.
fn expected_texts(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("case is readable");
    let header = text.lines().take_while(|line| line.starts_with('#'));
    header
        .filter_map(|line| {
            let help = line.strip_prefix("# expect-help: ").map(|help| format!("= help: {help}\n"));
            help.or_else(|| line.strip_prefix("# expect-text: ").map(str::to_owned))
        })
        .collect()
}

/// Runs `rayrepl --check` on `path`: exit code, stdout, stderr.
fn check(path: &Path) -> (Option<i32>, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_rayrepl")).arg("--check").arg(path).output().expect("binary runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stdout).into(),
        String::from_utf8_lossy(&output.stderr).into(),
    )
}

/// "3 spheres, 1 plane, 0 boxes, 2 lights" as "spheres=3 planes=1 boxes=0 lights=2".
fn normalise_summary(summary: &str) -> String {
    let counts: Vec<&str> = summary
        .rsplit_once(": ")
        .map_or(summary, |(_, counts)| counts)
        .trim()
        .split(", ")
        .map(|part| part.split(' ').next().unwrap_or_default())
        .collect();
    match counts.as_slice() {
        [s, p, b, l] => format!("spheres={s} planes={p} boxes={b} lights={l}"),
        _ => format!("unreadable summary: {summary}"),
    }
}

#[test]
fn valid_cases_evaluate_with_the_expected_counts() {
    let mut failures = Vec::new();
    for path in cases("valid") {
        let expected = expectation(&path, "# expect:");
        let (code, stdout, stderr) = check(&path);
        let got = normalise_summary(&stdout);
        if code != Some(0) || got != expected {
            failures.push(format!("{}: expected {expected}, got {got} (exit {code:?})\n{stderr}", path.display()));
        }
    }
    assert!(failures.is_empty(), "{} valid case(s) failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn invalid_cases_fail_at_the_expected_line() {
    let mut failures = Vec::new();
    for path in cases("invalid") {
        let expected = expectation(&path, "# expect-error: line");
        let (code, _, stderr) = check(&path);
        let name = path.display().to_string();
        let location = stderr
            .lines()
            .find_map(|line| line.split_once(&format!("{name}:")).map(|(_, rest)| rest.to_owned()))
            .unwrap_or_default();
        let line = location.split(':').next().unwrap_or_default();
        let clear = stderr.starts_with("error: ") && !stderr.contains("panicked");
        let missing: Vec<String> = expected_texts(&path).into_iter().filter(|text| !stderr.contains(text)).collect();
        if code != Some(1) || line != expected || !clear || !missing.is_empty() {
            failures.push(format!(
                "{name}: expected line {expected} and {missing:?}, got `{location}` (exit {code:?})\n{stderr}"
            ));
        }
    }
    assert!(failures.is_empty(), "{} invalid case(s) failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn every_bundled_scenario_is_valid() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    for entry in std::fs::read_dir(dir).expect("scenarios/ exists") {
        let path = entry.expect("readable entry").path();
        let (code, _, stderr) = check(&path);
        assert_eq!(code, Some(0), "{}:\n{stderr}", path.display());
    }
}
