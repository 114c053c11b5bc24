//! Packets: up to [`PACKET`] rays (camera rays of neighbouring pixels,
//! shadow rays towards one directional light) walked through the wide tree
//! together. A node is loaded, and its children sorted and stacked, once
//! for the packet; its children are tested ray by ray ([`meet`]) or, when
//! at least [`LANES_MIN`] rays that enter boxes by the same planes are
//! active, each child box against all of them at once (one lane per ray).
//!
//! Each ray's box tests are the very f32 operations of its single walk and
//! each ray keeps its own best `(t, index)` and limit, so a packet answers
//! what its rays alone answer; only the order in which a ray's leaves are
//! visited differs, as it differs between the single walk and the tree
//! order, which the tie rule of [`goes_before`](super::super::goes_before)
//! makes irrelevant.

use super::{
    Entry, Stack, WIDEN, WIDTH, Walk, WideBvh, WideNode, WideRay, lanes_at_most, limit_above, meet, reach_past,
};

/// Rays per packet (a bit each in the masks of the walks).
pub(crate) const PACKET: usize = 8;

/// Up to [`PACKET`] rays prepared for the node tests.
#[derive(Debug, Clone, Copy)]
pub(in crate::render::bvh) struct PacketRays {
    rays: [WideRay; PACKET],
    /// The rays to trace (bit `r` for `rays[r]`).
    lanes: u32,
    /// The rays one lane each, if they share their planes.
    soa: Option<Lanes>,
}

/// Rays that enter (and leave) boxes by the same planes, laid out one lane
/// per ray, so that a child box is tested against all of them at once.
#[derive(Debug, Clone, Copy)]
struct Lanes {
    entry_row: [usize; 3],
    exit_row: [usize; 3],
    entry_origin: [[f32; PACKET]; 3],
    exit_origin: [[f32; PACKET]; 3],
    entry_inv: [[f32; PACKET]; 3],
    exit_inv: [[f32; PACKET]; 3],
}

impl PacketRays {
    /// The rays of `lanes` among `rays` (at most [`PACKET`]).
    #[inline(always)]
    pub(in crate::render::bvh) fn new(rays: [WideRay; PACKET], lanes: u32) -> PacketRays {
        let first = rays[lanes.trailing_zeros() as usize % PACKET];
        let same = lanes_of(lanes).all(|r| rays[r].entry_row == first.entry_row);
        let soa = same.then(|| Lanes {
            entry_row: first.entry_row,
            exit_row: first.exit_row,
            entry_origin: std::array::from_fn(|axis| rays.map(|ray| ray.entry_origin[axis])),
            exit_origin: std::array::from_fn(|axis| rays.map(|ray| ray.exit_origin[axis])),
            entry_inv: std::array::from_fn(|axis| rays.map(|ray| ray.entry_inv[axis])),
            exit_inv: std::array::from_fn(|axis| rays.map(|ray| ray.exit_inv[axis])),
        });
        PacketRays { rays, lanes, soa }
    }

    /// [`meet_packet`], or [`meet_lanes`] when the rays share their planes.
    #[inline(always)]
    fn meet(&self, node: &WideNode, lanes: u32, limits: &[f32; PACKET]) -> ([u32; WIDTH], [f32; WIDTH]) {
        match &self.soa {
            Some(soa) if lanes.count_ones() >= LANES_MIN => meet_lanes(node, soa, lanes, limits),
            _ => meet_packet(node, self, lanes, limits),
        }
    }
}

/// Fewest rays for which the lane-per-ray test runs.
const LANES_MIN: u32 = 4;

