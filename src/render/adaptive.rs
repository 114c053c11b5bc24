//! Where adaptive anti-aliasing spends its samples.
//!
//! A first pass traces one ray through the centre of each pixel and keeps,
//! besides its colour, a [`Glimpse`] of what that ray met. [`refinement_mask`]
//! then picks the pixels whose average may differ from their centre's
//! colour: an edge between two neighbours that saw different things, a
//! bend in the colour (a highlight), or an object small enough to hide
//! between centres. A second pass gives those all the samples.
//!
//! A refined pixel gets exactly the bytes of the uniform render with that
//! many samples; any other keeps the bytes of the 1-sample render.

use image::RgbImage;

use super::geometry::{SceneGeometry, SurfaceHit};
use super::intersect::Ray;
use super::options::{Cancelled, Region, RenderControl, RenderOptions, RenderStats};
use super::pixels::Pass;
use super::shade::{LightTerm, PathObserver};
use crate::scene::Scene;

/// What adaptive anti-aliasing learns from a pixel's centre ray besides
/// its colour, gathered along its path by the tracer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Glimpse {
    /// A hash of what the path saw: each surface it hit (the object, and
    /// the face of a flat one) and, at each, which lights reached it. Where
    /// two rays have equal signatures the colour between them is a smooth
    /// function of the position on the screen: it changes abruptly only
    /// where the object, the face, a shadow or a reflected object changes.
    pub signature: u64,
    /// The apparent size, in pixels, of the smallest object the path met
    /// while its weight (the product of the `ks` above it) was at least
    /// [`FINE_WEIGHT`]; infinite if none. Objects of a pixel or two can hide
    /// between the centres of neighbouring pixels.
    pub finest: f64,
    /// The width of the beam of rays through the pixel where the current
    /// ray starts (world units), and the angle it spreads by (radians).
    beam_width: f64,
    beam_spread: f64,
}

/// Reflections weighing less than this (at most 5 levels of a pixel's
/// byte) do not count for [`Glimpse::finest`].
pub const FINE_WEIGHT: f64 = 0.02;

impl Glimpse {
    /// The glimpse of a path not yet traced, from a camera whose pixels
    /// span `pixel_angle` radians.
    pub fn start(pixel_angle: f64) -> Glimpse {
        Glimpse { signature: 0, finest: f64::INFINITY, beam_width: 0.0, beam_spread: pixel_angle }
    }
}

impl PathObserver for Glimpse {
    /// Mixes what was hit into the signature and follows the beam through
    /// the pixel: it widens along the ray by its spread, and a curved mirror
    /// spreads it further by twice the turn of the normal across its
    /// footprint (a ray cone, as in texture filtering).
    #[inline(always)]
    fn hit(&mut self, ray: &Ray, hit: Option<&SurfaceHit>, weight: f64) {
        let Some(hit) = hit else {
            self.signature = mix(self.signature, u64::MAX);
            return;
        };
        self.signature = mix(self.signature, hit.surface);
        if hit.curvature == 0.0 {
            // A flat surface: planes have one normal, a box one per face.
            let n = hit.normal;
            self.signature =
                mix(self.signature, n.x.to_bits() ^ n.y.to_bits().rotate_left(21) ^ n.z.to_bits().rotate_left(42));
        }
        let beam = self.beam_width + self.beam_spread * hit.t;
        if weight >= FINE_WEIGHT {
            self.finest = self.finest.min(hit.width / beam);
        }
        // The footprint stretches by 1 / |N·V| along the surface; past
        // 20 times, the ray grazes the silhouette, an edge anyway.
        let footprint = beam / hit.normal.dot(ray.dir).abs().max(0.05);
        self.beam_spread += 2.0 * footprint * hit.curvature;
        self.beam_width = beam;
    }

    #[inline(always)]
    fn light(&mut self, term: LightTerm) {
        self.signature = mix(self.signature, u64::from(matches!(term, LightTerm::Lit { .. })));
    }
}

/// Mixes `value` into the hash `seed`: a multiply-rotate step, cheap, with
/// a chance of about 2^-64 that two different inputs collide.
#[inline(always)]
fn mix(seed: u64, value: u64) -> u64 {
    (seed ^ value).wrapping_mul(0x9E37_79B9_7F4A_7C15).rotate_left(29)
}

/// Adaptive anti-aliasing refines both pixels of a neighbouring pair whose
/// centre rays have different [`Glimpse::signature`]s when one of their
/// channels differs by more than this many 8-bit levels.
pub const ADAPTIVE_THRESHOLD: u8 = 2;

