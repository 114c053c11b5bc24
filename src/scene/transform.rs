//! Similarity transformations (SPEC 4): rotations, translations and scalings,
//! applied to primitives.
//!
//! Every transformation maps a sphere to a sphere, a plane to a plane and an
//! oriented box to an oriented box, so the evaluator bakes them into the
//! primitives and the renderer never sees a matrix stack.

use glam::{DMat3, DVec3};

use super::{Primitive, Shape};

/// The rotation `(rx, ry, rz)` of SPEC 4: rx about x, then ry about y, then rz
/// about z, each counter-clockwise by the right-hand rule.
///
/// `R = Mz(rz) * My(ry) * Mx(rx)`.
pub fn rotation_matrix(rx: f64, ry: f64, rz: f64) -> DMat3 {
    rotation_z(rz) * rotation_y(ry) * rotation_x(rx)
}

/// `Mx(a) = [[1,0,0],[0,cos a,-sin a],[0,sin a,cos a]]` (rows; glam takes columns).
fn rotation_x(a: f64) -> DMat3 {
    let (s, c) = a.sin_cos();
    DMat3::from_cols(DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, c, s), DVec3::new(0.0, -s, c))
}

/// `My(a) = [[cos a,0,sin a],[0,1,0],[-sin a,0,cos a]]` (rows).
fn rotation_y(a: f64) -> DMat3 {
    let (s, c) = a.sin_cos();
    DMat3::from_cols(DVec3::new(c, 0.0, -s), DVec3::new(0.0, 1.0, 0.0), DVec3::new(s, 0.0, c))
}

/// `Mz(a) = [[cos a,-sin a,0],[sin a,cos a,0],[0,0,1]]` (rows).
fn rotation_z(a: f64) -> DMat3 {
    let (s, c) = a.sin_cos();
    DMat3::from_cols(DVec3::new(c, s, 0.0), DVec3::new(-s, c, 0.0), DVec3::new(0.0, 0.0, 1.0))
}

/// The direction `R(rotation) * (0, 1, 0)`: a plane's normal or a light's
/// direction (SPEC 4 and 6). It is the middle column of R.
pub fn rotated_up(rotation: &DMat3) -> DVec3 {
    rotation.y_axis
}

impl Shape {
    /// The shape moved by `v`: centres move; a plane `n·p = d` becomes
    /// `n·p = d + v·n` (SPEC 4).
    pub fn translated(self, v: DVec3) -> Shape {
        match self {
            Shape::Sphere { center, radius } => Shape::Sphere { center: center + v, radius },
            Shape::Plane { normal, shift } => Shape::Plane { normal, shift: shift + v.dot(normal) },
            Shape::Box { center, half, axes } => Shape::Box { center: center + v, half, axes },
        }
    }

    /// The shape rotated by `r` about the origin: centres, normals and box
    /// axes turn; sizes and plane distances stay (SPEC 4).
    pub fn rotated(self, r: &DMat3) -> Shape {
        match self {
            Shape::Sphere { center, radius } => Shape::Sphere { center: *r * center, radius },
            Shape::Plane { normal, shift } => Shape::Plane { normal: *r * normal, shift },
            Shape::Box { center, half, axes } => Shape::Box { center: *r * center, half, axes: *r * axes },
        }
    }

    /// The shape under the homothety `p -> k p` (k != 0) centred on the origin.
    ///
    /// Points are multiplied by k and sizes by |k|. The plane `{n·p = d}` with
    /// solid side `n·p <= d` maps to `{n·p' = k d}` with solid side
    /// `n·p'/k <= d`; for k < 0 that is `n·p' >= k d`, i.e. `(-n)·p' <= -k d`,
    /// so the normal flips and the shift becomes `-k d = |k| d`. Boxes are
    /// symmetric about their centre, so a point reflection keeps their axes.
    pub fn scaled(self, k: f64) -> Shape {
        let size = k.abs();
        match self {
            Shape::Sphere { center, radius } => Shape::Sphere { center: center * k, radius: radius * size },
            Shape::Plane { normal, shift } if k < 0.0 => Shape::Plane { normal: -normal, shift: shift * size },
            Shape::Plane { normal, shift } => Shape::Plane { normal, shift: shift * k },
            Shape::Box { center, half, axes } => Shape::Box { center: center * k, half: half * size, axes },
        }
    }

