//! The scene's geometry as Embree traces it: spheres and boxes in one
//! Embree user geometry, whose callbacks run rayrepl's exact f64 tests,
//! and the planes in a flat list, as rayrepl keeps them.
//!
//! Embree's rays are f32. Each query keeps the f64 ray and the best hit so
//! far in a [`Query`], an intersection context extended after Embree's own
//! (Embree hands the callbacks the context pointer it was given), and uses
//! Embree's f32 `tfar` only to cull, always set past any hit the f64 test
//! could still keep. Bounds are padded and rounded outwards to f32 for the
//! same reason: a node test on the f32 ray never loses an f64 hit.

use glam::{DMat3, DVec3};
use rayrepl::render::Ray;
use rayrepl::render::bvh::{nearer_than, reach_past};
use rayrepl::render::intersect::{Bounded, BoxShape, PlaneShape, ShapeClass};
use rayrepl::scene::{Material, Scene};

use crate::embree::{
    BoundsArguments, BuildQuality, EmbreeDevice, EmbreeScene, GEOM_ID, ID, INVALID_ID, IntersectArguments,
    OccludedArguments, PRIM_ID, RtcHit16, RtcIntersectContext, RtcRay, RtcRay16, RtcRayHit, RtcRayHit16, TFAR,
    UserCallbacks, Valid16, ray_field,
};

/// Rays a [`Query`] holds: one for single rays, sixteen for a packet.
pub const LANES: usize = 16;

/// rayrepl's `render::bvh::goes_before`: whether a hit at `t` of object `k`
/// goes before `best` (distance, object; `u32::MAX` for none yet). `k` is
/// the object's index in the scene's order (fixed objects first, then those
/// that depend on `time`, each in the order put), which is rayrepl's order
/// for ties.
#[inline(always)]
fn goes_before(t: f64, k: u32, best: (f64, u32)) -> bool {
    t < nearer_than(best.0) || (t <= reach_past(best.0) && k < best.1 && t < f64::INFINITY)
}

/// Embree's f32 `tfar` once the best hit is at `t`: above `reach_past(t)`
/// by a millionth (far more than the f32 rounding of the ray and of
/// Embree's node tests), rounded up.
#[inline(always)]
fn culling_distance(t: f64) -> f32 {
    round_up(reach_past(t) * (1.0 + 1e-6))
}

/// The smallest f32 at least `x`.
#[inline(always)]
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

/// The largest f32 at most `x`.
#[inline(always)]
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// The spheres and boxes, in the scene's order, as the callbacks read them.
pub struct Objects {
    /// The objects, static ones first, then the timed ones (rayrepl's order
    /// of `Scene::all_primitives`).
    pub list: Vec<Bounded>,
    /// How far every box is grown before rounding to f32: a millionth of
    /// the scene's reach, far above the distance between the f32 and the f64
    /// ray anywhere in the scene.
    pad: f64,
    /// When every object is a box with the same axes (a rotated grid of
    /// boxes): those axes as rows (`BoxShape::to_local`) and each box's
    /// centre and half sizes. Embree then builds and traverses in that
    /// frame, where the boxes are axis-aligned and their bounds tight, as
    /// rayrepl's `bvh::SharedFrame` does; the f64 test is
    /// `BoxShape::hit_in_frame`, the same arithmetic as `BoxShape::hit`.
    frame: Option<(DMat3, Vec<(DVec3, DVec3)>)>,
}

impl Objects {
    /// The objects `list` with bounds padded by `pad`, in their common
    /// frame when they share one.
    fn new(list: Vec<Bounded>, pad: f64) -> Objects {
        let to_local = match list.first() {
            Some(Bounded::Box(b)) => Some(b.to_local),
            _ => None,
        };
        let shared = to_local.filter(|&axes| list.iter().all(|o| matches!(o, Bounded::Box(b) if b.to_local == axes)));
        let frame = shared.map(|axes| {
            let boxes = list
                .iter()
                .map(|o| match o {
                    Bounded::Box(b) => (b.center, b.half),
                    Bounded::Sphere(_) => unreachable!("a shared frame holds only boxes"),
                })
                .collect();
            (axes, boxes)
        });
        Objects { list, pad, frame }
    }

    /// Whether Embree works in the boxes' common frame.
    pub fn in_frame(&self) -> bool {
        self.frame.is_some()
    }