/// Adaptive anti-aliasing refines a pixel when, in one channel, the sum of
/// the absolute second differences of the 1-sample image across it
/// (horizontally and vertically) exceeds this many levels.
///
/// Where the colour `f` is smooth, its average over a pixel differs from its
/// value at the centre by about `(f_xx + f_yy) / 24` (the mean of `x^2` over
/// a unit square is 1/12): 6 levels of bend leave the centre a quarter of a
/// level off. Rounding the bytes adds at most 4 levels to the measure.
pub const CURVATURE_THRESHOLD: i32 = 6;

/// Adaptive anti-aliasing refines a pixel whose centre ray met an object
/// smaller than this many pixels ([`Glimpse::finest`]).
pub const FINE_DETAIL: f64 = 2.0;

/// The pixels adaptive anti-aliasing renders again with all samples (row
/// major, one flag per pixel), from `image` (a 1-sample render) and the
/// [`Glimpse`] of each pixel's ray:
///
/// - both pixels of a neighbouring pair (8-neighbours) whose signatures
///   differ and whose colours differ by more than [`ADAPTIVE_THRESHOLD`]
///   levels in a channel: an edge runs between their centres;
/// - a pixel across which the colour bends by more than
///   [`CURVATURE_THRESHOLD`]: a highlight, or detail between the centres;
/// - a pixel whose ray met an object smaller than [`FINE_DETAIL`] pixels.
///
/// A smooth gradient, however steep, is left at one sample: its average
/// over the pixel is its value at the centre.
pub fn refinement_mask(image: &RgbImage, glimpses: &[Glimpse]) -> Vec<bool> {
    let (width, height) = (image.width() as usize, image.height() as usize);
    let raw = image.as_raw();
    let at = |x: usize, y: usize| &raw[(y * width + x) * 3..(y * width + x) * 3 + 3];
    let differ = |a: &[u8], b: &[u8]| a.iter().zip(b).any(|(&p, &q)| p.abs_diff(q) > ADAPTIVE_THRESHOLD);
    let mut mask: Vec<bool> = glimpses.iter().map(|g| g.finest < FINE_DETAIL).collect();
    for y in 0..height {
        for x in 0..width {
            let here = at(x, y);
            let signature = glimpses[y * width + x].signature;
            // Each unordered pair once: the right, lower-left, lower and
            // lower-right neighbours.
            for (dx, dy) in [(1, 0), (-1, 1), (0, 1), (1, 1)] {
                let (nx, ny) = (x as isize + dx, y + dy);
                if nx < 0 || nx as usize >= width || ny >= height {
                    continue;
                }
                let nx = nx as usize;
                if signature != glimpses[ny * width + nx].signature && differ(here, at(nx, ny)) {
                    mask[y * width + x] = true;
                    mask[ny * width + nx] = true;
                }
            }
            let second =
                |a: &[u8], b: &[u8], c: usize| (i32::from(a[c]) - 2 * i32::from(here[c]) + i32::from(b[c])).abs();
            let bends = (0..3).any(|c| {
                let across = if 0 < x && x + 1 < width { second(at(x - 1, y), at(x + 1, y), c) } else { 0 };
                let down = if 0 < y && y + 1 < height { second(at(x, y - 1), at(x, y + 1), c) } else { 0 };
                across + down > CURVATURE_THRESHOLD
            });
            mask[y * width + x] |= bends;
        }
    }
    mask
}

/// Adaptive anti-aliasing's two passes into `image`, the pixels of
/// `region`: every pixel at its centre, then all `options.samples` samples
/// for the pixels `refined` flags (one flag per pixel of the region) or,
/// when `None`, those [`refinement_mask`] picks. Whether a pixel is picked
/// depends on its eight neighbours, so the first pass also renders the
/// pixels around the region (within the image): its pixels are then picked
/// as they are in the whole image.
pub(crate) fn render_two_passes(
    scene: &Scene,
    geometry: &SceneGeometry,
    options: &RenderOptions,
    region: Region,
    control: &RenderControl,
    refined: Option<&[bool]>,
    image: &mut RgbImage,
) -> Result<RenderStats, Cancelled> {
    let seen = region.grown(1, options);
    let first = Pass::new(scene, geometry, options, control, 1).over(seen);
    let mut glimpses = vec![Glimpse::start(first.rays.pixel_angle()); seen.width() as usize * seen.height() as usize];
    let mut centres = RgbImage::new(seen.width(), seen.height());
    let mut rays = first.run(&mut centres, None, &mut glimpses)?;
    // A whole image (the usual case) is its own surroundings: nothing to cut.
    let whole = seen == region;
    let detected;
    let refined = match refined {
        Some(flags) => flags,
        None => {
            let mask = refinement_mask(&centres, &glimpses);
            detected = if whole { mask } else { within(&mask, seen, region) };
            &detected
        }
    };
    *image = if whole { centres } else { within_image(&centres, seen, region) };
    let second = Pass::new(scene, geometry, options, control, options.samples).without_progress().over(region);
    rays += second.run_plain(image, Some(refined))?;
    let refined_pixels = refined.iter().filter(|&&f| f).count() as u64;
    Ok(RenderStats { rays, refined_pixels, ..RenderStats::default() })
}

