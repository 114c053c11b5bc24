//! The loop over an image's pixels: bands of rows spread over rayon's
//! threads, tiles within a band, samples within a pixel, and the bytes of
//! each pixel (SPEC 6: `round(255 * c)` of the average of its samples).
//!
//! Every pixel is computed on its own, so the bytes do not depend on the
//! number of threads.

use std::sync::atomic::Ordering;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::camera::{PrimaryRays, sample_offsets};
use super::geometry::SceneGeometry;
use super::isa::Isa;
use super::options::{Cancelled, RayCounts, Region, RenderControl, RenderOptions};
use super::shade::{Lighting, PathObserver, Tracer};
use crate::scene::Scene;

/// Side of a square tile, in pixels; also the height of a band.
pub const TILE: u32 = 16;

/// One pass over the pixels of a region of an image (the whole image
/// unless [`Pass::over`] says otherwise): everything the loop needs,
/// shared by all threads. Buffers hold the region's pixels, row major.
pub(crate) struct Pass<'a> {
    /// The camera rays.
    pub rays: PrimaryRays,
    /// Where the samples of a pixel lie in it.
    pub offsets: Vec<DVec2>,
    lighting: Lighting<'a>,
    geometry: &'a SceneGeometry,
    /// The pixels the pass renders.
    region: Region,
    /// The region's width.
    width: u32,
    control: &'a RenderControl<'a>,
    /// Whether progress counts the pixels of this pass.
    reports_progress: bool,
}

/// A band of rows to render: the first row's number in the region, the band's RGB
/// bytes, the pixels to render (the band's share of the flags; all of them
/// without flags) and each pixel's observer.
struct Band<'b, O> {
    top: u32,
    pixels: &'b mut [u8],
    flags: Option<&'b [bool]>,
    observers: &'b mut [O],
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
            region: Region::whole(options),
            width: options.width,
            control,
            reports_progress: true,
        }
    }

    /// The same pass over the pixels of `region` only.
    pub fn over(self, region: Region) -> Pass<'a> {
        Pass { region, width: region.width(), ..self }
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
                self.band(Band { top: band as u32 * band_rows, pixels, flags, observers })
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

    /// Renders `band`, tile by tile, in the compiled form [`Isa::chosen`].
    fn band<O: PathObserver>(&self, band: Band<'_, O>) -> Result<RayCounts, Cancelled> {
        match Isa::chosen() {
            Isa::Portable => self.band_in_form(band),
            // SAFETY: `Avx2` is chosen only when the processor has AVX2.
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => unsafe { self.band_avx2(band) },
        }
    }

    /// [`Pass::band`] compiled for AVX2, with the tracing of each pixel
    /// inlined into it: the shading, the flat list's tests and the bytes'
    /// rounding in AVX2 instructions (the rounding is a call of `round` in
    /// the baseline, which has no rounding instruction).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn band_avx2<O: PathObserver>(&self, band: Band<'_, O>) -> Result<RayCounts, Cancelled> {
        self.band_in_form(band)
    }

    /// [`Pass::band`], inlined into the compiled form that calls it.
    #[inline(always)]
    fn band_in_form<O: PathObserver>(&self, band: Band<'_, O>) -> Result<RayCounts, Cancelled> {
        let Band { top, pixels, flags, observers } = band;
        let rows = (observers.len() / self.width as usize) as u32;
        let mut tracer = Tracer::new(self.geometry, &self.lighting);
        let mut left = 0;
        while left < self.width {
            if self.control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return Err(Cancelled);
            }
            let right = (left + TILE).min(self.width);
            for row in 0..rows {
                for i in left..right {
                    let index = row as usize * self.width as usize + i as usize;
                    if flags.is_some_and(|f| !f[index]) {
                        continue;
                    }
                    let (x, y) = (self.region.left + i, self.region.top + top + row);
                    let rgb = self.pixel(&mut tracer, x, y, &mut observers[index]);
                    pixels[index * 3..index * 3 + 3].copy_from_slice(&rgb);
                }
            }
            if let (Some(progress), true) = (self.control.progress, self.reports_progress) {
                progress(u64::from((right - left) * rows));
            }
            left = right;
        }
        Ok(tracer.counts)
    }

    /// The bytes of pixel `(i, j)` alone, its paths watched by `observer`
    /// (to explain that pixel).
    pub fn one_pixel<O: PathObserver>(&self, i: u32, j: u32, observer: &mut O) -> [u8; 3] {
        self.pixel(&mut Tracer::new(self.geometry, &self.lighting), i, j, observer)
    }

    /// The bytes of pixel `(i, j)`: `round(255 * c)` of the average of its
    /// samples' colours (SPEC 6).
    ///
    /// Always inlined, so that each compiled form of [`Pass::band`] traces
    /// in its own instructions.
    #[inline(always)]
    fn pixel<O: PathObserver>(&self, tracer: &mut Tracer, i: u32, j: u32, observer: &mut O) -> [u8; 3] {
        let mut sum = DVec3::ZERO;
        for &offset in &self.offsets {
            sum += tracer.trace(&self.rays.ray(i, j, offset), observer);
        }
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
