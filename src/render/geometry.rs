//! The scene's geometry in the form rays are traced against: a BVH over the
//! spheres and boxes, planes in a list of their own (unbounded, so tested
//! directly), and the materials.
//!
//! An animation keeps the part that does not depend on `time` across frames
//! ([`SceneGeometry::with_static`]) and rebuilds only the rest.
//!
//! Lengths are held in a unit of the scene's own size: every length is
//! multiplied by a power of two chosen from the scene ([`SceneGeometry::scale`]),
//! which is exact, so the pixels are those of the scene as given while no
//! square or product of lengths overflows or underflows, whatever the
//! scene's units (SPEC 6: the same pixels at every scale).

use std::sync::Arc;

use glam::DVec3;
use rayon::prelude::*;

use super::bvh::{self, Bvh};
use super::camera::{PrimaryRays, Screen};
use super::intersect::{Aabb, Bounded, PlaneShape, Ray, ShapeClass};
use super::isa::Isa;
use crate::scene::{Camera, Material, Primitive, Scene, Shape};

/// The primitives of one part of a scene, ready for ray queries.
#[derive(Debug, Clone)]
pub struct Geometry {
    bvh: Bvh,
    /// Materials of the bounded objects, in tree order.
    bounded_materials: Vec<Material>,
    planes: Vec<PlaneShape>,
    plane_materials: Vec<Material>,
    /// The power of two every length was multiplied by.
    scale: f64,
    /// Where each bounded object (in tree order), then each plane, stands
    /// in the list of primitives it was built from: to tell which `put`
    /// made what a ray hit.
    sources: Vec<u32>,
}

/// Which object of a [`Geometry`] a ray hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ObjectId {
    Bounded(u32),
    Plane(u32),
}

/// The nearest hit of a ray in a [`Geometry`].
#[derive(Debug, Clone, Copy, PartialEq)]
struct GeometryHit {
    t: f64,
    object: ObjectId,
}

impl GeometryHit {
    /// Whether this hit, on an object that depends on `time`, goes before
    /// `fixed`, the nearest hit on the static objects (which may be up to
    /// [`bvh::reach_past`] farther than this one and still count as level
    /// with it). It does when it is nearer by more than that tolerance, or
    /// when it is on a sphere or a box and `fixed` is on a plane: the order
    /// [`Geometry::closest_hit`] gives hits at the same distance in one list.
    fn goes_before_fixed(&self, fixed: GeometryHit) -> bool {
        self.t < bvh::nearer_than(fixed.t)
            || matches!((self.object, fixed.object), (ObjectId::Bounded(_), ObjectId::Plane(_)))
    }
}

/// A surface point found by a ray: what shading needs (SPEC 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    /// Distance along the ray.
    pub t: f64,
    /// The hit point P.
    pub point: DVec3,
    /// Unit normal N at P, facing the side the ray came from.
    pub normal: DVec3,
    /// The material of the object hit.
    pub material: Material,
    /// Whether the object hit depends on `time` (is in the part of the [`SceneGeometry`] rebuilt at every frame).
    pub timed: bool,
    /// Which object was hit: equal for two hits of one render exactly when
    /// they are on the same object.
    pub surface: u64,
    /// How wide the object looks from the ray, in world units: a sphere's
    /// diameter; for a box, its middle size foreshortened by the angle of
    /// the face hit; infinite for a plane. Over `t` it is the angle the
    /// object spans (see [`super::adaptive::Glimpse::finest`]).
    pub width: f64,
    /// The curvature of the surface at the hit: 1 / radius for a sphere, 0
    /// for a flat face.
    pub curvature: f64,
}

