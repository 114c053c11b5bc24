//! Rendering an animation: frame `k` is the scene evaluated with
//! `time = k`. Shared by the command line (`--anim`) and the session
//! (`:anim`).
//!
//! Three savings, each leaving every frame byte-identical to rendering it
//! alone:
//! - a scene that does not depend on `time` is rendered once for all frames;
//! - later frames evaluate only what depends on `time`, and reuse the first
//!   frame's static geometry and its BVH ([`SceneGeometry::with_static`]);
//! - when only bounded objects move, frames are evaluated a window at a time
//!   and each frame traces only the pixels a moving object may have changed
//!   ([`FrameReuse`]).

use std::ops::RangeInclusive;
use std::sync::Arc;

use image::RgbImage;

use crate::render::{self, Cancelled, FrameReuse, RenderControl, RenderOptions, RenderStats, SceneGeometry};
use crate::scene::Scene;

/// Most frames evaluated ahead of rendering for [`FrameReuse`]: a pixel is
/// traced at least once per window.
pub const WINDOW_FRAMES: usize = 256;

/// Most primitives depending on `time` held over a window (their geometry
/// is kept until the window is rendered).
pub const WINDOW_TIMED_PRIMITIVES: usize = 1_000_000;

/// Why an animation stopped.
#[derive(Debug)]
pub enum AnimationError<E> {
    /// Evaluating a frame, or taking a rendered one, failed. The frames
    /// before it were all handed over.
    Failed(E),
    /// The render was cancelled through [`RenderControl::cancel`].
    Cancelled,
}

impl<E> From<Cancelled> for AnimationError<E> {
    fn from(_: Cancelled) -> AnimationError<E> {
        AnimationError::Cancelled
    }
}

/// Renders the frames `frames` in order and hands each image to `sink`.
///
/// `evaluate(k, skip_static)` gives the scene at `time = k`; with
/// `skip_static` it may leave out the primitives that do not depend on
/// `time` (the first frame's are reused). Progress counts every pixel of
/// every frame, copied or traced. Returns the rays traced over all frames.
pub fn render_animation<E>(
    frames: RangeInclusive<u32>,
    mut evaluate: impl FnMut(u32, bool) -> Result<Scene, E>,
    options: &RenderOptions,
    control: &RenderControl,
    mut sink: impl FnMut(u32, RgbImage) -> Result<(), E>,
) -> Result<RenderStats, AnimationError<E>> {
    let (start, end) = (*frames.start(), *frames.end());
    let mut total = RenderStats::default();
    if start > end {
        return Ok(total);
    }
    let first = evaluate(start, false).map_err(AnimationError::Failed)?;
    let first_prepared = SceneGeometry::new(&first);
    if !first.depends_on_time() {
        let (image, stats) = render::render(&first, &first_prepared, options, control)?;
        sink(start, image.clone()).map_err(AnimationError::Failed)?;
        let per_frame = u64::from(options.width) * u64::from(options.height);
        for k in (start..=end).skip(1) {
            if let Some(progress) = control.progress {
                progress(per_frame);
            }
            sink(k, image.clone()).map_err(AnimationError::Failed)?;
        }
        return Ok(stats);
    }
    let reuse = FrameReuse::applies(&first, &first_prepared, options);
    let static_part = Arc::clone(first_prepared.static_part());
    let mut pending = Some((start, first, first_prepared));
    // The next frame to evaluate; u64 so that it can pass the last u32.
    let mut next = u64::from(start) + 1;
    let end = u64::from(end);
    loop {
        // Gather a window: frames that frame reuse can take together, or a
        // single frame that it cannot.
        let mut window: Vec<(u32, Scene, SceneGeometry)> = Vec::new();
        let mut timed = 0;
        let mut failure = None;
        let mut together = reuse;
        loop {
            let (k, scene, prepared) = match pending.take() {
                Some(frame) => frame,
                None if next > end => break,
                None => match evaluate(next as u32, true) {
                    Ok(scene) => {
                        let prepared = SceneGeometry::with_static(Arc::clone(&static_part), &scene.timed_primitives);
                        next += 1;
                        ((next - 1) as u32, scene, prepared)
                    }
                    Err(e) => {
                        failure = Some(e);
                        break;
                    }
                },
            };
            let fits = reuse && FrameReuse::holds_for(&scene, &prepared);
            if !fits && !window.is_empty() {
                pending = Some((k, scene, prepared));
                break;
            }
            together &= fits;
            timed += scene.timed_primitives.len();
            window.push((k, scene, prepared));
            if !together || window.len() >= WINDOW_FRAMES || timed >= WINDOW_TIMED_PRIMITIVES {
                break;
            }
        }
        render_window(&window, together, options, control, &mut total, &mut sink)?;
        if let Some(e) = failure {
            return Err(AnimationError::Failed(e));
        }
        if pending.is_none() && next > end {
            return Ok(total);
        }
    }
}

/// Renders the frames of one window in order, with [`FrameReuse`] when
/// `together`, and hands them to `sink`.
fn render_window<E>(
    window: &[(u32, Scene, SceneGeometry)],
    together: bool,
    options: &RenderOptions,
    control: &RenderControl,
    total: &mut RenderStats,
    sink: &mut impl FnMut(u32, RgbImage) -> Result<(), E>,
) -> Result<(), AnimationError<E>> {
    let mut reuse = together.then(|| FrameReuse::new(window.iter().map(|(_, _, prepared)| prepared), options));
    for (k, scene, prepared) in window {
        let (image, stats) = match &mut reuse {
            Some(reuse) => reuse.render(scene, prepared, control)?,
            None => render::render(scene, prepared, options, control)?,
        };
        *total += stats;
        sink(*k, image).map_err(AnimationError::Failed)?;
    }
    Ok(())
}
