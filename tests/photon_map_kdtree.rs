//! The kd-tree's k-nearest queries against brute force, on the point sets photon maps meet.

use morgana::photon_map::{KdTree, Neighbours};
use morgana::rng::{Rng, Stream};

/// Squared distance, computed exactly as the tree computes it (so ties are bit-identical).
fn dist2(p: [f32; 3], q: [f32; 3]) -> f32 {
    let (dx, dy, dz) = (p[0] - q[0], p[1] - q[1], p[2] - q[2]);
    dx * dx + dy * dy + dz * dz
}

/// Checks `got` (the tree's answer) against a brute-force search over `pts` (in tree order).
/// The neighbours must be exactly the brute-force ones, except that among items at the same
/// distance as the farthest one returned any may be chosen.
fn check(pts: &[[f32; 3]], q: [f32; 3], k: usize, max_dist2: f32, got: &Neighbours, what: &str) {
    let mut all: Vec<(f32, u32)> =
        pts.iter().enumerate().map(|(i, &p)| (dist2(p, q), i as u32)).filter(|&(d2, _)| d2 <= max_dist2).collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let want = all.len().min(k);
    assert_eq!(got.len(), want, "{what}: count (q {q:?}, k {k}, r² {max_dist2})");
    let mut seen = std::collections::HashSet::new();
    for &(i, d2) in &got.items {
        assert!(seen.insert(i), "{what}: index {i} returned twice");
        assert_eq!(d2, dist2(pts[i as usize], q), "{what}: wrong distance for {i}");
        assert!(d2 <= max_dist2, "{what}: {i} beyond the radius");
    }
    if want == 0 {
        assert_eq!(got.max_dist2(), 0.0);
        return;
    }
    let kth = all[want - 1].0;
    assert_eq!(got.max_dist2(), kth, "{what}: k-th distance");
    // Everything strictly nearer than the k-th must be there; the rest are ties with it.
    for &(d2, i) in &all {
        if d2 < kth {
            assert!(seen.contains(&i), "{what}: missed {i} at {d2} < {kth}");
        }
    }
}

fn uniform(rng: &mut Rng, n: usize) -> Vec<[f32; 3]> {
    (0..n).map(|_| [rng.uniform() as f32, rng.uniform() as f32, rng.uniform() as f32]).collect()
}

fn gauss(rng: &mut Rng) -> f64 {
    let [a, b] = rng.uniform2();
    (-2.0 * (1.0 - a).ln()).sqrt() * (std::f64::consts::TAU * b).cos()
}

/// Tight Gaussian clusters of very different sizes (caustics).
fn clustered(rng: &mut Rng, n: usize) -> Vec<[f32; 3]> {
    let centres: Vec<([f64; 3], f64)> = (0..8)
        .map(|c| {
            let centre = [rng.uniform(), rng.uniform(), rng.uniform()];
            (centre, 1e-4 * 10f64.powi(c % 4))
        })
        .collect();
    (0..n)
        .map(|_| {
            let (c, s) = centres[rng.below(centres.len() as u64) as usize];
            [(c[0] + s * gauss(rng)) as f32, (c[1] + s * gauss(rng)) as f32, (c[2] + s * gauss(rng)) as f32]
        })
        .collect()
}

/// Surface photons: on the floor z = 0 and on a tilted plane.
fn planes(rng: &mut Rng, n: usize) -> Vec<[f32; 3]> {
    (0..n)
        .map(|i| {
            let (u, v) = (rng.uniform(), rng.uniform());
            if i % 2 == 0 { [u as f32, v as f32, 0.0] } else { [u as f32, v as f32, (0.3 * u + 0.2 * v) as f32] }
        })
        .collect()
}

/// Many exactly repeated points and points on a coarse lattice (ties everywhere).
fn degenerate(rng: &mut Rng, n: usize) -> Vec<[f32; 3]> {
    (0..n)
        .map(|i| match i % 3 {
            0 => [0.5, 0.5, 0.5],
            1 => [rng.below(4) as f32 * 0.25, rng.below(4) as f32 * 0.25, rng.below(2) as f32 * 0.25],
            _ => [rng.uniform() as f32, 0.5, 0.5],
        })
        .collect()
}

