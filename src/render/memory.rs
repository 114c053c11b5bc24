//! Whether the memory a render needs can be had, asked before it is
//! taken: a scene too large for the memory the process may use is refused
//! with a message (how many primitives, about how much memory), not ended
//! by the abort of a failed allocation halfway through building its tree.
//!
//! The figures are measured (`/usr/bin/time -v` and `ulimit -v` on rotated
//! boxes and spheres, see docs/language.md section 10): a render takes
//! about [`RENDER_BYTES`] per primitive (of which the evaluated scene holds
//! about [`EVALUATE_BYTES`]) and [`PIXEL_BYTES`] or
//! [`ADAPTIVE_PIXEL_BYTES`] per pixel.

use std::fmt;

use super::options::RenderOptions;
use crate::scene::Scene;

/// Bytes a primitive takes in the evaluated scene (measured: about 178).
pub const EVALUATE_BYTES: u64 = 180;

/// Bytes a primitive takes to render, the evaluated scene included
/// (measured: about 490 at the peak of the resident memory, 485 for
/// rotated boxes and 450 for spheres).
pub const RENDER_BYTES: u64 = 500;

/// Bytes a pixel takes in a plain render: the image.
pub const PIXEL_BYTES: u64 = 3;

/// Bytes a pixel takes with adaptive anti-aliasing: the image, the 1-sample
/// image and what each of its pixels saw (measured: about 36).
pub const ADAPTIVE_PIXEL_BYTES: u64 = 40;

/// Not enough memory to render a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutOfMemory {
    /// The primitives of the scene.
    pub primitives: usize,
    /// About how many bytes the render would need in all.
    pub needed: u64,
}

impl fmt::Display for OutOfMemory {
    /// "not enough memory for 8400000 primitives: about 4.5 GB needed".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let gigabytes = self.needed as f64 / 1e9;
        let amount = if gigabytes < 10.0 { format!("{gigabytes:.2}") } else { format!("{gigabytes:.0}") };
        let amount = amount.trim_end_matches('0').trim_end_matches('.');
        let noun = if self.primitives == 1 { "primitive" } else { "primitives" };
        write!(f, "not enough memory for {} {noun}: about {amount} GB needed", self.primitives)
    }
}

impl std::error::Error for OutOfMemory {}

/// Checks that the memory to build `scene`'s geometry and render it with
/// `options` can be had: reserves the estimated growth (untouched, so it
/// costs no page) and gives it back at once. Fails when the allocator
/// refuses it, as it does past `ulimit -v` or what the system can commit.
pub fn reserve_for(scene: &Scene, options: &RenderOptions) -> Result<(), OutOfMemory> {
    let primitives = scene.primitives.len() + scene.timed_primitives.len();
    let pixels = u64::from(options.width) * u64::from(options.height);
    let per_pixel = if options.is_adaptive() { ADAPTIVE_PIXEL_BYTES } else { PIXEL_BYTES };
    let images = pixels.saturating_mul(per_pixel);
    let count = primitives as u64;
    let growth = count.saturating_mul(RENDER_BYTES - EVALUATE_BYTES).saturating_add(images);
    let mut room: Vec<u8> = Vec::new();
    match usize::try_from(growth).ok().map(|growth| room.try_reserve_exact(growth)) {
        Some(Ok(())) => Ok(()),
        _ => {
            // What the process holds already, where the system says it;
            // else the estimate of what the scene holds.
            let held = address_space().unwrap_or(count.saturating_mul(EVALUATE_BYTES));
            Err(OutOfMemory { primitives, needed: held.saturating_add(growth) })
        }
    }
}

/// The address space the process uses, in bytes, where the system tells
/// it (`VmSize` in `/proc/self/status` on Linux): what `ulimit -v` limits.
fn address_space() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find_map(|line| line.strip_prefix("VmSize:"))?;
    let kib: u64 = line.trim().strip_suffix("kB")?.trim().parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_message_gives_the_primitives_and_the_memory() {
        let message = |primitives, needed| OutOfMemory { primitives, needed }.to_string();
        assert_eq!(message(8_400_000, 4_536_000_000), "not enough memory for 8400000 primitives: about 4.54 GB needed");
        assert_eq!(message(300_000, 162_000_000), "not enough memory for 300000 primitives: about 0.16 GB needed");
        assert_eq!(message(1, 12_000_000_000), "not enough memory for 1 primitive: about 12 GB needed");
        assert_eq!(message(2, 3_000_000_000), "not enough memory for 2 primitives: about 3 GB needed");
    }

    #[test]
    fn an_impossible_amount_is_refused() {
        let scene = crate::lang::Interpreter::new(0.0, crate::lang::Limits::default()).into_scene();
        assert_eq!(reserve_for(&scene, &RenderOptions::DEFAULT), Ok(()));
        // 1.8e19 pixels: past any address space.
        let huge = RenderOptions { width: u32::MAX, height: u32::MAX, ..RenderOptions::DEFAULT };
        assert_eq!(
            reserve_for(&scene, &huge).map_err(|refused| (refused.primitives, refused.needed)),
            Err((0, u64::MAX))
        );
    }
}
