//! Which compiled form of the renderer's hot code runs: the target's
//! baseline, or on x86_64 a form compiled for AVX2 (the pixel loop with
//! everything inlined into it, and the tree's walks with their node test in
//! AVX2 intrinsics), chosen once at run time.
//!
//! The forms give the same bytes: they run the same floating-point
//! operations in the same order, and Rust never fuses a multiplication
//! and an addition it was not asked to fuse, so AVX2 code rounds as SSE2
//! code does (`tests/suite/cli.rs` renders with both and compares).

use std::sync::OnceLock;

/// The environment variable that, set to `portable`, makes the baseline
/// form run on any processor: to compare the forms' speed or bytes. Any
/// other value, or none, runs the widest form the processor has.
pub const ISA_VARIABLE: &str = "RAYREPL_ISA";

/// A compiled form of the renderer's hot code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// The baseline of the target (SSE2 on x86_64, NEON on aarch64).
    Portable,
    /// AVX2.
    #[cfg(target_arch = "x86_64")]
    Avx2,
}

impl Isa {
    /// Its name, as `--stats` prints it.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Portable => "portable",
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => "AVX2",
        }
    }

    /// The form that runs: the widest this processor has, or the portable
    /// one when [`ISA_VARIABLE`] asks for it.
    pub fn chosen() -> Isa {
        static CHOSEN: OnceLock<Isa> = OnceLock::new();
        *CHOSEN.get_or_init(|| {
            let portable = std::env::var(ISA_VARIABLE).is_ok_and(|v| v == Isa::Portable.name());
            if portable { Isa::Portable } else { *Isa::available().last().expect("the portable form always runs") }
        })
    }

    /// Every form this processor runs, the widest last.
    pub fn available() -> Vec<Isa> {
        #[allow(unused_mut, reason = "only x86_64 has other forms")]
        let mut all = vec![Isa::Portable];
        #[cfg(target_arch = "x86_64")]
        {
            if is_x86_feature_detected!("avx2") {
                all.push(Isa::Avx2);
            }
        }
        all
    }
}