type PointSet = fn(&mut Rng, usize) -> Vec<[f32; 3]>;

const SETS: [(&str, PointSet); 4] =
    [("uniform", uniform), ("clustered", clustered), ("planes", planes), ("degenerate", degenerate)];

/// Query points: near the data (a data point jittered), plus far away.
fn queries(rng: &mut Rng, pts: &[[f32; 3]], n: usize) -> Vec<[f32; 3]> {
    (0..n)
        .map(|i| {
            if i % 10 == 9 {
                [2.0, -1.0, 0.5]
            } else {
                let p = pts[rng.below(pts.len() as u64) as usize];
                let j = 10f64.powi(-(rng.below(5) as i32));
                [
                    p[0] + (j * (rng.uniform() - 0.5)) as f32,
                    p[1] + (j * (rng.uniform() - 0.5)) as f32,
                    p[2] + (j * (rng.uniform() - 0.5)) as f32,
                ]
            }
        })
        .collect()
}

#[test]
fn knn_matches_brute_force_on_all_point_sets() {
    let mut rng = Rng::for_task(11, Stream::Test, 0);
    let mut out = Neighbours::default();
    for (name, make) in SETS {
        for n in [1, 2, 5, 31, 32, 33, 100, 1000, 20_000] {
            let tree = KdTree::build(make(&mut rng, n));
            let pts = tree.items().to_vec();
            let nq = if n > 1000 { 60 } else { 20 };
            for q in queries(&mut rng, &pts, nq) {
                for k in [1, 2, 7, 32, 100, 1000, n + 5] {
                    for max_dist2 in [0.0, 1e-8, 1e-4, 1e-2, 0.3, f32::INFINITY] {
                        tree.knn(q, k, max_dist2, &mut out);
                        check(&pts, q, k, max_dist2, &out, name);
                    }
                }
            }
        }
    }
}

#[test]
fn knn_matches_brute_force_across_leaf_sizes() {
    let mut rng = Rng::for_task(12, Stream::Test, 0);
    let mut out = Neighbours::default();
    for leaf in [1, 2, 3, 8, 64] {
        for (name, make) in SETS {
            let tree = KdTree::build_with_leaf_size(make(&mut rng, 3000), leaf);
            let pts = tree.items().to_vec();
            for q in queries(&mut rng, &pts, 30) {
                for k in [1, 10, 100] {
                    for max_dist2 in [1e-4, 1e-2, f32::INFINITY] {
                        tree.knn(q, k, max_dist2, &mut out);
                        check(&pts, q, k, max_dist2, &out, name);
                    }
                }
            }
        }
    }
}

#[test]
fn k_zero_empty_tree_and_nan_give_nothing() {
    let mut rng = Rng::for_task(13, Stream::Test, 0);
    let tree = KdTree::build(uniform(&mut rng, 500));
    let mut out = Neighbours::default();
    out.items.push((7, 1.0)); // stale content must go
    tree.knn([0.5; 3], 0, f32::INFINITY, &mut out);
    assert!(out.is_empty());
    for q in [[f32::NAN, 0.5, 0.5], [0.5, 0.5, f32::NAN]] {
        tree.knn(q, 10, f32::INFINITY, &mut out);
        assert!(out.is_empty());
    }
    for max_dist2 in [f32::NAN, -1.0] {
        tree.knn([0.5; 3], 10, max_dist2, &mut out);
        assert!(out.is_empty());
    }
    let empty: KdTree<[f32; 3]> = KdTree::build(Vec::new());
    assert!(empty.is_empty());
    empty.knn([0.0; 3], 10, f32::INFINITY, &mut out);
    assert!(out.is_empty());
    assert_eq!(out.max_dist2(), 0.0);
}