    /// Whether every number describing the shape is finite (a transformation
    /// by huge values can overflow).
    pub fn is_finite(&self) -> bool {
        match self {
            Shape::Sphere { center, radius } => center.is_finite() && radius.is_finite(),
            Shape::Plane { normal, shift } => normal.is_finite() && shift.is_finite(),
            Shape::Box { center, half, axes } => center.is_finite() && half.is_finite() && axes.is_finite(),
        }
    }
}

impl Primitive {
    /// Moves the primitive by `v` (see [`Shape::translated`]).
    pub fn translate(&mut self, v: DVec3) {
        self.shape = self.shape.translated(v);
    }

    /// Rotates the primitive about the origin (see [`Shape::rotated`]).
    pub fn rotate(&mut self, r: &DMat3) {
        self.shape = self.shape.rotated(r);
    }

    /// Scales the primitive by `k` about the origin (see [`Shape::scaled`]).
    pub fn scale(&mut self, k: f64) {
        self.shape = self.shape.scaled(k);
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI};

    use super::*;

    const EPS: f64 = 1e-12;

    fn close(a: DVec3, b: DVec3, eps: f64) -> bool {
        (a - b).abs().max_element() <= eps
    }

    fn close_mat(a: &DMat3, b: &DMat3, eps: f64) -> bool {
        close(a.x_axis, b.x_axis, eps) && close(a.y_axis, b.y_axis, eps) && close(a.z_axis, b.z_axis, eps)
    }

    fn unit_box() -> Shape {
        Shape::Box { center: DVec3::new(1.0, 2.0, 3.0), half: DVec3::new(0.5, 1.0, 1.5), axes: DMat3::IDENTITY }
    }

