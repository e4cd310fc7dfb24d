//! Top-down binned SAH construction (Wald 2007; pbrt-v4 §7.3.2).
//!
//! Each node bins its shapes' box centres into equal bins along each axis (up to [`BINS`]), and
//! evaluates the surface-area heuristic at every bin boundary:
//!
//! ```text
//! cost(split) = C_trav + (N_l A_l + N_r A_r) / A,     cost(leaf) = N
//! ```
//!
//! in units of one shape test, where A is a box's surface area. Nodes of at most [`MAX_LEAF`]
//! shapes evaluate the SAH exactly instead (sorting the shapes by centre along each axis), and
//! become leaves when no split is cheaper. Beyond depth [`MAX_SAH_DEPTH`], or when all centres
//! coincide, larger nodes split at their median instead; halving down to MAX_LEAF takes at most
//! 29 levels for fewer than 2³² shapes, and a small node at most MAX_LEAF − 1 more, so the tree
//! is at most MAX_SAH_DEPTH + 36 deep (the traversal stack is sized for that).
//!
//! A node refers to its second child by distance, so a subtree's nodes do not depend on where
//! the subtree ends up. Large subtrees build their two halves in parallel into separate vectors,
//! which are concatenated once at the end in depth-first order. Every choice depends only on the
//! shapes, so the tree is the same for any number of threads.

use super::{Bvh, Node};
use crate::geometry::{Aabb, Shape};
use glam::DVec3;
use rayon::prelude::*;

/// Most bins per axis.
pub const BINS: usize = 16;
/// Most shapes in a leaf.
pub const MAX_LEAF: usize = 8;
/// Depth beyond which nodes split at the median.
pub const MAX_SAH_DEPTH: usize = 48;
/// Cost of visiting a node relative to one shape test.
const TRAVERSAL_COST: f64 = 1.0;
/// Subtrees at least this large build their halves in parallel.
const PARALLEL_MIN: usize = 4 * 1024;
/// Shapes per parallel binning task.
const BIN_CHUNK: usize = 64 * 1024;

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

/// A range of shapes to build a subtree over: their boxes' union, their centres' box, the index
/// of the first one in the final primitive list, and the subtree's depth.
#[derive(Clone, Copy)]
struct Task {
    bounds: Aabb,
    centres: Aabb,
    first: usize,
    depth: usize,
}

pub fn build(shapes: &[Shape]) -> Bvh {
    assert!(shapes.len() < u32::MAX as usize, "Bvh::build: {} shapes exceed the u32 index range", shapes.len());
    if shapes.is_empty() {
        return Bvh::default();
    }
    let mut refs: Vec<PrimRef> =
        shapes.par_iter().enumerate().map(|(i, s)| PrimRef { bounds: s.bounds(), index: i as u32 }).collect();
    let (bounds, centres) = enclose(&refs);
    let task = Task { bounds, centres, first: 0, depth: 1 };
    let chunks = build_parallel(&mut refs, task);
    Bvh { nodes: chunks.concat(), prims: refs.iter().map(|r| r.index).collect() }
}

/// The union of the shapes' boxes and the box of their centres (in parallel when large; min
/// and max are exact, so the result does not depend on the grouping).
fn enclose(refs: &[PrimRef]) -> (Aabb, Aabb) {
    let add = |(b, c): (Aabb, Aabb), r: &PrimRef| (b.union(r.bounds), c.include(r.centre()));
    let merge = |x: (Aabb, Aabb), y: (Aabb, Aabb)| (x.0.union(y.0), x.1.union(y.1));
    let empty = (Aabb::EMPTY, Aabb::EMPTY);
    if refs.len() < PARALLEL_MIN {
        return refs.iter().fold(empty, add);
    }
    refs.par_chunks(BIN_CHUNK).map(|c| c.iter().fold(empty, add)).reduce(|| empty, merge)
}

