//! The loop over an image's pixels (rayrepl's `render::pixels`): bands of
//! 16 rows spread over rayon's threads, 16 x 16 tiles within a band, and
//! the bytes of each pixel (SPEC 6: `round(255 * c)`), one sample at its
//! centre.

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use rayrepl::render::{PrimaryRays, RayCounts};

use crate::geometry::{Geometry, LANES};
use crate::shade::{Lighting, Tracer};

/// Side of a square tile, in pixels; also the height of a band (rayrepl's
/// `render::TILE`).
pub const TILE: u32 = 16;

/// Renders every pixel into `buffer` (RGB bytes, row major, `width` pixels
/// a row), with single rays or, with `packets`, 4 x 4 packets of camera
/// rays and of their shadow rays; returns the rays traced.
pub fn render(
    rays: &PrimaryRays,
    geometry: &Geometry,
    lighting: &Lighting,
    width: u32,
    buffer: &mut [u8],
    packets: bool,
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
                if packets {
                    tile_in_packets(&mut tracer, rays, (left, right), (top, rows), width, pixels);
                    left = right;
                    continue;
                }
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

/// Renders the tile of columns `columns` (left, right) of the band of
/// `band.1` rows starting at row `band.0` into the band's `pixels`, in
/// blocks of 4 x 4 pixels, each one packet.
fn tile_in_packets(
    tracer: &mut Tracer,
    rays: &PrimaryRays,
    (left, right): (u32, u32),
    (top, rows): (u32, u32),
    width: u32,
    pixels: &mut [u8],
) {
    let ray = |i: u32, j: u32| rays.ray(i, j, DVec2::splat(0.5));
    for block_row in (0..rows).step_by(4) {
        for block_left in (left..right).step_by(4) {
            let lane_pixel = |lane: usize| (block_left + lane as u32 % 4, block_row + lane as u32 / 4);
            let valid: [bool; LANES] = std::array::from_fn(|lane| {
                let (i, row) = lane_pixel(lane);
                i < right && row < rows
            });
            let primaries = std::array::from_fn(|lane| {
                let (i, row) = lane_pixel(lane);
                if valid[lane] { ray(i, top + row) } else { ray(left, top) }
            });
            let colours = tracer.trace16(&primaries, &valid);
            for lane in (0..LANES).filter(|&lane| valid[lane]) {
                let (i, row) = lane_pixel(lane);
                let index = row as usize * width as usize + i as usize;
                pixels[index * 3..index * 3 + 3].copy_from_slice(&to_bytes(colours[lane]));
            }
        }
    }
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
