//! Ray intersections with spheres, one-sided planes and oriented boxes
//! (SPEC 4 for the shapes, SPEC 6 for "the nearest hit with t > 0").
//!
//! Every test answers the distance `t` of the nearest hit with `t > 0`, or
//! `f64::INFINITY` for none; the normal is computed only for the one hit that
//! wins ([`Bounded::normal`], [`PlaneShape::normal`]), so the hot loops carry a
//! single number per object.

use glam::{DMat3, DVec3};

use crate::scene::Shape;

/// A ray `origin + t * dir`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: DVec3,
    /// Unit direction.
    pub dir: DVec3,
}

impl Ray {
    /// A ray from `origin` along the unit vector `dir`.
    #[inline]
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray { origin, dir }
    }

    /// The point at distance `t`.
    #[inline]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }
}

/// A sphere, ready for intersection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereShape {
    /// Centre.
    pub center: DVec3,
    /// Radius, > 0.
    pub radius: f64,
}

impl SphereShape {
    /// Distance to the nearest hit with `t > 0`, or infinity.
    ///
    /// With `f = S - C` and `b = f·V`: `t = -b ± sqrt(r² - |f - bV|²)`. The
    /// discriminant is computed from the perpendicular part `f - bV` (no
    /// cancellation of two large squares), and each root is taken in the
    /// form that does not subtract nearly equal numbers (`c / (-b + h)` with
    /// `c = |f|² - r²`), so far-away spheres keep full precision.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> f64 {
        sphere_hit(self.center, self.radius, ray.origin, ray.dir)
    }

    /// The outward unit normal at `point` on the surface.
    ///
    /// Normalised rather than divided by the radius: a hit point is off the
    /// surface by rounding, `(P - C) / r` is then not quite unit, the mirror
    /// ray `V - 2 (V·N) N` inherits the error in its length, and the next
    /// hit (computed for a unit direction) lands further off. Inside a
    /// sphere that compounds bounce after bounce: after 1,000 reflections
    /// the hit points were 18 units off a sphere of radius 20.
    #[inline]
    pub fn outward_normal(&self, point: DVec3) -> DVec3 {
        (point - self.center).normalize()
    }

    /// An axis-aligned box enclosing the sphere.
    pub fn bounds(&self) -> Aabb {
        let r = DVec3::splat(self.radius);
        Aabb { min: self.center - r, max: self.center + r }
    }
}

/// [`SphereShape::hit`]: the distance to the nearest
/// hit with `t > 0` of the ray `origin + t * dir` (unit `dir`) with the
/// sphere of `center` and `radius`, or infinity.
#[inline(always)]
fn sphere_hit(center: DVec3, radius: f64, origin: DVec3, dir: DVec3) -> f64 {
    let f = origin - center;
    let b = f.dot(dir);
    let r2 = radius * radius;
    let c = f.dot(f) - r2;
    if c > 0.0 && b >= 0.0 {
        // Outside and moving away.
        return f64::INFINITY;
    }
    let perp = f - dir * b;
    let disc = r2 - perp.dot(perp);
    if disc < 0.0 {
        return f64::INFINITY;
    }
    let h = disc.sqrt();
    let t = if c > 0.0 {
        // Outside, moving towards: the entry point -b - h.
        c / (h - b)
    } else if b > 0.0 {
        // Inside (or on the surface): the exit point -b + h.
        -c / (b + h)
    } else {
        h - b
    };
    if t > 0.0 { t } else { f64::INFINITY }
}

/// An oriented box, ready for intersection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxShape {
    /// Centre.
    pub center: DVec3,
    /// Half sizes along the box's own axes.
    pub half: DVec3,
    /// The box's own axes (columns of a rotation matrix), as rows: `to_local * v`
    /// expresses a world vector in the box's frame.
    pub to_local: DMat3,
}