/// A large subtree: its two halves build in parallel. Returns its nodes in depth-first order,
/// in pieces.
fn build_parallel(refs: &mut [PrimRef], task: Task) -> Vec<Vec<Node>> {
    let mut bins = Box::new(Bins::new());
    if refs.len() < PARALLEL_MIN {
        let mut nodes = Vec::with_capacity(refs.len());
        build_serial(refs, task, &mut nodes, &mut bins);
        return vec![nodes];
    }
    let Some((mid, left, right)) = split(refs, &task, &mut bins) else {
        return vec![vec![leaf(&task, refs.len())]];
    };
    let (left_refs, right_refs) = refs.split_at_mut(mid);
    let (left_chunks, right_chunks) =
        rayon::join(|| build_parallel(left_refs, left), || build_parallel(right_refs, right));
    let left_size: usize = left_chunks.iter().map(Vec::len).sum();
    let mut chunks = vec![vec![interior(&task, left_size)]];
    chunks.extend(left_chunks);
    chunks.extend(right_chunks);
    chunks
}

/// A subtree built on this thread, appended to `nodes` in depth-first order; `bins` is scratch.
fn build_serial(refs: &mut [PrimRef], task: Task, nodes: &mut Vec<Node>, bins: &mut Bins) {
    let Some((mid, left, right)) = split(refs, &task, bins) else {
        nodes.push(leaf(&task, refs.len()));
        return;
    };
    let at = nodes.len();
    nodes.push(interior(&task, 0));
    let (left_refs, right_refs) = refs.split_at_mut(mid);
    build_serial(left_refs, left, nodes, bins);
    nodes[at].offset = (nodes.len() - at) as u32;
    build_serial(right_refs, right, nodes, bins);
}

fn leaf(task: &Task, count: usize) -> Node {
    Node { bounds: [task.bounds.min.into(), task.bounds.max.into()], offset: task.first as u32, count: count as u32 }
}

/// An interior node whose first subtree has `left_size` nodes: the second child is
/// `1 + left_size` nodes further on.
fn interior(task: &Task, left_size: usize) -> Node {
    Node { bounds: [task.bounds.min.into(), task.bounds.max.into()], offset: (1 + left_size) as u32, count: 0 }
}

/// Splits the shapes of `task`, reordering `refs`: the size of the first part and both parts'
/// tasks, or `None` when the node should be a leaf. `bins` is scratch.
fn split(refs: &mut [PrimRef], task: &Task, bins: &mut Bins) -> Option<(usize, Task, Task)> {
    let n = refs.len();
    if n == 1 {
        return None;
    }
    if n <= MAX_LEAF {
        return small_split(refs, task);
    }
    if task.depth <= MAX_SAH_DEPTH
        && bins.fill(refs, &task.centres)
        && let Some(best) = bins.cheapest(&task.bounds)
    {
        let (mid, left_centres, right_centres) = partition(refs, |c| bins.bin_of(c, best.axis) < best.bin);
        if mid > 0 && mid < n {
            let child = |bounds, centres, first| Task { bounds, centres, first, depth: task.depth + 1 };
            return Some((
                mid,
                child(best.left_bounds, left_centres, task.first),
                child(best.right_bounds, right_centres, task.first + mid),
            ));
        }
    }
    Some(median_split(refs, task))
}

/// Exact SAH for at most [`MAX_LEAF`] shapes: along each axis, sort by centre and evaluate every
/// boundary. `None` when a leaf is no dearer than the best split.
fn small_split(refs: &mut [PrimRef], task: &Task) -> Option<(usize, Task, Task)> {
    let n = refs.len();
    let area = task.bounds.surface_area();
    let mut best: Option<(f64, usize, usize)> = None; // cost, axis, boundary
    for axis in 0..3 {
        sort_by_centre(refs, axis);
        let mut right = [Aabb::EMPTY; MAX_LEAF + 1];
        for k in (1..n).rev() {
            right[k] = right[k + 1];
            grow(&mut right[k], &refs[k].bounds);
        }
        let mut left = Aabb::EMPTY;
        for k in 1..n {
            grow(&mut left, &refs[k - 1].bounds);
            let cost = TRAVERSAL_COST + (k as f64 * area_of(&left) + (n - k) as f64 * area_of(&right[k])) / area;
            if cost < best.map_or(n as f64, |b| b.0) {
                best = Some((cost, axis, k));
            }
        }
    }
    let (_, axis, mid) = best?;
    sort_by_centre(refs, axis);
    let child = |part: &[PrimRef], first| {
        let (bounds, centres) = enclose(part);
        Task { bounds, centres, first, depth: task.depth + 1 }
    };
    let (left, right) = refs.split_at(mid);
    Some((mid, child(left, task.first), child(right, task.first + mid)))
}

