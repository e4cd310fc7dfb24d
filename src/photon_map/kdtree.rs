//! A kd-tree over points stored as f32: an implicit, perfectly balanced tree with leaf buckets.
//!
//! # Layout
//!
//! The items are reordered so that every subtree owns a contiguous run of them. The tree is
//! complete: all `2^depth` leaves lie at the same depth, and leaf `j` owns items
//! `[⌊j·n / 2^depth⌋, ⌊(j+1)·n / 2^depth⌋)` — at most [`LEAF_SIZE`] of them. Internal nodes are
//! kept in a separate array in depth-first (pre-)order, 8 bytes each (split value and axis):
//! the left child of node `i` at height `h` is `i + 1` and the right child `i + 2^(h-1)`. No
//! child pointers or item ranges are stored; everything follows from `n` and `depth`.
//!
//! This replaces Jensen's left-balanced tree with one photon per node: a leaf bucket is scanned
//! linearly (cache-friendly, no branch per photon on the way down), and the nodes cost 8 bytes
//! per leaf, about 0.3–0.4 bytes per item. On 1M points with k = 100 (2-core VM, one query
//! thread) queries take 4–4.5 µs (large radius) and 1.4–1.6 µs (small) against 16–21 and
//! 5.3–6.7 µs for Jensen's tree with its max-heap; see `benches/photon_map.rs`.
//!
//! # Build
//!
//! Each node splits its items at the median (by count, `select_nth_unstable_by`) along the axis of
//! largest extent of their bounding box, as in Jensen 2000, §2.2. Subtrees larger than
//! [`PARALLEL_MIN`] are built in parallel with `rayon::join`. Each subtree is built from its own
//! items only, by deterministic code, so the result is the same for any number of threads.
//!
//! # Query
//!
//! `knn` is the depth-first search of Jensen 2000, §3.4 (near child first, far child only if it
//! may hold an item within the current bound), with an explicit stack instead of recursion and the
//! incremental distance of Arya & Mount 1993 (the squared distance from the query to the far
//! child's cell, not only to its splitting plane, decides).
//!
//! Candidates are collected in a buffer of `2k` (the caller's [`Neighbours`], so nothing is
//! allocated once it has grown) rather than a max-heap: each item of a leaf is written to the
//! buffer's end unconditionally and kept (the length advanced) only if it is within the bound,
//! which costs no unpredictable branch. When the buffer is full, `select_nth_unstable` keeps the
//! `k` nearest and the `k`-th distance becomes the new bound (new items must be strictly nearer).
//! On the benchmark scene this made queries 1.4–2.5× faster than a binary max-heap of `k`
//! (Jensen's choice; a 4-ary heap or Floyd's sift-down gained under 10%): with a radius that
//! admits hundreds of candidates, a heap pays a sift-down of mispredicted branches for nearly
//! every one. Software prefetching of deferred leaves gained under 10% and was left out.
//!
//! # References
//! - Jensen 2000, "A Practical Guide to Global Illumination using Photon Maps", SIGGRAPH course
//!   notes, §2 (balanced kd-tree) and §3.4 (locating the nearest photons).
//! - Bentley 1975, "Multidimensional binary search trees used for associative searching", CACM 18.
//! - Arya & Mount 1993, "Algorithms for fast vector quantization", Proc. DCC (incremental
//!   distance computation).

/// A point the kd-tree can hold.
pub trait KdPoint: Copy + Send + Sync {
    /// Position in the tree's coordinates.
    fn position(&self) -> [f32; 3];
}

impl KdPoint for [f32; 3] {
    #[inline(always)]
    fn position(&self) -> [f32; 3] {
        *self
    }
}

/// Result buffer of a k-nearest query: (index, squared distance) pairs.
///
/// The order of the items is unspecified. Reuse one buffer across queries: a query uses it as a
/// candidate buffer of `2k` entries, so once it has grown to that, queries do not allocate.
#[derive(Clone, Debug, Default)]
pub struct Neighbours {
    /// (item index in tree order, squared distance) pairs.
    pub items: Vec<(u32, f32)>,
}