/// The values of `values` (one per pixel of `outer`, row major) at the
/// pixels of `inner`, a region inside `outer`.
fn within<T: Copy>(values: &[T], outer: Region, inner: Region) -> Vec<T> {
    let width = outer.width() as usize;
    let (left, right) = ((inner.left - outer.left) as usize, (inner.right - outer.left) as usize);
    (inner.top..inner.bottom)
        .flat_map(|y| {
            let row = (y - outer.top) as usize * width;
            values[row + left..row + right].iter().copied()
        })
        .collect()
}

/// The pixels of `image` (the pixels of `outer`) at those of `inner`.
fn within_image(image: &RgbImage, outer: Region, inner: Region) -> RgbImage {
    let bytes = within(image.as_raw().as_chunks::<3>().0, outer, inner).concat();
    RgbImage::from_raw(inner.width(), inner.height(), bytes).expect("three bytes a pixel")
}

/// Adaptive anti-aliasing's first pass alone: every pixel of `scene`
/// rendered at its centre, and the [`Glimpse`] of each pixel's ray (row
/// major). [`refinement_mask`] of the two gives the pixels the second pass
/// renders again.
pub fn glimpse_pass(scene: &Scene, geometry: &SceneGeometry, options: &RenderOptions) -> (RgbImage, Vec<Glimpse>) {
    let control = RenderControl::default();
    let pass = Pass::new(scene, geometry, options, &control, 1);
    let mut image = RgbImage::new(options.width, options.height);
    let mut glimpses = vec![Glimpse::start(pass.rays.pixel_angle()); image.len() / 3];
    pass.run(&mut image, None, &mut glimpses).expect("no cancel flag: never cancelled");
    (image, glimpses)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grey image from rows of levels.
    fn grey(rows: &[&[u8]]) -> RgbImage {
        let (width, height) = (rows[0].len() as u32, rows.len() as u32);
        RgbImage::from_fn(width, height, |x, y| image::Rgb([rows[y as usize][x as usize]; 3]))
    }

    /// Glimpses with these signatures (row major) and no fine detail.
    fn seen(signatures: &[u64]) -> Vec<Glimpse> {
        signatures.iter().map(|&signature| Glimpse { signature, ..Glimpse::start(1e-3) }).collect()
    }

    #[test]
    fn a_steep_gradient_on_one_surface_stays_at_one_sample() {
        let row: &[u8] = &[0, 40, 80, 120, 160];
        assert_eq!(refinement_mask(&grey(&[row, row, row]), &seen(&[7; 15])), [false; 15]);
    }

    #[test]
    fn an_edge_between_different_surfaces_refines_both_sides() {
        let step = grey(&[&[50, 200]]);
        assert_eq!(refinement_mask(&step, &seen(&[1, 2])), [true, true]);
        // The same surface (no bend measurable on two pixels): no edge.
        assert_eq!(refinement_mask(&step, &seen(&[1, 1])), [false, false]);
        // Different surfaces of nearly the same colour: nothing to smooth.
        assert_eq!(refinement_mask(&grey(&[&[50, 52]]), &seen(&[1, 2])), [false, false]);
        // Diagonal neighbours count too.
        let diagonal = grey(&[&[50, 50], &[50, 200]]);
        assert_eq!(refinement_mask(&diagonal, &seen(&[1, 1, 1, 2])), [true, true, true, true]);
    }

    #[test]
    fn a_bend_refines_its_pixel() {
        let bump = |centre| grey(&[&[100, 100, 100], &[100, centre, 100], &[100, 100, 100]]);
        let centre_only = [false, false, false, false, true, false, false, false, false];
        // Second differences 6 + 6 = 12 > 6 levels.
        assert_eq!(refinement_mask(&bump(103), &seen(&[3; 9])), centre_only);
        // 2 + 2: within rounding.
        assert_eq!(refinement_mask(&bump(101), &seen(&[3; 9])), [false; 9]);
    }

    #[test]
    fn an_object_under_two_pixels_refines_its_pixel() {
        let flat = grey(&[&[90, 90, 90]]);
        let mut glimpses = seen(&[5, 5, 5]);
        glimpses[0].finest = 1.5;
        glimpses[2].finest = 2.5;
        assert_eq!(refinement_mask(&flat, &glimpses), [true, false, false]);
    }
}
