//! The one place the program reads the time. It only ever asks how long
//! something took (a render, an input being typed, whether to show a
//! progress bar yet), so that is all this module offers: a platform whose
//! standard library has no clock (WebAssembly in a browser, where
//! `Instant::now` panics) supplies one function, [`supply_clock`], and
//! until it does every duration reads zero.

use std::sync::OnceLock;
use std::time::Duration;

/// Measures how long has passed since it was started.
#[derive(Debug, Clone, Copy)]
pub struct Stopwatch(Duration);

impl Stopwatch {
    /// A stopwatch started now.
    pub fn start() -> Stopwatch {
        Stopwatch(now())
    }

    /// The time since [`Stopwatch::start`].
    pub fn elapsed(&self) -> Duration {
        now().saturating_sub(self.0)
    }
}

/// The clock a platform supplies: the time since a moment of its choosing.
static SUPPLIED: OnceLock<fn() -> Duration> = OnceLock::new();

/// Makes `clock` (the time since a moment of its choosing, never going
/// back) the program's clock, for a platform whose standard library has
/// none (in a browser, `performance.now()`). Only the first call counts;
/// says whether this one did.
pub fn supply_clock(clock: fn() -> Duration) -> bool {
    SUPPLIED.set(clock).is_ok()
}

/// The time since a fixed moment: the supplied clock's, or else the
/// standard library's where it has one.
fn now() -> Duration {
    if let Some(clock) = SUPPLIED.get() {
        return clock();
    }
    #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
    {
        static FIRST_READ: OnceLock<std::time::Instant> = OnceLock::new();
        FIRST_READ.get_or_init(std::time::Instant::now).elapsed()
    }
    #[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
    Duration::ZERO
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source_tree::rust_sources;

    #[test]
    fn a_stopwatch_measures_what_passed() {
        let watch = Stopwatch::start();
        std::thread::sleep(Duration::from_millis(5));
        assert!(watch.elapsed() >= Duration::from_millis(5));
    }

    #[test]
    fn the_time_is_read_here_only() {
        for (path, text) in rust_sources().iter().filter(|(path, _)| !path.ends_with("clock.rs")) {
            let reads = ["Instant::now", "SystemTime::now"].iter().any(|call| text.contains(call));
            assert!(!reads, "{} reads the time itself: use clock::Stopwatch", path.display());
        }
    }
}
