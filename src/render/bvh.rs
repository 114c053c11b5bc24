//! A bounding volume hierarchy over spheres and boxes: binned SAH build
//! over f32 boxes rounded outwards (subtrees built in parallel, and the
//! binning of large ranges too) that writes flattened depth-first binary
//! nodes directly, collapsed into the 8-wide tree of [`wide`] for the
//! closest hit and any hit.
//!
//! Small sets (at most [`BRUTE_FORCE_MAX`] objects) are not given a tree:
//! testing every object directly is cheaper than the node tests.

mod wide;

use glam::{DMat3, DVec3, Vec3, Vec3A};
use rayon::prelude::*;

use self::wide::{Leaves, WideBvh, WideRay, round_down, round_up};
use super::intersect::{Aabb, Bounded, BoxShape, Ray};

/// Up to this many objects a tree costs more than it saves: on the solar
/// bench scene (3 spheres) a one-leaf tree runs 18% more instructions than
/// the flat list (callgrind, 320x180); an object test costs about what a node
/// test does, so a handful of objects leaves a tree nothing to prune.
pub const BRUTE_FORCE_MAX: usize = 4;

/// Number of bins per axis of the SAH build.
const BINS: usize = 16;

/// Node ranges at least this large build their two children in parallel.
const PARALLEL_MIN: usize = 4096;

/// Node ranges at least this large are binned in parallel, in chunks of
/// [`PARALLEL_MIN`] items.
const PARALLEL_BINNING_MIN: usize = 65536;

/// Most objects a leaf may hold.
const MAX_LEAF: usize = 8;

/// Below this depth the SAH decides splits; deeper, ranges are split by
/// object count, which halves them, so the tree depth stays below
/// `SAH_MAX_DEPTH + 32` for up to 2³² objects, whatever their layout.
const SAH_MAX_DEPTH: usize = 32;

/// Most levels of a tree: the depth bound above, from which the walks'
/// stack is sized.
const STACK_SIZE: usize = 64;

/// Estimated cost of a node's box test relative to an object test (SAH).
const TRAVERSAL_COST: f64 = 1.0;

/// A node of the flattened tree.
///
/// Interior nodes have `count == 0`; their left child is the next node and
/// their right child is at `index`. Leaves hold the objects
/// `index .. index + count` of [`Bvh::objects`].
///
/// 32 bytes (its box as two unaligned [`Vec3`]): the build writes and the
/// collapse reads them in less memory.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct Node {
    min: Vec3,
    index: u32,
    max: Vec3,
    count: u16,
}

impl Node {
    /// The node over `bounds`: a leaf holding `count` objects from `index`,
    /// or, with `count == 0`, an interior node whose right child is at
    /// `index`.
    fn new(bounds: &Box32, index: u32, count: u16) -> Node {
        Node { min: bounds.min.into(), index, max: bounds.max.into(), count }
    }

    /// Its box.
    fn bounds(&self) -> Box32 {
        Box32 { min: self.min.into(), max: self.max.into() }
    }
}

/// A BVH over bounded objects, or a flat list when they are few.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    /// The tree; empty for a flat list.
    wide: WideBvh,
    objects: Vec<Bounded>,
    /// When every object is a box with the same axes (a rotated grid of
    /// boxes): a compact copy for faster traversal.
    shared: Option<Box<SharedFrame>>,
    /// Where each object (tree order) stood among the objects given to
    /// [`Bvh::build`], for ties ([`goes_before`]); empty for a flat list,
    /// whose order is that one.
    put_order: Vec<u32>,
}

/// Boxes that all have the same axes, seen in their common frame.
///
/// There each box is axis-aligned, so a node is bounded by the box of its
/// boxes in that frame, much tighter than the world box of their rotated
/// world boxes (a cube turned on two axes fills about a third of its world
/// box); the ray is turned into the frame once per query, not once per box.
/// Hit distances are computed by the very arithmetic of [`BoxShape::hit`]
/// (with `1 / (to_local * dir)` shared), so they are the same to the bit;
/// the node boxes (of the tree built in the frame) are padded, so culling
/// is conservative.
#[derive(Debug, Clone)]
struct SharedFrame {
    /// The common axes, as rows ([`BoxShape::to_local`]).
    to_local: DMat3,
    /// Per object (tree order): centre and half sizes.
    boxes: Vec<(DVec3, DVec3)>,
}

