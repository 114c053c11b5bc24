//! The colour of a path: a port of rayrepl's `render::shade` (SPEC 6),
//! the same arithmetic in the same order, with the same work-saving skips
//! (no shadow ray towards a light facing away, no specular term and no
//! reflection ray when `ks` is 0), so the images and the ray counts are
//! rayrepl's.
//!
//! ```text
//! colour(V) = clamp( kd*Ia*C
//!                  + Σ_j visible, N·Lj > 0 ( kd*(N·Lj)*Ij*C + ks*max(0, N·Hj)^n*Ij*C )
//!                  + ks * colour(reflected ray) )        Hj = normalize(Lj - V)
//! ```

use glam::DVec3;
use rayrepl::render::intersect::PlaneShape;
use rayrepl::render::shade::{clamp_unit, offset_origin, phong_power};
use rayrepl::render::{MAX_DEPTH, Ray, RayCounts};
use rayrepl::scene::{Light, Material, Scene};

use crate::geometry::{Geometry, LANES, Query, SurfaceHit};

/// Everything constant over one image that the formula needs (rayrepl's
/// `shade::Lighting`).
pub struct Lighting<'a> {
    /// Ambient intensity Ia.
    pub ambient: f64,
    /// The lights.
    pub lights: &'a [Light],
    /// For each light, the planes that can block rays towards it: those
    /// with `n·L < 0` (rayrepl's `SceneGeometry::planes_blocking`).
    pub blocking_planes: Vec<Vec<PlaneShape>>,
    /// Number of reflections followed (SPEC 6 `depth`).
    pub depth: u32,
}

impl<'a> Lighting<'a> {
    /// The lighting of `scene` over the planes `planes`, followed down to
    /// `depth` reflections (at most rayrepl's `MAX_DEPTH`).
    pub fn new(scene: &'a Scene, planes: &[PlaneShape], depth: u32) -> Lighting<'a> {
        let blocking_planes = scene
            .lights
            .iter()
            .map(|l| planes.iter().copied().filter(|p| p.normal.dot(l.direction) < 0.0).collect())
            .collect();
        Lighting { ambient: scene.ambient, lights: &scene.lights, blocking_planes, depth: depth.min(MAX_DEPTH) }
    }
}

/// One level of a path: the local colour and the weight `ks` of the
/// reflection term (0 when there is none).
#[derive(Debug, Clone, Copy)]
struct Level {
    local: DVec3,
    ks: f64,
}

/// Traces paths through the geometry with single rays and counts them
/// (rayrepl's `shade::Tracer` with the unit observer).
pub struct Tracer<'a> {
    geometry: &'a Geometry<'a>,
    lighting: &'a Lighting<'a>,
    query: Box<Query>,
    /// The query of packets (coherent rays).
    packet_query: Box<Query>,
    /// For the camera rays of a packet: per light, per lane, whether the
    /// shadow ray is blocked.
    packet_blocked: Vec<[bool; LANES]>,
    /// Rays traced so far.
    pub counts: RayCounts,
    levels: Vec<Level>,
}

