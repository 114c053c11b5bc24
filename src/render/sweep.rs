//! Where the timed objects of an animation are, frame by frame: the question
//! that decides how long a traced pixel stays valid.
//!
//! When only some bounded objects move (camera, lights, ambient and planes
//! all fixed), a pixel's path at frame `k` is traced against the fixed part
//! and the moving part. If that path did not hit a moving object, each of
//! its rays gives the same answer in a later frame `j` unless an object of
//! frame `j` lies on the part of the ray that was looked at: a closest-hit
//! ray between its origin and its hit, a shadow ray that the fixed part did
//! not block anywhere along it. [`Sweep::first_meeting`] answers the first
//! such frame, so the pixel can be copied until then, byte for byte.
//!
//! The boxes are padded (see [`PAD`]) and the slab test treats a zero
//! direction component exactly, so the answer errs only on the side of
//! tracing again: a miss here is a miss of the renderer's own intersection.
//!
//! The frames are kept in a segment tree: each node holds the union box of
//! a range of frames, each leaf the boxes of one frame. A ray far from every
//! orbit costs one box test; a ray crossing an orbit descends only towards
//! the frames whose objects it can meet.

use glam::DVec3;

use super::intersect::{Aabb, Ray};

/// Relative padding of the boxes: a hit that the renderer computes lies
/// within a few units in the last place (`~1e-15` relative) of the true
/// surface; a millionth of the box's size or of its distance from the
/// origin is far more than that and costs nothing measurable.
pub const PAD: f64 = 1e-6;

/// The boxes of the moving objects in each frame of a run of frames.
#[derive(Debug, Clone)]
pub struct Sweep {
    frames: u32,
    /// Number of leaves: `frames` rounded up to a power of two.
    leaves: usize,
    /// The segment tree, heap order from 1: node `n` covers the frames of
    /// its children `2n` and `2n + 1`; leaf `leaves + f` is frame `f`.
    nodes: Vec<Aabb>,
    /// The padded boxes of frame `f`: `boxes[starts[f]..starts[f + 1]]`.
    boxes: Vec<Aabb>,
    starts: Vec<usize>,
}

impl Sweep {
    /// A sweep over `frames`, each given as the boxes of its moving objects
    /// (frame 0 first).
    pub fn new<'a>(frames: impl IntoIterator<Item = &'a [Aabb]>) -> Sweep {
        let mut boxes = Vec::new();
        let mut starts = vec![0];
        for frame in frames {
            boxes.extend(frame.iter().map(padded));
            starts.push(boxes.len());
        }
        let count = starts.len() - 1;
        let leaves = count.next_power_of_two().max(1);
        let mut nodes = vec![Aabb::EMPTY; 2 * leaves];
        for f in 0..count {
            nodes[leaves + f] = boxes[starts[f]..starts[f + 1]].iter().fold(Aabb::EMPTY, |u, b| u.union(*b));
        }
        for n in (1..leaves).rev() {
            nodes[n] = nodes[2 * n].union(nodes[2 * n + 1]);
        }
        Sweep { frames: count as u32, leaves, nodes, boxes, starts }
    }

    /// Number of frames.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// The first frame after `after` with a moving object whose box meets
    /// the ray somewhere in `[0, t_max]`, or [`Sweep::frames`] if none does.
    pub fn first_meeting(&self, ray: &Ray, t_max: f64, after: u32) -> u32 {
        // The far end moves out a little, like the boxes: a moving object
        // hit just beyond the recorded hit, within rounding, still counts.
        let t_max = t_max + t_max * PAD;
        self.descend(1, 0, self.leaves as u32, ray, t_max, after).unwrap_or(self.frames)
    }

    /// [`Sweep::first_meeting`] within node `node`, which covers the frames
    /// `first..first + span`.
    fn descend(&self, node: usize, first: u32, span: u32, ray: &Ray, t_max: f64, after: u32) -> Option<u32> {
        if first + span <= after + 1 || first >= self.frames || !meets(&self.nodes[node], ray, t_max) {
            return None;
        }
        if span == 1 {
            let f = first as usize;
            let boxes = &self.boxes[self.starts[f]..self.starts[f + 1]];
            return (boxes.len() == 1 || boxes.iter().any(|b| meets(b, ray, t_max))).then_some(first);
        }
        let half = span / 2;
        self.descend(2 * node, first, half, ray, t_max, after)
            .or_else(|| self.descend(2 * node + 1, first + half, half, ray, t_max, after))
    }
}

/// `b` grown by [`PAD`] times the larger of its size and its distance from
/// the origin (at least 1).
fn padded(b: &Aabb) -> Aabb {
    let reach = b.min.abs().max(b.max.abs()).max_element().max((b.max - b.min).max_element()).max(1.0);
    let pad = DVec3::splat(PAD * reach);
    Aabb { min: b.min - pad, max: b.max + pad }
}