impl BoxShape {
    /// The per-axis slab distances in the box's frame: `(t_enter, t_exit)`
    /// for each axis, where `t = (±half - o) / d` with `o`, `d` the ray's origin
    /// and direction in the box's frame (SPEC 4: a box is axis-aligned in its
    /// own frame).
    #[inline]
    fn slabs(&self, ray: &Ray) -> (DVec3, DVec3) {
        let d = self.to_local * ray.dir;
        slabs_in_frame(self.to_local, self.center, self.half, ray.origin, d.recip())
    }

    /// Distance to the nearest hit with `t > 0`, or infinity, for a box
    /// whose axes are `to_local`, given the ray's `1 / (to_local * dir)`
    /// (computed once per ray when many boxes share their axes): the same
    /// arithmetic as [`BoxShape::hit`], so the same answer to the bit.
    #[inline(always)]
    pub fn hit_in_frame(to_local: DMat3, center: DVec3, half: DVec3, origin: DVec3, inv: DVec3) -> f64 {
        let (near, far) = slabs_in_frame(to_local, center, half, origin, inv);
        entry_or_exit(near, far)
    }
}

/// [`BoxShape::slabs`] with the ray direction in the box's frame already
/// inverted (`inv`).
#[inline(always)]
fn slabs_in_frame(to_local: DMat3, center: DVec3, half: DVec3, origin: DVec3, inv: DVec3) -> (DVec3, DVec3) {
    let o = to_local * (origin - center);
    let t1 = (-half - o) * inv;
    let t2 = (half - o) * inv;
    // A ray lying in a face plane gives `0 * ∞ = NaN` for that face.
    // glam's `min`/`max` return their right operand on NaN, and the NaN
    // then made `max_element`/`min_element` drop another axis's bound (a
    // phantom hit outside the box); `f64::min`/`max` return the other,
    // infinite, distance, so such a ray misses (it sees the face edge-on).
    let min = DVec3::new(t1.x.min(t2.x), t1.y.min(t2.y), t1.z.min(t2.z));
    let max = DVec3::new(t1.x.max(t2.x), t1.y.max(t2.y), t1.z.max(t2.z));
    (min, max)
}

/// The hit distance from the slab distances: the entry point when the
/// origin is outside, the exit point when it is inside, infinity for none.
#[inline(always)]
fn entry_or_exit(near: DVec3, far: DVec3) -> f64 {
    let t_near = near.max_element();
    let t_far = far.min_element();
    if t_near > t_far || t_far <= 0.0 {
        f64::INFINITY
    } else if t_near > 0.0 {
        t_near
    } else {
        t_far
    }
}

impl BoxShape {
    /// Distance to the nearest hit with `t > 0`, or infinity: the entry point
    /// when the origin is outside, the exit point when it is inside.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> f64 {
        let (near, far) = self.slabs(ray);
        entry_or_exit(near, far)
    }

    /// The unit normal of the face hit by `ray`, facing the side the ray comes
    /// from (against `ray.dir`).
    ///
    /// The face is the slab that decides the hit: the entering slab (largest
    /// near distance) when the origin is outside, the leaving slab (smallest
    /// far distance) when inside. Either way, in the box's frame the normal
    /// facing the ray is `-sign(d_i) e_i`.
    pub fn facing_normal(&self, ray: &Ray) -> DVec3 {
        let (near, far) = self.slabs(ray);
        let t_near = near.max_element();
        let axis = if t_near > 0.0 { argmax(near) } else { argmin(far) };
        let d = self.to_local.row(axis).dot(ray.dir);
        let e = self.to_local.row(axis);
        if d > 0.0 { -e } else { e }
    }

    /// The middle one of the three half sizes: half the width of the box's
    /// narrower side on its broadest faces.
    pub fn middle_half_size(&self) -> f64 {
        let h = self.half;
        h.x.min(h.y).max(h.x.max(h.y).min(h.z))
    }

    /// An axis-aligned box enclosing the oriented box: `C ± |A| h` where `|A|`
    /// is the axes matrix with absolute entries.
    pub fn bounds(&self) -> Aabb {
        let axes = self.to_local.transpose();
        let extent =
            axes.x_axis.abs() * self.half.x + axes.y_axis.abs() * self.half.y + axes.z_axis.abs() * self.half.z;
        Aabb { min: self.center - extent, max: self.center + extent }
    }
}