#[test]
fn all_points_beyond_the_radius_give_nothing() {
    let mut rng = Rng::for_task(14, Stream::Test, 0);
    let tree = KdTree::build(uniform(&mut rng, 10_000));
    let mut out = Neighbours::default();
    tree.knn([5.0, 5.0, 5.0], 100, 1.0, &mut out);
    assert!(out.is_empty());
}

#[test]
fn identical_points_fill_k_at_distance_zero() {
    let tree = KdTree::build(vec![[0.25f32, -3.0, 7.5]; 5000]);
    let mut out = Neighbours::default();
    tree.knn([0.25, -3.0, 7.5], 100, 0.0, &mut out);
    assert_eq!(out.len(), 100);
    assert_eq!(out.max_dist2(), 0.0);
    tree.knn([0.25, -3.0, 8.5], 100, 1.0, &mut out);
    assert_eq!(out.len(), 100);
    assert_eq!(out.max_dist2(), 1.0);
    tree.knn([0.25, -3.0, 8.5], 100, 0.99, &mut out);
    assert!(out.is_empty());
}

#[test]
fn items_with_nan_coordinates_are_never_returned() {
    let mut rng = Rng::for_task(15, Stream::Test, 0);
    let mut pts = uniform(&mut rng, 4000);
    for (i, p) in pts.iter_mut().enumerate() {
        if i % 3 == 0 {
            p[(i / 3) % 3] = if i % 2 == 0 { f32::NAN } else { -f32::NAN };
        }
    }
    // Mostly NaN on one axis, so that NaN lands on medians.
    pts.extend((0..6000).map(|_| [f32::NAN, 0.5, 0.5]));
    let tree = KdTree::build(pts);
    let items = tree.items().to_vec();
    let mut out = Neighbours::default();
    for q in [[0.5f32; 3], [0.1, 0.9, 0.2], [0.0, 0.0, 0.0], [2.0, 0.5, 0.5]] {
        for k in [1, 50, 500] {
            tree.knn(q, k, f32::INFINITY, &mut out);
            check(&items, q, k, f32::INFINITY, &out, "nan items");
            assert!(out.items.iter().all(|&(_, d2)| !d2.is_nan()));
        }
    }
}

#[test]
fn query_buffer_is_reused_without_reallocation() {
    let mut rng = Rng::for_task(16, Stream::Test, 0);
    let tree = KdTree::build(planes(&mut rng, 50_000));
    let mut out = Neighbours::default();
    tree.knn([0.5, 0.5, 0.0], 100, f32::INFINITY, &mut out);
    let (ptr, cap) = (out.items.as_ptr(), out.items.capacity());
    for q in queries(&mut rng, tree.items(), 200) {
        for max_dist2 in [1e-6, 1e-3, f32::INFINITY] {
            tree.knn(q, 100, max_dist2, &mut out);
            assert_eq!((out.items.as_ptr(), out.items.capacity()), (ptr, cap));
        }
    }
}

/// Builds `items` on a pool of `threads` threads.
fn build_on(threads: usize, items: Vec<[f32; 3]>) -> KdTree<[f32; 3]> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| KdTree::build(items))
}

#[test]
fn build_is_identical_for_one_and_two_threads() {
    let mut rng = Rng::for_task(17, Stream::Test, 0);
    for (name, make) in SETS {
        // Large enough for several levels of parallel subtrees.
        let pts = make(&mut rng, 300_000);
        let a = build_on(1, pts.clone());
        let b = build_on(2, pts);
        let bits = |t: &KdTree<[f32; 3]>| -> Vec<[u32; 3]> { t.items().iter().map(|p| p.map(f32::to_bits)).collect() };
        assert!(bits(&a) == bits(&b), "{name}: item order differs");
        assert_eq!(a.depth(), b.depth());
        let mut oa = Neighbours::default();
        let mut ob = Neighbours::default();
        for q in queries(&mut rng, a.items(), 100) {
            a.knn(q, 50, 1e-3, &mut oa);
            b.knn(q, 50, 1e-3, &mut ob);
            assert_eq!(oa.items, ob.items, "{name}: query results differ");
        }
    }
}