/// Stable insertion sort by centre along `axis` (the slices are tiny).
fn sort_by_centre(refs: &mut [PrimRef], axis: usize) {
    for i in 1..refs.len() {
        let mut j = i;
        while j > 0 && refs[j - 1].centre()[axis] > refs[j].centre()[axis] {
            refs.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Splits at the median centre along the axis of largest centre extent.
fn median_split(refs: &mut [PrimRef], task: &Task) -> (usize, Task, Task) {
    let axis = task.centres.diagonal().max_position();
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| a.centre()[axis].total_cmp(&b.centre()[axis]));
    let (left, right) = refs.split_at(mid);
    let child = |part: &[PrimRef], first| {
        let (bounds, centres) = enclose(part);
        Task { bounds, centres, first, depth: task.depth + 1 }
    };
    (mid, child(left, task.first), child(right, task.first + mid))
}

/// The cheapest bin boundary: shapes in bins `< bin` along `axis` go first.
#[derive(Clone, Copy, Debug)]
struct Split {
    axis: usize,
    bin: usize,
    cost: f64,
    left_bounds: Aabb,
    right_bounds: Aabb,
}

/// Per-axis bins of shape centres: each bin's count and the union of its shapes' boxes.
#[derive(Clone)]
struct Bins {
    /// Bins in use per axis.
    count: usize,
    /// Centre-box minimum, and bins per unit length (0 on an axis where the centres coincide).
    origin: [f64; 3],
    scale: [f64; 3],
    bounds: [[Aabb; BINS]; 3],
    counts: [[usize; BINS]; 3],
}

impl Bins {
    fn new() -> Bins {
        Bins { count: 0, origin: [0.0; 3], scale: [0.0; 3], bounds: [[Aabb::EMPTY; BINS]; 3], counts: [[0; BINS]; 3] }
    }

    /// Bins `refs` by centre; false when the centres coincide on every axis.
    fn fill(&mut self, refs: &[PrimRef], centres: &Aabb) -> bool {
        if !self.reset(refs.len().clamp(2, BINS), centres) {
            return false;
        }
        if refs.len() < 2 * BIN_CHUNK {
            self.add_all(refs);
            return true;
        }
        let parts: Vec<Bins> = refs
            .par_chunks(BIN_CHUNK)
            .map(|c| {
                let mut part = self.clone();
                part.add_all(c);
                part
            })
            .collect();
        for part in &parts {
            self.merge(part);
        }
        true
    }

    /// Empties `count` bins per axis over the box of centres; false when it is a point.
    fn reset(&mut self, count: usize, centres: &Aabb) -> bool {
        let extent = centres.diagonal();
        self.count = count;
        self.origin = centres.min.into();
        self.scale = [0, 1, 2].map(|a| {
            let s = count as f64 / extent[a];
            if extent[a] > 0.0 && s.is_finite() { s } else { 0.0 }
        });
        for a in 0..3 {
            self.bounds[a][..count].fill(Aabb::EMPTY);
            self.counts[a][..count].fill(0);
        }
        self.scale != [0.0; 3]
    }

    /// Bin of a centre along `axis`: ⌊(c − min) · scale⌋, clamped to the bins in use. (Clamped
    /// as a float first, so the conversion needs no saturation; NaN goes to bin 0.)
    #[inline]
    fn bin_of(&self, c: DVec3, axis: usize) -> usize {
        let x = (c[axis] - self.origin[axis]) * self.scale[axis];
        let last = (self.count - 1) as f64;
        let x = if x < last { x } else { last };
        if x > 0.0 { x as u32 as usize } else { 0 }
    }

    fn add_all(&mut self, refs: &[PrimRef]) {
        for r in refs {
            let c = r.centre();
            for a in 0..3 {
                let k = self.bin_of(c, a);
                grow(&mut self.bounds[a][k], &r.bounds);
                self.counts[a][k] += 1;
            }
        }
    }

    fn merge(&mut self, other: &Bins) {
        for a in 0..3 {
            for k in 0..self.count {
                grow(&mut self.bounds[a][k], &other.bounds[a][k]);
                self.counts[a][k] += other.counts[a][k];
            }
        }
    }

    /// The cheapest boundary over the axes on which the centres spread.
    fn cheapest(&self, bounds: &Aabb) -> Option<Split> {
        let area = bounds.surface_area();
        let mut best: Option<Split> = None;
        for axis in (0..3).filter(|&a| self.scale[a] > 0.0) {
            if let Some(s) = self.cheapest_on_axis(axis, area)
                && best.is_none_or(|b| s.cost < b.cost)
            {
                best = Some(s);
            }
        }
        best
    }

    /// A sweep from the right accumulates the second part's area × count, one from the left
    /// the first part's; the SAH cost at every boundary follows.
    fn cheapest_on_axis(&self, axis: usize, area: f64) -> Option<Split> {
        let (bounds, counts) = (&self.bounds[axis][..self.count], &self.counts[axis]);
        let mut right_cost = [0.0; BINS];
        let (mut right, mut n_right) = (Aabb::EMPTY, 0);
        for k in (1..self.count).rev() {
            grow(&mut right, &bounds[k]);
            n_right += counts[k];
            right_cost[k] = n_right as f64 * area_of(&right);
        }
        let (mut left, mut n_left) = (Aabb::EMPTY, 0);
        let (mut best_cost, mut best_bin) = (f64::INFINITY, 0);
        for k in 1..self.count {
            grow(&mut left, &bounds[k - 1]);
            n_left += counts[k - 1];
            let cost = TRAVERSAL_COST + (n_left as f64 * area_of(&left) + right_cost[k]) / area;
            if cost < best_cost {
                (best_cost, best_bin) = (cost, k);
            }
        }
        if !best_cost.is_finite() {
            return None;
        }
        let union = |part: &[Aabb]| {
            part.iter().fold(Aabb::EMPTY, |mut b, x| {
                grow(&mut b, x);
                b
            })
        };
        Some(Split {
            axis,
            bin: best_bin,
            cost: best_cost,
            left_bounds: union(&bounds[..best_bin]),
            right_bounds: union(&bounds[best_bin..]),
        })
    }
}

/// Surface area of a box known not to be empty.
#[inline]
fn area_of(b: &Aabb) -> f64 {
    let d = b.max - b.min;
    2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
}

/// `a` grown to contain the point `p` (plain comparisons, as in [`grow`]).
#[inline]
fn grow_point(a: &mut Aabb, p: DVec3) {
    grow(a, &Aabb { min: p, max: p });
}

/// `a` grown to contain `b`. Plain comparisons (one instruction each) rather than the
/// NaN-aware `f64::min`: this is the builder's innermost loop.
#[inline]
fn grow(a: &mut Aabb, b: &Aabb) {
    let lo = |x: f64, y: f64| if y < x { y } else { x };
    let hi = |x: f64, y: f64| if y > x { y } else { x };
    a.min = DVec3::new(lo(a.min.x, b.min.x), lo(a.min.y, b.min.y), lo(a.min.z, b.min.z));
    a.max = DVec3::new(hi(a.max.x, b.max.x), hi(a.max.y, b.max.y), hi(a.max.z, b.max.z));
}

/// Moves the shapes whose centre satisfies `first` to the front (Hoare's scheme; deterministic).
/// Returns how many there are, and the boxes of the centres of both parts.
fn partition(refs: &mut [PrimRef], first: impl Fn(DVec3) -> bool) -> (usize, Aabb, Aabb) {
    let (mut left, mut right) = (Aabb::EMPTY, Aabb::EMPTY);
    let (mut i, mut j) = (0, refs.len());
    loop {
        while i < j {
            let c = refs[i].centre();
            if !first(c) {
                break;
            }
            grow_point(&mut left, c);
            i += 1;
        }
        while i < j {
            let c = refs[j - 1].centre();
            if first(c) {
                break;
            }
            grow_point(&mut right, c);
            j -= 1;
        }
        if i >= j {
            return (i, left, right);
        }
        refs.swap(i, j - 1);
        grow_point(&mut left, refs[i].centre());
        grow_point(&mut right, refs[j - 1].centre());
        i += 1;
        j -= 1;
    }
}