#[inline]
fn argmax(v: DVec3) -> usize {
    if v.x >= v.y && v.x >= v.z {
        0
    } else if v.y >= v.z {
        1
    } else {
        2
    }
}

#[inline]
fn argmin(v: DVec3) -> usize {
    if v.x <= v.y && v.x <= v.z {
        0
    } else if v.y <= v.z {
        1
    } else {
        2
    }
}

/// A one-sided plane `{p : n·p = shift}`, seen only from the side `n` points
/// to (SPEC 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneShape {
    /// Unit normal.
    pub normal: DVec3,
    /// Signed distance from the origin.
    pub shift: f64,
}

impl PlaneShape {
    /// Distance to the hit, or infinity.
    ///
    /// SPEC 4: a ray whose origin satisfies `n·S <= d` never hits; otherwise
    /// it hits when it moves towards the plane (`n·V < 0`), at
    /// `t = (d - n·S) / (n·V)`.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> f64 {
        let above = self.normal.dot(ray.origin) - self.shift;
        let towards = self.normal.dot(ray.dir);
        // `a - b <= 0` exactly when `a <= b` in IEEE arithmetic.
        if above <= 0.0 || towards >= 0.0 {
            return f64::INFINITY;
        }
        let t = -above / towards;
        if t > 0.0 { t } else { f64::INFINITY }
    }

    /// The normal at any hit: `n`, which faces the ray since only rays on
    /// that side can hit.
    #[inline]
    pub fn normal(&self) -> DVec3 {
        self.normal
    }
}

/// A bounded primitive: what the BVH holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bounded {
    /// A sphere.
    Sphere(SphereShape),
    /// An oriented box.
    Box(BoxShape),
}

impl Bounded {
    /// Distance to the nearest hit with `t > 0`, or infinity.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> f64 {
        match self {
            Bounded::Sphere(s) => s.hit(ray),
            Bounded::Box(b) => b.hit(ray),
        }
    }

    /// The unit normal at the hit at distance `t`, facing the side the ray
    /// comes from (SPEC 6: "N facing the side the ray came from"; for a ray
    /// starting inside, the hit is the exit point and N points inwards).
    #[inline]
    pub fn normal(&self, ray: &Ray, t: f64) -> DVec3 {
        match self {
            Bounded::Sphere(s) => {
                let n = s.outward_normal(ray.at(t));
                if n.dot(ray.dir) > 0.0 { -n } else { n }
            }
            Bounded::Box(b) => b.facing_normal(ray),
        }
    }

    /// An axis-aligned box enclosing the primitive.
    pub fn bounds(&self) -> Aabb {
        match self {
            Bounded::Sphere(s) => s.bounds(),
            Bounded::Box(b) => b.bounds(),
        }
    }
}

/// A scene shape in the form the renderer intersects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ShapeClass {
    /// A sphere or a box.
    Bounded(Bounded),
    /// A plane.
    Plane(PlaneShape),
}