impl SharedFrame {
    /// The common axes of the `count` objects `object(k)`, if there are
    /// some and they are all boxes with equal axes.
    fn common_axes(count: usize, object: &(impl Fn(usize) -> Bounded + Sync)) -> Option<DMat3> {
        let to_local = match (count > 0).then(|| object(0))? {
            Bounded::Box(b) => b.to_local,
            Bounded::Sphere(_) => return None,
        };
        (0..count)
            .into_par_iter()
            .all(|k| matches!(object(k), Bounded::Box(b) if b.to_local == to_local))
            .then_some(to_local)
    }

    /// The box of `object` (a box with axes `to_local`) in the frame.
    fn local_bounds(to_local: DMat3, object: &Bounded) -> Aabb {
        match object {
            Bounded::Box(b) => {
                let c = to_local * b.center;
                Aabb { min: c - b.half, max: c + b.half }
            }
            Bounded::Sphere(_) => unreachable!("a shared frame holds only boxes"),
        }
    }

    /// The frame of the boxes `objects`, whose axes are `to_local`.
    fn new(to_local: DMat3, objects: &[Bounded]) -> SharedFrame {
        let boxes = objects
            .par_iter()
            .map(|o| match o {
                Bounded::Box(b) => (b.center, b.half),
                Bounded::Sphere(_) => unreachable!("a shared frame holds only boxes"),
            })
            .collect();
        SharedFrame { to_local, boxes }
    }

    /// A node's box in the frame, padded far above the rounding of either
    /// way of turning a ray into the frame (a few ulps of the coordinates
    /// involved), so culling is conservative.
    fn padded(b: &Aabb) -> Aabb {
        let p = 1e-6 * b.min.abs().max(b.max.abs()).max_element();
        Aabb { min: b.min - p, max: b.max + p }
    }

    /// The ray in the frame, for the node tests, and `1 / direction` there.
    #[inline(always)]
    fn local_ray(&self, ray: &Ray) -> (WideRay, DVec3) {
        let inverse = (self.to_local * ray.dir).recip();
        (WideRay::new(self.to_local * ray.origin, inverse), inverse)
    }

    /// [`Bvh::closest_hit`] through the frame; `tree` was built in the frame.
    fn closest_hit(&self, tree: &WideBvh, put_order: &[u32], ray: &Ray, t_max: f64) -> (f64, u32) {
        let (local, inverse) = self.local_ray(ray);
        tree.closest_hit(&local, t_max, &FrameLeaves { frame: self, put_order, origin: ray.origin, inverse })
    }

    /// [`Bvh::any_hit`] through the frame.
    fn any_hit(&self, tree: &WideBvh, put_order: &[u32], ray: &Ray, t_max: f64) -> bool {
        let (local, inverse) = self.local_ray(ray);
        tree.any_hit(&local, t_max, &FrameLeaves { frame: self, put_order, origin: ray.origin, inverse })
    }
}

/// The boxes of a shared frame in the leaves of its tree, tested against a
/// ray from `origin` with `1 / direction` in the frame `inverse`.
struct FrameLeaves<'a> {
    frame: &'a SharedFrame,
    put_order: &'a [u32],
    origin: DVec3,
    inverse: DVec3,
}

impl Leaves for FrameLeaves<'_> {
    #[inline(always)]
    fn closest(&self, start: usize, count: usize, best: &mut (f64, u32)) {
        for (k, &(center, half)) in self.frame.boxes[start..start + count].iter().enumerate() {
            let t = BoxShape::hit_in_frame(self.frame.to_local, center, half, self.origin, self.inverse);
            let k = (start + k) as u32;
            if goes_before(t, k, *best, self.put_order) {
                *best = (t, k);
            }
        }
    }

    #[inline(always)]
    fn any(&self, start: usize, count: usize, t_max: f64) -> bool {
        // Plain loops here: `Iterator::any` is not always inlined.
        for &(center, half) in &self.frame.boxes[start..start + count] {
            if BoxShape::hit_in_frame(self.frame.to_local, center, half, self.origin, self.inverse) < t_max {
                return true;
            }
        }
        false
    }
}

/// The objects in the leaves of a tree, tested against `ray`.
struct ObjectLeaves<'a> {
    objects: &'a [Bounded],
    put_order: &'a [u32],
    ray: &'a Ray,
}

