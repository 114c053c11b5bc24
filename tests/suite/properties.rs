//! Property tests of the intersection code against the transformations of
//! SPEC 4, and of the secondary-ray offset of SPEC 6.
//!
//! (BVH against brute force, and shadow any-hit against closest-hit
//! existence, are in `tests/suite/render.rs`.)

use glam::{DMat3, DVec3};
use proptest::prelude::*;
use rayrepl::render::Ray;
use rayrepl::render::intersect::{Bounded, ShapeClass};
use rayrepl::render::shade::offset_origin;
use rayrepl::scene::Shape;
use rayrepl::scene::transform::rotation_matrix;

/// A similarity `p -> R (k p) + v`, applied the way the evaluator does:
/// scale, then rotate, then translate.
#[derive(Debug, Clone, Copy)]
struct Similarity {
    k: f64,
    r: DMat3,
    v: DVec3,
}

impl Similarity {
    fn shape(&self, s: Shape) -> Shape {
        s.scaled(self.k).rotated(&self.r).translated(self.v)
    }

    fn point(&self, p: DVec3) -> DVec3 {
        self.r * (p * self.k) + self.v
    }

    /// The inverse image of a ray: origin `T⁻¹(o)`, direction
    /// `normalize(R^T d / k) = sign(k) R^T d`.
    fn inverse_ray(&self, ray: &Ray) -> Ray {
        let origin = self.r.transpose() * (ray.origin - self.v) / self.k;
        Ray::new(origin, self.r.transpose() * ray.dir * self.k.signum())
    }
}

fn vec3(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn unit() -> impl Strategy<Value = DVec3> {
    vec3(1.0).prop_filter("non-zero", |d| d.length() > 1e-2).prop_map(|d| d.normalize())
}

fn similarity() -> impl Strategy<Value = Similarity> {
    (0.01..100.0f64, any::<bool>(), vec3(3.2), vec3(100.0)).prop_map(|(k, negative, angles, v)| Similarity {
        k: if negative { -k } else { k },
        r: rotation_matrix(angles.x, angles.y, angles.z),
        v,
    })
}

fn shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (vec3(10.0), 0.05..5.0f64).prop_map(|(center, radius)| Shape::Sphere { center, radius }),
        (unit(), -10.0..10.0f64).prop_map(|(normal, shift)| Shape::Plane { normal, shift }),
        (vec3(10.0), (0.05..5.0f64, 0.05..5.0f64, 0.05..5.0f64), vec3(3.2)).prop_map(|(center, h, a)| Shape::Box {
            center,
            half: DVec3::new(h.0, h.1, h.2),
            axes: rotation_matrix(a.x, a.y, a.z),
        }),
    ]
}

/// Distance to the hit and the facing normal there, if any.
fn hit(shape: &Shape, ray: &Ray) -> Option<(f64, DVec3)> {
    match ShapeClass::from(shape) {
        ShapeClass::Bounded(b) => {
            let t = b.hit(ray);
            (t < f64::INFINITY).then(|| (t, b.normal(ray, t)))
        }
        ShapeClass::Plane(p) => {
            let t = p.hit(ray);
            (t < f64::INFINITY).then(|| (t, p.normal()))
        }
    }
}