impl From<&Shape> for ShapeClass {
    fn from(shape: &Shape) -> ShapeClass {
        match *shape {
            Shape::Sphere { center, radius } => ShapeClass::Bounded(Bounded::Sphere(SphereShape { center, radius })),
            Shape::Plane { normal, shift } => ShapeClass::Plane(PlaneShape { normal, shift }),
            Shape::Box { center, half, axes } => {
                ShapeClass::Bounded(Bounded::Box(BoxShape { center, half, to_local: axes.transpose() }))
            }
        }
    }
}

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box (the identity of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };

    /// The smallest box containing both.
    #[inline]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// The smallest box containing `self` and the point `p`.
    #[inline]
    pub fn grow(self, p: DVec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }

    /// The centre.
    #[inline]
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// Half the surface area (what the SAH compares), 0 for an empty box.
    #[inline]
    pub fn half_area(&self) -> f64 {
        let d = (self.max - self.min).max(DVec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(DVec3::from(o), DVec3::from(d).normalize())
    }

    #[test]
    fn sphere_from_outside_hits_entry_point() {
        let s = SphereShape { center: DVec3::new(0.0, 0.0, -10.0), radius: 2.0 };
        assert_eq!(s.hit(&ray([0.0, 0.0, 0.0], [0.0, 0.0, -1.0])), 8.0);
        assert_eq!(s.hit(&ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])), f64::INFINITY);
        assert_eq!(s.hit(&ray([0.0, 3.0, 0.0], [0.0, 0.0, -1.0])), f64::INFINITY);
    }

    #[test]
    fn sphere_from_inside_hits_exit_point_with_inward_normal() {
        let s = Bounded::Sphere(SphereShape { center: DVec3::ZERO, radius: 2.0 });
        let r = ray([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]);
        let t = s.hit(&r);
        assert_eq!(t, 3.0);
        assert_eq!(s.normal(&r, t), DVec3::Z);
    }

    #[test]
    fn plane_is_one_sided() {
        let p = PlaneShape { normal: DVec3::Y, shift: -1.0 };
        assert_eq!(p.hit(&ray([0.0, 1.0, 0.0], [0.0, -1.0, 0.0])), 2.0);
        // From below (the solid side) it is never hit.
        assert_eq!(p.hit(&ray([0.0, -2.0, 0.0], [0.0, 1.0, 0.0])), f64::INFINITY);
        // Origin on the plane: n·S <= d, never hits.
        assert_eq!(p.hit(&ray([0.0, -1.0, 0.0], [0.0, -1.0, 0.0])), f64::INFINITY);
    }

    #[test]
    fn box_entry_exit_and_normals() {
        let b =
            Bounded::Box(BoxShape { center: DVec3::ZERO, half: DVec3::new(1.0, 2.0, 3.0), to_local: DMat3::IDENTITY });
        let r = ray([0.0, 10.0, 0.0], [0.0, -1.0, 0.0]);
        assert_eq!(b.hit(&r), 8.0);
        assert_eq!(b.normal(&r, 8.0), DVec3::Y);
        let inside = ray([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        assert_eq!(b.hit(&inside), 1.0);
        assert_eq!(b.normal(&inside, 1.0), -DVec3::X);
        assert_eq!(b.hit(&ray([5.0, 10.0, 0.0], [0.0, -1.0, 0.0])), f64::INFINITY);
    }

    #[test]
    fn ray_in_a_face_plane_keeps_the_other_slabs() {
        // The ray runs in the plane y = 1 of the top face (d.y = 0, so that
        // slab is 0 * inf = NaN) and passes x = 5, far right of the box.
        // Before the fix the NaN dropped the x bound: a hit at x = 5.
        let b = Bounded::Box(BoxShape { center: DVec3::ZERO, half: DVec3::ONE, to_local: DMat3::IDENTITY });
        assert_eq!(b.hit(&ray([5.0, 1.0, 10.0], [0.0, 0.0, -1.0])), f64::INFINITY);
        assert_eq!(b.hit(&ray([0.0, 1.0, 10.0], [0.0, 0.0, -1.0])), f64::INFINITY);
        assert_eq!(b.hit(&ray([0.0, 0.5, 10.0], [0.0, 0.0, -1.0])), 9.0);
    }

    #[test]
    fn rotated_box_bounds_contain_corners() {
        let axes = DMat3::from_rotation_z(0.3) * DMat3::from_rotation_x(0.7);
        let b =
            BoxShape { center: DVec3::new(1.0, 2.0, 3.0), half: DVec3::new(1.0, 0.5, 2.0), to_local: axes.transpose() };
        let aabb = b.bounds();
        for sx in [-1.0, 1.0] {
            for sy in [-1.0, 1.0] {
                for sz in [-1.0, 1.0] {
                    let corner = b.center + axes * (b.half * DVec3::new(sx, sy, sz));
                    assert!(corner.cmpge(aabb.min - 1e-12).all() && corner.cmple(aabb.max + 1e-12).all());
                }
            }
        }
    }
}