impl Leaves for ObjectLeaves<'_> {
    #[inline(always)]
    fn closest(&self, start: usize, count: usize, best: &mut (f64, u32)) {
        test_range(&self.objects[start..start + count], start, self.put_order, self.ray, best);
    }

    #[inline(always)]
    fn any(&self, start: usize, count: usize, t_max: f64) -> bool {
        // A plain loop: `Iterator::any` is not always inlined, which would
        // put the ray through memory again.
        for object in &self.objects[start..start + count] {
            if object.hit(self.ray) < t_max {
                return true;
            }
        }
        false
    }
}

/// A box in f32, rounded outwards from the f64 boxes it stands for, so that
/// it holds them: what the build sorts and bins, in half the bytes of an
/// [`Aabb`] and one SIMD register per corner. The wide nodes are f32 and
/// padded anyway, and the objects are still tested in f64.
#[derive(Debug, Clone, Copy)]
struct Box32 {
    min: Vec3A,
    max: Vec3A,
}

impl Box32 {
    const EMPTY: Box32 = Box32 { min: Vec3A::INFINITY, max: Vec3A::NEG_INFINITY };

    /// The smallest f32 box holding `b`.
    fn enclosing(b: &Aabb) -> Box32 {
        Box32 {
            min: Vec3A::from_array(b.min.to_array().map(round_down)),
            max: Vec3A::from_array(b.max.to_array().map(round_up)),
        }
    }

    /// The smallest box containing both.
    #[inline(always)]
    fn union(self, other: Box32) -> Box32 {
        Box32 { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// The smallest box containing `self` and the point `p`.
    #[inline(always)]
    fn grow(self, p: Vec3A) -> Box32 {
        Box32 { min: self.min.min(p), max: self.max.max(p) }
    }

    /// The same box in f64 (exact).
    fn aabb(&self) -> Aabb {
        Aabb { min: self.min.as_dvec3(), max: self.max.as_dvec3() }
    }

    /// Half the surface area, computed in f64 (no overflow).
    #[inline(always)]
    fn half_area(&self) -> f64 {
        self.aabb().half_area()
    }
}

/// Build-time record of one object: 32 bytes, so the partitions move
/// little memory.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct Item {
    min: Vec3,
    index: u32,
    max: Vec3,
    /// Its bin on each axis in the range last binned (set by [`Bins::fill`],
    /// read by the partition that follows; it fits in the padding).
    bins: [u8; 3],
}

impl Item {
    /// The item of object `index`, whose box is `b`.
    fn new(index: u32, b: &Box32) -> Item {
        Item { min: b.min.into(), index, max: b.max.into(), bins: [0; 3] }
    }

    /// Its box.
    #[inline(always)]
    fn bounds(&self) -> Box32 {
        Box32 { min: self.min.into(), max: self.max.into() }
    }

    /// The centre of its box.
    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        (Vec3A::from(self.min) + Vec3A::from(self.max)) * 0.5
    }
}

/// The bounds of a range of items and the bounds of their centroids.
#[derive(Debug, Clone, Copy)]
struct Extent {
    bounds: Box32,
    centroids: Box32,
}

impl Extent {
    const EMPTY: Extent = Extent { bounds: Box32::EMPTY, centroids: Box32::EMPTY };

    /// The extent of `items`.
    fn of(items: &[Item]) -> Extent {
        items.iter().fold(Extent::EMPTY, |e, it| e.add(it))
    }

    /// The extent grown to hold `it`.
    fn add(self, it: &Item) -> Extent {
        Extent { bounds: self.bounds.union(it.bounds()), centroids: self.centroids.grow(it.centroid()) }
    }

    /// The extent holding both.
    fn union(self, other: Extent) -> Extent {
        Extent { bounds: self.bounds.union(other.bounds), centroids: self.centroids.union(other.centroids) }
    }
}

