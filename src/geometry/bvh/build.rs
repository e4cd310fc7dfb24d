//! Top-down binned SAH construction (Wald 2007; pbrt-v4 §7.3.2).
//!
//! Each node bins its primitives' box centres into [`BINS`] equal bins along each axis, and
//! evaluates the surface-area heuristic at every bin boundary:
//!
//! ```text
//! cost(split) = C_trav + (N_l A_l + N_r A_r) / A,     cost(leaf) = N
//! ```
//!
//! in units of one shape test, where A is a box's surface area. A node becomes a leaf when it
//! holds at most [`MAX_LEAF`] shapes and no split is cheaper. Beyond depth [`MAX_SAH_DEPTH`], or
//! when all centres coincide, the shapes are split at their median instead, which bounds the depth
//! of the tree by MAX_SAH_DEPTH + 32 (the traversal stack is sized for that).
//!
//! The node array is first laid out in an arena where a node over n shapes owns 2n − 1 slots (the
//! most its subtree can need): the node itself, then its first child's slots, then its second
//! child's. Disjoint slices let the two children build in parallel, and the final array, the arena
//! with its unused slots squeezed out, is independent of scheduling: the build is deterministic.

use super::{Bvh, Node};
use crate::geometry::{Aabb, Shape};
use glam::DVec3;
use rayon::prelude::*;

/// Bins per axis.
pub const BINS: usize = 16;
/// Most shapes in a leaf.
pub const MAX_LEAF: usize = 8;
/// Depth beyond which nodes split at the median.
pub const MAX_SAH_DEPTH: usize = 48;
/// Cost of visiting a node relative to one shape test.
const TRAVERSAL_COST: f64 = 1.0;
/// Subtrees at least this large build in parallel.
const PARALLEL_MIN: usize = 8 * 1024;

/// A shape as the builder sees it.
#[derive(Clone, Copy, Debug)]
struct PrimRef {
    bounds: Aabb,
    index: u32,
}

impl PrimRef {
    fn centre(&self) -> DVec3 {
        self.bounds.centre()
    }
}

const UNUSED: Node = Node {
    bounds: [[0.0; 3]; 2],
    offset: 0,
    count: u32::MAX,
};

pub fn build(shapes: &[Shape]) -> Bvh {
    assert!(
        shapes.len() < u32::MAX as usize,
        "Bvh::build: {} shapes exceed the u32 index range",
        shapes.len()
    );
    if shapes.is_empty() {
        return Bvh::default();
    }
    let mut refs: Vec<PrimRef> = shapes
        .par_iter()
        .enumerate()
        .map(|(i, s)| PrimRef {
            bounds: s.bounds(),
            index: i as u32,
        })
        .collect();
    let mut arena = vec![UNUSED; 2 * refs.len() - 1];
    let job = Job {
        first: 0,
        base: 0,
        depth: 1,
    };
    build_node(&mut refs, &mut arena, job);
    Bvh {
        nodes: compact(&arena),
        prims: refs.iter().map(|r| r.index).collect(),
    }
}

/// Where a subtree goes: the index of its first shape in the reference list, its first arena
/// slot, and its depth.
#[derive(Clone, Copy)]
struct Job {
    first: usize,
    base: usize,
    depth: usize,
}

/// Builds the subtree over `refs` into `arena` (its 2 n − 1 slots), reordering `refs` so that
/// every leaf's shapes are contiguous.
fn build_node(refs: &mut [PrimRef], arena: &mut [Node], job: Job) {
    let bounds = refs.iter().fold(Aabb::EMPTY, |b, r| b.union(r.bounds));
    let centres = refs.iter().fold(Aabb::EMPTY, |b, r| b.include(r.centre()));
    let n = refs.len();
    let mid = match choose_split(refs, &bounds, &centres, job.depth) {
        Some(mid) => mid,
        None => {
            arena[0] = node(&bounds, job.first, n);
            return;
        }
    };
    arena[0] = node(&bounds, job.base + 2 * mid, 0);
    let (left_refs, right_refs) = refs.split_at_mut(mid);
    let (left_arena, right_arena) = arena[1..].split_at_mut(2 * mid - 1);
    let left = Job {
        first: job.first,
        base: job.base + 1,
        depth: job.depth + 1,
    };
    let right = Job {
        first: job.first + mid,
        base: job.base + 2 * mid,
        depth: job.depth + 1,
    };
    if n >= PARALLEL_MIN {
        rayon::join(
            || build_node(left_refs, left_arena, left),
            || build_node(right_refs, right_arena, right),
        );
    } else {
        build_node(left_refs, left_arena, left);
        build_node(right_refs, right_arena, right);
    }
}

fn node(bounds: &Aabb, offset: usize, count: usize) -> Node {
    Node {
        bounds: [bounds.min.into(), bounds.max.into()],
        offset: offset as u32,
        count: count as u32,
    }
}

