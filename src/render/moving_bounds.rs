//! Where the timed objects of an animation are, frame by frame: the question
//! that decides how long a traced pixel stays valid.
//!
//! When only some bounded objects move (camera, lights, ambient and planes
//! all fixed), a pixel's path at frame `k` is traced against the fixed part
//! and the moving part. If that path did not hit a moving object, each of
//! its rays gives the same answer in a later frame `j` unless an object of
//! frame `j` lies on the part of the ray that was looked at: a closest-hit
//! ray between its origin and its hit, a shadow ray that the fixed part did
//! not block anywhere along it. [`MovingBounds::first_meeting`] answers the first
//! such frame, so the pixel can be copied until then, byte for byte.
//!
//! The boxes are padded (see [`PAD`]) and the slab test treats a zero
//! direction component exactly, so the answer errs only on the side of
//! tracing again: a miss here is a miss of the renderer's own intersection.
//!
//! The boxes of all frames sit in one bounding volume hierarchy whose
//! nodes also know the range of frames below them: a ray far from every
//! moving object costs one box test, and the search for the first frame
//! skips any subtree whose frames are all too early or later than the best
//! found so far. (A tree over frames alone, with one union box per range of
//! frames, was tried first: with forty asteroids circling the sun every
//! union box is the whole ring, and a ray through it tested every box of
//! every frame.)

use glam::DVec3;

use super::intersect::{Aabb, Ray};

/// Relative padding of the boxes: a hit that the renderer computes lies
/// within a few units in the last place (`~1e-15` relative) of the true
/// surface; a millionth of the box's size or of its distance from the
/// origin is far more than that and costs nothing measurable.
pub const PAD: f64 = 1e-6;

/// The boxes of the moving objects in each frame of a run of frames.
#[derive(Debug, Clone)]
pub struct MovingBounds {
    frames: u32,
    /// The tree, depth first: an interior node's first child follows it.
    nodes: Vec<Node>,
    /// The padded boxes with their frames, in tree order.
    items: Vec<Item>,
}

/// A moving object's padded box in one frame.
#[derive(Debug, Clone, Copy)]
struct Item {
    bounds: Aabb,
    frame: u32,
}

/// A node of the tree: the union of its boxes and their frames.
#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    first_frame: u32,
    last_frame: u32,
    /// A leaf's items are `items[start..start + count]`; an interior node
    /// (`count == 0`) has its children at the next index and at `start`.
    start: u32,
    count: u32,
}

/// Most items in a leaf.
const LEAF_ITEMS: usize = 4;

impl MovingBounds {
    /// A sweep over `frames`, each given as the boxes of its moving objects
    /// (frame 0 first).
    pub fn new<'a>(frames: impl IntoIterator<Item = &'a [Aabb]>) -> MovingBounds {
        let mut items = Vec::new();
        let mut count = 0;
        for (frame, boxes) in frames.into_iter().enumerate() {
            items.extend(boxes.iter().map(|b| Item { bounds: padded(b), frame: frame as u32 }));
            count += 1;
        }
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF_ITEMS + 1);
        if !items.is_empty() {
            build(&mut items, 0, &mut nodes);
        }
        MovingBounds { frames: count, nodes, items }
    }

    /// Number of frames.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// The first frame after `after` with a moving object whose box meets
    /// the ray somewhere in `[0, t_max]`, or [`MovingBounds::frames`] if none does.
    pub fn first_meeting(&self, ray: &Ray, t_max: f64, after: u32) -> u32 {
        // The far end moves out a little, like the boxes: a moving object
        // hit just beyond the recorded hit, within rounding, still counts.
        let t_max = t_max + t_max * PAD;
        let mut best = self.frames;
        let mut stack = [0u32; 64];
        let mut depth = usize::from(!self.nodes.is_empty());
        while depth > 0 {
            depth -= 1;
            let node = &self.nodes[stack[depth] as usize];
            if node.last_frame <= after || node.first_frame >= best || !meets(&node.bounds, ray, t_max) {
                continue;
            }
            if node.count > 0 {
                let items = &self.items[node.start as usize..(node.start + node.count) as usize];
                for item in items {
                    if item.frame > after && item.frame < best && meets(&item.bounds, ray, t_max) {
                        best = item.frame;
                    }
                }
                continue;
            }
            // The child with the earlier frames is searched first.
            let (left, right) = (stack[depth] + 1, node.start);
            let (first, second) = if self.nodes[left as usize].first_frame <= self.nodes[right as usize].first_frame {
                (left, right)
            } else {
                (right, left)
            };
            stack[depth] = second;
            stack[depth + 1] = first;
            depth += 2;
        }
        best
    }
}

/// Builds the subtree over `items` (which start at `offset` in the whole
/// list) into `nodes`, depth first: each node's box and frame range, items
/// split at the median along the widest spread of their centres, or of
/// their frames when the boxes do not move apart.
fn build(items: &mut [Item], offset: usize, nodes: &mut Vec<Node>) {
    let bounds = items.iter().fold(Aabb::EMPTY, |u, i| u.union(i.bounds));
    let first_frame = items.iter().map(|i| i.frame).min().unwrap_or(0);
    let last_frame = items.iter().map(|i| i.frame).max().unwrap_or(0);
    let here = nodes.len();
    nodes.push(Node { bounds, first_frame, last_frame, start: offset as u32, count: items.len() as u32 });
    if items.len() <= LEAF_ITEMS {
        return;
    }
    let centres = items.iter().fold(Aabb::EMPTY, |u, i| u.grow(i.bounds.center()));
    let spread = centres.max - centres.min;
    let axis = if spread.x >= spread.y && spread.x >= spread.z {
        0
    } else if spread.y >= spread.z {
        1
    } else {
        2
    };
    let middle = items.len() / 2;
    if spread[axis] > 0.0 {
        items.select_nth_unstable_by(middle, |a, b| a.bounds.center()[axis].total_cmp(&b.bounds.center()[axis]));
    } else {
        items.select_nth_unstable_by_key(middle, |i| i.frame);
    }
    let (left, right) = items.split_at_mut(middle);
    build(left, offset, nodes);
    let second = nodes.len();
    build(right, offset + middle, nodes);
    nodes[here].start = second as u32;
    nodes[here].count = 0;
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
    fn marching(frames: u32) -> MovingBounds {
        let frames: Vec<Vec<Aabb>> = (0..frames).map(|f| unit_box_at(f64::from(f))).collect();
        MovingBounds::new(frames.iter().map(Vec::as_slice))
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
        let sweep = MovingBounds::new(frames.iter().map(Vec::as_slice));
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