impl Neighbours {
    /// Number of neighbours found.
    pub fn len(&self) -> usize {
        self.items.len()
    }
    /// True when none was found.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
    /// Largest squared distance among the items (0 if empty).
    pub fn max_dist2(&self) -> f32 {
        self.items.iter().fold(0.0, |m, &(_, d2)| m.max(d2))
    }
}

/// Most items in a leaf bucket. Leaves hold between `LEAF_SIZE / 2` and `LEAF_SIZE` items
/// (unless the whole tree holds fewer). Chosen by measurement (`benches/photon_map.rs`, 1M
/// points, k = 100): leaves of ≤ 32 and ≤ 64 query equally fast; ≤ 16 is up to 20% and ≤ 8 up
/// to 30% slower.
pub const LEAF_SIZE: usize = 32;

/// Height limit: with fewer than 2^32 items and leaves of at least two, 31 levels suffice. The
/// query's stack of deferred subtrees holds at most one per level.
const MAX_DEPTH: usize = 32;

/// Subtrees with at least this many items are built in parallel.
pub const PARALLEL_MIN: usize = 1 << 13;

/// A splitting plane: `value` on axis `axis` (0, 1, 2). Items left of it have coordinates
/// `≤ value`, items right of it `≥ value`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Split {
    value: f32,
    axis: u32,
}

/// An implicit balanced kd-tree with leaf buckets (see the module docs).
#[derive(Clone, Debug)]
pub struct KdTree<T> {
    /// The items, in tree order.
    items: Vec<T>,
    /// Internal nodes in depth-first order; `2^depth - 1` of them.
    nodes: Vec<Split>,
    /// Height of the tree: leaves are at depth `depth`.
    depth: u32,
}

impl<T: KdPoint> KdTree<T> {
    /// Builds the tree (reordering `items`), in parallel on the current rayon pool. The result
    /// does not depend on the number of threads.
    ///
    /// Items with a NaN coordinate are kept but never returned by queries.
    ///
    /// # Panics
    /// If there are `u32::MAX` items or more (indices are u32).
    pub fn build(items: Vec<T>) -> KdTree<T> {
        Self::build_with_leaf_size(items, LEAF_SIZE)
    }

    /// [`KdTree::build`] with leaves of at most `leaf_size` items instead of [`LEAF_SIZE`]: for
    /// tuning. Sizes below 2 count as 2 (so that no leaf is empty).
    pub fn build_with_leaf_size(mut items: Vec<T>, leaf_size: usize) -> KdTree<T> {
        let n = items.len();
        assert!(n < u32::MAX as usize, "kd-tree holds fewer than 2^32 - 1 items");
        let depth = Self::depth_for(n, leaf_size);
        let mut nodes = vec![Split { value: 0.0, axis: 0 }; (1usize << depth) - 1];
        let shape = Shape { n, depth };
        shape.build_subtree(&mut items, &mut nodes, depth, 0);
        KdTree { items, nodes, depth }
    }

    /// The height of a tree of `n` items with leaves of at most `leaf_size` (at least 2): the
    /// least depth whose `2^depth` leaves hold at most `leaf_size` items each.
    pub fn depth_for(n: usize, leaf_size: usize) -> u32 {
        let leaf_size = leaf_size.max(2);
        let mut depth = 0;
        while n.div_ceil(1 << depth) > leaf_size {
            depth += 1;
        }
        depth
    }

