//! The evaluation's stack: grown on demand in segments, so that deep
//! recursion in a program (or deeply nested constructs) never overflows the
//! native stack, and bounded, so that a recursion deeper than the memory
//! allows (with `--max-calls` raised) is an error, never a crash.

use std::cell::Cell;

use super::errors::{EvalError, EvalResult};
use crate::lang::diagnostic::Diagnostic;
use crate::lang::source::Span;

/// Free native stack below which a nested evaluation switches to a new segment.
const RED_ZONE: usize = 256 * 1024;

/// Size of each new native stack segment.
const STACK_SEGMENT: usize = 8 * 1024 * 1024;

/// Memory left free beside a new segment, for the work of reporting the
/// error once the stack is full (the chain of calls, the message).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const HEADROOM: usize = 64 * 1024 * 1024;

thread_local! {
    /// How many segments the evaluations of this thread use now.
    static SEGMENTS: Cell<usize> = const { Cell::new(0) };
}

/// Runs `f` (evaluating the construct at `span()`) on a fresh stack segment
/// if the current one is nearly full; the error "recursion too deep for
/// the memory" if the segments would pass half of the machine's memory, or
/// the memory the process may still take (`ulimit -v`) could not hold one
/// more.
#[inline]
pub(crate) fn grow<R>(span: impl FnOnce() -> Span, f: impl FnOnce() -> EvalResult<R>) -> EvalResult<R> {
    if stacker::remaining_stack().is_some_and(|left| left >= RED_ZONE) { f() } else { grow_segment(span, f) }
}

/// Runs `f` on a new segment, as [`grow`] says.
#[cold]
#[inline(never)]
fn grow_segment<R>(span: impl FnOnce() -> Span, f: impl FnOnce() -> EvalResult<R>) -> EvalResult<R> {
    if stacker::remaining_stack().is_none() {
        // Where the stack's end is unknown, stacker finds it on a segment
        // of its own, or runs `f` where it is.
        return stacker::maybe_grow(RED_ZONE, STACK_SEGMENT, f);
    }
    let segments = SEGMENTS.get();
    if segments >= most_segments() || !segment_fits() {
        return Err(too_deep_for_the_memory(span()));
    }
    SEGMENTS.set(segments + 1);
    let result = stacker::grow(STACK_SEGMENT, f);
    SEGMENTS.set(segments);
    result
}

/// The most segments the evaluation may use: half of the machine's memory.
fn most_segments() -> usize {
    memory_bytes() / 2 / STACK_SEGMENT
}

/// The machine's memory, in bytes.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn memory_bytes() -> usize {
    // SAFETY: `sysconf` only reads a system setting.
    let (pages, page) = unsafe { (libc::sysconf(libc::_SC_PHYS_PAGES), libc::sysconf(libc::_SC_PAGESIZE)) };
    match (usize::try_from(pages), usize::try_from(page)) {
        (Ok(pages), Ok(page)) if pages > 0 && page > 0 => pages.saturating_mul(page),
        _ => FALLBACK_MEMORY,
    }
}

/// Elsewhere the memory is taken to be this.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn memory_bytes() -> usize {
    FALLBACK_MEMORY
}

/// The machine's memory where it cannot be asked.
const FALLBACK_MEMORY: usize = 8 << 30;

/// Whether the address space can take one more segment with room to spare:
/// a segment that cannot be mapped would end the program.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn segment_fits() -> bool {
    let size = STACK_SEGMENT + HEADROOM;
    // SAFETY: maps fresh inaccessible pages, nowhere in particular, and
    // unmaps them at once; nothing else refers to them.
    unsafe {
        let probe = libc::mmap(
            std::ptr::null_mut(),
            size,
            libc::PROT_NONE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS | libc::MAP_NORESERVE,
            -1,
            0,
        );
        if probe == libc::MAP_FAILED {
            return false;
        }
        libc::munmap(probe, size);
    }
    true
}

/// Elsewhere only the share of the memory bounds the segments.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn segment_fits() -> bool {
    true
}

/// The error of a construct at `span` that needs more stack than the memory
/// allows; the calls add themselves to its chain as it unwinds.
#[cold]
#[inline(never)]
fn too_deep_for_the_memory(span: Span) -> Box<EvalError> {
    let diagnostic = Diagnostic::error(span, "recursion too deep for the memory: its stack would not fit")
        .with_code("recursion-too-deep-for-memory")
        .with_label("the stack ran out of memory here")
        .with_help("check that the recursion stops (an `if` whose condition becomes false), or recurse less deeply");
    Box::new(EvalError { diagnostic, chain: Some(Vec::new()) })
}
