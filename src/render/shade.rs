//! The colour of a path: SPEC 6's formula, and nothing else.
//!
//! ```text
//! colour(V) = clamp( kd*Ia*C
//!                  + Σ_j visible, N·Lj > 0 ( kd*(N·Lj)*Ij*C + ks*max(0, N·Hj)^n*Ij*C )
//!                  + ks * colour(reflected ray) )        Hj = normalize(Lj - V)
//! ```
//!
//! [`Tracer`]'s `trace` computes it level by level down a path of mirror
//! reflections and folds the levels back up.
//! What frame reuse, adaptive anti-aliasing and the explanation of a pixel
//! learn about a path reaches them through a [`PathObserver`]; the unit
//! observer `()` does nothing and compiles away.

use glam::DVec3;

use super::geometry::{Blocker, SceneGeometry, SurfaceHit};
use super::intersect::{PlaneShape, Ray};
use super::options::{MAX_DEPTH, RayCounts, Skips};
use crate::scene::{Light, Material, Scene};

/// Watches the paths traced for a pixel. Every method does nothing by
/// default, so `()`, the observer of a plain render, costs nothing.
pub(crate) trait PathObserver {
    /// Whether [`PathObserver::shadow`] is wanted: it needs to know which
    /// part of the geometry blocks a shadow ray, a dearer query than
    /// whether anything does.
    const WANTS_BLOCKER: bool = false;

    /// A ray whose colour reaches the pixel with weight `weight` (the
    /// product of the `ks` above it) met `hit`, or nothing.
    #[inline(always)]
    fn hit(&mut self, _ray: &Ray, _hit: Option<&SurfaceHit>, _weight: f64) {}

    /// The ambient part `kd*Ia*C` of the current hit's colour.
    #[inline(always)]
    fn ambient(&mut self, _part: DVec3) {}

    /// What the next light adds at the current hit; called for every
    /// light, in order.
    #[inline(always)]
    fn light(&mut self, _term: LightTerm) {}

    /// What blocks the shadow ray `ray` (only with
    /// [`PathObserver::WANTS_BLOCKER`]).
    #[inline(always)]
    fn shadow(&mut self, _ray: &Ray, _blocker: Blocker) {}

    /// The colour of level `level` of the path (0: the camera ray's hit),
    /// clamped; called from the deepest level up, the last call giving the
    /// path's colour.
    #[inline(always)]
    fn level_colour(&mut self, _level: usize, _colour: DVec3) {}
}

/// What one light adds at a hit (SPEC 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum LightTerm {
    /// `N·L <= 0`: the light is behind the surface; nothing.
    FacingAway,
    /// Something blocks the shadow ray: nothing.
    Shadowed(Ray),
    /// The diffuse part `kd*(N·L)*I*C` and the specular part
    /// `ks*max(0, N·H)^n*I*C`.
    Lit {
        /// The diffuse part.
        diffuse: DVec3,
        /// The specular part.
        specular: DVec3,
    },
}

impl PathObserver for () {}

/// Everything constant over one image that the formula needs.
#[derive(Debug, Clone)]
pub(crate) struct Lighting<'a> {
    /// Ambient intensity Ia.
    pub ambient: f64,
    /// The lights.
    pub lights: &'a [Light],
    /// For each light, the planes that can block rays towards it
    /// ([`SceneGeometry::planes_blocking`]).
    pub blocking_planes: Vec<Vec<PlaneShape>>,
    /// Number of reflections followed (SPEC 6 `depth`).
    pub depth: u32,
    /// Which work-saving shortcuts are on.
    pub skips: Skips,
}