impl Geometry {
    /// Prepares `primitives` with every length multiplied by `scale` (a
    /// power of two): builds the BVH over spheres and boxes and lists the
    /// planes, in parallel with rayon.
    fn build(primitives: &[Primitive], scale: f64) -> Geometry {
        // Memory runs out long before: each primitive takes over 100 bytes.
        let count = u32::try_from(primitives.len()).expect("fewer than 2^32 primitives");
        let shape = |k: u32| ShapeClass::from(&primitives[k as usize].shape.scaled(scale));
        let (plane_sources, bounded_sources): (Vec<u32>, Vec<u32>) =
            (0..count).into_par_iter().partition(|&k| matches!(shape(k), ShapeClass::Plane(_)));
        let (bvh, order) = Bvh::build(bounded_sources.len(), |k| match shape(bounded_sources[k]) {
            ShapeClass::Bounded(b) => b,
            ShapeClass::Plane(_) => unreachable!("the planes were set apart"),
        });
        let planes: Vec<PlaneShape> = plane_sources
            .iter()
            .map(|&k| match shape(k) {
                ShapeClass::Plane(p) => p,
                ShapeClass::Bounded(_) => unreachable!("only the planes were set apart"),
            })
            .collect();
        let sources: Vec<u32> = order.par_iter().map(|&k| bounded_sources[k as usize]).chain(plane_sources).collect();
        let material = |&k: &u32| primitives[k as usize].material;
        let (bounded_sources, plane_sources) = sources.split_at(order.len());
        Geometry {
            bvh,
            bounded_materials: bounded_sources.par_iter().map(material).collect(),
            planes,
            plane_materials: plane_sources.iter().map(material).collect(),
            scale,
            sources,
        }
    }

    /// The union of two geometries without trees (both small), `a` first:
    /// one flat list is cheaper to query than two.
    fn concat_flat(a: &Geometry, b: &Geometry) -> Option<Geometry> {
        let bvh = Bvh::concat_flat(&a.bvh, &b.bvh)?;
        let join = |x: &[Material], y: &[Material]| x.iter().chain(y).copied().collect();
        let (a_bounded, b_bounded) = (a.bvh.objects().len(), b.bvh.objects().len());
        let sources = a.sources[..a_bounded]
            .iter()
            .chain(&b.sources[..b_bounded])
            .chain(&a.sources[a_bounded..])
            .chain(&b.sources[b_bounded..])
            .copied()
            .collect();
        Some(Geometry {
            bvh,
            bounded_materials: join(&a.bounded_materials, &b.bounded_materials),
            planes: a.planes.iter().chain(&b.planes).copied().collect(),
            plane_materials: join(&a.plane_materials, &b.plane_materials),
            scale: a.scale,
            sources,
        })
    }

    /// Whether there is no primitive at all.
    pub fn is_empty(&self) -> bool {
        self.bvh.is_empty() && self.planes.is_empty()
    }

    /// For `--stats`: how the spheres and boxes are searched, in a tree or
    /// a flat list.
    fn search(&self) -> String {
        let count = self.bvh.objects().len();
        if self.bvh.is_flat() { format!("a list of {count}") } else { format!("a tree of {count}") }
    }

    /// Number of primitives.
    pub fn len(&self) -> usize {
        self.bvh.objects().len() + self.planes.len()
    }

    /// The nearest hit with `0 < t < t_max`, if any (up to the BVH's
    /// tolerance past `t_max`). Of hits at the same distance (within
    /// [`bvh::reach_past`]), a sphere or a box goes before a plane, and an
    /// earlier object before a later one.
    #[inline(always)]
    fn closest_hit(&self, ray: &Ray, t_max: f64) -> Option<GeometryHit> {
        let (mut t, index) = self.bvh.closest_hit(ray, t_max);
        let mut object = (index != u32::MAX).then_some(ObjectId::Bounded(index));
        let mut before = bvh::nearer_than(t);
        for (k, plane) in self.planes.iter().enumerate() {
            let tp = plane.hit(ray);
            if tp < before {
                (t, before) = (tp, bvh::nearer_than(tp));
                object = Some(ObjectId::Plane(k as u32));
            }
        }
        object.map(|object| GeometryHit { t, object })
    }

