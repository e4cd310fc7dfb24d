//! Bounding-volume hierarchy over shapes.
//!
//! A binary tree of axis-aligned boxes in one flat array, in depth-first order: an interior
//! node's first child follows it, and it stores the distance to its second child; a leaf stores
//! a range of the primitive index list. Built top-down by binned surface-area heuristic
//! (`bvh/build.rs`), traversed iteratively nearest child first (`bvh/traverse.rs`).
//!
//! The tree depends only on the shapes, never on the number of threads that built it.
//!
//! # References
//! - Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies" (binned SAH).
//! - Pharr, Jakob & Humphreys 2023, *Physically Based Rendering* 4th ed., §7.3 (pbrt-v4).

mod build;
mod traverse;

use super::{Aabb, Hit, Ray, Shape};

/// A bounding-volume hierarchy over a slice of shapes (see the module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Shape indices, grouped by leaf.
    prims: Vec<u32>,
}

/// A node: its box as `[min, max]`, and either a leaf's primitive range
/// (`prims[offset..offset + count]`, count > 0) or, for an interior node (count = 0), the
/// distance to its second child (`nodes[i + offset]`; the first child is `nodes[i + 1]`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    bounds: [[f64; 3]; 2],
    offset: u32,
    count: u32,
}

impl Bvh {
    /// Binned-SAH build over `shapes` (at most u32::MAX − 1 of them); deterministic.
    pub fn build(shapes: &[Shape]) -> Bvh {
        build::build(shapes)
    }

    /// Nearest hit with t in (0, t_max) among `shapes` (the slice it was built over).
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray, t_max: f64) -> Option<Hit> {
        let (prim, t) = self.traverse::<false>(shapes, ray, t_max)?;
        let shape = &shapes[prim as usize];
        let point = shape.hit_point(ray, t);
        Some(Hit { t, point, normal: shape.normal_at(point), prim })
    }

    /// Whether anything is hit with t in (0, t_max).
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray, t_max: f64) -> bool {
        self.traverse::<true>(shapes, ray, t_max).is_some()
    }

    /// Whether any of `shapes` may have surface inside `b`: boxes are tested against the tree's
    /// nodes, and at the leaves against each shape ([`Shape::may_touch_box`]: exact for spheres,
    /// by bounding box otherwise). False means certainly not: a path segment inside `b` needs
    /// no intersection tests.
    pub fn may_touch_box(&self, shapes: &[Shape], b: &Aabb) -> bool {
        self.touching_box(shapes, b, 1, &mut |_| {}) > 0
    }

    /// The one shape (index into `shapes`) that may have surface inside `b`, if no other may
    /// ([`Bvh::may_touch_box`]'s test): `None` when none or several may.
    pub fn sole_shape_touching_box(&self, shapes: &[Shape], b: &Aabb) -> Option<u32> {
        let mut found = None;
        let count = self.touching_box(shapes, b, 2, &mut |p| found = Some(p));
        (count == 1).then_some(found).flatten()
    }

    /// Counts the shapes that may touch `b`, up to `limit` (then it stops), handing each to
    /// `seen`; a tree too deep for the stack counts as `limit`.
    fn touching_box(&self, shapes: &[Shape], b: &Aabb, limit: usize, seen: &mut impl FnMut(u32)) -> usize {
        let mut count = 0;
        let overlaps = |n: &Node| (0..3).all(|k| n.bounds[0][k] <= b.max[k] && n.bounds[1][k] >= b.min[k]);
        let mut stack = [0usize; 64];
        let mut top = 0usize;
        if self.nodes.is_empty() {
            return 0;
        }
        stack[0] = 0;
        top += 1;
        while top > 0 {
            top -= 1;
            let i = stack[top];
            let n = &self.nodes[i];
            if !overlaps(n) {
                continue;
            }
            if n.count > 0 {
                let prims = &self.prims[n.offset as usize..(n.offset + n.count) as usize];
                for &p in prims.iter().filter(|p| shapes[**p as usize].may_touch_box(b)) {
                    seen(p);
                    count += 1;
                    if count >= limit {
                        return count;
                    }
                }
                continue;
            }
            if top + 2 > stack.len() {
                return limit;
            }
            stack[top] = i + 1;
            stack[top + 1] = i + n.offset as usize;
            top += 2;
        }
        count
    }

    /// Number of nodes (interior and leaves).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Length of the longest root-to-leaf path, counting nodes (0 when empty).
    pub fn depth(&self) -> usize {
        self.depth_below(0)
    }

    fn depth_below(&self, index: usize) -> usize {
        match self.nodes.get(index) {
            None => 0,
            Some(node) if node.count > 0 => 1,
            Some(node) => 1 + self.depth_below(index + 1).max(self.depth_below(index + node.offset as usize)),
        }
    }

    /// Box around all shapes (empty when there are none).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| Aabb { min: n.bounds[0].into(), max: n.bounds[1].into() })
    }
}