/// Whether the ray meets the box at some `t` in `[0, t_max]`. A direction
/// component of 0 is decided by the origin's coordinate alone (no `0 * inf`
/// NaN), and a NaN anywhere counts as meeting: this test may only err on
/// the side of yes.
#[inline]
fn meets(b: &Aabb, ray: &Ray, t_max: f64) -> bool {
    if b.min.x > b.max.x {
        return false; // empty
    }
    let mut near = 0.0_f64;
    let mut far = t_max;
    for axis in 0..3 {
        let (o, d) = (ray.origin[axis], ray.dir[axis]);
        let (lo, hi) = (b.min[axis], b.max[axis]);
        if d == 0.0 {
            if o < lo || o > hi {
                return false;
            }
            continue;
        }
        let (t1, t2) = ((lo - o) / d, (hi - o) / d);
        let (t_in, t_out) = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
        // `!(a <= b)` keeps NaN on the "meets" side.
        if t_in > near {
            near = t_in;
        }
        if t_out < far {
            far = t_out;
        }
    }
    near <= far || near.is_nan() || far.is_nan()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box_at(x: f64) -> Vec<Aabb> {
        vec![Aabb { min: DVec3::new(x - 0.5, -0.5, -0.5), max: DVec3::new(x + 0.5, 0.5, 0.5) }]
    }

    /// Frame f has a unit box centred at x = f.
    fn marching(frames: u32) -> Sweep {
        let frames: Vec<Vec<Aabb>> = (0..frames).map(|f| unit_box_at(f64::from(f))).collect();
        Sweep::new(frames.iter().map(Vec::as_slice))
    }

    fn down_at(x: f64) -> Ray {
        Ray::new(DVec3::new(x, 10.0, 0.0), DVec3::new(0.0, -1.0, 0.0))
    }

    #[test]
    fn finds_the_first_frame_after_the_given_one() {
        let sweep = marching(10);
        assert_eq!(sweep.first_meeting(&down_at(7.0), f64::INFINITY, 0), 7);
        assert_eq!(sweep.first_meeting(&down_at(7.0), f64::INFINITY, 7), 10);
        assert_eq!(sweep.first_meeting(&down_at(7.0), f64::INFINITY, 6), 7);
        // Between two boxes at x = 3.5 both frames 3 and 4 touch (padded).
        assert_eq!(sweep.first_meeting(&down_at(3.5), f64::INFINITY, 0), 3);
        assert_eq!(sweep.first_meeting(&down_at(3.5), f64::INFINITY, 3), 4);
        assert_eq!(sweep.first_meeting(&down_at(42.0), f64::INFINITY, 0), 10);
    }

    #[test]
    fn stops_at_the_segment_end() {
        let sweep = marching(10);
        // The box top is at y = 0.5, 9.5 away from the origin.
        assert_eq!(sweep.first_meeting(&down_at(5.0), 9.0, 0), 10);
        assert_eq!(sweep.first_meeting(&down_at(5.0), 9.5, 0), 5);
    }

    #[test]
    fn a_ray_along_a_face_still_meets_the_box() {
        let sweep = marching(4);
        // Lies in the plane y = 0.5 of the box tops, along x.
        let along = Ray::new(DVec3::new(-5.0, 0.5, 0.0), DVec3::X);
        assert_eq!(sweep.first_meeting(&along, f64::INFINITY, 0), 1);
        let outside = Ray::new(DVec3::new(-5.0, 0.6, 0.0), DVec3::X);
        assert_eq!(sweep.first_meeting(&outside, f64::INFINITY, 0), 4);
    }

    #[test]
    fn frames_without_moving_objects_meet_nothing() {
        let frames = [unit_box_at(0.0), vec![], unit_box_at(0.0)];
        let sweep = Sweep::new(frames.iter().map(Vec::as_slice));
        assert_eq!(sweep.frames(), 3);
        assert_eq!(sweep.first_meeting(&down_at(0.0), f64::INFINITY, 0), 2);
    }

    #[test]
    fn agrees_with_testing_every_frame() {
        let sweep = marching(37);
        for x in (0..80).map(|i| f64::from(i) * 0.5 - 2.0) {
            for after in 0..37 {
                let ray = down_at(x);
                let brute = (after + 1..37).find(|&f| (x - f64::from(f)).abs() <= 0.5 + 1e-5).unwrap_or(37);
                assert_eq!(sweep.first_meeting(&ray, f64::INFINITY, after), brute, "x = {x}, after {after}");
            }
        }
    }
}
