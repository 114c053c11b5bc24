//! The shading formula of SPEC 6, and nothing else.
//!
//! ```text
//! colour(V) = clamp( kd*Ia*C
//!                  + Σ_j visible, N·Lj > 0 ( kd*(N·Lj)*Ij*C + ks*max(0, N·Hj)^n*Ij*C )
//!                  + ks * colour(reflected ray) )        Hj = normalize(Lj - V)
//! ```
//!
//! The recursion is followed iteratively: going down the path of mirror
//! reflections, each level's local part (everything but the reflection term)
//! and its `ks` are recorded; going back up, `c = clamp(local + ks * c_next)`
//! folds them, clamping at every level as SPEC 6 requires.
//!
//! # The reflection-weight cutoff, and why it is exact
//!
//! A path whose accumulated weight `w = Π ks` (the factor by which a deeper
//! colour reaches the pixel) falls below half an 8-bit level pauses when
//! [`Skips::negligible_reflection`] is on. The colour `x` it did not compute
//! lies in `[0, 1]`, and every step of the fold (`local + ks * x`, then clamp)
//! is monotone in `x`, in floating point too (correctly rounded `+`, and `*`
//! by a non-negative number, are monotone, and so is clamping). So the exact
//! value lies between the fold with `x = 0` (`lo`) and with `x = 1` (`hi`);
//! averaging samples and `round(255 * c)` are monotone as well. The cutoff
//! alone (`hi - lo <= w < 0.5/255`) does not settle the byte: a value just
//! below a `.5` boundary still rounds up once the missing `< 0.5/255` is
//! added. Hence the tracer returns the pair `(lo, hi)`; when both give the
//! same byte that byte is the exact one, and otherwise the caller resumes the
//! paused paths ([`Tracer::resume`]) where they stopped. Nothing is traced
//! twice, and the image is byte-identical to the one without the skip, by
//! construction.

use glam::DVec3;

use super::Skips;
use super::adaptive::Glimpse;
use super::geometry::{Blocker, Intersector, Prepared, SurfaceHit};
use super::intersect::{PlaneShape, Ray};
use super::sweep::Sweep;
use crate::scene::{Light, Material};

/// Paths whose accumulated weight is below this stop (half an 8-bit level).
pub const NEGLIGIBLE_WEIGHT: f64 = 0.5 / 255.0;

/// Rays traced, counted per tile and summed (no atomics per ray).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RayCounts {
    /// Camera rays.
    pub primary: u64,
    /// Rays towards lights.
    pub shadow: u64,
    /// Mirror rays.
    pub reflection: u64,
}

impl RayCounts {
    /// All rays, of every kind.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflection
    }
}

impl std::ops::AddAssign for RayCounts {
    fn add_assign(&mut self, other: RayCounts) {
        self.primary += other.primary;
        self.shadow += other.shadow;
        self.reflection += other.reflection;
    }
}

/// The colour of a path as bounds: the exact colour lies in `[lo, hi]`
/// (equal unless the reflection-weight cutoff dropped a term).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// The colour with dropped reflections taken as black.
    pub lo: DVec3,
    /// The colour with dropped reflections taken as white.
    pub hi: DVec3,
}

/// One level of a path: the local part of the colour and the weight of the
/// reflection term (0 when there is no reflection term).
#[derive(Debug, Clone, Copy)]
struct Level {
    local: DVec3,
    ks: f64,
}

/// A path of reflections from one primary ray: its levels so far and, if
/// the cutoff paused it, where it would go on.
#[derive(Debug, Clone, Default)]
struct Path {
    levels: Vec<Level>,
    paused: Option<Ray>,
}

/// What lies past the last level of a path.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Tail {
    /// Nothing (no reflection term, or the reflected ray hit nothing: black).
    Black,
    /// A reflected colour in `[0, 1]` that the cutoff did not compute.
    Unknown,
}

