//! Angles are in radians; numbers that were most likely meant in degrees.
//!
//! One place decides what "looks like degrees" means, for the camera's
//! error (`angle-in-degrees`) and the warning about the other angles
//! (`crate::lint`, check `degrees`), and writes the fix they both suggest.

use std::f64::consts::{PI, TAU};

use crate::lang::number::format_number;

/// Whether a camera `angle` (a field of view, valid strictly between 0 and
/// pi) was meant in degrees: from pi to 180, where no field of view in
/// radians lies and every usual one in degrees does.
pub fn field_of_view_looks_like_degrees(angle: f64) -> bool {
    (PI..180.0).contains(&angle)
}

/// Whether a turn by `angle` radians (a light's or a plane's `rotation`,
/// `rotate ... by`), which any number may be, was most likely meant in
/// degrees: a whole multiple of 5 above a full turn (2 pi) and up to 360
/// (10, 15, 30, 45, 90, 180, 360 and their negatives). A program that means
/// radians writes them as fractions of `pi`, or as decimals.
pub fn turn_looks_like_degrees(angle: f64) -> bool {
    let size = angle.abs();
    size > TAU && size <= 360.0 && size % 5.0 == 0.0
}

/// The help of both: how to write `angle`, taken as degrees, in radians
/// (`for 45 degrees, write `45 * pi / 180` (that is 0.785398 radians)`),
/// `before` being what comes before the number (`angle ` for the camera).
pub fn in_radians_help(angle: f64, before: &str) -> String {
    let a = format_number(angle);
    format!("for {a} degrees, write `{before}{a} * pi / 180` (that is {} radians)", format_number(angle.to_radians()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_turns_above_a_full_turn_look_like_degrees() {
        for degrees in [10.0, 15.0, 45.0, 90.0, -90.0, 180.0, 270.0, 360.0] {
            assert!(turn_looks_like_degrees(degrees), "{degrees}");
        }
        for radians in [0.0, 0.5, PI, 5.0, 6.0, 7.0, 45.5, 365.0, 720.0, f64::NAN] {
            assert!(!turn_looks_like_degrees(radians), "{radians}");
        }
        assert!(field_of_view_looks_like_degrees(60.0) && !field_of_view_looks_like_degrees(1.0));
        assert_eq!(in_radians_help(45.0, ""), "for 45 degrees, write `45 * pi / 180` (that is 0.785398 radians)");
    }
}