impl Bvh {
    /// Builds the hierarchy over the `count` objects `object(0 .. count)`.
    ///
    /// The objects are asked for, not given, so that a caller holding them
    /// in another form (the scene's primitives) does not copy them all
    /// once more in their given order: only the tree's copy is made.
    /// `object(k)` is asked for several times (for the shared frame, the
    /// boxes and the copy), so it must be cheap and always the same.
    /// Returns the tree and the permutation applied: the tree's object `k`
    /// is `object(order[k])`, so callers can reorder data kept alongside.
    pub fn build(count: usize, object: impl Fn(usize) -> Bounded + Sync) -> (Bvh, Vec<u32>) {
        if count <= BRUTE_FORCE_MAX {
            let flat = Bvh {
                wide: WideBvh::default(),
                objects: (0..count).map(object).collect(),
                shared: None,
                put_order: Vec::new(),
            };
            return (flat, (0..count as u32).collect());
        }
        // Boxes that share their axes are grouped in their common frame,
        // where they are axis-aligned: far tighter nodes than their world
        // boxes give.
        let frame = SharedFrame::common_axes(count, &object);
        let mut items: Vec<Item> = (0..count as u32)
            .into_par_iter()
            .map(|k| {
                let o = object(k as usize);
                let bounds = match frame {
                    Some(to_local) => SharedFrame::local_bounds(to_local, &o),
                    None => o.bounds(),
                };
                Item::new(k, &Box32::enclosing(&bounds))
            })
            .collect();
        // Over fixed chunks merged in order, so that the extent does not
        // depend on threads (a box past f32's range has a NaN centroid,
        // whose minimum with another takes the order).
        let chunks: Vec<Extent> = items.par_chunks(PARALLEL_MIN).map(Extent::of).collect();
        let extent = chunks.into_iter().fold(Extent::EMPTY, Extent::union);
        let mut nodes = Vec::with_capacity(2 * count);
        let mut bins = Bins::EMPTY;
        build_range(&mut items, 0, 0, extent, &mut nodes, &mut bins);
        let order: Vec<u32> = items.iter().map(|it| it.index).collect();
        // The items are freed before the objects are copied in tree order:
        // they are not at the peak together. The copy runs beside the
        // collapse, which is serial.
        drop(items);
        let (wide, objects) = rayon::join(
            || match frame {
                Some(_) => WideBvh::collapse(&nodes, |k| SharedFrame::padded(&nodes[k].bounds().aabb())),
                None => WideBvh::collapse(&nodes, |k| nodes[k].bounds().aabb()),
            },
            || order.par_iter().map(|&k| object(k as usize)).collect::<Vec<Bounded>>(),
        );
        drop(nodes);
        let shared = frame.map(|to_local| Box::new(SharedFrame::new(to_local, &objects)));
        (Bvh { wide, objects, shared, put_order: order.clone() }, order)
    }

    /// Whether this is a flat list (no tree: at most [`BRUTE_FORCE_MAX`]
    /// objects).
    pub fn is_flat(&self) -> bool {
        self.wide.is_empty()
    }

    /// A flat list of the objects of two flat lists, `a`'s first.
    pub fn concat_flat(a: &Bvh, b: &Bvh) -> Option<Bvh> {
        (a.is_flat() && b.is_flat()).then(|| Bvh {
            wide: WideBvh::default(),
            objects: a.objects.iter().chain(&b.objects).copied().collect(),
            shared: None,
            put_order: Vec::new(),
        })
    }

    /// The objects, in tree order.
    pub fn objects(&self) -> &[Bounded] {
        &self.objects
    }