/// Everything constant over one image that the formula needs.
#[derive(Debug, Clone, Copy)]
pub struct Lighting<'a> {
    /// Ambient intensity Ia.
    pub ambient: f64,
    /// The lights.
    pub lights: &'a [Light],
    /// For each light, the planes that can block rays towards it
    /// ([`Prepared::planes_blocking`]).
    pub blocking_planes: &'a [Vec<PlaneShape>],
    /// Number of reflections followed (SPEC 6 `depth`).
    pub depth: u32,
    /// Which work-saving shortcuts are on.
    pub skips: Skips,
    /// The angle one pixel spans (radians): how fast the beam of rays
    /// through a pixel widens, for [`Glimpse::finest`].
    pub pixel_angle: f64,
}

/// Traces paths; holds the ray counts of one tile and reusable buffers.
///
/// With `WATCH`, it also works out how long each pixel stays valid for
/// frame reuse ([`Tracer::watching`]); the still-image tracer
/// (`WATCH = false`) compiles without that bookkeeping. With `GLIMPSE`, it
/// records a [`Glimpse`] of each path for adaptive anti-aliasing's first
/// pass. `G` is the geometry in the precision of the intersection tests
/// ([`Prepared`] for f64, [`super::geometry::PreparedF32`] for f32).
pub struct Tracer<'a, const WATCH: bool = false, const GLIMPSE: bool = false, G: Intersector = Prepared> {
    geometry: &'a G,
    lighting: Lighting<'a>,
    /// Rays traced so far.
    pub counts: RayCounts,
    /// Paused paths resumed so far.
    pub resumed: u64,
    /// One path per sample slot (kept to resume it).
    paths: Vec<Path>,
    /// Frame reuse, when on: the frames' moving objects and the frame
    /// being traced.
    watch: Option<(&'a Sweep, u32)>,
    /// With frame reuse: the last frame for which the paths traced since it
    /// was reset give the same colours (see [`super::sweep`]).
    pub valid_until: u32,
    /// With `GLIMPSE`: what the last path traced met.
    pub glimpse: Glimpse,
}