impl<'a> Lighting<'a> {
    /// The lighting of `scene`, whose geometry is `geometry`, followed down
    /// to `depth` reflections (at most [`MAX_DEPTH`]).
    pub fn new(scene: &'a Scene, geometry: &SceneGeometry, depth: u32, skips: Skips) -> Lighting<'a> {
        let blocking_planes = scene.lights.iter().map(|l| geometry.planes_blocking(l.direction)).collect();
        Lighting { ambient: scene.ambient, lights: &scene.lights, blocking_planes, depth: depth.min(MAX_DEPTH), skips }
    }
}

/// Traces paths through a scene's geometry and counts the rays.
pub(crate) struct Tracer<'a> {
    geometry: &'a SceneGeometry,
    lighting: &'a Lighting<'a>,
    /// Rays traced so far.
    pub counts: RayCounts,
    /// The levels of the path being traced (a buffer kept for reuse; at
    /// most `depth + 1` long).
    levels: Vec<Level>,
}

/// One level of a path: the local colour and the weight `ks` of the
/// reflection term (0 when there is none).
#[derive(Debug, Clone, Copy)]
struct Level {
    local: DVec3,
    ks: f64,
}

impl<'a> Tracer<'a> {
    /// A tracer over `geometry` with the image constants `lighting`.
    pub fn new(geometry: &'a SceneGeometry, lighting: &'a Lighting<'a>) -> Tracer<'a> {
        Tracer { geometry, lighting, counts: RayCounts::default(), levels: Vec::with_capacity(8) }
    }

    /// SPEC 6: the colour seen along a camera ray, each component in [0, 1].
    ///
    /// Down the path of mirror reflections, each level's local colour (all
    /// of the formula but the reflection term) and its `ks` are recorded, to
    /// level `depth` at most; back up, `colour = clamp(local + ks *
    /// colour(reflected ray))` folds them, clamping at every level. Below
    /// the last level the colour is black: the ray met nothing, or the
    /// reflection term is dropped. (A loop, not recursion: measured faster.)
    #[inline(always)]
    pub fn trace<O: PathObserver>(&mut self, primary: &Ray, observer: &mut O) -> DVec3 {
        self.counts.primary += 1;
        let mut levels = std::mem::take(&mut self.levels);
        levels.clear();
        let (mut ray, mut weight) = (*primary, 1.0);
        loop {
            let found = self.geometry.closest_hit(&ray);
            observer.hit(&ray, found.as_ref(), weight);
            let Some(hit) = found else { break };
            // Shadow and mirror rays start at P moved off the surface.
            let origin = offset_origin(hit.point, hit.normal, hit.t);
            let local = self.local_colour(&ray, &hit, origin, observer);
            let ks = hit.material.ks;
            // With ks = 0 the reflection term is `0 * colour = +0`, which
            // changes nothing.
            let reflects = levels.len() < self.lighting.depth as usize && (ks != 0.0 || !self.lighting.skips.zero_ks);
            levels.push(Level { local, ks: if reflects { ks } else { 0.0 } });
            if !reflects {
                break;
            }
            self.counts.reflection += 1;
            weight *= ks;
            ray = reflected(&ray, &hit, origin);
        }
        let colour = levels.iter().enumerate().rev().fold(DVec3::ZERO, |next, (depth, level)| {
            let colour = clamp_unit(level.local + next * level.ks);
            observer.level_colour(depth, colour);
            colour
        });
        self.levels = levels;
        colour
    }

    /// All of SPEC 6's formula at `hit` but the reflection term: the ambient
    /// part and, for each light on the front side that nothing blocks, the
    /// diffuse and specular parts. Shadow rays start at `origin`.
    #[inline(always)]
    fn local_colour<O: PathObserver>(&mut self, ray: &Ray, hit: &SurfaceHit, origin: DVec3, observer: &mut O) -> DVec3 {
        let Material { color, kd, ks, phong } = hit.material;
        let (n, skips) = (hit.normal, self.lighting.skips);
        // kd * Ia * C
        let mut c = color * (kd * self.lighting.ambient);
        observer.ambient(c);
        for (light, planes) in self.lighting.lights.iter().zip(&self.lighting.blocking_planes) {
            let l = light.direction;
            let n_dot_l = n.dot(l);
            // Only lights with N·L > 0 count: for the others the shadow ray
            // cannot matter, and the skip avoids it.
            if skips.back_facing_light && n_dot_l <= 0.0 {
                observer.light(LightTerm::FacingAway);
                continue;
            }
            let lit = self.visible(&Ray::new(origin, l), planes, observer) && n_dot_l > 0.0;
            if !lit {
                // Built only for an observer that reads it: the unit
                // observer's render does not pay for it.
                let term =
                    if n_dot_l <= 0.0 { LightTerm::FacingAway } else { LightTerm::Shadowed(Ray::new(origin, l)) };
                observer.light(term);
                continue;
            }
            // kd * (N·L) * I * C
            let diffuse = color * (kd * n_dot_l * light.intensity);
            c += diffuse;
            // ks * max(0, N·H)^n * I * C: exactly +0 when ks = 0 (the power
            // is finite, in [0, 1]), and when N·H <= 0 (n > 0, SPEC 3).
            if skips.zero_ks && ks == 0.0 {
                observer.light(LightTerm::Lit { diffuse, specular: DVec3::ZERO });
                continue;
            }
            let h = (l - ray.dir).normalize_or_zero();
            let n_dot_h = n.dot(h);
            let mut specular = DVec3::ZERO;
            if n_dot_h > 0.0 || phong <= 0.0 {
                specular = color * (ks * phong_power(n_dot_h.max(0.0), phong) * light.intensity);
                c += specular;
            }
            observer.light(LightTerm::Lit { diffuse, specular });
        }
        c
    }

    /// Whether nothing blocks the shadow ray `ray`, whose direction is the
    /// one `planes` was made for (SPEC 6: any object at any distance).
    #[inline(always)]
    fn visible<O: PathObserver>(&mut self, ray: &Ray, planes: &[PlaneShape], observer: &mut O) -> bool {
        self.counts.shadow += 1;
        if !O::WANTS_BLOCKER {
            return !self.geometry.blocked(ray, planes);
        }
        let blocker = self.geometry.blocker(ray, planes);
        observer.shadow(ray, blocker);
        blocker == Blocker::Nothing
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
pub fn phong_power(x: f64, n: f64) -> f64 {
    if n.fract() == 0.0 && n.abs() <= f64::from(i32::MAX) { x.powi(n as i32) } else { x.powf(n) }
}

/// Clamps each component to [0, 1]; a NaN component becomes 0.
#[inline]
pub fn clamp_unit(c: DVec3) -> DVec3 {
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
/// A hit point `P = S + t V` computed in f64 is off the true surface by a
/// few units in the last place of the larger of `|S|` and `t` (about
/// `2.2e-16` times it, times the small error growth of the intersection
/// formulas, which are written to avoid cancellation). The offset is
/// `1e-9 * max(max |P_i|, t)`: `|S| <= |P| + t`, so that is a million times
/// the error and a surface never shadows or reflects itself; and it is far
/// below anything visible: a shadow or reflection goes wrong only where two
/// surfaces are closer than a billionth of their distance from the origin
/// or from the ray's start. It has no absolute floor, so a scene with every
/// length multiplied by `2^k` gets offsets multiplied by exactly `2^k`.
pub const OFFSET_SCALE: f64 = 1e-9;

/// SPEC 6: the start of secondary rays, P (at distance `t` along the ray
/// that found it) moved along N by an offset that scales with the
/// magnitude of P's coordinates and with `t` (see [`OFFSET_SCALE`]).
#[inline]
pub fn offset_origin(point: DVec3, normal: DVec3, t: f64) -> DVec3 {
    let scale = point.abs().max_element().max(t);
    point + normal * (OFFSET_SCALE * scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_scales_with_coordinates_and_distance() {
        assert_eq!(offset_origin(DVec3::ZERO, DVec3::Y, 2.0), DVec3::new(0.0, 2e-9, 0.0));
        let far = offset_origin(DVec3::new(50_000.0, 0.0, 0.0), DVec3::Y, 2.0);
        assert!((far.y - 5e-5).abs() < 1e-15);
        let tiny = offset_origin(DVec3::new(0.0, 3e-200, 0.0), DVec3::Y, 1e-200);
        assert_eq!(tiny.y, 3e-200 + 3e-209);
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