/// Partitions `refs` for a split and returns the size of the first part (0 < mid < n), or
/// `None` when the node should be a leaf.
fn choose_split(
    refs: &mut [PrimRef],
    bounds: &Aabb,
    centres: &Aabb,
    depth: usize,
) -> Option<usize> {
    let n = refs.len();
    if n == 1 {
        return None;
    }
    if depth <= MAX_SAH_DEPTH
        && let Some(split) = best_bin_split(refs, bounds, centres)
    {
        if n <= MAX_LEAF && split.cost >= n as f64 {
            return None;
        }
        let mid = partition(refs, |r| {
            bin_of(r.centre(), centres, split.axis) < split.bin
        });
        if mid > 0 && mid < n {
            return Some(mid);
        }
    }
    if n <= MAX_LEAF {
        return None;
    }
    Some(median_split(refs, centres))
}

/// Splits at the median centre along the axis of largest centre extent.
fn median_split(refs: &mut [PrimRef], centres: &Aabb) -> usize {
    let axis = centres.diagonal().max_position();
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| a.centre()[axis].total_cmp(&b.centre()[axis]));
    mid
}

/// The cheapest bin boundary: shapes in bins `< bin` along `axis` go first.
#[derive(Clone, Copy, Debug)]
struct Split {
    axis: usize,
    bin: usize,
    cost: f64,
}

/// Bin of a centre along `axis`: ⌊BINS (c − min)/(max − min)⌋, clamped to the last bin.
fn bin_of(c: DVec3, centres: &Aabb, axis: usize) -> usize {
    let (lo, hi) = (centres.min[axis], centres.max[axis]);
    let k = ((c[axis] - lo) * (BINS as f64 / (hi - lo))) as usize;
    k.min(BINS - 1)
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: usize,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    count: 0,
};

/// Binned SAH over the three axes; `None` when the centres coincide on every axis.
fn best_bin_split(refs: &[PrimRef], bounds: &Aabb, centres: &Aabb) -> Option<Split> {
    let extent = centres.diagonal();
    let axes: Vec<usize> = (0..3).filter(|&a| extent[a] > 0.0).collect();
    let mut bins = [[EMPTY_BIN; BINS]; 3];
    for r in refs {
        let c = r.centre();
        for &a in &axes {
            let bin = &mut bins[a][bin_of(c, centres, a)];
            bin.bounds = bin.bounds.union(r.bounds);
            bin.count += 1;
        }
    }
    let area = bounds.surface_area();
    axes.iter()
        .filter_map(|&a| best_on_axis(&bins[a], a, area))
        .min_by(|x, y| x.cost.total_cmp(&y.cost))
}

/// The cheapest boundary among one axis's bins: a sweep from the right accumulates the cost of
/// the second part, one from the left the first part's.
fn best_on_axis(bins: &[Bin; BINS], axis: usize, area: f64) -> Option<Split> {
    let mut right_cost = [0.0; BINS];
    let (mut b, mut count) = (Aabb::EMPTY, 0);
    for k in (1..BINS).rev() {
        b = b.union(bins[k].bounds);
        count += bins[k].count;
        right_cost[k] = count as f64 * b.surface_area();
    }
    let (mut b, mut count) = (Aabb::EMPTY, 0);
    let mut best: Option<Split> = None;
    for k in 1..BINS {
        b = b.union(bins[k - 1].bounds);
        count += bins[k - 1].count;
        let cost = TRAVERSAL_COST + (count as f64 * b.surface_area() + right_cost[k]) / area;
        if best.is_none_or(|s| cost < s.cost) {
            best = Some(Split { axis, bin: k, cost });
        }
    }
    best.filter(|s| s.cost.is_finite())
}

/// Moves the elements satisfying `first` to the front; returns how many there are. (Hoare's
/// scheme; deterministic.)
fn partition(refs: &mut [PrimRef], first: impl Fn(&PrimRef) -> bool) -> usize {
    let (mut i, mut j) = (0, refs.len());
    loop {
        while i < j && first(&refs[i]) {
            i += 1;
        }
        while i < j && !first(&refs[j - 1]) {
            j -= 1;
        }
        if i >= j {
            return i;
        }
        refs.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
}

/// The arena without its unused slots; second-child indices renumbered.
fn compact(arena: &[Node]) -> Vec<Node> {
    let mut new_index = vec![0u32; arena.len()];
    let mut next = 0u32;
    for (slot, node) in arena.iter().enumerate() {
        new_index[slot] = next;
        if node.count != UNUSED.count {
            next += 1;
        }
    }
    arena
        .iter()
        .filter(|n| n.count != UNUSED.count)
        .map(|n| match n.count {
            0 => Node {
                offset: new_index[n.offset as usize],
                ..*n
            },
            _ => *n,
        })
        .collect()
}