impl<'a, const WATCH: bool, const GLIMPSE: bool, G: Intersector> Tracer<'a, WATCH, GLIMPSE, G> {
    /// A tracer over `geometry` with the image constants `lighting`, for
    /// `slots` samples per pixel.
    pub fn new(geometry: &'a G, lighting: Lighting<'a>, slots: usize) -> Tracer<'a, WATCH, GLIMPSE, G> {
        let paths = (0..slots.max(1)).map(|_| Path { levels: Vec::with_capacity(8), paused: None }).collect();
        Tracer {
            geometry,
            lighting,
            counts: RayCounts::default(),
            resumed: 0,
            paths,
            watch: None,
            valid_until: 0,
            glimpse: Glimpse::start(lighting.pixel_angle),
        }
    }

    /// The same tracer, working out [`Tracer::valid_until`] for frame
    /// `frame` of the frames of `sweep` (only with `WATCH`). The geometry's
    /// timed part must have no plane.
    pub fn watching(self, sweep: &'a Sweep, frame: u32) -> Tracer<'a, WATCH, GLIMPSE, G> {
        Tracer { watch: Some((sweep, frame)), ..self }
    }

    /// Frame reuse: lowers [`Tracer::valid_until`] to the frame before the
    /// first one whose moving objects could change what `ray` found in
    /// `[0, t]`. A hit on a moving object (`timed`) holds for this frame only.
    #[inline]
    fn watch(&mut self, ray: &Ray, t: f64, timed: bool) {
        let Some((sweep, frame)) = self.watch else { return };
        if self.valid_until <= frame {
            return;
        }
        self.valid_until = if timed { frame } else { self.valid_until.min(sweep.first_meeting(ray, t, frame) - 1) };
    }

    /// The colour seen along a primary ray, each component in [0, 1]
    /// (SPEC 6), as a bracket. The path is kept in `slot` so that
    /// [`Tracer::resume`] can finish it if the cutoff paused it.
    pub fn trace(&mut self, slot: usize, primary: &Ray) -> Bracket {
        self.counts.primary += 1;
        if GLIMPSE {
            self.glimpse = Glimpse::start(self.lighting.pixel_angle);
        }
        let mut levels = std::mem::take(&mut self.paths[slot].levels);
        levels.clear();
        let (tail, paused) = self.follow(&mut levels, *primary, self.lighting.skips.negligible_reflection);
        let bracket = fold(&levels, tail);
        self.paths[slot] = Path { levels, paused };
        bracket
    }

    /// The exact colour of the path in `slot`: a paused path is followed to
    /// its end without the cutoff; any other is folded again as it is.
    pub fn resume(&mut self, slot: usize) -> DVec3 {
        let mut levels = std::mem::take(&mut self.paths[slot].levels);
        let tail = match self.paths[slot].paused.take() {
            Some(ray) => {
                self.resumed += 1;
                self.counts.reflection += 1;
                self.follow(&mut levels, ray, false).0
            }
            None => Tail::Black,
        };
        let colour = fold(&levels, tail).lo;
        self.paths[slot].levels = levels;
        colour
    }

    /// Follows the path from `ray` (at level `levels.len()`), appending a
    /// level per hit. Returns what lies past the last level and, when the
    /// cutoff stopped it, the reflected ray not traced.
    #[inline(always)]
    fn follow(&mut self, levels: &mut Vec<Level>, mut ray: Ray, cutoff: bool) -> (Tail, Option<Ray>) {
        let mut weight: f64 = levels.iter().map(|l| l.ks).product();
        loop {
            let found = self.geometry.closest_hit(&ray);
            if WATCH {
                self.watch(&ray, found.map_or(f64::INFINITY, |h| h.t), found.is_some_and(|h| h.timed));
            }
            let Some(hit) = found else {
                if GLIMPSE {
                    self.glimpse.miss();
                }
                return (Tail::Black, None);
            };
            if GLIMPSE {
                self.glimpse.hit(&ray, &hit, weight);
            }
            let origin = offset_by(hit.point, hit.normal, G::OFFSET_SCALE);
            let local = self.local_colour(&ray, &hit, origin);
            let ks = hit.material.ks;
            let level = levels.len() as u32;
            if level >= self.lighting.depth || (ks == 0.0 && self.lighting.skips.zero_ks) {
                // SPEC 6: at level `depth` the reflection term is dropped; with
                // ks = 0 it is `0 * colour = +0` and adding it changes nothing.
                levels.push(Level { local, ks: 0.0 });
                return (Tail::Black, None);
            }
            levels.push(Level { local, ks });
            weight *= ks;
            ray = reflected(&ray, &hit, origin);
            if cutoff && weight < NEGLIGIBLE_WEIGHT {
                return (Tail::Unknown, Some(ray));
            }
            self.counts.reflection += 1;
        }
    }

    /// Whether nothing blocks the shadow ray `ray`, whose direction is the
    /// one `planes` was made for. With frame reuse, the ray's answer is
    /// watched: fixed if the static part blocks it, this frame's only if
    /// just a moving object does, otherwise until a moving object may cross it.
    #[inline(always)]
    fn visible(&mut self, ray: &Ray, planes: &[PlaneShape]) -> bool {
        if !WATCH {
            return !self.geometry.blocked(ray, planes);
        }
        match self.geometry.blocker(ray, planes) {
            Blocker::Static => false,
            Blocker::Timed => {
                self.watch(ray, f64::INFINITY, true);
                false
            }
            Blocker::Nothing => {
                self.watch(ray, f64::INFINITY, false);
                true
            }
        }
    }

    /// Everything in SPEC 6's formula but the reflection term: the ambient
    /// part and, for each visible light on the front side, the diffuse and
    /// specular parts. Shadow rays start at `origin`, P moved off the surface.
    #[inline(always)]
    fn local_colour(&mut self, ray: &Ray, hit: &SurfaceHit, origin: DVec3) -> DVec3 {
        let Material { color, kd, ks, phong } = hit.material;
        let n = hit.normal;
        let skips = self.lighting.skips;
        // kd * Ia * C
        let mut c = color * (kd * self.lighting.ambient);
        for (light, planes) in self.lighting.lights.iter().zip(self.lighting.blocking_planes) {
            let l = light.direction;
            let n_dot_l = n.dot(l);
            // The formula sums only lights with N·L > 0: for the others the
            // shadow ray cannot matter, and the skip avoids it.
            if skips.back_facing_light && n_dot_l <= 0.0 {
                if GLIMPSE {
                    self.glimpse.light(false);
                }
                continue;
            }
            self.counts.shadow += 1;
            let lit = self.visible(&Ray::new(origin, l), planes) && n_dot_l > 0.0;
            if GLIMPSE {
                self.glimpse.light(lit);
            }
            if !lit {
                continue;
            }
            // kd * (N·L) * I * C
            c += color * (kd * n_dot_l * light.intensity);
            // ks * max(0, N·H)^n * I * C, with H = normalize(L - V). When
            // ks = 0 this adds exactly +0 (the power is finite, in [0, 1]).
            if skips.zero_ks && ks == 0.0 {
                continue;
            }
            let h = (l - ray.dir).normalize_or_zero();
            let n_dot_h = n.dot(h);
            // max(0, N·H)^n is exactly 0 for N·H <= 0 (n > 0, SPEC 3), and
            // adding +0 changes nothing: no need for the power.
            if n_dot_h > 0.0 || phong <= 0.0 {
                c += color * (ks * phong_power(n_dot_h.max(0.0), phong) * light.intensity);
            }
        }
        c
    }
}