    /// Whether there is no object.
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty()
    }

    /// The nearest hit with `0 < t < t_max`: `(t, object index in tree
    /// order)`, or `(t_max, u32::MAX)` for none.
    ///
    /// Inlined for flat lists, so that a ray just computed by the caller is
    /// read from registers (loading it back from memory right after storing
    /// it, in other widths, stalls store forwarding: measured 18% of the
    /// time on the solar scene).
    #[inline(always)]
    pub fn closest_hit(&self, ray: &Ray, t_max: f64) -> (f64, u32) {
        if self.is_flat() {
            let mut best = (t_max, u32::MAX);
            self.object_leaves(ray).closest(0, self.objects.len(), &mut best);
            return best;
        }
        self.closest_hit_in_tree(ray, t_max)
    }

    /// The objects of the leaves (of the whole list when flat), tested
    /// against `ray`.
    #[inline(always)]
    fn object_leaves<'a>(&'a self, ray: &'a Ray) -> ObjectLeaves<'a> {
        ObjectLeaves { objects: &self.objects, put_order: &self.put_order, ray }
    }

    /// [`Bvh::closest_hit`] when there is a tree.
    fn closest_hit_in_tree(&self, ray: &Ray, t_max: f64) -> (f64, u32) {
        if let Some(shared) = &self.shared {
            return shared.closest_hit(&self.wide, &self.put_order, ray, t_max);
        }
        let wide_ray = WideRay::new(ray.origin, ray.dir.recip());
        self.wide.closest_hit(&wide_ray, t_max, &self.object_leaves(ray))
    }

    /// Whether some object is hit at `0 < t < t_max`; stops at the first hit
    /// found (for shadow rays).
    ///
    /// Inlined for flat lists, as [`Bvh::closest_hit`] is.
    #[inline(always)]
    pub fn any_hit(&self, ray: &Ray, t_max: f64) -> bool {
        if self.is_flat() {
            return self.object_leaves(ray).any(0, self.objects.len(), t_max);
        }
        self.any_hit_in_tree(ray, t_max)
    }

    /// [`Bvh::any_hit`] when there is a tree.
    fn any_hit_in_tree(&self, ray: &Ray, t_max: f64) -> bool {
        if let Some(shared) = &self.shared {
            return shared.any_hit(&self.wide, &self.put_order, ray, t_max);
        }
        let wide_ray = WideRay::new(ray.origin, ray.dir.recip());
        self.wide.any_hit(&wide_ray, t_max, &self.object_leaves(ray))
    }

    /// The depth of the tree (1 for a single node, 0 without a tree).
    pub fn depth(&self) -> usize {
        self.wide.depth()
    }
}

/// Tests `objects` (whose first one has index `first`), keeping the nearest
/// hit in `best`; `put_order` as [`Bvh::put_order`].
#[inline(always)]
fn test_range(objects: &[Bounded], first: usize, put_order: &[u32], ray: &Ray, best: &mut (f64, u32)) {
    // [`goes_before`] with its two bounds kept across the objects: a miss
    // (the usual answer) costs two comparisons.
    let (mut low, mut high) = (nearer_than(best.0), reach_past(best.0));
    for (k, object) in objects.iter().enumerate() {
        let t = object.hit(ray);
        let k = (first + k) as u32;
        if t < low || (t <= high && t < f64::INFINITY && put_before(put_order, k, best.1)) {
            *best = (t, k);
            (low, high) = (nearer_than(t), reach_past(t));
        }
    }
}

/// Hits whose distances differ by less than this fraction of them are at
/// one distance: faces that coincide (two boxes sharing a face) are then
/// told apart by the order in which the objects were put, not by the
/// rounding of their distances, which changes with the scene's units
/// (SPEC 6: the same pixels at every scale). A billionth, as the offset of
/// secondary rays.
const SAME_DISTANCE: f64 = 1e-9;

/// The distance up to which a hit may still go before one at `t`
/// ([`goes_before`]): subtrees are pruned beyond it.
#[inline(always)]
pub fn reach_past(t: f64) -> f64 {
    t * (1.0 + SAME_DISTANCE)
}

/// Whether a hit at `t` of object `k` goes before `best` (distance, object;
/// `u32::MAX` for none yet): nearer by more than [`SAME_DISTANCE`], or at
/// the same distance and put before it (`put_order` as [`Bvh::put_order`]).
/// The tree's order plays no part, so any tree gives the same picture
/// (but for three or more hits each within a billionth of the next, which
/// this rule compares in the order the walk meets them).
#[inline(always)]
fn goes_before(t: f64, k: u32, best: (f64, u32), put_order: &[u32]) -> bool {
    t < nearer_than(best.0) || (t <= reach_past(best.0) && t < f64::INFINITY && put_before(put_order, k, best.1))
}

/// Whether object `k` was put before object `other` (`u32::MAX`: none yet,
/// which every object goes before); both in tree order, `put_order` as
/// [`Bvh::put_order`]. Only hits at the same distance ask it.
#[inline(always)]
fn put_before(put_order: &[u32], k: u32, other: u32) -> bool {
    match put_order {
        [] => k < other,
        order => other == u32::MAX || order[k as usize] < order[other as usize],
    }
}

/// The distance under which a hit is nearer than one at `t` by more than
/// [`SAME_DISTANCE`].
#[inline(always)]
pub fn nearer_than(t: f64) -> f64 {
    t * (1.0 - SAME_DISTANCE)
}

