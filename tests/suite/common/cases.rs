//! The scenes of `tests/cases/`: valid ones start with
//! `# expect: spheres=N planes=N boxes=N lights=N`, invalid ones with
//! `# expect-error: line L`.

use std::path::{Path, PathBuf};

/// The `.ray` files of one folder of `tests/cases`, sorted.
pub fn cases(folder: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cases").join(folder);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/cases exists")
        .map(|entry| entry.expect("readable entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ray"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no cases in {}", dir.display());
    files
}