/// `x^n` for the Phong term, `x` in [0, 1]. A whole exponent (the usual
/// case) is raised by repeated squaring: a handful of multiplications
/// instead of a general `pow`, which took a fifth of the render time. Its
/// relative error stays below about `n` units in the last place (`pow` is
/// within one); on the term, at most 1 in value, that is far below half an
/// 8-bit level, and the renders of every scene in the repository came out
/// byte-identical to the `pow` ones.
#[inline]
fn phong_power(x: f64, n: f64) -> f64 {
    if n.fract() == 0.0 && n.abs() <= f64::from(i32::MAX) { x.powi(n as i32) } else { x.powf(n) }
}

/// Folds a path back up: `c = clamp(local + ks * c_next)` from the last
/// level to the first (SPEC 6: clamped at every level). The tail gives
/// `c_next` below the last level: black, or unknown in `[0, 1]`.
fn fold(levels: &[Level], tail: Tail) -> Bracket {
    let (mut lo, mut hi) = match tail {
        Tail::Black => (DVec3::ZERO, DVec3::ZERO),
        Tail::Unknown => (DVec3::ZERO, DVec3::ONE),
    };
    for level in levels.iter().rev() {
        lo = clamp_unit(level.local + lo * level.ks);
        hi = clamp_unit(level.local + hi * level.ks);
    }
    Bracket { lo, hi }
}

/// Clamps each component to [0, 1]; a NaN component becomes 0.
#[inline]
fn clamp_unit(c: DVec3) -> DVec3 {
    // f64::max returns the non-NaN operand, so NaN maps to 0.
    c.max(DVec3::ZERO).min(DVec3::ONE)
}

/// The mirror ray of SPEC 6: from `origin` (P moved off the surface) along
/// `V - 2 (V·N) N`.
#[inline]
fn reflected(ray: &Ray, hit: &SurfaceHit, origin: DVec3) -> Ray {
    let v = ray.dir;
    let n = hit.normal;
    Ray::new(origin, v - n * (2.0 * v.dot(n)))
}

/// Relative size of the offset that moves secondary rays off a surface.
///
/// A hit point computed in f64 is off the true surface by a few units in
/// the last place of its largest coordinate (about `2.2e-16 * |P|`, times
/// the small error growth of the intersection formulas, which are written
/// to avoid cancellation). `1e-9 * max(1, max |P_i|)` is about a million
/// times that, so a surface never shadows or reflects itself, even at
/// coordinates of 50,000 (offset 5e-5); and it is far below anything
/// visible: a shadow or reflection goes wrong only where two surfaces are
/// closer than the offset (a billionth of the scene's size).
pub const OFFSET_SCALE: f64 = 1e-9;