    /// Bytes of a tree of `n` items with leaves of at most [`LEAF_SIZE`], as
    /// [`KdTree::memory_bytes`] reports it once built, less the struct itself.
    pub fn bytes_for(n: usize) -> usize {
        n * size_of::<T>() + ((1usize << Self::depth_for(n, LEAF_SIZE)) - 1) * size_of::<Split>()
    }
    /// Number of items.
    pub fn len(&self) -> usize {
        self.items.len()
    }
    /// True when the tree holds no item.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
    /// The items in tree order; the indices in [`Neighbours`] index this slice.
    pub fn items(&self) -> &[T] {
        &self.items
    }
    /// Height of the tree (leaves are at this depth; 0 for a single leaf).
    pub fn depth(&self) -> u32 {
        self.depth
    }
    /// The items leaf `j` owns (indices into [`KdTree::items`]), for `j < 2^depth`; the leaves
    /// own consecutive runs, in order.
    pub fn leaf_range(&self, j: usize) -> std::ops::Range<usize> {
        let shape = Shape { n: self.items.len(), depth: self.depth };
        shape.leaf_start(j)..shape.leaf_start(j + 1)
    }
    /// Bytes held by the tree (items and nodes, by capacity, plus the struct itself).
    pub fn memory_bytes(&self) -> usize {
        size_of::<Self>() + self.items.capacity() * size_of::<T>() + self.nodes.capacity() * size_of::<Split>()
    }

    /// The up-to-`k` items nearest to `q` with squared distance ≤ `max_dist2`.
    ///
    /// The items of `out` are replaced, in no particular order. Returns nothing for `k = 0`, an
    /// empty tree, a NaN coordinate in `q`, or a NaN or negative `max_dist2`. Among items at the
    /// same distance as the `k`-th nearest, which are kept is unspecified. Items with NaN
    /// coordinates are never returned.
    ///
    /// Does not allocate once `out` has held `2 · min(k, len)` items.
    pub fn knn(&self, q: [f32; 3], k: usize, max_dist2: f32, out: &mut Neighbours) {
        if k == 0 || self.items.is_empty() || q.iter().any(|c| c.is_nan()) || max_dist2.is_nan() || max_dist2 < 0.0 {
            out.items.clear();
            return;
        }
        let k = k.min(self.items.len());
        // The candidate buffer; its contents are overwritten before they are read.
        out.items.resize(2 * k, (0, 0.0));
        let mut search = Search {
            tree: self,
            shape: Shape { n: self.items.len(), depth: self.depth },
            q,
            k,
            bound: max_dist2,
            buf: &mut out.items,
            len: 0,
        };
        search.run();
        let len = search.len;
        out.items.truncate(len);
        if len > k {
            keep_nearest(&mut out.items, k);
            out.items.truncate(k);
        }
    }
}

/// The implicit shape of a tree: which items each leaf owns.
#[derive(Clone, Copy)]
struct Shape {
    n: usize,
    depth: u32,
}

impl Shape {
    /// First item of leaf `j` (for `j = 2^depth`: one past the last item).
    #[inline(always)]
    fn leaf_start(self, j: usize) -> usize {
        ((j as u64 * self.n as u64) >> self.depth) as usize
    }

    /// Builds the subtree of height `h` whose first leaf is `leaf0`, over `items` (exactly the
    /// items it owns) and `nodes` (exactly its `2^h - 1` nodes, depth-first).
    fn build_subtree<T: KdPoint>(self, items: &mut [T], nodes: &mut [Split], h: u32, leaf0: usize) {
        if h == 0 {
            return;
        }
        let lo = self.leaf_start(leaf0);
        let half = 1usize << (h - 1);
        let mid = self.leaf_start(leaf0 + half) - lo;
        let axis = widest_axis(items);
        let key = |t: &T| t.position()[axis];
        items.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
        // A NaN at the median (NaNs sort to the ends) becomes the infinity on its side, so that
        // the plane still separates the finite items.
        let value = key(&items[mid]);
        let value = match (value.is_nan(), value.is_sign_negative()) {
            (false, _) => value,
            (true, false) => f32::INFINITY,
            (true, true) => f32::NEG_INFINITY,
        };
        nodes[0] = Split { value, axis: axis as u32 };
        let parallel = items.len() >= PARALLEL_MIN;
        let (left_items, right_items) = items.split_at_mut(mid);
        let (left_nodes, right_nodes) = nodes[1..].split_at_mut(half - 1);
        if parallel {
            rayon::join(
                || self.build_subtree(left_items, left_nodes, h - 1, leaf0),
                || self.build_subtree(right_items, right_nodes, h - 1, leaf0 + half),
            );
        } else {
            self.build_subtree(left_items, left_nodes, h - 1, leaf0);
            self.build_subtree(right_items, right_nodes, h - 1, leaf0 + half);
        }
    }
}