    /// Whether anything is hit at `0 < t` (planes first: they are cheap and
    /// large).
    #[inline]
    fn any_hit(&self, ray: &Ray) -> bool {
        self.planes.iter().any(|p| p.hit(ray) < f64::INFINITY) || self.bvh.any_hit(ray, f64::INFINITY)
    }

    /// The planes that a ray along `dir` moves towards (`n·dir < 0`): the
    /// only ones that can stop it.
    fn planes_facing(&self, dir: DVec3) -> impl Iterator<Item = PlaneShape> + '_ {
        self.planes.iter().copied().filter(move |p| p.normal.dot(dir) < 0.0)
    }

    /// The surface data of a hit found by [`Geometry::closest_hit`].
    #[inline(always)]
    fn surface(&self, ray: &Ray, hit: GeometryHit, timed: bool) -> SurfaceHit {
        let point = ray.at(hit.t);
        let (key, normal, material, width, curvature) = match hit.object {
            ObjectId::Bounded(k) => {
                let object: &Bounded = &self.bvh.objects()[k as usize];
                let normal = object.normal(ray, hit.t);
                let (width, curvature) = match object {
                    Bounded::Sphere(s) => (2.0 * s.radius, 1.0 / s.radius),
                    Bounded::Box(b) => (2.0 * b.middle_half_size() * normal.dot(ray.dir).abs(), 0.0),
                };
                (u64::from(k) << 2, normal, self.bounded_materials[k as usize], width, curvature)
            }
            ObjectId::Plane(k) => {
                let (normal, material) = (self.planes[k as usize].normal(), self.plane_materials[k as usize]);
                (u64::from(k) << 2 | 1, normal, material, f64::INFINITY, 0.0)
            }
        };
        let surface = key | u64::from(timed) << 1;
        SurfaceHit { t: hit.t, point, normal, material, timed, surface, width, curvature }
    }
}

/// The power of two `2^-e` that brings the scene's size into `[1, 2)`:
/// in that unit the intersection formulas' squares stay far from overflow
/// and underflow. The size is the camera distance, which sets the scale of
/// what the picture shows (a huge sphere used as a floor does not push the
/// rest out of range); without one, the largest primitive's reach.
/// Multiplying by a power of two is exact, and every formula of the
/// renderer gives lengths proportional to its input lengths (no absolute
/// epsilon), so the choice changes no pixel.
pub fn working_scale(scene: &Scene) -> f64 {
    let reach = |shape: &Shape| match *shape {
        Shape::Sphere { center, radius } => center.abs().max_element() + radius,
        Shape::Box { center, half, .. } => center.abs().max_element() + half.max_element(),
        Shape::Plane { shift, .. } => shift.abs(),
    };
    let distance = scene.camera.distance.abs();
    let size = if distance > 0.0 && distance.is_finite() {
        distance
    } else {
        scene.primitives.iter().chain(&scene.timed_primitives).map(|p| reach(&p.shape)).fold(0.0, f64::max)
    };
    if !(size > 0.0 && size.is_finite()) {
        return 1.0;
    }
    // Within f64's normal range, so the power itself is exact; no tighter,
    // so that every size of that range gets a unit that follows it (the
    // same bytes when the scene is scaled by a power of two).
    let exponent = size.log2().floor().clamp(-1022.0, 1022.0) as i32;
    2f64.powi(-exponent)
}

/// What blocks a shadow ray ([`SceneGeometry::blocker`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Blocker {
    /// Nothing: the light is visible.
    Nothing,
    /// A primitive that does not depend on `time`.
    Static,
    /// Only primitives that depend on `time`.
    Timed,
}

/// A scene's geometry split for animations: the static part (built once,
/// shared across frames) and the part that depends on `time`.
#[derive(Debug, Clone)]
pub struct SceneGeometry {
    static_part: Arc<Geometry>,
    timed: Geometry,
    /// Both parts in one flat list, when both are small.
    merged: Option<Geometry>,
}