/// SPEC 6: the start of secondary rays, P moved along N by an offset that
/// scales with the magnitude of P's coordinates (see [`OFFSET_SCALE`]).
#[inline]
pub fn offset_origin(point: DVec3, normal: DVec3) -> DVec3 {
    offset_by(point, normal, OFFSET_SCALE)
}

/// The offset of [`OFFSET_SCALE`] for f32 intersection tests
/// ([`super::Precision::F32`]): the rays are rounded to f32 (relative error
/// `6e-8`), and a hit distance computed in f32 is off by a few units in the
/// last place of the coordinates involved, so the f64 offset (a billionth)
/// would leave the secondary ray's origin inside the surface it starts from
/// as often as not (shadow acne all over the solar scene's spheres). `1e-4`
/// is about 800 f32 ulps: a thinner margin than f64's, which is why f32 gets
/// shadows wrong where two surfaces are closer than `1e-4 * |P|`.
pub const OFFSET_SCALE_F32: f64 = 1e-4;

/// [`offset_origin`] with the relative offset `relative`.
#[inline(always)]
pub fn offset_by(point: DVec3, normal: DVec3, relative: f64) -> DVec3 {
    let scale = point.abs().max_element().max(1.0);
    point + normal * (relative * scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fold_clamps_at_every_level() {
        // Level 0: local 0.5, ks 0.5; level 1: local 3.0 (clamped to 1).
        let levels = [Level { local: DVec3::splat(0.5), ks: 0.5 }, Level { local: DVec3::splat(3.0), ks: 0.0 }];
        let c = fold(&levels, Tail::Black);
        // Clamped per level: 0.5 + 0.5 * 1 = 1.0; unclamped would also be 1,
        // so check a case where it matters: local 0.2 -> 0.2 + 0.5*1 = 0.7,
        // not 0.2 + 0.5*3 = 1.7 -> 1.
        assert_eq!(c.lo, DVec3::ONE);
        let levels = [Level { local: DVec3::splat(0.2), ks: 0.5 }, Level { local: DVec3::splat(3.0), ks: 0.0 }];
        assert_eq!(fold(&levels, Tail::Black).lo, DVec3::splat(0.7));
    }

    #[test]
    fn fold_brackets_an_unknown_tail() {
        let levels = [Level { local: DVec3::new(0.1, 0.99, 0.5), ks: 0.001 }];
        let b = fold(&levels, Tail::Unknown);
        assert_eq!(b.lo, DVec3::new(0.1, 0.99, 0.5));
        assert_eq!(b.hi, DVec3::new(0.1 + 0.001, 0.99 + 0.001, 0.5 + 0.001));
    }

    #[test]
    fn offset_scales_with_coordinates() {
        assert_eq!(offset_origin(DVec3::ZERO, DVec3::Y), DVec3::new(0.0, 1e-9, 0.0));
        let far = offset_origin(DVec3::new(50_000.0, 0.0, 0.0), DVec3::Y);
        assert!((far.y - 5e-5).abs() < 1e-15);
    }

    #[test]
    fn phong_power_agrees_with_powf() {
        for n in [1.0, 2.0, 7.0, 20.0, 50.0, 80.0, 333.0, 10_000.0, 0.5, 12.75] {
            for k in 0..=1000 {
                let x = f64::from(k) / 1000.0;
                let (ours, general) = (phong_power(x, n), x.powf(n));
                let tolerance = (n + 4.0) * f64::EPSILON * general + f64::MIN_POSITIVE;
                assert!((ours - general).abs() <= tolerance, "{x}^{n}: {ours} against {general}");
            }
        }
    }

    #[test]
    fn clamp_unit_removes_nan() {
        assert_eq!(clamp_unit(DVec3::new(f64::NAN, -1.0, 2.0)), DVec3::new(0.0, 0.0, 1.0));
    }
}