    #[test]
    fn elementary_rotations_match_the_spec_matrices() {
        let a = 0.3_f64;
        let (s, c) = a.sin_cos();
        // Rows of SPEC 4, written out; glam's `from_cols_array_2d` takes columns,
        // so the transpose of the row lists is passed.
        let mx = DMat3::from_cols_array_2d(&[[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]]);
        let my = DMat3::from_cols_array_2d(&[[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]]);
        let mz = DMat3::from_cols_array_2d(&[[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]);
        assert!(close_mat(&rotation_matrix(a, 0.0, 0.0), &mx, EPS));
        assert!(close_mat(&rotation_matrix(0.0, a, 0.0), &my, EPS));
        assert!(close_mat(&rotation_matrix(0.0, 0.0, a), &mz, EPS));
        // Row 1, column 2 of Mx is -sin a: the image of z has y component -sin a.
        assert!((rotation_matrix(a, 0.0, 0.0).z_axis.y + s).abs() < EPS);
    }

    #[test]
    fn quarter_turns_follow_the_right_hand_rule() {
        let up = DVec3::Y;
        // About x by +90°: y goes to z.
        assert!(close(rotation_matrix(FRAC_PI_2, 0.0, 0.0) * up, DVec3::Z, EPS));
        // About z by +90°: y goes to -x.
        assert!(close(rotation_matrix(0.0, 0.0, FRAC_PI_2) * up, -DVec3::X, EPS));
        // About y by +90°: z goes to x.
        assert!(close(rotation_matrix(0.0, FRAC_PI_2, 0.0) * DVec3::Z, DVec3::X, EPS));
    }

    #[test]
    fn the_order_is_x_then_y_then_z() {
        // x by 90° takes y to z; then y by 90° takes z to x; then z by 90° takes x to y.
        let r = rotation_matrix(FRAC_PI_2, FRAC_PI_2, FRAC_PI_2);
        assert!(close(r * DVec3::Y, DVec3::Y, EPS));
        assert!(close(rotated_up(&r), DVec3::Y, EPS));
        // x: x-rot keeps x; y-rot takes x to -z; z-rot keeps -z.
        assert!(close(r * DVec3::X, -DVec3::Z, EPS));
    }

    #[test]
    fn translation_moves_centres_and_plane_shifts() {
        let v = DVec3::new(1.0, -2.0, 0.5);
        let s = Shape::Sphere { center: DVec3::new(1.0, 1.0, 1.0), radius: 2.0 }.translated(v);
        assert_eq!(s, Shape::Sphere { center: DVec3::new(2.0, -1.0, 1.5), radius: 2.0 });
        let b = unit_box().translated(v);
        assert_eq!(
            b,
            Shape::Box { center: DVec3::new(2.0, 0.0, 3.5), half: DVec3::new(0.5, 1.0, 1.5), axes: DMat3::IDENTITY }
        );
        // Plane y = 1 moved by v: y = 1 + (-2) = -1.
        let p = Shape::Plane { normal: DVec3::Y, shift: 1.0 }.translated(v);
        assert_eq!(p, Shape::Plane { normal: DVec3::Y, shift: -1.0 });
        // Tilted plane: n = (0.6, 0.8, 0), d = 2, v·n = 0.6 - 1.6 = -1.
        let p = Shape::Plane { normal: DVec3::new(0.6, 0.8, 0.0), shift: 2.0 }.translated(v);
        let Shape::Plane { shift, .. } = p else { panic!("still a plane") };
        assert!((shift - 1.0).abs() < EPS);
    }

    #[test]
    fn rotation_turns_centres_normals_and_axes() {
        let r = rotation_matrix(0.0, 0.0, FRAC_PI_2);
        let Shape::Sphere { center, radius } =
            Shape::Sphere { center: DVec3::new(1.0, 0.0, 0.0), radius: 2.0 }.rotated(&r)
        else {
            panic!("still a sphere")
        };
        assert!(close(center, DVec3::Y, EPS));
        assert_eq!(radius, 2.0);

        let Shape::Plane { normal, shift } = Shape::Plane { normal: DVec3::Y, shift: 3.0 }.rotated(&r) else {
            panic!("still a plane")
        };
        assert!(close(normal, -DVec3::X, EPS));
        assert_eq!(shift, 3.0);

        let Shape::Box { center, half, axes } = unit_box().rotated(&r) else { panic!("still a box") };
        // (1, 2, 3) about z by 90°: (-2, 1, 3).
        assert!(close(center, DVec3::new(-2.0, 1.0, 3.0), EPS));
        assert_eq!(half, DVec3::new(0.5, 1.0, 1.5));
        assert!(close(axes.x_axis, DVec3::Y, EPS));
        assert!(close(axes.y_axis, -DVec3::X, EPS));
        assert!(close(axes.z_axis, DVec3::Z, EPS));
    }

    #[test]
    fn positive_scale_multiplies_points_sizes_and_shifts() {
        let s = Shape::Sphere { center: DVec3::new(1.0, -1.0, 2.0), radius: 0.5 }.scaled(2.0);
        assert_eq!(s, Shape::Sphere { center: DVec3::new(2.0, -2.0, 4.0), radius: 1.0 });
        let b = unit_box().scaled(2.0);
        assert_eq!(
            b,
            Shape::Box { center: DVec3::new(2.0, 4.0, 6.0), half: DVec3::new(1.0, 2.0, 3.0), axes: DMat3::IDENTITY }
        );
        let p = Shape::Plane { normal: DVec3::Y, shift: -1.5 }.scaled(2.0);
        assert_eq!(p, Shape::Plane { normal: DVec3::Y, shift: -3.0 });
    }

    #[test]
    fn negative_scale_is_a_point_reflection() {
        let s = Shape::Sphere { center: DVec3::new(1.0, -1.0, 2.0), radius: 0.5 }.scaled(-2.0);
        assert_eq!(s, Shape::Sphere { center: DVec3::new(-2.0, 2.0, -4.0), radius: 1.0 });
        let b = unit_box().scaled(-1.0);
        assert_eq!(
            b,
            Shape::Box { center: DVec3::new(-1.0, -2.0, -3.0), half: DVec3::new(0.5, 1.0, 1.5), axes: DMat3::IDENTITY }
        );
        // The floor y = -1, solid below (y <= -1), reflected through the origin by
        // k = -2: the solid becomes y >= 2, i.e. -y <= -2: normal -y, shift -2.
        let p = Shape::Plane { normal: DVec3::Y, shift: -1.0 }.scaled(-2.0);
        assert_eq!(p, Shape::Plane { normal: -DVec3::Y, shift: -2.0 });
        // Check by points: (0, 3, 0) is solid after (it is the image of (0, -1.5, 0),
        // solid before); (0, 1, 0) is not (image of (0, -0.5, 0), empty before).
        let Shape::Plane { normal, shift } = p else { panic!("still a plane") };
        assert!(normal.dot(DVec3::new(0.0, 3.0, 0.0)) <= shift);
        assert!(normal.dot(DVec3::new(0.0, 1.0, 0.0)) > shift);
    }

    #[test]
    fn scaled_planes_keep_the_image_of_every_point_on_the_right_side() {
        let normal = DVec3::new(0.0, 0.6, 0.8);
        let plane = Shape::Plane { normal, shift: 1.25 };
        let points = [DVec3::new(1.0, 2.0, -1.0), DVec3::new(-3.0, 0.0, 0.5), DVec3::new(0.0, 1.0, 1.0)];
        for k in [3.0, 0.5, -0.5, -3.0] {
            let Shape::Plane { normal: n2, shift: d2 } = plane.scaled(k) else { panic!("still a plane") };
            for p in points {
                let before = normal.dot(p) - 1.25;
                let after = n2.dot(p * k) - d2;
                assert_eq!(before <= 0.0, after <= 0.0, "k = {k}, p = {p}");
                assert!((after - before * k.abs()).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn a_thousand_small_rotations_equal_one_big_one() {
        let steps = 1000;
        let total = (0.9, -1.7, 2.3);
        let n = steps as f64;
        let step = rotation_matrix(total.0 / n, 0.0, 0.0);
        let mut shape = unit_box();
        for _ in 0..steps {
            shape = shape.rotated(&step);
        }
        let once = unit_box().rotated(&rotation_matrix(total.0, 0.0, 0.0));
        let (Shape::Box { center: c1, half: h1, axes: a1 }, Shape::Box { center: c2, half: h2, axes: a2 }) =
            (shape, once)
        else {
            panic!("still boxes")
        };
        assert!(close(c1, c2, 1e-9));
        assert_eq!(h1, h2);
        assert!(close_mat(&a1, &a2, 1e-9));

        // About a general axis: 1000 steps of R(small) equal R(small)^1000.
        let step = rotation_matrix(total.0 / n, total.1 / n, total.2 / n);
        let mut shape = unit_box();
        let mut power = DMat3::IDENTITY;
        for _ in 0..steps {
            shape = shape.rotated(&step);
            power = step * power;
        }
        let once = unit_box().rotated(&power);
        let (Shape::Box { center: c1, axes: a1, .. }, Shape::Box { center: c2, axes: a2, .. }) = (shape, once) else {
            panic!("still boxes")
        };
        assert!(close(c1, c2, 1e-9));
        assert!(close_mat(&a1, &a2, 1e-9));
        // And the axes are still orthonormal.
        assert!(close_mat(&(a1.transpose() * a1), &DMat3::IDENTITY, 1e-9));
    }

    #[test]
    fn full_turn_is_the_identity() {
        let r = rotation_matrix(2.0 * PI, 2.0 * PI, 2.0 * PI);
        assert!(close_mat(&r, &DMat3::IDENTITY, 1e-12));
    }
}