/// The axis along which the items' bounding box is widest (NaN coordinates are ignored; ties
/// go to the lower axis).
fn widest_axis<T: KdPoint>(items: &[T]) -> usize {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for t in items {
        let p = t.position();
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let mut axis = 0;
    for a in 1..3 {
        if ext[a] > ext[axis] {
            axis = a;
        }
    }
    axis
}

/// State of one k-nearest query.
struct Search<'a, T> {
    tree: &'a KdTree<T>,
    shape: Shape,
    q: [f32; 3],
    k: usize,
    /// Squared distance an item must not exceed to be kept: `max_dist2` until the buffer has
    /// first been reduced to the `k` nearest, then just below the `k`-th nearest distance.
    bound: f32,
    /// Candidate buffer of `2k` entries; the first `len` are kept candidates.
    buf: &'a mut [(u32, f32)],
    len: usize,
}

/// A subtree still to visit: depth-first node index, first leaf, height, and the query's squared
/// distance `rd` to its cell with the per-axis distances `off` (`rd = Σ off[a]²`).
#[derive(Clone, Copy, Default)]
struct Pending {
    node: u32,
    leaf0: u32,
    h: u32,
    rd: f32,
    off: [f32; 3],
}

impl<T: KdPoint> Search<'_, T> {
    fn run(&mut self) {
        let nodes = &self.tree.nodes[..];
        let mut stack = [Pending::default(); MAX_DEPTH];
        let mut sp = 0;
        let mut cur = Pending { h: self.shape.depth, ..Pending::default() };
        loop {
            // Descend to the leaf on the query's side, deferring the far children.
            while cur.h > 0 {
                let split = nodes[cur.node as usize];
                let axis = split.axis as usize;
                let diff = self.q[axis] - split.value;
                let half = 1u32 << (cur.h - 1);
                let left = (cur.node + 1, cur.leaf0);
                let right = (cur.node + half, cur.leaf0 + half);
                let (near, far) = if diff < 0.0 { (left, right) } else { (right, left) };
                cur.h -= 1;
                let old = cur.off[axis];
                let far_rd = cur.rd - old * old + diff * diff;
                if far_rd <= self.bound {
                    let mut off = cur.off;
                    off[axis] = diff;
                    stack[sp] = Pending { node: far.0, leaf0: far.1, h: cur.h, rd: far_rd, off };
                    sp += 1;
                }
                (cur.node, cur.leaf0) = near;
            }
            self.scan_leaf(cur.leaf0 as usize);
            // Resume with the nearest-deferred subtree still within the (shrunk) bound.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                cur = stack[sp];
                if cur.rd <= self.bound {
                    break;
                }
            }
        }
    }

    #[inline(always)]
    fn scan_leaf(&mut self, leaf: usize) {
        let lo = self.shape.leaf_start(leaf);
        let hi = self.shape.leaf_start(leaf + 1);
        let q = self.q;
        let mut len = self.len;
        let mut bound = self.bound;
        for (i, t) in self.tree.items[lo..hi].iter().enumerate() {
            let p = t.position();
            let (dx, dy, dz) = (p[0] - q[0], p[1] - q[1], p[2] - q[2]);
            let d2 = dx * dx + dy * dy + dz * dz;
            // Branch-free: always write, keep only if within the bound (false for NaN).
            self.buf[len] = ((lo + i) as u32, d2);
            len += usize::from(d2 <= bound);
            if len == self.buf.len() {
                keep_nearest(self.buf, self.k);
                len = self.k;
                // Ties with the k-th cannot improve the result.
                bound = self.buf[self.k - 1].1.next_down();
            }
        }
        self.len = len;
        self.bound = bound;
    }
}