impl ObjectId {
    /// Whether, in the merged list of two geometries, this object comes
    /// from the second one (`first` is the first one).
    #[inline]
    fn in_second(self, first: &Geometry) -> bool {
        match self {
            ObjectId::Bounded(k) => k as usize >= first.bvh.objects().len(),
            ObjectId::Plane(k) => k as usize >= first.planes.len(),
        }
    }
}

impl SceneGeometry {
    /// Prepares both parts of `scene`.
    pub fn new(scene: &Scene) -> SceneGeometry {
        let scale = working_scale(scene);
        let (static_part, timed) = rayon::join(
            || Geometry::build(&scene.primitives, scale),
            || Geometry::build(&scene.timed_primitives, scale),
        );
        SceneGeometry::from_parts(Arc::new(static_part), timed)
    }

    /// Reuses an already built static part and prepares only `timed`
    /// (the next frame of an animation), in the static part's unit.
    pub fn with_static(static_part: Arc<Geometry>, timed: &[Primitive]) -> SceneGeometry {
        let timed = Geometry::build(timed, static_part.scale);
        SceneGeometry::from_parts(static_part, timed)
    }

    /// The power of two every length of the scene was multiplied by: rays
    /// traced against this geometry, and the points and distances it
    /// answers, are in that unit.
    pub fn scale(&self) -> f64 {
        self.static_part.scale
    }

    /// The primary rays of a `width` x `height` image seen by `camera`, in
    /// the geometry's unit ([`SceneGeometry::scale`]): the rays to trace
    /// against it.
    pub fn primary_rays(&self, camera: &Camera, width: u32, height: u32, screen: Screen) -> PrimaryRays {
        let camera = Camera { distance: camera.distance * self.scale(), ..*camera };
        PrimaryRays::new(&camera, width, height, screen)
    }

    fn from_parts(static_part: Arc<Geometry>, timed: Geometry) -> SceneGeometry {
        let merged = if timed.is_empty() { None } else { Geometry::concat_flat(&static_part, &timed) };
        SceneGeometry { static_part, timed, merged }
    }

    /// The geometry of [`Scene::primitives`], the same for every frame of an
    /// animation: pass it to [`SceneGeometry::with_static`] for the next frame.
    pub fn static_part(&self) -> &Arc<Geometry> {
        &self.static_part
    }

    /// For `--stats`: how the spheres and boxes are searched, in a tree or
    /// a flat list, for the fixed and the moving part, and the compiled
    /// form of the renderer that runs ([`Isa::chosen`]).
    pub fn search(&self) -> String {
        let search = match &self.merged {
            Some(merged) => merged.search(),
            None if self.timed.is_empty() => self.static_part.search(),
            None => format!("{}; those depending on time: {}", self.static_part.search(), self.timed.search()),
        };
        format!("spheres and boxes: {search}; {} code", Isa::chosen().name())
    }

    /// The nearest hit with `t > 0` (SPEC 6), with its point, facing normal
    /// and material. Of hits at the same distance (within
    /// [`bvh::reach_past`]), a sphere or a box goes before a plane, then a
    /// fixed object before a timed one, then the one put first: the order
    /// of the merged list, whichever way the parts are asked.
    #[inline(always)]
    pub fn closest_hit(&self, ray: &Ray) -> Option<SurfaceHit> {
        if let Some(merged) = &self.merged {
            return merged
                .closest_hit(ray, f64::INFINITY)
                .map(|h| merged.surface(ray, h, h.object.in_second(&self.static_part)));
        }
        let static_hit = self.static_part.closest_hit(ray, f64::INFINITY);
        if self.timed.is_empty() {
            return static_hit.map(|h| self.static_part.surface(ray, h, false));
        }
        let t_max = static_hit.map_or(f64::INFINITY, |h| h.t);
        match (self.timed.closest_hit(ray, t_max), static_hit) {
            (Some(h), Some(s)) if !h.goes_before_fixed(s) => Some(self.static_part.surface(ray, s, false)),
            (Some(h), _) => Some(self.timed.surface(ray, h, true)),
            (None, s) => s.map(|s| self.static_part.surface(ray, s, false)),
        }
    }