/// Builds the subtree over `items` (which start at `offset` in the whole
/// array, and have the bounds and centroid bounds `extent`), reordering
/// them in place and appending its nodes depth-first to `nodes`: the node,
/// its left subtree, its right subtree. `bins` is room for binning, reused
/// down the recursion.
fn build_range(
    items: &mut [Item],
    offset: usize,
    depth: usize,
    extent: Extent,
    nodes: &mut Vec<Node>,
    bins: &mut Bins,
) {
    let count = items.len();
    let leaf = Node::new(&extent.bounds, offset as u32, count as u16);
    if count <= 2 {
        nodes.push(leaf);
        return;
    }
    let split = if depth < SAH_MAX_DEPTH { sah_split(items, &extent, bins) } else { None };
    let (mid, left_extent, right_extent) = match split {
        Some(Split::Leaf) if count <= MAX_LEAF => {
            nodes.push(leaf);
            return;
        }
        Some(Split::At { mid, left, right }) => (mid, left, right),
        _ => {
            let mid = median_split(items, &extent.centroids);
            (mid, Extent::of(&items[..mid]), Extent::of(&items[mid..]))
        }
    };
    let at = nodes.len();
    nodes.push(Node::new(&extent.bounds, 0, 0));
    let (left, right) = items.split_at_mut(mid);
    if count >= PARALLEL_MIN {
        // The right subtree is built into its own list, with indices from
        // its start, then appended. Each leaf holds an object at least, so
        // a subtree has fewer than twice as many nodes as objects: that
        // capacity never grows (and pages never written cost nothing).
        let mut right_nodes = Vec::with_capacity(2 * right.len());
        rayon::join(
            || build_range(left, offset, depth + 1, left_extent, nodes, bins),
            || {
                let mut right_bins = Bins::EMPTY;
                build_range(right, offset + mid, depth + 1, right_extent, &mut right_nodes, &mut right_bins);
            },
        );
        let base = nodes.len() as u32;
        nodes[at].index = base;
        nodes.extend(
            right_nodes.into_iter().map(|n| if n.count == 0 { Node { index: n.index + base, ..n } } else { n }),
        );
    } else {
        build_range(left, offset, depth + 1, left_extent, nodes, bins);
        nodes[at].index = nodes.len() as u32;
        build_range(right, offset + mid, depth + 1, right_extent, nodes, bins);
    }
}

/// What the SAH chose for a range.
// Only ever returned, never stored: boxing the extents would allocate per node.
#[allow(clippy::large_enum_variant)]
enum Split {
    /// Keeping the range as a leaf is cheapest.
    Leaf,
    /// Split: `items[..mid]` go left after reordering; the extents of both
    /// sides.
    At { mid: usize, left: Extent, right: Extent },
}

/// Which of `count` bins along each axis an item's centroid falls in: the
/// centroid bounds cut into equal slices.
struct Binning {
    min: Vec3A,
    scale: Vec3A,
    count: usize,
}

impl Binning {
    /// The bins over `centroids` of `items` items: [`BINS`] for large
    /// ranges, fewer for small ones (`4 + items / 20`, as Embree has it),
    /// whose evaluation would otherwise cost more than their binning. On an
    /// axis where the centroids do not spread, the scale is infinite or
    /// NaN, and that axis is not evaluated.
    fn new(centroids: &Box32, items: usize) -> Binning {
        let count = BINS.min(4 + items / 20);
        Binning { min: centroids.min, scale: count as f32 / (centroids.max - centroids.min), count }
    }

    /// The bin of `centroid` on each axis.
    #[inline(always)]
    fn bins(&self, centroid: Vec3A) -> [u32; 3] {
        // Clamped to the bins in f32, so the conversion needs no
        // saturation. A NaN (on an axis that is not evaluated, or the
        // centroid of a box past f32's range, which also leaves centroid
        // bounds that miss some centroids) gives the first bin.
        let last = Vec3A::splat((self.count - 1) as f32);
        let bins = ((centroid - self.min) * self.scale).max(Vec3A::ZERO).min(last);
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{__m128i, _mm_cvttps_epi32};
            // LLVM converts lane by lane, each with the checks of a
            // saturating cast; one SSE conversion does all three.
            // SAFETY: SSE2 is part of the x86_64 baseline, and an `__m128i`
            // is four `u32`.
            let lanes: [u32; 4] = unsafe { std::mem::transmute::<__m128i, [u32; 4]>(_mm_cvttps_epi32(bins.into())) };
            [lanes[0], lanes[1], lanes[2]]
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            bins.to_array().map(|b| b as u32)
        }
    }
}