impl<'a> Tracer<'a> {
    /// A tracer over `geometry` with the image constants `lighting`.
    pub fn new(geometry: &'a Geometry<'a>, lighting: &'a Lighting<'a>) -> Tracer<'a> {
        Tracer {
            geometry,
            lighting,
            query: Query::new(false),
            packet_query: Query::new(true),
            packet_blocked: vec![[false; LANES]; lighting.lights.len()],
            counts: RayCounts::default(),
            levels: Vec::new(),
        }
    }

    /// SPEC 6: the colour seen along a camera ray (rayrepl's `Tracer::trace`).
    #[inline(always)]
    pub fn trace(&mut self, primary: &Ray) -> DVec3 {
        self.counts.primary += 1;
        let first = self.geometry.closest_hit(&mut self.query, primary);
        self.trace_from(primary, first, None)
    }

    /// [`Tracer::trace`] for up to 16 camera rays (those `valid` marks):
    /// their closest hits and their shadow rays are traced as packets
    /// (`rtcIntersect16`, `rtcOccluded16`, one packet per light), the
    /// reflections as single rays. Returns each lane's colour (black for
    /// the others).
    pub fn trace16(&mut self, primaries: &[Ray; LANES], valid: &[bool; LANES]) -> [DVec3; LANES] {
        self.counts.primary += valid.iter().filter(|&&v| v).count() as u64;
        let hits = self.geometry.closest_hits16(&mut self.packet_query, primaries, valid);
        let origins: [DVec3; LANES] =
            std::array::from_fn(|i| hits[i].map_or(DVec3::ZERO, |h| offset_origin(h.point, h.normal, h.t)));
        for (j, (light, planes)) in self.lighting.lights.iter().zip(&self.lighting.blocking_planes).enumerate() {
            let l = light.direction;
            let mut wanted = [false; LANES];
            for lane in 0..LANES {
                // The shadow rays `local_colour` would trace: N·L > 0.
                wanted[lane] = hits[lane].is_some_and(|h| h.normal.dot(l) > 0.0);
            }
            self.counts.shadow += wanted.iter().filter(|&&w| w).count() as u64;
            let rays = std::array::from_fn(|lane| Ray::new(origins[lane], l));
            self.packet_blocked[j] = self.geometry.blocked16(&mut self.packet_query, &rays, &wanted, planes);
        }
        std::array::from_fn(|lane| {
            if valid[lane] { self.trace_from(&primaries[lane], hits[lane], Some(lane)) } else { DVec3::ZERO }
        })
    }

    /// [`Tracer::trace`] once the camera ray's hit `first` is known; the
    /// primary ray is counted by the caller. With `lane`, the camera ray's
    /// shadow rays were traced by [`Tracer::trace16`] (lane `lane`).
    #[inline(always)]
    fn trace_from(&mut self, primary: &Ray, first: Option<SurfaceHit>, lane: Option<usize>) -> DVec3 {
        let mut levels = std::mem::take(&mut self.levels);
        levels.clear();
        let mut ray = *primary;
        let mut found = first;
        let mut lane = lane;
        while let Some(hit) = found {
            // Shadow and mirror rays start at P moved off the surface.
            let origin = offset_origin(hit.point, hit.normal, hit.t);
            let local = self.local_colour(&ray, &hit, origin, lane.take());
            let ks = hit.material.ks;
            // With ks = 0 the reflection term is `0 * colour = +0`.
            let reflects = levels.len() < self.lighting.depth as usize && ks != 0.0;
            levels.push(Level { local, ks: if reflects { ks } else { 0.0 } });
            if !reflects {
                break;
            }
            self.counts.reflection += 1;
            ray = reflected(&ray, &hit, origin);
            found = self.geometry.closest_hit(&mut self.query, &ray);
        }
        let colour = levels.iter().rev().fold(DVec3::ZERO, |next, level| clamp_unit(level.local + next * level.ks));
        self.levels = levels;
        colour
    }

    /// rayrepl's `Tracer::local_colour`: all of SPEC 6's formula at `hit`
    /// but the reflection term. Shadow rays start at `origin`; with
    /// `lane`, they were traced in a packet, lane `lane`.
    #[inline(always)]
    fn local_colour(&mut self, ray: &Ray, hit: &SurfaceHit, origin: DVec3, lane: Option<usize>) -> DVec3 {
        let Material { color, kd, ks, phong } = hit.material;
        let n = hit.normal;
        // kd * Ia * C
        let mut c = color * (kd * self.lighting.ambient);
        for (j, (light, planes)) in self.lighting.lights.iter().zip(&self.lighting.blocking_planes).enumerate() {
            let l = light.direction;
            let n_dot_l = n.dot(l);
            // Only lights with N·L > 0 count: no shadow ray for the others.
            if n_dot_l <= 0.0 {
                continue;
            }
            let blocked = match lane {
                Some(lane) => self.packet_blocked[j][lane],
                None => {
                    self.counts.shadow += 1;
                    self.geometry.blocked(&mut self.query, &Ray::new(origin, l), planes)
                }
            };
            if blocked {
                continue;
            }
            // kd * (N·L) * I * C
            c += color * (kd * n_dot_l * light.intensity);
            // ks * max(0, N·H)^n * I * C: exactly +0 when ks = 0.
            if ks == 0.0 {
                continue;
            }
            let h = (l - ray.dir).normalize_or_zero();
            let n_dot_h = n.dot(h);
            if n_dot_h > 0.0 || phong <= 0.0 {
                c += color * (ks * phong_power(n_dot_h.max(0.0), phong) * light.intensity);
            }
        }
        c
    }
}

/// rayrepl's `shade::reflected`: from `origin` along `V - 2 (V·N) N`.
#[inline]
fn reflected(ray: &Ray, hit: &SurfaceHit, origin: DVec3) -> Ray {
    let v = ray.dir;
    let n = hit.normal;
    Ray::new(origin, v - n * (2.0 * v.dot(n)))
}