    /// The ray as Embree traverses it (in the common frame if there is
    /// one), and `1 / direction` in that frame (for
    /// `BoxShape::hit_in_frame`).
    #[inline(always)]
    pub fn traversed(&self, ray: &Ray) -> (Ray, DVec3) {
        match &self.frame {
            Some((to_local, _)) => {
                let d = *to_local * ray.dir;
                (Ray::new(*to_local * ray.origin, d), d.recip())
            }
            None => (*ray, DVec3::ZERO),
        }
    }

    /// rayrepl's f64 test of object `k`: the distance of its nearest hit
    /// with `t > 0` along `ray`, or infinity; `inv` is from
    /// [`Objects::traversed`].
    #[inline(always)]
    fn hit(&self, k: usize, ray: &Ray, inv: DVec3) -> f64 {
        match &self.frame {
            Some((to_local, boxes)) => {
                let (center, half) = boxes[k];
                BoxShape::hit_in_frame(*to_local, center, half, ray.origin, inv)
            }
            None => self.list[k].hit(ray),
        }
    }

    /// The box Embree builds over for object `k`: in the common frame if
    /// there is one, else in the world.
    fn bounds(&self, k: usize) -> (DVec3, DVec3) {
        match &self.frame {
            Some((to_local, boxes)) => {
                let (center, half) = boxes[k];
                let c = *to_local * center;
                (c - half, c + half)
            }
            None => {
                let b = self.list[k].bounds();
                (b.min, b.max)
            }
        }
    }
}

/// An intersection query: Embree's context first, then the f64 rays and
/// the best hits, which the callbacks reach through the context pointer.
#[repr(C)]
pub struct Query {
    context: RtcIntersectContext,
    /// The f64 rays, by Embree ray id.
    pub rays: [Ray; LANES],
    /// `1 / direction` of each ray in the objects' common frame, if any.
    pub inv: [DVec3; LANES],
    /// The best hit of each ray so far: distance and object index (scene
    /// order), `(INFINITY, u32::MAX)` for none.
    pub best: [(f64, u32); LANES],
}

impl Query {
    /// A query for incoherent (single) or `coherent` (packet) rays.
    pub fn new(coherent: bool) -> Box<Query> {
        let ray = Ray::new(DVec3::ZERO, DVec3::ZERO);
        Box::new(Query {
            context: RtcIntersectContext::new(coherent),
            rays: [ray; LANES],
            inv: [DVec3::ZERO; LANES],
            best: [(f64::INFINITY, u32::MAX); LANES],
        })
    }

    /// Embree's part of the context.
    pub fn context(&mut self) -> &mut RtcIntersectContext {
        &mut self.context
    }
}

/// A surface point found by a ray: what shading needs (rayrepl's
/// `SurfaceHit`, without what only adaptive sampling reads).
#[derive(Debug, Clone, Copy)]
pub struct SurfaceHit {
    /// Distance along the ray.
    pub t: f64,
    /// The hit point P.
    pub point: DVec3,
    /// Unit normal at P, facing the side the ray came from.
    pub normal: DVec3,
    /// The material of the object hit.
    pub material: Material,
}

/// Which object a ray hit.
#[derive(Debug, Clone, Copy)]
pub enum ObjectId {
    Bounded(u32),
    Plane(u32),
}

/// The geometry in rayrepl's working unit: Embree's scene over the objects,
/// the planes, the materials.
pub struct Geometry<'a> {
    objects: &'a Objects,
    scene: EmbreeScene<'a, Objects>,
    materials: &'a [Material],
    pub planes: &'a [PlaneShape],
    plane_materials: &'a [Material],
    /// Test every object for every ray, in the scene's order, without
    /// Embree (`--brute-force`): a check of the culling.
    pub brute_force: bool,
}

/// What the geometry is made of, in the scene's order, before Embree builds
/// anything.
pub struct Parts {
    pub objects: Objects,
    pub materials: Vec<Material>,
    pub planes: Vec<PlaneShape>,
    pub plane_materials: Vec<Material>,
}

impl Parts {
    /// The shapes of `scene` with every length multiplied by `scale` (the
    /// static primitives, then the timed ones).
    pub fn new(scene: &Scene, scale: f64, camera_distance: f64) -> Parts {
        let (mut list, mut materials, mut planes, mut plane_materials) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for primitive in scene.primitives.iter().chain(&scene.timed_primitives) {
            match ShapeClass::from(&primitive.shape.scaled(scale)) {
                ShapeClass::Bounded(b) => {
                    list.push(b);
                    materials.push(primitive.material);
                }
                ShapeClass::Plane(p) => {
                    planes.push(p);
                    plane_materials.push(primitive.material);
                }
            }
        }
        let reach = list
            .iter()
            .map(|b| {
                let bounds = b.bounds();
                bounds.min.abs().max(bounds.max.abs()).max_element()
            })
            .fold(camera_distance.abs(), f64::max);
        Parts { objects: Objects::new(list, 1e-6 * reach), materials, planes, plane_materials }
    }
}

