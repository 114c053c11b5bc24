//! The one place the program reads the time. It only ever asks how long
//! something took (a render, an input being typed, whether to show a
//! progress bar yet), so that is all this module offers: a platform whose
//! standard library has no clock (WebAssembly in a browser) needs to supply
//! this one type and nothing else.

use std::time::{Duration, Instant};

/// Measures how long has passed since it was started.
#[derive(Debug, Clone, Copy)]
pub struct Stopwatch(Instant);

impl Stopwatch {
    /// A stopwatch started now.
    pub fn start() -> Stopwatch {
        Stopwatch(Instant::now())
    }

    /// The time since [`Stopwatch::start`].
    pub fn elapsed(&self) -> Duration {
        self.0.elapsed()
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// Every `.rs` file under `dir`, with its text.
    fn sources(dir: &Path, found: &mut Vec<(String, String)>) {
        for entry in std::fs::read_dir(dir).expect("src is readable").flatten() {
            let path = entry.path();
            if path.is_dir() {
                sources(&path, found);
            } else if path.extension().is_some_and(|ext| ext == "rs") {
                let text = std::fs::read_to_string(&path).expect("a source file is text");
                found.push((path.display().to_string(), text));
            }
        }
    }

    #[test]
    fn the_time_is_read_here_only() {
        let mut found = Vec::new();
        sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut found);
        for (path, text) in found.iter().filter(|(path, _)| !path.ends_with("clock.rs")) {
            let reads = ["Instant::now", "SystemTime::now"].iter().any(|call| text.contains(call));
            assert!(!reads, "{path} reads the time itself: use clock::Stopwatch");
        }
    }
}
