//! Two pictures of the same size compared pixel by pixel: how many pixels
//! are off by more than a tolerance, the largest difference and where it
//! is, and a picture of the differences.

use image::{Rgb, RgbImage};
use serde_json::{Value, json};

/// How two pictures differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PictureDifference {
    /// How many pixels each picture has.
    pub pixels: u64,
    /// How many pixels differ by more than the tolerance in some channel.
    pub off: u64,
    /// The largest difference of a channel, 0 to 255.
    pub largest: u8,
    /// The first pixel (row by row from the top left) with the largest
    /// difference, if any pixel differs at all.
    pub at: Option<(u32, u32)>,
}

/// The largest difference of a channel between two pixels.
fn pixel_difference(a: &Rgb<u8>, b: &Rgb<u8>) -> u8 {
    a.0.iter().zip(b.0).map(|(x, y)| x.abs_diff(y)).max().unwrap_or(0)
}

/// Compares `submission` with `reference` (the same size): the pixels off
/// by more than `tolerance` levels.
///
/// # Panics
///
/// If the sizes differ (both are rendered with the same options).
pub fn compare_pictures(reference: &RgbImage, submission: &RgbImage, tolerance: u8) -> PictureDifference {
    assert_eq!(reference.dimensions(), submission.dimensions(), "pictures rendered with the same options");
    let mut found = PictureDifference {
        pixels: u64::from(reference.width()) * u64::from(reference.height()),
        off: 0,
        largest: 0,
        at: None,
    };
    for ((x, y, a), b) in reference.enumerate_pixels().zip(submission.pixels()) {
        let difference = pixel_difference(a, b);
        if difference > tolerance {
            found.off += 1;
        }
        if difference > found.largest {
            found.largest = difference;
            found.at = Some((x, y));
        }
    }
    found
}

/// The picture of the differences: a pixel off by more than `tolerance`
/// is red, from half bright for a small difference to full for 255; the
/// others show the reference's pixel at a third of its brightness, so that
/// the scene can be recognised around the differences.
pub fn difference_picture(reference: &RgbImage, submission: &RgbImage, tolerance: u8) -> RgbImage {
    RgbImage::from_fn(reference.width(), reference.height(), |x, y| {
        let (a, b) = (reference.get_pixel(x, y), submission.get_pixel(x, y));
        let difference = pixel_difference(a, b);
        if difference > tolerance { Rgb([128 + difference / 2, 0, 0]) } else { Rgb(a.0.map(|channel| channel / 3)) }
    })
}

impl PictureDifference {
    /// Whether more than `share` (0 to 1) of the pixels are off.
    pub fn differs(&self, share: f64) -> bool {
        self.off as f64 > share * self.pixels as f64
    }

    /// In words, for pixels off by more than `tolerance` levels: "312 of
    /// 4800 pixels (6.5%) are off by more than 2 levels; the largest
    /// difference, 181 levels, is at pixel (40, 22)".
    pub fn words(&self, tolerance: u8) -> String {
        let share = 100.0 * self.off as f64 / self.pixels.max(1) as f64;
        let mut text = format!(
            "{} of {} pixels ({}%) are off by more than {}",
            self.off,
            self.pixels,
            crate::lang::number::format_number((share * 10.0).round() / 10.0),
            levels(tolerance)
        );
        if let Some((x, y)) = self.at {
            text.push_str(&format!("; the largest difference, {}, is at pixel ({x}, {y})", levels(self.largest)));
        }
        text
    }

    /// `{"pixels", "off", "largest", "at"}`, `at` `[x, y]` or `null`.
    pub fn to_json(&self) -> Value {
        json!({"pixels": self.pixels, "off": self.off, "largest": self.largest, "at": self.at.map(|(x, y)| [x, y])})
    }
}

/// "1 level", "2 levels".
fn levels(n: u8) -> String {
    if n == 1 { "1 level".to_string() } else { format!("{n} levels") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn off_pixels_are_counted_and_the_largest_found() {
        let reference = RgbImage::from_pixel(4, 3, Rgb([100, 100, 100]));
        let mut submission = reference.clone();
        submission.put_pixel(1, 0, Rgb([101, 100, 100]));
        submission.put_pixel(2, 1, Rgb([100, 40, 100]));
        submission.put_pixel(3, 2, Rgb([100, 100, 160]));
        let found = compare_pictures(&reference, &submission, 2);
        assert_eq!(found, PictureDifference { pixels: 12, off: 2, largest: 60, at: Some((2, 1)) });
        assert!(found.differs(0.1) && !found.differs(0.2));
        assert_eq!(
            found.words(2),
            "2 of 12 pixels (16.7%) are off by more than 2 levels; the largest difference, 60 levels, is at pixel (2, 1)"
        );
        let picture = difference_picture(&reference, &submission, 2);
        assert_eq!(picture.get_pixel(2, 1), &Rgb([158, 0, 0]));
        assert_eq!(picture.get_pixel(1, 0), &Rgb([33, 33, 33]), "within the tolerance");
    }
}
