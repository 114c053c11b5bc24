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
    use crate::source_tree::rust_sources;

    #[test]
    fn the_time_is_read_here_only() {
        for (path, text) in rust_sources().iter().filter(|(path, _)| !path.ends_with("clock.rs")) {
            let reads = ["Instant::now", "SystemTime::now"].iter().any(|call| text.contains(call));
            assert!(!reads, "{} reads the time itself: use clock::Stopwatch", path.display());
        }
    }
}