/// [`meet_packet`] with one lane per ray: each child box against all the
/// rays at once. Lane by lane, the operations of [`meet`].
#[inline(always)]
fn meet_lanes(node: &WideNode, rays: &Lanes, lanes: u32, limits: &[f32; PACKET]) -> ([u32; WIDTH], [f32; WIDTH]) {
    let limits: [f32; PACKET] =
        std::array::from_fn(|r| if lanes >> r & 1 == 1 { limits[r] } else { f32::NEG_INFINITY });
    let mut met = [0u32; WIDTH];
    let mut nearest = [f32::INFINITY; WIDTH];
    for i in 0..WIDTH {
        let mut entry = [0.0f32; PACKET];
        let mut exit = limits;
        for axis in 0..3 {
            let lower = node.bounds[rays.entry_row[axis]][i];
            let upper = node.bounds[rays.exit_row[axis]][i];
            for r in 0..PACKET {
                let t_in = (lower - rays.entry_origin[axis][r]) * rays.entry_inv[axis][r];
                let t_out = (upper - rays.exit_origin[axis][r]) * rays.exit_inv[axis][r];
                entry[r] = if t_in > entry[r] { t_in } else { entry[r] };
                exit[r] = if t_out < exit[r] { t_out } else { exit[r] };
            }
        }
        let exit = exit.map(|t| t * WIDEN);
        met[i] = lanes_at_most(&entry, &exit);
        let entries: [f32; PACKET] =
            std::array::from_fn(|r| if entry[r] <= exit[r] { entry[r] } else { f32::INFINITY });
        nearest[i] = entries.into_iter().fold(f32::INFINITY, |a, b| if b < a { b } else { a });
    }
    (met, nearest)
}

/// A child waiting on the packet's stack: where it is, its object count (0
/// for a node), the rays that meet its box, and the nearest distance at
/// which one of them enters it (the order of the stack).
#[derive(Debug, Clone, Copy)]
struct PacketPending {
    child: u32,
    count: u32,
    rays: u32,
    nearest: f32,
}

impl Entry for PacketPending {
    #[inline(always)]
    fn entry(&self) -> f32 {
        self.nearest
    }
}

/// The children of `node` that the rays of `lanes` meet within their
/// limits: for each child, the mask of those rays, and the nearest of
/// their entry distances. Each ray's test is its single walk's ([`meet`]).
#[inline(always)]
fn meet_packet(node: &WideNode, rays: &PacketRays, lanes: u32, limits: &[f32; PACKET]) -> ([u32; WIDTH], [f32; WIDTH]) {
    // Row r of the bit matrix (byte r) holds the children ray r meets.
    let mut by_ray = 0u64;
    let mut nearest = [f32::INFINITY; WIDTH];
    for r in lanes_of(lanes) {
        let (entries, met) = meet(node, &rays.rays[r], limits[r]);
        by_ray |= u64::from(met) << (8 * r);
        for i in 0..WIDTH {
            let entry = if met >> i & 1 == 1 { entries[i] } else { f32::INFINITY };
            nearest[i] = if entry < nearest[i] { entry } else { nearest[i] };
        }
    }
    let by_child = transpose(by_ray);
    (std::array::from_fn(|i| (by_child >> (8 * i)) as u32 & 0xff), nearest)
}

/// The transpose of the 8 x 8 bit matrix whose row `r` is byte `r` (bit
/// `i` of it is column `i`): three rounds of swapping blocks across the
/// diagonal (Hacker's Delight, 7-3).
#[inline(always)]
fn transpose(mut x: u64) -> u64 {
    x = x & 0xaa55_aa55_aa55_aa55 | (x & 0x00aa_00aa_00aa_00aa) << 7 | (x >> 7) & 0x00aa_00aa_00aa_00aa;
    x = x & 0xcccc_3333_cccc_3333 | (x & 0x0000_cccc_0000_cccc) << 14 | (x >> 14) & 0x0000_cccc_0000_cccc;
    x & 0xf0f0_f0f0_0f0f_0f0f | (x & 0x0000_0000_f0f0_f0f0) << 28 | (x >> 28) & 0x0000_0000_f0f0_f0f0
}

/// The lanes of `mask`, lowest first.
#[inline(always)]
fn lanes_of(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        let r = mask.trailing_zeros() as usize;
        mask &= mask.wrapping_sub(1);
        (r < 32).then_some(r)
    })
}

impl WideBvh {
    /// [`WideBvh::closest_hit`] for each ray of `rays`: `leaf(start,
    /// count, r, best)` tests the objects `start .. start + count` against
    /// ray `r` and keeps its nearest hit in `best`. Lanes without a ray
    /// answer `(t_max, u32::MAX)`.
    #[inline(always)]
    pub(in crate::render::bvh) fn closest_hits(
        &self,
        rays: &PacketRays,
        t_max: f64,
        leaf: impl FnMut(usize, usize, usize, &mut (f64, u32)),
    ) -> [(f64, u32); PACKET] {
        self.run(ClosestPacket { rays, t_max, leaf })
    }