/// The bounds and item counts of the bins of a range, on every axis.
#[derive(Clone, Copy)]
struct Bins {
    bounds: [[Box32; BINS]; 3],
    counts: [[u32; BINS]; 3],
}

impl Bins {
    const EMPTY: Bins = Bins { bounds: [[Box32::EMPTY; BINS]; 3], counts: [[0; BINS]; 3] };

    /// Bins `items` (after emptying the bins of `binning`, the only ones
    /// then read), noting each item's bins in it: for large ranges, binned
    /// in parallel over chunks that are then merged in order, so that the
    /// result does not depend on threads (not even the sign of a zero bound,
    /// which a minimum of 0 and -0 takes from its order).
    fn fill(&mut self, items: &mut [Item], binning: &Binning) {
        let add_all = |bins: &mut Bins, items: &mut [Item]| {
            for it in items {
                let b = binning.bins(it.centroid());
                it.bins = b.map(|b| b as u8);
                let bounds = it.bounds();
                for (axis, &k) in b.iter().enumerate() {
                    let k = k as usize;
                    bins.bounds[axis][k] = bins.bounds[axis][k].union(bounds);
                    bins.counts[axis][k] += 1;
                }
            }
        };
        for axis in 0..3 {
            self.bounds[axis][..binning.count].fill(Box32::EMPTY);
            self.counts[axis][..binning.count].fill(0);
        }
        if items.len() < PARALLEL_BINNING_MIN {
            add_all(self, items);
            return;
        }
        let chunks: Vec<Bins> = items
            .par_chunks_mut(PARALLEL_MIN)
            .map(|chunk| {
                let mut bins = Bins::EMPTY;
                add_all(&mut bins, chunk);
                bins
            })
            .collect();
        for chunk in &chunks {
            self.merge(chunk);
        }
    }

    /// Adds the items of `other`.
    fn merge(&mut self, other: &Bins) {
        for axis in 0..3 {
            for k in 0..BINS {
                self.bounds[axis][k] = self.bounds[axis][k].union(other.bounds[axis][k]);
                self.counts[axis][k] += other.counts[axis][k];
            }
        }
    }
}

/// The binned surface area heuristic: over the bins of [`Binning`] on each
/// axis of the centroid bounds, the split minimising
/// `C_trav + (A_l N_l + A_r N_r) / A`, compared with the leaf cost `N`.
/// `None` when the centroids all coincide. `bins` is room for the binning.
fn sah_split(items: &mut [Item], extent: &Extent, bins: &mut Bins) -> Option<Split> {
    let size = extent.centroids.max - extent.centroids.min;
    // Axes where the centroids spread (not 0, not NaN).
    let spread = |axis: usize| size[axis] > 0.0;
    if !(0..3).any(spread) {
        return None;
    }
    let binning = Binning::new(&extent.centroids, items.len());
    bins.fill(items, &binning);
    let n_bins = binning.count;
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in (0..3).filter(|&axis| spread(axis)) {
        let (bounds, counts) = (&bins.bounds[axis], &bins.counts[axis]);
        // Sweep from the right to get the right-hand area and count of each
        // split, then from the left to evaluate. Only splits right after a
        // bin that is not empty are evaluated: past an empty bin nothing
        // changes, so the cost is the one just evaluated, and of equal
        // costs the first is kept.
        let mut right_area = [0.0; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut area, mut n) = (Box32::EMPTY, 0.0, 0);
        for b in (1..n_bins).rev() {
            if counts[b] > 0 {
                acc = acc.union(bounds[b]);
                area = acc.half_area();
                n += counts[b];
            }
            right_area[b] = area;
            right_count[b] = n;
        }
        let (mut acc, mut n) = (Box32::EMPTY, 0);
        for b in 1..n_bins {
            if counts[b - 1] == 0 {
                continue;
            }
            acc = acc.union(bounds[b - 1]);
            n += counts[b - 1];
            if right_count[b] == 0 {
                break;
            }
            let cost = acc.half_area() * n as f64 + right_area[b] * right_count[b] as f64;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, b));
            }
        }
    }
    let (cost, axis, bin) = best?;
    let area = extent.bounds.half_area();
    let split_cost = if area > 0.0 { TRAVERSAL_COST + cost / area } else { f64::INFINITY };
    if split_cost >= items.len() as f64 {
        return Some(Split::Leaf);
    }
    let side_bounds = |bins: &[Box32]| bins.iter().copied().fold(Box32::EMPTY, Box32::union);
    let (mid, left_centroids, right_centroids) = partition(items, |it| usize::from(it.bins[axis]) < bin);
    let left = Extent { bounds: side_bounds(&bins.bounds[axis][..bin]), centroids: left_centroids };
    let right = Extent { bounds: side_bounds(&bins.bounds[axis][bin..n_bins]), centroids: right_centroids };
    Some(Split::At { mid, left, right })
}

