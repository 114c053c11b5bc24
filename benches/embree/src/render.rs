//! The loop over an image's pixels (rayrepl's `render::pixels`): bands of
//! 16 rows spread over rayon's threads, 16 x 16 tiles within a band, and
//! the bytes of each pixel (SPEC 6: `round(255 * c)`), one sample at its
//! centre.

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use rayrepl::render::{PrimaryRays, RayCounts};

use crate::geometry::Geometry;
use crate::shade::{Lighting, Tracer};

/// Side of a square tile, in pixels; also the height of a band (rayrepl's
/// `render::TILE`).
pub const TILE: u32 = 16;

/// Renders every pixel into `buffer` (RGB bytes, row major, `width` pixels
/// a row) with single rays; returns the rays traced.
pub fn render(
    rays: &PrimaryRays,
    geometry: &Geometry,
    lighting: &Lighting,
    width: u32,
    buffer: &mut [u8],
) -> RayCounts {
    let band_pixels = TILE as usize * width as usize;
    if band_pixels == 0 {
        return RayCounts::default();
    }
    let bands: Vec<RayCounts> = buffer
        .par_chunks_mut(band_pixels * 3)
        .enumerate()
        .map(|(band, pixels)| {
            let mut tracer = Tracer::new(geometry, lighting);
            let rows = (pixels.len() / 3 / width as usize) as u32;
            let top = band as u32 * TILE;
            let mut left = 0;
            while left < width {
                let right = (left + TILE).min(width);
                for row in 0..rows {
                    for i in left..right {
                        let index = row as usize * width as usize + i as usize;
                        let colour = tracer.trace(&rays.ray(i, top + row, DVec2::splat(0.5)));
                        pixels[index * 3..index * 3 + 3].copy_from_slice(&to_bytes(colour));
                    }
                }
                left = right;
            }
            tracer.counts
        })
        .collect();
    let mut counts = RayCounts::default();
    for band in bands {
        counts += band;
    }
    counts
}

/// rayrepl's `pixels::to_bytes`: `round(255 * c)` per channel, saturating
/// (NaN gives 0).
#[inline]
pub fn to_bytes(c: DVec3) -> [u8; 3] {
    [to_byte(c.x), to_byte(c.y), to_byte(c.z)]
}

/// `round(255 * c)` for one channel; `as u8` saturates and maps NaN to 0.
#[inline]
fn to_byte(c: f64) -> u8 {
    (255.0 * c).round() as u8
}
