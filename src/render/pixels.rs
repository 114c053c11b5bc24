//! The loop over an image's pixels: bands of rows spread over rayon's
//! threads, tiles within a band, samples within a pixel, and the bytes of
//! each pixel (SPEC 6: `round(255 * c)` of the average of its samples).
//!
//! Every pixel is computed on its own, so the bytes do not depend on the
//! number of threads.

use std::sync::atomic::Ordering;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::bvh::PACKET;
use super::camera::{PrimaryRays, sample_offsets};
use super::geometry::SceneGeometry;
use super::geometry::SurfaceHit;
use super::intersect::Ray;
use super::options::{Cancelled, RayCounts, RenderControl, RenderOptions};
use super::shade::{Lighting, PathObserver, Tracer, offset_origin};
use crate::scene::Scene;

/// Side of a square tile, in pixels; also the height of a band.
pub const TILE: u32 = 16;

/// One pass over the pixels of an image: everything the loop needs,
/// shared by all threads.
pub(crate) struct Pass<'a> {
    /// The camera rays.
    pub rays: PrimaryRays,
    /// Where the samples of a pixel lie in it.
    pub offsets: Vec<DVec2>,
    lighting: Lighting<'a>,
    geometry: &'a SceneGeometry,
    width: u32,
    control: &'a RenderControl<'a>,
    /// Whether progress counts the pixels of this pass.
    reports_progress: bool,
}

