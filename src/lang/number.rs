//! How the language writes a number in messages, `print` and `:env`.

use std::fmt;

/// A number the way a learner writes it: `3`, `0.75`, `-1.570796` (six
/// decimals at most, trailing zeros dropped; `0` for -0; tiny and huge numbers in the
/// shortest form that reads back, with an exponent: `1e-9`, `1.5e300`).
pub fn format_number(value: f64) -> String {
    Number(value).to_string()
}

/// [`format_number`], formatted straight into the text that shows it.
pub struct Number(pub f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let Number(value) = *self;
        if value == value.trunc() && value.abs() < 1e15 {
            // Exact as an integer, which formats faster than the float; `-0`
            // (from `0 * -1`) is the same number as 0 to a learner, and is
            // written `0`.
            return write!(f, "{}", value as i64);
        }
        if value.abs() >= 1e15 {
            // Not a long run of digits: `1e300`, not 301 of them.
            return write!(f, "{value:e}");
        }
        let text = format!("{value:.6}");
        let text = text.trim_end_matches('0').trim_end_matches('.');
        if text == "0" || text == "-0" { write!(f, "{value:e}") } else { f.write_str(text) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_like_the_language() {
        assert_eq!(format_number(3.0), "3");
        assert_eq!(format_number(-2.0), "-2");
        assert_eq!(format_number(0.75), "0.75");
        assert_eq!(format_number(std::f64::consts::PI), "3.141593");
        assert_eq!(format_number(1e-9), "1e-9");
        assert_eq!(format_number(0.0), "0");
        assert_eq!(format_number(-0.0), "0", "no sign on zero");
        assert_eq!(format_number(-123_456_789_012_345.0), "-123456789012345");
        assert_eq!(format_number(1e300), "1e300");
        assert_eq!(format_number(-1.5e20), "-1.5e20");
        assert_eq!(format_number(1e15 + 0.5), "1.0000000000000005e15");
        assert_eq!(format_number(-1e-300), "-1e-300");
    }

    #[test]
    fn huge_and_tiny_numbers_take_the_shortest_form_that_reads_back() {
        for value in [1e308, f64::MAX, -1.7976931348623157e308, 1e-308, 5e-324, 1.2345678901234567e100] {
            let text = format_number(value);
            assert!(text.contains('e') && text.len() <= 24, "{text}");
            assert_eq!(text.parse::<f64>(), Ok(value), "{text} reads back");
        }
        assert_eq!(format_number(1e308), "1e308");
    }
}