    /// Whether the ray hits anything at any distance `t > 0` (shadow rays,
    /// SPEC 6: "any object at any distance blocks it").
    #[inline]
    pub fn any_hit(&self, ray: &Ray) -> bool {
        self.static_part.any_hit(ray) || self.timed.any_hit(ray)
    }

    /// The planes, of both parts, that can block rays along `dir` (a
    /// light's direction): those with `n·dir < 0`. Shadow rays towards that
    /// light test only these, with [`SceneGeometry::blocked`].
    pub fn planes_blocking(&self, dir: DVec3) -> Vec<PlaneShape> {
        self.static_part.planes_facing(dir).chain(self.timed.planes_facing(dir)).collect()
    }

    /// The same answer as [`SceneGeometry::any_hit`] for a ray whose direction
    /// is the one `planes` was made for by [`SceneGeometry::planes_blocking`].
    ///
    /// Such a plane stops the ray exactly when its origin is on the seen
    /// side (`n·S > d`): moving towards the plane from there, it meets it at
    /// `t = (n·S - d) / -(n·V) > 0` (SPEC 4). One dot product per plane.
    ///
    /// Always inlined: called, it loaded the shadow ray that the shading
    /// loop had just stored, in other widths, which stalls store forwarding.
    #[inline(always)]
    pub fn blocked(&self, ray: &Ray, planes: &[PlaneShape]) -> bool {
        if planes.iter().any(|p| p.normal.dot(ray.origin) > p.shift) {
            return true;
        }
        match &self.merged {
            Some(merged) => merged.bvh.any_hit(ray, f64::INFINITY),
            None => self.static_part.bvh.any_hit(ray, f64::INFINITY) || self.timed.bvh.any_hit(ray, f64::INFINITY),
        }
    }

    /// [`SceneGeometry::blocked`], saying which part blocks the ray (the static
    /// part is asked first), for a scene whose timed part has no plane:
    /// frame reuse needs to know whether the answer can change with `time`.
    #[inline]
    pub fn blocker(&self, ray: &Ray, planes: &[PlaneShape]) -> Blocker {
        debug_assert!(self.timed.planes.is_empty(), "the blocking planes are taken as static");
        if planes.iter().any(|p| p.normal.dot(ray.origin) > p.shift) || self.static_part.bvh.any_hit(ray, f64::INFINITY)
        {
            Blocker::Static
        } else if self.timed.bvh.any_hit(ray, f64::INFINITY) {
            Blocker::Timed
        } else {
            Blocker::Nothing
        }
    }

    /// Where the primitive `hit` is on stands among
    /// [`Scene::all_primitives`] (static ones first).
    pub fn primitive_index(&self, hit: &SurfaceHit) -> usize {
        let part = match (&self.merged, hit.timed) {
            (Some(merged), _) => merged,
            (None, true) => &self.timed,
            (None, false) => &*self.static_part,
        };
        let key = (hit.surface >> 2) as usize;
        let position = if hit.surface & 1 == 1 { part.bvh.objects().len() + key } else { key };
        let source = part.sources[position] as usize;
        if hit.timed { self.static_part.len() + source } else { source }
    }

    /// The bounding boxes of the spheres and boxes among `primitives`, in
    /// this geometry's unit: what frame reuse needs to know of a frame,
    /// without building its tree.
    pub fn bounds_of(&self, primitives: &[Primitive]) -> Vec<Aabb> {
        let scale = self.static_part.scale;
        primitives
            .iter()
            .filter_map(|primitive| match ShapeClass::from(&primitive.shape.scaled(scale)) {
                ShapeClass::Bounded(b) => Some(b.bounds()),
                ShapeClass::Plane(_) => None,
            })
            .collect()
    }
}