/// Reorders `c` so that its first `k` entries are the `k` nearest and entry `k - 1` the
/// farthest of them. The distances must be non-negative and not NaN (so that their bit patterns
/// order like the values: +0 is the only zero a sum of squares yields).
#[inline]
fn keep_nearest(c: &mut [(u32, f32)], k: usize) {
    c.select_nth_unstable_by_key(k - 1, |e| e.1.to_bits());
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};

    fn points(n: usize, seed: u64) -> Vec<[f32; 3]> {
        let mut rng = Rng::for_task(seed, Stream::Test, 0);
        (0..n)
            .map(|i| {
                let p = [rng.uniform() as f32, rng.uniform() as f32, rng.uniform() as f32];
                // A third on a plane, some exact duplicates.
                match i % 6 {
                    0 | 1 => [p[0], p[1], 0.0],
                    2 => [0.5, 0.5, 0.5],
                    _ => p,
                }
            })
            .collect()
    }

    /// Every leaf holds at most `leaf_size` items, and every split plane separates its subtrees.
    fn check_structure(tree: &KdTree<[f32; 3]>, leaf_size: usize) {
        let shape = Shape { n: tree.len(), depth: tree.depth };
        assert_eq!(tree.nodes.len(), (1 << tree.depth) - 1);
        for j in 0..1usize << tree.depth {
            let size = shape.leaf_start(j + 1) - shape.leaf_start(j);
            let leaf_size = leaf_size.max(2);
            assert!(size <= leaf_size);
            assert!(tree.len() <= leaf_size || size >= leaf_size / 2, "leaf {j}: {size}");
        }
        fn walk(t: &KdTree<[f32; 3]>, s: Shape, node: usize, h: u32, leaf0: usize) {
            if h == 0 {
                return;
            }
            let half = 1usize << (h - 1);
            let Split { value, axis } = t.nodes[node];
            let (lo, mid, hi) = (s.leaf_start(leaf0), s.leaf_start(leaf0 + half), s.leaf_start(leaf0 + 2 * half));
            let a = axis as usize;
            assert!(t.items[lo..mid].iter().all(|p| p[a] <= value));
            assert!(t.items[mid..hi].iter().all(|p| p[a] >= value));
            walk(t, s, node + 1, h - 1, leaf0);
            walk(t, s, node + half, h - 1, leaf0 + half);
        }
        walk(tree, shape, 0, tree.depth, 0);
    }

    #[test]
    fn leaves_are_bounded_and_splits_separate() {
        for n in [0, 1, 2, 31, 32, 33, 64, 65, 1000, 12_345] {
            for leaf in [1, 2, 5, LEAF_SIZE] {
                check_structure(&KdTree::build_with_leaf_size(points(n, 1), leaf), leaf);
            }
        }
    }

    #[test]
    fn nodes_are_identical_for_one_and_two_threads() {
        let pts = points(200_000, 2);
        let build = |threads| {
            rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| KdTree::build(pts.clone()))
        };
        let (a, b) = (build(1), build(2));
        let bits = |t: &KdTree<[f32; 3]>| -> (Vec<[u32; 3]>, Vec<(u32, u32)>) {
            (
                t.items.iter().map(|p| p.map(f32::to_bits)).collect(),
                t.nodes.iter().map(|s| (s.value.to_bits(), s.axis)).collect(),
            )
        };
        assert!(bits(&a) == bits(&b));
        check_structure(&a, LEAF_SIZE);
    }

    #[test]
    fn keep_nearest_orders_by_distance_bits() {
        let mut c: Vec<(u32, f32)> =
            [3.0, 0.0, 2.5, 1e-30, 7.0, 1.0].iter().enumerate().map(|(i, &d)| (i as u32, d)).collect();
        keep_nearest(&mut c, 3);
        let mut first: Vec<f32> = c[..3].iter().map(|e| e.1).collect();
        first.sort_by(f32::total_cmp);
        assert_eq!(first, vec![0.0, 1e-30, 1.0]);
        assert_eq!(c[2].1, 1.0);
    }
}