    /// [`WideBvh::any_hit`] for each ray of `rays`: the mask of those for
    /// which `leaf(start, count, r)` returns true for the objects of some
    /// leaf whose box ray `r` meets before `t_max`.
    #[inline(always)]
    pub(in crate::render::bvh) fn any_hits(
        &self,
        rays: &PacketRays,
        t_max: f64,
        leaf: impl FnMut(usize, usize, usize) -> bool,
    ) -> u32 {
        self.run(AnyPacket { rays, t_max, leaf })
    }
}

/// [`WideBvh::closest_hits`]' walk.
struct ClosestPacket<'a, L> {
    rays: &'a PacketRays,
    t_max: f64,
    leaf: L,
}

impl<L: FnMut(usize, usize, usize, &mut (f64, u32))> Walk for ClosestPacket<'_, L> {
    type Output = [(f64, u32); PACKET];

    /// The single closest-hit walk, per lane: children visited nearest
    /// (by the packet's nearest ray) first, each ray only while its entry
    /// is within [`reach_past`] of its own best.
    #[inline(always)]
    fn walk(mut self, nodes: &[WideNode]) -> [(f64, u32); PACKET] {
        let rays = self.rays;
        let mut best = [(self.t_max, u32::MAX); PACKET];
        let mut limits = [limit_above(reach_past(self.t_max)); PACKET];
        let mut reach = limits.map(|limit| limit * WIDEN);
        let mut stack = Stack::<PacketPending>::new();
        let mut current = PacketPending { child: 0, count: 0, rays: rays.lanes, nearest: 0.0 };
        loop {
            if current.count > 0 {
                for r in lanes_of(current.rays) {
                    (self.leaf)(current.child as usize, current.count as usize, r, &mut best[r]);
                    limits[r] = limit_above(reach_past(best[r].0));
                    reach[r] = limits[r] * WIDEN;
                }
            } else {
                let node = &nodes[current.child as usize];
                let (met, nearest) = rays.meet(node, current.rays, &limits);
                let first = stack.len;
                for i in 0..WIDTH {
                    if met[i] != 0 {
                        let child = PacketPending {
                            child: node.child[i],
                            count: node.count[i],
                            rays: met[i],
                            nearest: nearest[i],
                        };
                        stack.push_sorted(first, child);
                    }
                }
            }
            // The nearest waiting child, with the rays it may still be
            // within reach of (each ray's own entry is tested at the node).
            loop {
                let Some(mut next) = stack.pop() else { return best };
                next.rays &= lanes_at_most(&[next.nearest; PACKET], &reach);
                if next.rays != 0 {
                    current = next;
                    break;
                }
            }
        }
    }
}

/// [`WideBvh::any_hits`]' walk.
struct AnyPacket<'a, L> {
    rays: &'a PacketRays,
    t_max: f64,
    leaf: L,
}

impl<L: FnMut(usize, usize, usize) -> bool> Walk for AnyPacket<'_, L> {
    type Output = u32;

    /// The single any-hit walk, per lane: children in slot order, each ray
    /// until it is blocked.
    #[inline(always)]
    fn walk(mut self, nodes: &[WideNode]) -> u32 {
        let rays = self.rays;
        let limits = [limit_above(self.t_max); PACKET];
        let mut blocked = 0;
        let mut stack = Stack::<(u32, u32, u32)>::new();
        let mut current = (0, 0, rays.lanes);
        loop {
            let (child, count, lanes) = current;
            let open = lanes & !blocked;
            if open != 0 {
                if count > 0 {
                    for r in lanes_of(open) {
                        if (self.leaf)(child as usize, count as usize, r) {
                            blocked |= 1 << r;
                        }
                    }
                    if blocked == rays.lanes {
                        return blocked;
                    }
                } else {
                    let node = &nodes[child as usize];
                    let (met, _) = rays.meet(node, open, &limits);
                    for i in (0..WIDTH).rev() {
                        if met[i] != 0 {
                            stack.push((node.child[i], node.count[i], met[i]));
                        }
                    }
                }
            }
            let Some(next) = stack.pop() else { return blocked };
            current = next;
        }
    }
}
