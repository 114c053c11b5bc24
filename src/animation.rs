//! Rendering an animation: frame `k` is the scene evaluated at the time its
//! timeline gives frame `k` (`time = k` unless `--time-start` or
//! `--time-step` say otherwise). Shared by the command line (`--anim`) and the session
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

use crate::render::intersect::Aabb;
use crate::render::{
    self, Cancelled, FrameReuse, Geometry, OutOfMemory, RenderControl, RenderOptions, RenderStats, SceneGeometry,
};
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
    /// The memory to render the first frame cannot be had.
    OutOfMemory(OutOfMemory),
}

impl<E> From<Cancelled> for AnimationError<E> {
    fn from(_: Cancelled) -> AnimationError<E> {
        AnimationError::Cancelled
    }
}

/// Renders the frames `frames` in order and hands each image to `sink`.
///
/// `evaluate(k, skip_static)` gives the scene of frame `k`; with
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
    render::reserve_for(&first, options).map_err(AnimationError::OutOfMemory)?;
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
    let reuse = FrameReuse::applies(&first, options);
    let static_part = Arc::clone(first_prepared.static_part());
    // A frame waiting for a window, with the boxes of its moving objects,
    // held in no more memory than they need; without frame reuse a window
    // is one frame, and the boxes are not needed.
    let waiting = |k: u32, mut scene: Scene| {
        if !reuse {
            return Frame { k, scene, bounds: Vec::new() };
        }
        scene.timed_primitives.shrink_to_fit();
        scene.lights.shrink_to_fit();
        let mut bounds = first_prepared.bounds_of(&scene.timed_primitives);
        bounds.shrink_to_fit();
        Frame { k, scene, bounds }
    };
    let mut pending = Some(waiting(start, first));
    // The next frame to evaluate; u64 so that it can pass the last u32.
    let mut next = u64::from(start) + 1;
    let end = u64::from(end);
    loop {
        // Gather a window: frames that frame reuse can take together, or a
        // single frame that it cannot.
        let mut window: Vec<Frame> = Vec::new();
        let mut timed = 0;
        let mut failure = None;
        let mut together = reuse;
        loop {
            let frame = match pending.take() {
                Some(frame) => frame,
                None if next > end => break,
                None => match evaluate(next as u32, true) {
                    Ok(scene) => {
                        next += 1;
                        waiting((next - 1) as u32, scene)
                    }
                    Err(e) => {
                        failure = Some(e);
                        break;
                    }
                },
            };
            let fits = reuse && FrameReuse::holds_for(&frame.scene);
            if !fits && !window.is_empty() {
                pending = Some(frame);
                break;
            }
            together &= fits;
            timed += frame.scene.timed_primitives.len();
            window.push(frame);
            if !together || window.len() >= WINDOW_FRAMES || timed >= WINDOW_TIMED_PRIMITIVES {
                break;
            }
        }
        render_window(&window, &static_part, together, options, control, &mut total, &mut sink)?;
        if let Some(e) = failure {
            return Err(AnimationError::Failed(e));
        }
        if pending.is_none() && next > end {
            return Ok(total);
        }
    }
}

/// A frame evaluated and waiting in a window: its number, its scene and the
/// boxes of its moving objects. Its geometry is built when it is rendered,
/// so a window holds little more than the scene.
struct Frame {
    k: u32,
    scene: Scene,
    bounds: Vec<Aabb>,
}

/// Renders the frames of one window in order, over the shared
/// `static_part`, with [`FrameReuse`] when `together`, and hands them to
/// `sink`.
fn render_window<E>(
    window: &[Frame],
    static_part: &Arc<Geometry>,
    together: bool,
    options: &RenderOptions,
    control: &RenderControl,
    total: &mut RenderStats,
    sink: &mut impl FnMut(u32, RgbImage) -> Result<(), E>,
) -> Result<(), AnimationError<E>> {
    let mut reuse = together.then(|| FrameReuse::new(window.iter().map(|frame| frame.bounds.as_slice()), options));
    for Frame { k, scene, .. } in window {
        let prepared = SceneGeometry::with_static(Arc::clone(static_part), &scene.timed_primitives);
        let (image, stats) = match &mut reuse {
            Some(reuse) => reuse.render(scene, &prepared, control)?,
            None => render::render(scene, &prepared, options, control)?,
        };
        *total += stats;
        sink(*k, image).map_err(AnimationError::Failed)?;
    }
    Ok(())
}