/// Splits by object count along the longest centroid axis (the fallback
/// when the SAH cannot or should not decide); returns the left side's count.
fn median_split(items: &mut [Item], centroids: &Box32) -> usize {
    let extent = centroids.max - centroids.min;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.centroid()[axis].total_cmp(&b.centroid()[axis]).then(a.index.cmp(&b.index))
    });
    mid
}

/// Moves the items satisfying `left` to the front, swapping the first
/// misplaced item from each end; returns their count and the centroid
/// bounds of both sides. Deterministic (no dependence on threads).
fn partition(items: &mut [Item], left: impl Fn(&Item) -> bool) -> (usize, Box32, Box32) {
    let (mut start, mut end) = (0, items.len());
    let (mut left_centroids, mut right_centroids) = (Box32::EMPTY, Box32::EMPTY);
    loop {
        while start < end && left(&items[start]) {
            left_centroids = left_centroids.grow(items[start].centroid());
            start += 1;
        }
        while start < end && !left(&items[end - 1]) {
            right_centroids = right_centroids.grow(items[end - 1].centroid());
            end -= 1;
        }
        if start == end {
            return (start, left_centroids, right_centroids);
        }
        items.swap(start, end - 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::intersect::SphereShape;

    #[test]
    fn coincident_centroids_still_give_a_shallow_tree() {
        let spheres: Vec<Bounded> =
            (0..1000).map(|k| Bounded::Sphere(SphereShape { center: DVec3::ZERO, radius: 1.0 + k as f64 })).collect();
        let (bvh, order) = Bvh::build(spheres.len(), |k| spheres[k]);
        assert!(bvh.depth() < STACK_SIZE);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert!(sorted.iter().enumerate().all(|(k, &v)| k as u32 == v));
    }

    #[test]
    fn objects_past_the_f32_range_are_found_and_the_tree_does_not_depend_on_threads() {
        // Small spheres around a huge one, whose f32 box is infinite and
        // whose centroid is NaN.
        let mut spheres: Vec<Bounded> = (0..6000)
            .map(|k| Bounded::Sphere(SphereShape { center: DVec3::new(k as f64 * 0.1, 0.0, 0.0), radius: 0.03 }))
            .collect();
        spheres.insert(3000, Bounded::Sphere(SphereShape { center: DVec3::new(0.0, -1e39, 0.0), radius: 1e39 }));
        let build_on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool");
            pool.install(|| Bvh::build(spheres.len(), |k| spheres[k]))
        };
        let ((bvh, order), (_, order_on_two)) = (build_on(1), build_on(2));
        assert_eq!(order, order_on_two);
        for k in 0..2000 {
            let ray = Ray::new(DVec3::new(k as f64 * 0.3, 5.0, 0.01), DVec3::NEG_Y);
            let nearest = bvh.objects().iter().map(|o| o.hit(&ray)).fold(f64::INFINITY, f64::min);
            assert_eq!(bvh.closest_hit(&ray, f64::INFINITY).0, nearest);
            assert_eq!(bvh.any_hit(&ray, f64::INFINITY), nearest < f64::INFINITY);
        }
    }

    #[test]
    fn exponential_layout_depth_is_bounded() {
        let spheres: Vec<Bounded> = (0..2000)
            .map(|k| Bounded::Sphere(SphereShape { center: DVec3::new(1.01f64.powi(k), 0.0, 0.0), radius: 1e-3 }))
            .collect();
        let (bvh, _) = Bvh::build(spheres.len(), |k| spheres[k]);
        assert!(bvh.depth() < STACK_SIZE, "depth {}", bvh.depth());
    }
}