impl<'a> Geometry<'a> {
    /// Builds Embree's scene over `parts` on `device` (`rtcCommitScene`).
    pub fn build(device: &EmbreeDevice, parts: &'a Parts, quality: BuildQuality) -> Result<Geometry<'a>, String> {
        let callbacks = UserCallbacks { bounds, intersect, occluded };
        let count = u32::try_from(parts.objects.list.len()).map_err(|_| "too many objects for Embree".to_owned())?;
        let scene = EmbreeScene::build(device, &parts.objects, count, &callbacks, quality)?;
        Ok(Geometry {
            objects: &parts.objects,
            scene,
            materials: &parts.materials,
            planes: &parts.planes,
            plane_materials: &parts.plane_materials,
            brute_force: false,
        })
    }

    /// rayrepl's `Geometry::closest_hit` and `SceneGeometry::closest_hit`:
    /// the nearest hit with `t > 0`; of hits at one distance, a sphere or a
    /// box before a plane, an earlier object before a later one.
    #[inline]
    pub fn closest_hit(&self, query: &mut Query, ray: &Ray) -> Option<SurfaceHit> {
        if self.brute_force {
            let mut best = (f64::INFINITY, u32::MAX);
            for k in 0..self.objects.list.len() {
                let t = self.objects.list[k].hit(ray);
                if goes_before(t, k as u32, best) {
                    best = (t, k as u32);
                }
            }
            return self.resolve(ray, best.0, best.1);
        }
        let (traversed, inv) = self.objects.traversed(ray);
        (query.rays[0], query.inv[0]) = (*ray, inv);
        query.best[0] = (f64::INFINITY, u32::MAX);
        let mut rayhit = RtcRayHit { ray: f32_ray(&traversed, 0), ..RtcRayHit::default() };
        rayhit.hit.geom_id = INVALID_ID;
        self.scene.intersect1(query.context(), &mut rayhit);
        let (t, index) = query.best[0];
        self.resolve(ray, t, index)
    }

    /// [`Geometry::closest_hit`] for up to 16 rays at once
    /// (`rtcIntersect16`): `rays[i]` for each lane `i` with `valid[i]`; the
    /// others' answers are `None`.
    pub fn closest_hits16(
        &self,
        query: &mut Query,
        rays: &[Ray; LANES],
        valid: &[bool; LANES],
    ) -> [Option<SurfaceHit>; LANES] {
        let mut packet = packet16();
        let mut mask = Valid16::default();
        for lane in 0..LANES {
            if !valid[lane] {
                continue;
            }
            mask.0[lane] = -1;
            let (traversed, inv) = self.objects.traversed(&rays[lane]);
            (query.rays[lane], query.inv[lane]) = (rays[lane], inv);
            query.best[lane] = (f64::INFINITY, u32::MAX);
            set_lane(&mut packet.ray, lane, &traversed);
        }
        self.scene.intersect16(&mask, query.context(), &mut packet);
        std::array::from_fn(|lane| {
            if !valid[lane] {
                return None;
            }
            let (t, index) = query.best[lane];
            self.resolve(&rays[lane], t, index)
        })
    }

    /// [`Geometry::blocked`] for up to 16 shadow rays along one light's
    /// direction, whose blocking planes are `planes` (`rtcOccluded16`): for
    /// each lane `i` with `valid[i]`, whether `rays[i]` is blocked.
    pub fn blocked16(
        &self,
        query: &mut Query,
        rays: &[Ray; LANES],
        valid: &[bool; LANES],
        planes: &[PlaneShape],
    ) -> [bool; LANES] {
        let mut blocked = [false; LANES];
        let mut packet = packet16().ray;
        let mut mask = Valid16::default();
        let mut any = false;
        for lane in 0..LANES {
            if !valid[lane] {
                continue;
            }
            let ray = &rays[lane];
            if planes.iter().any(|p| p.normal.dot(ray.origin) > p.shift) {
                blocked[lane] = true;
                continue;
            }
            mask.0[lane] = -1;
            any = true;
            let (traversed, inv) = self.objects.traversed(ray);
            (query.rays[lane], query.inv[lane]) = (*ray, inv);
            set_lane(&mut packet, lane, &traversed);
        }
        if any {
            self.scene.occluded16(&mask, query.context(), &mut packet);
            for ((blocked, &traced), &tfar) in blocked.iter_mut().zip(&mask.0).zip(&packet.tfar) {
                // Embree marks an occluded ray with tfar = -inf.
                *blocked |= traced != 0 && tfar == f32::NEG_INFINITY;
            }
        }
        blocked
    }

    /// The closest hit, given the best sphere or box hit `(t, index)`
    /// (`(INFINITY, u32::MAX)` for none): the planes are tested after the
    /// objects, as in rayrepl's `Geometry::closest_hit`.
    #[inline]
    pub fn resolve(&self, ray: &Ray, t: f64, index: u32) -> Option<SurfaceHit> {
        let mut t = t;
        let mut object = (index != u32::MAX).then_some(ObjectId::Bounded(index));
        let mut before = nearer_than(t);
        for (k, plane) in self.planes.iter().enumerate() {
            let tp = plane.hit(ray);
            if tp < before {
                (t, before) = (tp, nearer_than(tp));
                object = Some(ObjectId::Plane(k as u32));
            }
        }
        object.map(|object| self.surface(ray, t, object))
    }

    /// rayrepl's `Geometry::surface`: the point, the facing normal and the
    /// material of a hit.
    #[inline]
    fn surface(&self, ray: &Ray, t: f64, object: ObjectId) -> SurfaceHit {
        let point = ray.at(t);
        let (normal, material) = match object {
            ObjectId::Bounded(k) => (self.objects.list[k as usize].normal(ray, t), self.materials[k as usize]),
            ObjectId::Plane(k) => (self.planes[k as usize].normal(), self.plane_materials[k as usize]),
        };
        SurfaceHit { t, point, normal, material }
    }

    /// rayrepl's `SceneGeometry::blocked`: whether anything is hit at any
    /// `t > 0` by `ray`, whose direction is the one `planes` was made for
    /// (the planes facing it). One dot product per plane, then
    /// `rtcOccluded1`.
    #[inline]
    pub fn blocked(&self, query: &mut Query, ray: &Ray, planes: &[PlaneShape]) -> bool {
        if planes.iter().any(|p| p.normal.dot(ray.origin) > p.shift) {
            return true;
        }
        let (traversed, inv) = self.objects.traversed(ray);
        (query.rays[0], query.inv[0]) = (*ray, inv);
        let mut shadow = f32_ray(&traversed, 0);
        self.scene.occluded1(query.context(), &mut shadow);
        shadow.tfar == f32::NEG_INFINITY
    }
}

/// The f32 ray Embree traverses for `ray`, with id `id` (its index in the
/// [`Query`]), from `t = 0` to infinity.
#[inline(always)]
pub fn f32_ray(ray: &Ray, id: u32) -> RtcRay {
    RtcRay {
        org: [ray.origin.x as f32, ray.origin.y as f32, ray.origin.z as f32],
        tnear: 0.0,
        dir: [ray.dir.x as f32, ray.dir.y as f32, ray.dir.z as f32],
        time: 0.0,
        tfar: f32::INFINITY,
        mask: u32::MAX,
        id,
        flags: 0,
    }
}

/// An empty packet of 16 rays and hits.
fn packet16() -> RtcRayHit16 {
    RtcRayHit16 {
        ray: RtcRay16 {
            org_x: [0.0; LANES],
            org_y: [0.0; LANES],
            org_z: [0.0; LANES],
            tnear: [0.0; LANES],
            dir_x: [0.0; LANES],
            dir_y: [0.0; LANES],
            dir_z: [0.0; LANES],
            time: [0.0; LANES],
            tfar: [f32::INFINITY; LANES],
            mask: [u32::MAX; LANES],
            id: std::array::from_fn(|lane| lane as u32),
            flags: [0; LANES],
        },
        hit: RtcHit16 {
            ng_x: [0.0; LANES],
            ng_y: [0.0; LANES],
            ng_z: [0.0; LANES],
            u: [0.0; LANES],
            v: [0.0; LANES],
            prim_id: [INVALID_ID; LANES],
            geom_id: [INVALID_ID; LANES],
            inst_id: [[INVALID_ID; LANES]; 1],
        },
    }
}

/// Puts the f32 form of `ray` in lane `lane` of `packet` (id = lane).
#[inline(always)]
fn set_lane(packet: &mut RtcRay16, lane: usize, ray: &Ray) {
    let r = f32_ray(ray, lane as u32);
    (packet.org_x[lane], packet.org_y[lane], packet.org_z[lane]) = (r.org[0], r.org[1], r.org[2]);
    (packet.dir_x[lane], packet.dir_y[lane], packet.dir_z[lane]) = (r.dir[0], r.dir[1], r.dir[2]);
    (packet.tnear[lane], packet.tfar[lane], packet.id[lane]) = (r.tnear, r.tfar, r.id);
}

/// Embree's bounds callback: the object's box, grown by the padding and
/// rounded outwards to f32.
unsafe extern "C" fn bounds(args: *const BoundsArguments) {
    // SAFETY: Embree passes valid arguments; `user` is the `Objects` the
    // scene was built over (it outlives the scene) and `bounds` points to
    // writable bounds.
    unsafe {
        let args = &*args;
        let objects = &*(args.user as *const Objects);
        let (min, max) = objects.bounds(args.prim_id as usize);
        let out = &mut *args.bounds;
        for axis in 0..3 {
            out.lower[axis] = round_down(min[axis] - objects.pad);
            out.upper[axis] = round_up(max[axis] + objects.pad);
        }
    }
}

/// Embree's intersect callback: rayrepl's f64 test of object `prim_id`
/// against each valid ray, keeping the best hit by rayrepl's tie rule and
/// pulling Embree's `tfar` in conservatively.
unsafe extern "C" fn intersect(args: *const IntersectArguments) {
    // SAFETY: Embree passes valid arguments: `valid` has `n` entries,
    // `rayhit` holds `n` rays and hits in `RTCRayHitN` layout, `user` is our
    // `Objects` and `context` the one given to `rtcIntersect*`, which is
    // always the first field of a live `Query` (only `Geometry` calls
    // Embree), whose `rays` hold each lane's ray at its id.
    unsafe {
        let args = &*args;
        let objects = &*(args.user as *const Objects);
        let query = &mut *(args.context as *mut Query);
        let (n, k) = (args.n as usize, args.prim_id);
        for lane in 0..n {
            if *args.valid.add(lane) == 0 {
                continue;
            }
            let id = *(args.rayhit.add(ray_field(ID, n, lane)) as *const u32) as usize;
            let t = objects.hit(k as usize, &query.rays[id], query.inv[id]);
            if goes_before(t, k, query.best[id]) {
                query.best[id] = (t, k);
                *args.rayhit.add(ray_field(TFAR, n, lane)) = culling_distance(t);
                *(args.rayhit.add(ray_field(PRIM_ID, n, lane)) as *mut u32) = k;
                *(args.rayhit.add(ray_field(GEOM_ID, n, lane)) as *mut u32) = args.geom_id;
            }
        }
    }
}

/// Embree's occluded callback: any f64 hit at `t > 0` occludes the ray
/// (`tfar = -inf`, Embree's mark).
unsafe extern "C" fn occluded(args: *const OccludedArguments) {
    // SAFETY: as for `intersect`, with `ray` holding `n` rays in `RTCRayN`
    // layout.
    unsafe {
        let args = &*args;
        let objects = &*(args.user as *const Objects);
        let query = &*(args.context as *const Query);
        let (n, k) = (args.n as usize, args.prim_id as usize);
        for lane in 0..n {
            if *args.valid.add(lane) == 0 {
                continue;
            }
            let id = *(args.ray.add(ray_field(ID, n, lane)) as *const u32) as usize;
            if objects.hit(k, &query.rays[id], query.inv[id]) < f64::INFINITY {
                *args.ray.add(ray_field(TFAR, n, lane)) = f32::NEG_INFINITY;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_round_outwards() {
        for x in [0.1, -0.1, 1.0 / 3.0, -7.7e-9, 1e30, 3.0] {
            assert!(f64::from(round_down(x)) <= x && x <= f64::from(round_up(x)), "{x}");
        }
        assert_eq!(round_up(3.0), 3.0);
    }

    #[test]
    fn culling_keeps_every_hit_the_tie_rule_could_keep() {
        for t in [1e-12, 0.37, 1.0, 5e7] {
            assert!(f64::from(culling_distance(t)) > reach_past(t), "{t}");
        }
    }

    #[test]
    fn ties_go_to_the_earlier_object() {
        let best = (1.0, 5);
        assert!(goes_before(1.0 + 1e-10, 3, best));
        assert!(!goes_before(1.0 - 1e-10, 7, best));
        assert!(goes_before(1.0 - 1e-8, 7, best));
        assert!(!goes_before(f64::INFINITY, 0, (f64::INFINITY, u32::MAX)));
    }
}
