//! Iterative traversal, nearest child first, with a fixed-size stack (no allocation per query).
//!
//! # Ray–box test
//! The slab test of Kay & Kajiya 1986 with the rounding margins of pbrt-v4 §6.8.2: each slab's
//! exit distance is scaled by 1 + 2γ₃ and its entry distance by 1 − 2γ₃, so a box is never missed
//! through rounding. Slab bounds are picked by the sign of the direction (Williams et al. 2005),
//! and a NaN from 0·∞ (origin on a slab plane, direction parallel to it) fails both comparisons
//! and leaves that slab unbounded, which is right for a closed box.

use super::{Bvh, Node};
use crate::geometry::rounding::gamma;
use crate::geometry::shape::Shear;
use crate::geometry::{Ray, Shape};

/// Stack entries needed: at most one per level, and the tree is at most MAX_SAH_DEPTH + 36
/// nodes deep (`bvh/build.rs`).
const STACK: usize = super::build::MAX_SAH_DEPTH + 40;

/// The stack of a small tree: each entry waits below an interior node of the current path, and a
/// tree of n nodes has (n − 1)/2 interior nodes, so a tree of at most 2·SMALL_STACK + 1 nodes
/// needs no more. Zeroing the full stack's 1.4 kB on every query was 2 % of `sunset_sea`'s photon
/// pass and 8 % of `fluorescent_glass_block`'s (a few shapes, a query per bounce).
const SMALL_STACK: usize = 16;

/// The ray's constants for box tests.
struct Slabs {
    origin: [f64; 3],
    inv_dir: [f64; 3],
    /// 1 where the direction component is negative: the slab is entered at its max.
    neg: [usize; 3],
}

impl Slabs {
    fn new(ray: &Ray) -> Slabs {
        let inv = ray.dir.recip();
        Slabs { origin: ray.origin.into(), inv_dir: inv.into(), neg: [0, 1, 2].map(|i| usize::from(inv[i] < 0.0)) }
    }

    /// Distance at which the ray enters the node's box, if it does so within [0, t_max].
    #[inline(always)]
    fn entry(&self, node: &Node, t_max: f64) -> Option<f64> {
        const LOW: f64 = 1.0 - 2.0 * gamma(3);
        const HIGH: f64 = 1.0 + 2.0 * gamma(3);
        let (mut t0, mut t1) = (0.0, t_max);
        for i in 0..3 {
            let near = (node.bounds[self.neg[i]][i] - self.origin[i]) * self.inv_dir[i] * LOW;
            let far = (node.bounds[1 - self.neg[i]][i] - self.origin[i]) * self.inv_dir[i] * HIGH;
            if near > t0 {
                t0 = near;
            }
            if far < t1 {
                t1 = far;
            }
        }
        (t0 <= t1).then_some(t0)
    }
}

/// Subtrees still to visit, with the distance at which the ray enters each; nearest on top.
struct Stack<const N: usize> {
    entries: [(u32, f64); N],
    len: usize,
}

impl<const N: usize> Stack<N> {
    fn new() -> Stack<N> {
        Stack { entries: [(0, 0.0); N], len: 0 }
    }

    #[inline(always)]
    fn push(&mut self, node: usize, t_entry: f64) {
        self.entries[self.len] = (node as u32, t_entry);
        self.len += 1;
    }

    /// The next subtree that the ray enters before `t_max`, dropping the ones it does not.
    #[inline(always)]
    fn pop_within(&mut self, t_max: f64) -> Option<usize> {
        while self.len > 0 {
            self.len -= 1;
            let (node, t_entry) = self.entries[self.len];
            if t_entry <= t_max {
                return Some(node as usize);
            }
        }
        None
    }
}

/// The nearest hit so far: shape index and distance (t_max until something is hit).
struct Best {
    prim: Option<u32>,
    t: f64,
}

impl Bvh {
    /// The nearest hit (or with `ANY`, the first found) with t in (0, t_max): shape index and t.
    pub(super) fn traverse<const ANY: bool>(&self, shapes: &[Shape], ray: &Ray, t_max: f64) -> Option<(u32, f64)> {
        if self.nodes.len() <= 2 * SMALL_STACK + 1 {
            self.traverse_with::<ANY, SMALL_STACK>(shapes, ray, t_max)
        } else {
            self.traverse_with::<ANY, STACK>(shapes, ray, t_max)
        }
    }

    /// [`Bvh::traverse`] with a stack of `N` entries (enough for the tree).
    fn traverse_with<const ANY: bool, const N: usize>(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_max: f64,
    ) -> Option<(u32, f64)> {
        let slabs = Slabs::new(ray);
        let shear = Shear::new(ray);
        slabs.entry(self.nodes.first()?, t_max)?;
        let mut best = Best { prim: None, t: t_max };
        let mut stack = Stack::<N>::new();
        let mut index = 0;
        loop {
            let node = &self.nodes[index];
            let next = if node.count > 0 {
                let found = self.test_leaf(node, shapes, ray, &shear, &mut best);
                if ANY && found {
                    break;
                }
                None
            } else {
                self.descend(index, node, &slabs, best.t, &mut stack)
            };
            match next.or_else(|| stack.pop_within(best.t)) {
                Some(i) => index = i,
                None => break,
            }
        }
        best.prim.map(|p| (p, best.t))
    }

    /// Tests a leaf's shapes, keeping the nearest hit; whether there was one.
    #[inline(always)]
    fn test_leaf(&self, node: &Node, shapes: &[Shape], ray: &Ray, shear: &Shear, best: &mut Best) -> bool {
        let first = node.offset as usize;
        let mut found = false;
        for &prim in &self.prims[first..first + node.count as usize] {
            if let Some(t) = shapes[prim as usize].distance_sheared(ray, shear, best.t) {
                (best.prim, best.t) = (Some(prim), t);
                found = true;
            }
        }
        found
    }

    /// The child of interior node `index` to visit next: the nearer of those the ray enters
    /// before `t_max`, the other one pushed for later.
    #[inline(always)]
    fn descend<const N: usize>(
        &self,
        index: usize,
        node: &Node,
        slabs: &Slabs,
        t_max: f64,
        stack: &mut Stack<N>,
    ) -> Option<usize> {
        let (a, b) = (index + 1, index + node.offset as usize);
        match (slabs.entry(&self.nodes[a], t_max), slabs.entry(&self.nodes[b], t_max)) {
            (Some(ta), Some(tb)) => {
                let (near, far, t_far) = if ta <= tb { (a, b, tb) } else { (b, a, ta) };
                stack.push(far, t_far);
                Some(near)
            }
            (Some(_), None) => Some(a),
            (None, Some(_)) => Some(b),
            (None, None) => None,
        }
    }
}