/// Whether `ray` is within `eps` (relative) of a case where the answer
/// flips or the face changes: tangent to a sphere, starting on or moving
/// along a plane, through a box edge or starting on its surface. There the
/// two computations may rightly disagree by rounding.
fn near_degenerate(shape: &Shape, ray: &Ray, eps: f64) -> bool {
    match *shape {
        Shape::Sphere { center, radius } => {
            let f = ray.origin - center;
            let perp = f - ray.dir * f.dot(ray.dir);
            (perp.length() - radius).abs() < eps * radius || (f.length() - radius).abs() < eps * radius
        }
        Shape::Plane { normal, shift } => {
            (normal.dot(ray.origin) - shift).abs() < eps * ray.origin.length().max(1.0)
                || normal.dot(ray.dir).abs() < eps
        }
        Shape::Box { center, half, axes } => {
            let o = axes.transpose() * (ray.origin - center);
            let d = axes.transpose() * ray.dir;
            let t1 = (-half - o) / d;
            let t2 = (half - o) / d;
            let mut near = [t1.x.min(t2.x), t1.y.min(t2.y), t1.z.min(t2.z)];
            let mut far = [t1.x.max(t2.x), t1.y.max(t2.y), t1.z.max(t2.z)];
            near.sort_by(f64::total_cmp);
            far.sort_by(f64::total_cmp);
            let scale = o.length() + half.length();
            let close = |a: f64, b: f64| (a - b).abs() < eps * scale;
            // Two faces tie (an edge), entry meets exit (a grazing corner),
            // or the origin is on the surface.
            close(near[2], near[1])
                || close(far[0], far[1])
                || close(near[2], far[0])
                || close(near[2], 0.0)
                || close(far[0], 0.0)
                || d.abs().min_element() < eps
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Intersecting a transformed shape equals transforming the hit of the
    /// untransformed shape by the inverse-transformed ray: same existence,
    /// `t` scaled by |k|, hit point mapped by T, normal turned by sign(k) R.
    #[test]
    fn hit_of_transformed_shape_is_transformed_hit(
        shape in shape(),
        t in similarity(),
        origin in vec3(200.0),
        dir in unit(),
        aim in any::<bool>(),
        jitter in vec3(3.0),
    ) {
        // Half the rays aim near the object, so that most of them hit it.
        let target = match shape {
            Shape::Sphere { center, .. } | Shape::Box { center, .. } => t.point(center + jitter),
            Shape::Plane { normal, shift } => t.point(normal * shift + jitter),
        };
        let dir = if aim && (target - origin).length() > 1e-6 { (target - origin).normalize() } else { dir };
        let world_ray = Ray::new(origin, dir);
        let local_ray = t.inverse_ray(&world_ray);
        prop_assume!(!near_degenerate(&shape, &local_ray, 1e-7));
        let world = hit(&t.shape(shape), &world_ray);
        let local = hit(&shape, &local_ray);
        prop_assert_eq!(world.is_some(), local.is_some(), "world {:?} local {:?}", world, local);
        if let (Some((tw, nw)), Some((tl, nl))) = (world, local) {
            let scale = t.k.abs() * (local_ray.origin.length() + tl + 10.0) + t.v.length();
            prop_assert!((tw - t.k.abs() * tl).abs() <= 1e-9 * scale, "t {} vs {}", tw, t.k.abs() * tl);
            let pw = world_ray.at(tw);
            let pl = t.point(local_ray.at(tl));
            prop_assert!((pw - pl).length() <= 1e-9 * scale, "point {:?} vs {:?}", pw, pl);
            let expected = t.r * nl * t.k.signum();
            prop_assert!((nw - expected).length() <= 1e-9, "normal {:?} vs {:?}", nw, expected);
        }
    }

    /// SPEC 6's offset keeps a convex object from shadowing or reflecting
    /// itself: from a hit seen from outside, moved off along N, neither the
    /// mirror ray nor a ray towards any light on the front side hits the
    /// same sphere or box again, whatever the size and position.
    #[test]
    fn secondary_rays_never_hit_their_own_convex_object(
        center in vec3(1.0),
        size in (0.05..5.0f64, 0.05..5.0f64, 0.05..5.0f64),
        angles in vec3(3.2),
        exponent in -4.0..7.0f64,
        dir in unit(),
        light in unit(),
        kind in any::<bool>(),
    ) {
        let magnitude = 10f64.powf(exponent);
        let center = center * magnitude;
        let half = DVec3::new(size.0, size.1, size.2) * magnitude;
        let shape = if kind {
            Shape::Sphere { center, radius: half.x }
        } else {
            Shape::Box { center, half, axes: rotation_matrix(angles.x, angles.y, angles.z) }
        };
        let ShapeClass::Bounded(object) = ShapeClass::from(&shape) else { unreachable!("a bounded shape") };
        // A ray from outside, aimed at the centre from far away.
        let ray = Ray::new(center - dir * (20.0 * magnitude), dir);
        let t = object.hit(&ray);
        prop_assert!(t < f64::INFINITY);
        let n = Bounded::normal(&object, &ray, t);
        let origin = offset_origin(ray.at(t), n, t);
        let mirror = Ray::new(origin, ray.dir - n * (2.0 * ray.dir.dot(n)));
        prop_assert_eq!(object.hit(&mirror), f64::INFINITY, "the mirror ray hits its own object");
        if n.dot(light) > 1e-6 {
            prop_assert_eq!(object.hit(&Ray::new(origin, light)), f64::INFINITY, "self-shadowing");
        }
    }
}
