//! Primary rays (SPEC 5) and the positions of samples inside a pixel.

use glam::{DVec2, DVec3};

use super::intersect::Ray;
use crate::scene::Camera;

/// Where the z axis meets the screen (SPEC 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Screen {
    /// Through the centre of the screen (the default).
    #[default]
    Centered,
    /// Through the middle of the screen's bottom edge (the original
    /// handout's convention).
    Bottom,
}

/// Generates the primary rays of one image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrimaryRays {
    eye: DVec3,
    half_width: f64,
    /// The y coordinate of a pixel's top edge row 0 on the screen.
    top: f64,
    focal: f64,
    /// 1, or 0 for a field of view so narrow that the focal distance is
    /// not a finite number: every ray is then the axis, the limit of a
    /// narrowing view (never a NaN direction and a black picture).
    spread: f64,
}

impl PrimaryRays {
    /// The rays of a `width` x `height` image seen by `camera`.
    ///
    /// SPEC 5: eye `E = (0, 0, D)`, focal distance `f = W / (2 tan(A/2))`.
    pub fn new(camera: &Camera, width: u32, height: u32, screen: Screen) -> PrimaryRays {
        let (w, h) = (f64::from(width), f64::from(height));
        let top = match screen {
            Screen::Centered => h / 2.0,
            Screen::Bottom => h,
        };
        let focal = w / (2.0 * (camera.angle / 2.0).tan());
        let (focal, spread) = if focal.is_finite() { (focal, 1.0) } else { (1.0, 0.0) };
        PrimaryRays { eye: DVec3::new(0.0, 0.0, camera.distance), half_width: w / 2.0, top, focal, spread }
    }

    /// The directions (not normalised) from the eye through the four corners
    /// of an image `height` pixels high made by these rays, in order around
    /// it: every primary ray, whatever its samples, points between them (the
    /// formula of [`PrimaryRays::ray`] at the outer edges of the corner pixels).
    pub fn corner_directions(&self, height: u32) -> [DVec3; 4] {
        let (left, right) = (-self.half_width, self.half_width);
        let (top, bottom) = (self.top, self.top - f64::from(height));
        [(left, top), (right, top), (right, bottom), (left, bottom)]
            .map(|(x, y)| DVec3::new(x * self.spread, y * self.spread, -self.focal))
    }

    /// The angle (radians) one pixel spans at the centre of the image.
    pub fn pixel_angle(&self) -> f64 {
        self.spread / self.focal
    }

    /// The ray through the point `(i + u, j + v)` of the image (pixel `(i,
    /// j)`, offset `(u, v)` in 0..1 from its top-left corner).
    ///
    /// SPEC 5: direction `normalize(i + u - W/2, H/2 - (j + v), -f)`, with `H`
    /// in place of `H/2` for [`Screen::Bottom`]; `u = v = 0.5` is the pixel
    /// centre. A degenerate camera (zero direction) gives a zero direction,
    /// which hits nothing: the pixel is black, never NaN.
    #[inline]
    pub fn ray(&self, i: u32, j: u32, offset: DVec2) -> Ray {
        let x = (f64::from(i) + offset.x - self.half_width) * self.spread;
        let y = (self.top - (f64::from(j) + offset.y)) * self.spread;
        let dir = DVec3::new(x, y, -self.focal).normalize_or_zero();
        Ray::new(self.eye, dir)
    }
}

/// The sample positions inside a pixel, as offsets from its top-left corner.
///
/// One sample is the pixel centre (SPEC 5). `n = k²` samples form a k x k
/// grid of stratum centres. Any other `n` uses a rank-1 lattice (Fibonacci
/// style): sample `s` at `((s + 0.5)/n, frac((s + 0.5) φ⁻¹))`, one per column
/// stratum and well spread vertically. The pattern is the same for every
/// pixel, so images are deterministic.
pub fn sample_offsets(n: u32) -> Vec<DVec2> {
    let n = n.max(1);
    if n == 1 {
        return vec![DVec2::splat(0.5)];
    }
    let k = (f64::from(n).sqrt().round()) as u32;
    if k * k == n {
        let step = 1.0 / f64::from(k);
        return (0..n).map(|s| DVec2::new((f64::from(s % k) + 0.5) * step, (f64::from(s / k) + 0.5) * step)).collect();
    }
    let inv_golden = (5f64.sqrt() - 1.0) / 2.0;
    (0..n)
        .map(|s| {
            let x = (f64::from(s) + 0.5) / f64::from(n);
            let y = ((f64::from(s) + 0.5) * inv_golden).fract();
            DVec2::new(x, y)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_of_odd_image_looks_down_minus_z() {
        let rays = PrimaryRays::new(&Camera { distance: 5.0, angle: 1.0 }, 3, 3, Screen::Centered);
        let r = rays.ray(1, 1, DVec2::splat(0.5));
        assert_eq!(r.origin, DVec3::new(0.0, 0.0, 5.0));
        assert_eq!(r.dir, DVec3::new(0.0, 0.0, -1.0));
    }

    #[test]
    fn a_field_of_view_too_narrow_for_a_finite_focal_distance_looks_along_the_axis() {
        let rays = PrimaryRays::new(&Camera { distance: 5.0, angle: 1e-320 }, 4, 3, Screen::Centered);
        assert_eq!(rays.ray(0, 0, DVec2::ZERO).dir, DVec3::NEG_Z);
        assert_eq!(rays.ray(3, 2, DVec2::ONE).dir, DVec3::NEG_Z);
    }

    #[test]
    fn bottom_screen_puts_axis_at_bottom_edge() {
        let rays = PrimaryRays::new(&Camera { distance: 5.0, angle: 1.0 }, 4, 4, Screen::Bottom);
        // Row 3 (the last) centre is at y = 4 - 3.5 = 0.5 above the axis.
        let f = 4.0 / (2.0 * 0.5f64.tan());
        let expected = DVec3::new(0.5 - 2.0 + 1.0, 0.5, -f).normalize();
        assert_eq!(rays.ray(1, 3, DVec2::splat(0.5)).dir, expected);
    }

    #[test]
    fn the_corner_directions_are_the_rays_through_the_outer_corners() {
        for screen in [Screen::Centered, Screen::Bottom] {
            let rays = PrimaryRays::new(&Camera { distance: 5.0, angle: 1.0 }, 4, 3, screen);
            let corners = rays.corner_directions(3);
            assert_eq!(rays.ray(0, 0, DVec2::ZERO).dir, corners[0].normalize());
            assert_eq!(rays.ray(3, 0, DVec2::new(1.0, 0.0)).dir, corners[1].normalize());
            assert_eq!(rays.ray(3, 2, DVec2::ONE).dir, corners[2].normalize());
            assert_eq!(rays.ray(0, 2, DVec2::new(0.0, 1.0)).dir, corners[3].normalize());
        }
    }

    #[test]
    fn sample_patterns_are_stratified() {
        assert_eq!(sample_offsets(1), vec![DVec2::splat(0.5)]);
        assert_eq!(
            sample_offsets(4),
            vec![DVec2::new(0.25, 0.25), DVec2::new(0.75, 0.25), DVec2::new(0.25, 0.75), DVec2::new(0.75, 0.75)]
        );
        let five = sample_offsets(5);
        assert_eq!(five.len(), 5);
        for (s, p) in five.iter().enumerate() {
            assert!((p.x * 5.0).floor() as usize == s && (0.0..1.0).contains(&p.y));
        }
    }
}