impl<'a> Pass<'a> {
    /// The pass over the pixels of `scene` (whose geometry is `geometry`)
    /// with `samples` samples each.
    pub fn new(
        scene: &'a Scene,
        geometry: &'a SceneGeometry,
        options: &RenderOptions,
        control: &'a RenderControl<'a>,
        samples: u32,
    ) -> Pass<'a> {
        Pass {
            rays: geometry.primary_rays(&scene.camera, options.width, options.height, options.screen),
            offsets: sample_offsets(samples),
            lighting: Lighting::new(scene, geometry, options.depth, options.skips),
            geometry,
            width: options.width,
            control,
            reports_progress: true,
        }
    }

    /// The same pass, leaving progress alone: for a second pass over
    /// pixels already counted.
    pub fn without_progress(self) -> Pass<'a> {
        Pass { reports_progress: false, ..self }
    }

    /// Renders into `buffer` (RGB bytes, row major) every pixel, or those
    /// `flags` marks (one flag per pixel), each watched by its own observer
    /// in `observers` (one per pixel). Returns the rays traced.
    pub fn run<O: PathObserver + Send>(
        &self,
        buffer: &mut [u8],
        flags: Option<&[bool]>,
        observers: &mut [O],
    ) -> Result<RayCounts, Cancelled> {
        // A pass over some pixels only (adaptive refinement, frame reuse)
        // finds them bunched in a few places, along edges or around what
        // moves: bands of one row keep both threads busy to the end.
        let band_rows = if flags.is_some() { 1 } else { TILE };
        let band_pixels = band_rows as usize * self.width as usize;
        if band_pixels == 0 {
            return Ok(RayCounts::default());
        }
        let bands: Vec<RayCounts> = buffer
            .par_chunks_mut(band_pixels * 3)
            .zip(observers.par_chunks_mut(band_pixels))
            .enumerate()
            .map(|(band, (pixels, observers))| {
                let first = band * band_pixels;
                let flags = flags.map(|f| &f[first..first + observers.len()]);
                self.band(band as u32 * band_rows, pixels, flags, observers)
            })
            .collect::<Result<_, Cancelled>>()?;
        let mut counts = RayCounts::default();
        for band in bands {
            counts += band;
        }
        Ok(counts)
    }

    /// [`Pass::run`] with no observer.
    pub fn run_plain(&self, buffer: &mut [u8], flags: Option<&[bool]>) -> Result<RayCounts, Cancelled> {
        self.run(buffer, flags, &mut vec![(); buffer.len() / 3])
    }

    /// Renders the band of rows starting at row `top` into `pixels` (its
    /// RGB bytes), tile by tile: the pixels `flags` marks (the band's share
    /// of them), each watched by its observer.
    fn band<O: PathObserver>(
        &self,
        top: u32,
        pixels: &mut [u8],
        flags: Option<&[bool]>,
        observers: &mut [O],
    ) -> Result<RayCounts, Cancelled> {
        let rows = (observers.len() / self.width as usize) as u32;
        let mut tracer = Tracer::new(self.geometry, &self.lighting);
        let mut left = 0;
        while left < self.width {
            if self.control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return Err(Cancelled);
            }
            let right = (left + TILE).min(self.width);
            if self.geometry.has_tree() {
                self.tile_in_packets(&mut tracer, (top, rows), (left, right), pixels, flags, observers);
            } else {
                for row in 0..rows {
                    for i in left..right {
                        let index = row as usize * self.width as usize + i as usize;
                        if flags.is_some_and(|f| !f[index]) {
                            continue;
                        }
                        let rgb = self.pixel(&mut tracer, i, top + row, &mut observers[index]);
                        pixels[index * 3..index * 3 + 3].copy_from_slice(&rgb);
                    }
                }
            }
            if let (Some(progress), true) = (self.control.progress, self.reports_progress) {
                progress(u64::from((right - left) * rows));
            }
            left = right;
        }
        Ok(tracer.counts)
    }

    /// The tile of the band (`top`, `rows` rows) between columns `left` and
    /// `right` (excluded), as [`Pass::band`] renders it, in blocks of
    /// [`PACKET`] pixels (4 x 2, or 8 x 1 in a band of one row) whose camera
    /// rays find their closest hits as one packet, sample by sample.
    fn tile_in_packets<O: PathObserver>(
        &self,
        tracer: &mut Tracer,
        (top, rows): (u32, u32),
        (left, right): (u32, u32),
        pixels: &mut [u8],
        flags: Option<&[bool]>,
        observers: &mut [O],
    ) {
        // A band holds at least one row.
        let block_rows = rows.min(2);
        let block_columns = PACKET as u32 / block_rows;
        for first_row in (0..rows).step_by(block_rows as usize) {
            for first_column in (left..right).step_by(block_columns as usize) {
                // The pixels of the block to render: (column, row, index).
                let mut block = [(0, 0, 0); PACKET];
                let mut len = 0;
                for row in first_row..(first_row + block_rows).min(rows) {
                    for i in first_column..(first_column + block_columns).min(right) {
                        let index = row as usize * self.width as usize + i as usize;
                        if flags.is_none_or(|f| f[index]) {
                            block[len] = (i, top + row, index);
                            len += 1;
                        }
                    }
                }
                let block = &block[..len];
                let sums = self.block_sums(tracer, block, observers);
                for (&(_, _, index), &sum) in block.iter().zip(&sums) {
                    pixels[index * 3..index * 3 + 3].copy_from_slice(&self.bytes(sum));
                }
            }
        }
    }

    /// The sums of the samples' colours of each pixel of `block` (column,
    /// row, index in `observers`), each sample's camera rays traced as one
    /// packet.
    #[inline(always)]
    fn block_sums<O: PathObserver>(
        &self,
        tracer: &mut Tracer,
        block: &[(u32, u32, usize)],
        observers: &mut [O],
    ) -> [DVec3; PACKET] {
        let mut sums = [DVec3::ZERO; PACKET];
        let mut rays = [Ray::new(DVec3::ZERO, DVec3::ZERO); PACKET];
        let mut hits = [None; PACKET];
        for &offset in &self.offsets {
            for (ray, &(i, j, _)) in rays.iter_mut().zip(block) {
                *ray = self.rays.ray(i, j, offset);
            }
            let (rays, hits) = (&rays[..block.len()], &mut hits[..block.len()]);
            self.geometry.closest_hits(rays, hits);
            let blocked = if O::WANTS_BLOCKER { None } else { self.shadows(hits) };
            for (k, (((ray, hit), &(_, _, index)), sum)) in
                rays.iter().zip(hits.iter()).zip(block).zip(&mut sums).enumerate()
            {
                tracer.first_blocked = blocked.map(|b| b[k]);
                *sum += tracer.trace_from(ray, *hit, &mut observers[index]);
            }
        }
        sums
    }

    /// For each of `hits`, which lights' shadow rays are blocked (bit `j`
    /// for light `j`), each light's rays traced as one packet; `None` with
    /// more lights than bits.
    fn shadows(&self, hits: &[Option<SurfaceHit>]) -> Option<[u64; PACKET]> {
        let lighting = &self.lighting;
        if lighting.lights.len() > 64 {
            return None;
        }
        let mut masks = [0u64; PACKET];
        for (j, (light, planes)) in lighting.lights.iter().zip(&lighting.blocking_planes).enumerate() {
            let mut rays = [Ray::new(DVec3::ZERO, light.direction); PACKET];
            let mut blocked = [true; PACKET];
            for ((hit, ray), blocked) in hits.iter().zip(&mut rays).zip(&mut blocked) {
                let Some(hit) = hit else { continue };
                if lighting.skips.back_facing_light && hit.normal.dot(light.direction) <= 0.0 {
                    continue;
                }
                ray.origin = offset_origin(hit.point, hit.normal, hit.t);
                *blocked = false;
            }
            let traced: [bool; PACKET] = std::array::from_fn(|k| !blocked[k]);
            self.geometry.blocked_all(&rays[..hits.len()], planes, &mut blocked[..hits.len()]);
            for k in 0..hits.len() {
                if traced[k] && blocked[k] {
                    masks[k] |= 1 << j;
                }
            }
        }
        Some(masks)
    }

    /// The bytes of pixel `(i, j)` alone, its paths watched by `observer`
    /// (to explain that pixel).
    pub fn one_pixel<O: PathObserver>(&self, i: u32, j: u32, observer: &mut O) -> [u8; 3] {
        self.pixel(&mut Tracer::new(self.geometry, &self.lighting), i, j, observer)
    }

    /// The bytes of pixel `(i, j)`: `round(255 * c)` of the average of its
    /// samples' colours (SPEC 6).
    #[inline]
    fn pixel<O: PathObserver>(&self, tracer: &mut Tracer, i: u32, j: u32, observer: &mut O) -> [u8; 3] {
        let mut sum = DVec3::ZERO;
        for &offset in &self.offsets {
            sum += tracer.trace(&self.rays.ray(i, j, offset), observer);
        }
        self.bytes(sum)
    }

    /// The bytes of a pixel whose samples' colours add up to `sum`.
    #[inline]
    fn bytes(&self, sum: DVec3) -> [u8; 3] {
        let mean = if self.offsets.len() == 1 { sum } else { sum / self.offsets.len() as f64 };
        to_bytes(mean)
    }
}

/// SPEC 6: the stored byte is `round(255 * c)`, no gamma. NaN gives 0.
#[inline]
fn to_bytes(c: DVec3) -> [u8; 3] {
    [to_byte(c.x), to_byte(c.y), to_byte(c.z)]
}

/// `round(255 * c)` for one channel, saturating to 0..=255 (NaN gives 0).
#[inline]
fn to_byte(c: f64) -> u8 {
    // `as u8` saturates and maps NaN to 0.
    (255.0 * c).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_round_half_away_from_zero_and_saturate() {
        assert_eq!(to_byte(0.0), 0);
        assert_eq!(to_byte(1.0), 255);
        assert_eq!(to_byte(0.5), 128); // 127.5 rounds up
        assert_eq!(to_byte(f64::NAN), 0);
        assert_eq!(to_byte(-3.0), 0);
        assert_eq!(to_byte(7.0), 255);
    }
}
