//! Spreading an animation over processes, as the guide shows it: GNU
//! parallel runs several `rayrepl --frames A..B` at once, and the frames
//! they write are byte for byte those of one run. Skipped, saying so, when
//! `parallel` is not installed.

use std::path::Path;
use std::process::{Command, Stdio};

/// The frames written into `dir`, by name, with their bytes.
fn frames_in(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut frames: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .expect("the folder")
        .map(|entry| {
            let entry = entry.expect("an entry");
            (entry.file_name().to_string_lossy().into_owned(), std::fs::read(entry.path()).expect("a frame"))
        })
        .collect();
    frames.sort();
    frames
}

#[test]
fn frames_split_over_processes_by_gnu_parallel_equal_one_run() {
    let has_parallel = Command::new("parallel").arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status();
    if !has_parallel.is_ok_and(|status| status.success()) {
        eprintln!("skipped frames_split_over_processes_by_gnu_parallel_equal_one_run: GNU `parallel` is not installed");
        return;
    }
    let rayrepl = assert_cmd::cargo::cargo_bin("rayrepl");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/solar.ray");
    let work = tempfile::tempdir().expect("temporary folder");
    let (one, split) = (work.path().join("one"), work.path().join("split"));
    std::fs::create_dir(&one).expect("a folder");
    std::fs::create_dir(&split).expect("a folder");
    // Fractional times, so that a job computes its frames' times from --anim, not from its range.
    let common = "--width 64 --height 48 --anim 12 --time-start 2 --time-step 0.5 -q";
    let single = Command::new("sh")
        .arg("-c")
        .arg(format!("'{}' '{}' {common} -o '{}/solar.png'", rayrepl.display(), scene.display(), one.display()))
        .status()
        .expect("sh runs");
    assert!(single.success());
    // The guide's command (docs/guide/scale-out.md): four jobs of three frames, at most four at once.
    let jobs = format!(
        "seq 0 3 | parallel -j 4 \"'{}' '{}' {common} --frames \\$(({{}}*3+1))..\\$(({{}}*3+3)) -o '{}/solar.png'\"",
        rayrepl.display(),
        scene.display(),
        split.display()
    );
    let output = Command::new("sh").arg("-c").arg(&jobs).output().expect("sh runs");
    assert!(output.status.success(), "{jobs}\n{}", String::from_utf8_lossy(&output.stderr));
    let (one, split) = (frames_in(&one), frames_in(&split));
    assert_eq!(one.len(), 12);
    assert_eq!(one.iter().map(|(name, _)| name.as_str()).collect::<Vec<_>>()[..2], ["solar0001.png", "solar0002.png"]);
    for ((name, bytes), (split_name, split_bytes)) in one.iter().zip(&split) {
        assert_eq!(name, split_name);
        assert!(bytes == split_bytes, "{name} differs between one run and the split");
    }
    assert_eq!(split.len(), 12);
}
