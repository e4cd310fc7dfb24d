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
        Slabs {
            origin: ray.origin.into(),
            inv_dir: inv.into(),
            neg: [0, 1, 2].map(|i| usize::from(inv[i] < 0.0)),
        }
    }

    /// Distance at which the ray enters the node's box, if it does so within [0, t_max].
    #[inline]
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

impl Bvh {
    /// The nearest hit (or with `ANY`, the first found) with t in (0, t_max): shape index and t.
    pub(super) fn traverse<const ANY: bool>(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_max: f64,
    ) -> Option<(u32, f64)> {
        let slabs = Slabs::new(ray);
        let shear = Shear::new(ray);
        let root = self.nodes.first()?;
        slabs.entry(root, t_max)?;
        let (mut best, mut t_best) = (None, t_max);
        let mut stack = [(0u32, 0.0f64); STACK];
        let (mut sp, mut index) = (0, 0usize);
        loop {
            let node = &self.nodes[index];
            if node.count > 0 {
                let first = node.offset as usize;
                for &prim in &self.prims[first..first + node.count as usize] {
                    if let Some(t) = shapes[prim as usize].distance_sheared(ray, &shear, t_best) {
                        (best, t_best) = (Some(prim), t);
                        if ANY {
                            return best.map(|p| (p, t_best));
                        }
                    }
                }
            } else {
                let (a, b) = (index + 1, index + node.offset as usize);
                match (
                    slabs.entry(&self.nodes[a], t_best),
                    slabs.entry(&self.nodes[b], t_best),
                ) {
                    (Some(ta), Some(tb)) => {
                        let (near, far, t_far) = if ta <= tb { (a, b, tb) } else { (b, a, ta) };
                        stack[sp] = (far as u32, t_far);
                        sp += 1;
                        index = near;
                        continue;
                    }
                    (Some(_), None) => {
                        index = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        index = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the nearest pending subtree that can still hold a nearer hit.
            loop {
                if sp == 0 {
                    return best.map(|p| (p, t_best));
                }
                sp -= 1;
                let (next, t_entry) = stack[sp];
                if t_entry <= t_best {
                    index = next as usize;
                    break;
                }
            }
        }
    }
}
