//! Photon map benchmark: morgana's kd-tree against kiddo 6 on the same photons and queries.
//!
//! Run with `cargo bench --bench photon_map` (or `scripts/bench_photon_map.sh`); about five
//! minutes on 2 cores, most of it kiddo's queries. `PHOTON_MAP_BENCH_QUICK=1` uses 100k queries and skips the 10M-photon
//! memory check, for a run of about a minute.
//!
//! Scene: 1M photons in a 4 × 4 × 3 m room placed 2 km from the world origin — 40% in fog
//! (uniform in the volume, no normal), 40% on the floor, 20% in a caustic on the floor (a
//! Gaussian spot of σ = 0.1 m). Queries: 1M points drawn from the same distribution with
//! another seed (eye-path vertices land where photons are), in random order, one thread.
//! k = 100 with two radii: "large", the 75th percentile of the distance to the 100th nearest
//! photon (most queries return 100), and "small", an eighth of it.
//!
//! Compared: `PhotonMap::knn` (32-byte photons, as the renderer queries them) and kiddo's
//! `nearest_n(k).within(r²).unsorted()` on the same points (f32, relative to the map's origin) in
//! its fastest configuration for this workload, Eytzinger stems with `FlatVec` leaves of 8.
//! Kiddo's query returns a new `Vec`; ours fills a reused buffer, which is how the renderer calls
//! it. Builds: `PhotonMap::build` from records (encoding included), `KdTree<[f32; 3]>::build` and
//! kiddo's parallel build from the same points.
//!
//! A design section then times, on 100k of the queries, Jensen's left-balanced tree, our tree
//! over bare points (as kiddo holds them) with several leaf sizes, and kiddo's default
//! `ImmutableKdTree` against the configuration above.
//!
//! Criterion reports each benchmark; its "Unable to complete 10 samples" warnings are expected
//! (a sample is one pass over all queries). The summary at the end gives the medians of the
//! samples and the ratios to kiddo.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::hint::black_box;
use std::num::NonZeroUsize;
use std::time::{Duration, Instant};

use criterion::{Criterion, SamplingMode};
use glam::DVec3;
use kiddo::{Eytzinger, FlatVec, ImmutableKdTree, SquaredEuclidean};
use morgana::photon_map::{KdTree, Neighbours, PhotonMap, PhotonPath, PhotonRecord};
use morgana::rng::{Rng, Stream};

const K: usize = 100;

/// Kiddo's fastest configuration here (see the design section).
type KiddoTree = kiddo::KdTree<f32, u32, Eytzinger, FlatVec<f32, u32, 3, 8>, 3, 8>;

fn gauss(rng: &mut Rng) -> f64 {
    let [a, b] = rng.uniform2();
    (-2.0 * (1.0 - a).ln()).sqrt() * (std::f64::consts::TAU * b).cos()
}

fn uniform_dir(rng: &mut Rng) -> DVec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// One photon of the benchmark scene.
fn scene_photon(rng: &mut Rng) -> PhotonRecord {
    let room = DVec3::new(1000.0, 2000.0, 10.0);
    let u = rng.uniform();
    let (offset, normal) = if u < 0.4 {
        let v = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        (v * DVec3::new(4.0, 4.0, 3.0), DVec3::ZERO)
    } else if u < 0.8 {
        let v = DVec3::new(4.0 * rng.uniform(), 4.0 * rng.uniform(), 0.0);
        (v, DVec3::Z)
    } else {
        let v = DVec3::new(1.2 + 0.1 * gauss(rng), 2.4 + 0.1 * gauss(rng), 0.0);
        (v, DVec3::Z)
    };
    let mut dir = uniform_dir(rng);
    if normal != DVec3::ZERO {
        dir.z = -dir.z.abs();
    }
    PhotonRecord {
        position: room + offset,
        dir,
        normal,
        wavelength_nm: 380.0 + 400.0 * rng.uniform(),
        power_w: 1e-6,
        path: PhotonPath::Diffuse,
    }
}

fn scene(n: usize, seed: u64) -> Vec<PhotonRecord> {
    let mut rng = Rng::for_task(seed, Stream::Test, 0);
    (0..n).map(|_| scene_photon(&mut rng)).collect()
}

fn rel_f32(x: DVec3, origin: DVec3) -> [f32; 3] {
    let r = x - origin;
    [r.x as f32, r.y as f32, r.z as f32]
}

/// Per-iteration times of each benchmark, as measured (warm-up first, then the samples).
#[derive(Default)]
struct Times(RefCell<BTreeMap<String, Vec<f64>>>);

impl Times {
    fn record(&self, name: &str, total: Duration, iters: u64) {
        let per_iter = total.as_secs_f64() / iters as f64;
        self.0.borrow_mut().entry(name.to_string()).or_default().push(per_iter);
    }
    /// Median of the last `samples` records (the measured samples), in seconds.
    fn median(&self, name: &str, samples: usize) -> f64 {
        let map = self.0.borrow();
        let all = &map[name];
        let mut t = all[all.len().saturating_sub(samples)..].to_vec();
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    }
}

const SAMPLES: usize = 10;

fn main() {
    let quick = std::env::var_os("PHOTON_MAP_BENCH_QUICK").is_some();
    let n_queries = if quick { 100_000 } else { 1_000_000 };
    let threads = rayon::current_num_threads();
    let mut c = Criterion::default().sample_size(SAMPLES).warm_up_time(Duration::from_millis(1)).configure_from_args();
    let times = Times::default();

    let records = scene(1_000_000, 1);
    let map = PhotonMap::build(&records);
    let origin = map.origin();
    let points: Vec<[f32; 3]> = records.iter().map(|r| rel_f32(r.position, origin)).collect();
    let queries: Vec<DVec3> = scene(n_queries, 2).iter().map(|r| r.position).collect();
    let queries_f32: Vec<[f32; 3]> = queries.iter().map(|&q| rel_f32(q, origin)).collect();
    let tree = KdTree::build(points.clone());
    let kiddo = KiddoTree::new_from_slice_parallel(&points).expect("kiddo builds");

    // Radii from the distances to the 100th nearest photon.
    let mut out = Neighbours::default();
    let mut d100: Vec<f32> = queries_f32[..10_000]
        .iter()
        .map(|&q| {
            tree.knn(q, K, f32::INFINITY, &mut out);
            out.max_dist2().sqrt()
        })
        .collect();
    d100.sort_by(f32::total_cmp);
    let r_large = f64::from(d100[d100.len() * 3 / 4]);
    let settings = [("large", r_large), ("small", r_large / 8.0)];

    // ---- Build ----
    {
        let mut g = c.benchmark_group("photon_map/build_1M");
        g.sampling_mode(SamplingMode::Flat).measurement_time(Duration::from_secs(3));
        g.bench_function("morgana PhotonMap::build", |b| {
            b.iter_custom(|iters| {
                let t = Instant::now();
                for _ in 0..iters {
                    black_box(PhotonMap::build(&records));
                }
                let e = t.elapsed();
                times.record("build map", e, iters);
                e
            })
        });
        g.bench_function("morgana KdTree<[f32;3]>::build", |b| {
            b.iter_custom(|iters| {
                let mut e = Duration::ZERO;
                for _ in 0..iters {
                    let input = points.clone();
                    let t = Instant::now();
                    black_box(KdTree::build(input));
                    e += t.elapsed();
                }
                times.record("build points", e, iters);
                e
            })
        });
        g.bench_function("kiddo new_from_slice_parallel", |b| {
            b.iter_custom(|iters| {
                let t = Instant::now();
                for _ in 0..iters {
                    black_box(KiddoTree::new_from_slice_parallel(&points).expect("kiddo builds"));
                }
                let e = t.elapsed();
                times.record("build kiddo", e, iters);
                e
            })
        });
        g.finish();
    }

    // ---- Queries ----
    let mut found = BTreeMap::new();
    for (name, r) in settings {
        let r2 = (r * r) as f32;
        let mut g = c.benchmark_group(format!("photon_map/knn_{}k_k100_{name}", n_queries / 1000));
        g.sampling_mode(SamplingMode::Flat).measurement_time(Duration::from_secs(1));
        g.bench_function("morgana PhotonMap::knn", |b| {
            b.iter_custom(|iters| {
                let mut out = Neighbours::default();
                let mut n = 0;
                let t = Instant::now();
                for _ in 0..iters {
                    for &q in &queries {
                        map.knn(q, K, r, &mut out);
                        n += out.len();
                    }
                }
                let e = t.elapsed();
                found.insert((name, "map"), n / iters as usize);
                times.record(&format!("{name} map"), e, iters);
                e
            })
        });
        g.bench_function("kiddo nearest_n.within.unsorted", |b| {
            b.iter_custom(|iters| {
                let k = NonZeroUsize::new(K).expect("k > 0");
                let mut n = 0;
                let t = Instant::now();
                for _ in 0..iters {
                    for q in &queries_f32 {
                        let res = kiddo.query(q).nearest_n::<SquaredEuclidean<f32>>(k).within(r2).unsorted().execute();
                        n += res.len();
                    }
                }
                let e = t.elapsed();
                found.insert((name, "kiddo"), n / iters as usize);
                times.record(&format!("{name} kiddo"), e, iters);
                e
            })
        });
        g.finish();
    }

    let designs = design_comparison(&points, &queries_f32[..100_000.min(n_queries)], &settings);

    // ---- Memory ----
    let bytes_1m = map.memory_bytes();
    let (bytes_10m, build_10m) = if quick {
        (None, None)
    } else {
        let big = scene(10_000_000, 3);
        let t = Instant::now();
        let m = PhotonMap::build(&big);
        let e = t.elapsed();
        (Some(m.memory_bytes()), Some(e))
    };

    c.final_summary();

    // ---- Summary ----
    let ms = |key: &str| times.median(key, SAMPLES) * 1e3;
    println!();
    println!(
        "## photon_map: 1M photons, {n_queries} queries, k = {K}; medians of {SAMPLES} samples; \
         builds on {threads} rayon threads, queries on one"
    );
    println!();
    println!("| operation | morgana | kiddo 6 | morgana / kiddo |");
    println!("|---|---:|---:|---:|");
    let kb = ms("build kiddo");
    println!(
        "| build, points (parallel) | {:.1} ms | {kb:.1} ms | {:.2} |",
        ms("build points"),
        ms("build points") / kb
    );
    println!(
        "| build, PhotonMap from records (encode + tree) | {:.1} ms | — | {:.2} |",
        ms("build map"),
        ms("build map") / kb
    );
    for (name, r) in settings {
        let kq = ms(&format!("{name} kiddo"));
        let per = |v: f64| v * 1e3 / n_queries as f64;
        let v = ms(&format!("{name} map"));
        println!(
            "| knn {name}: r = {:.4} m, {:.1} found | {v:.0} ms ({:.2} µs/q) | {kq:.0} ms ({:.2} µs/q) | {:.2} |",
            r,
            found[&(name, "map")] as f64 / n_queries as f64,
            per(v),
            per(kq),
            v / kq
        );
        assert_eq!(found[&(name, "map")], found[&(name, "kiddo")], "same work");
    }
    println!();
    println!("memory: {:.2} bytes/photon at 1M ({:.1} MB)", bytes_1m as f64 / map.len() as f64, bytes_1m as f64 / 1e6);
    if let (Some(b), Some(e)) = (bytes_10m, build_10m) {
        println!(
            "memory: {:.2} bytes/photon at 10M ({:.1} MB); PhotonMap::build of 10M: {:.2} s",
            b as f64 / 1e7,
            b as f64 / 1e6,
            e.as_secs_f64()
        );
    }
    println!();
    println!("{designs}");
}

/// A k-nearest query (point, squared radius) returning the number found.
type Query<'a> = Box<dyn Fn([f32; 3], f32) -> usize + 'a>;

/// Tree designs compared on a subset of the queries (best and median of 3 rounds, µs/query,
/// one thread): Jensen's left-balanced tree (one point per node, max-heap of k), ours with
/// several leaf sizes, and kiddo's default `ImmutableKdTree` against the configuration used above.
fn design_comparison(points: &[[f32; 3]], queries: &[[f32; 3]], settings: &[(&str, f64)]) -> String {
    let k = NonZeroUsize::new(K).expect("k > 0");
    let mut rows: Vec<(String, Query<'_>)> = Vec::new();
    let t = Instant::now();
    let jensen = jensen::Tree::build(points);
    let jensen_build = t.elapsed();
    rows.push((format!("Jensen 2000 left-balanced, max-heap (serial build {jensen_build:.0?})"), {
        let out = RefCell::new(Vec::new());
        Box::new(move |q, r2| {
            let mut out = out.borrow_mut();
            jensen.knn(q, K, r2, &mut out);
            out.len()
        })
    }));
    for leaf in [8, 16, 32, 64] {
        let tree = KdTree::build_with_leaf_size(points.to_vec(), leaf);
        let out = RefCell::new(Neighbours::default());
        rows.push((
            format!("morgana KdTree, leaves ≤ {leaf} (depth {})", tree.depth()),
            Box::new(move |q, r2| {
                let mut out = out.borrow_mut();
                tree.knn(q, K, r2, &mut out);
                out.len()
            }),
        ));
    }
    let default = ImmutableKdTree::<f32, 3>::new_from_slice_parallel(points).expect("kiddo builds");
    rows.push((
        "kiddo ImmutableKdTree<f32, 3> (default: arenas of 32)".into(),
        Box::new(move |q, r2| {
            let res = default.query(&q).nearest_n::<SquaredEuclidean<f32>>(k);
            res.within(r2).unsorted().execute().len()
        }),
    ));
    let tuned = KiddoTree::new_from_slice_parallel(points).expect("kiddo builds");
    rows.push((
        "kiddo Eytzinger + FlatVec<8> (used above)".into(),
        Box::new(move |q, r2| {
            let res = tuned.query(&q).nearest_n::<SquaredEuclidean<f32>>(k);
            res.within(r2).unsorted().execute().len()
        }),
    ));
    let mut s =
        format!("## designs: {} queries, k = {K}, µs/query (best / median of 3 rounds)\n\n| tree |", queries.len());
    for (name, _) in settings {
        s += &format!(" {name} |");
    }
    s += "\n|---|";
    s += &"---:|".repeat(settings.len());
    s += "\n";
    let mut cells = vec![vec![Vec::new(); settings.len()]; rows.len()];
    let mut counts = vec![vec![0usize; settings.len()]; rows.len()];
    for _round in 0..3 {
        for (si, (_, r)) in settings.iter().enumerate() {
            let r2 = (r * r) as f32;
            for (ri, (_, f)) in rows.iter().enumerate() {
                let t = Instant::now();
                let n: usize = queries.iter().map(|&q| f(q, r2)).sum();
                cells[ri][si].push(t.elapsed().as_secs_f64() * 1e6 / queries.len() as f64);
                counts[ri][si] = n;
            }
        }
    }
    for (ri, (name, _)) in rows.iter().enumerate() {
        s += &format!("| {name} |");
        for si in 0..settings.len() {
            let mut t = cells[ri][si].clone();
            t.sort_by(f64::total_cmp);
            s += &format!(" {:.2} / {:.2} |", t[0], t[t.len() / 2]);
            assert_eq!(counts[ri][si], counts[0][si], "{name}: same number found");
        }
        s += "\n";
    }
    s
}

/// Jensen's photon map tree (2000, §2 and fig. 10) as the baseline: left-balanced, stored
/// heap-ordered with one point per node (no pointers), searched with a max-heap of `k`.
mod jensen {
    pub struct Tree {
        /// 1-based heap order: (position, split axis).
        nodes: Vec<([f32; 3], u32)>,
    }

    /// Size of the left subtree of a left-balanced tree of `n` nodes.
    fn left_size(n: usize) -> usize {
        if n <= 1 {
            return 0;
        }
        let h = n.ilog2();
        let half = 1usize << (h - 1);
        let last = n - ((1usize << h) - 1);
        (half - 1) + last.min(half)
    }

    impl Tree {
        pub fn build(points: &[[f32; 3]]) -> Tree {
            let mut items = points.to_vec();
            let mut nodes = vec![([0.0; 3], 0); points.len() + 1];
            balance(&mut items, &mut nodes, 1);
            Tree { nodes }
        }

        pub fn knn(&self, q: [f32; 3], k: usize, max_dist2: f32, out: &mut Vec<(u32, f32)>) {
            out.clear();
            let mut bound = max_dist2;
            if self.nodes.len() > 1 {
                self.locate(1, q, k, &mut bound, out);
            }
        }

        fn locate(&self, p: usize, q: [f32; 3], k: usize, bound: &mut f32, out: &mut Vec<(u32, f32)>) {
            let n = self.nodes.len() - 1;
            let (pos, axis) = self.nodes[p];
            if 2 * p <= n {
                let delta = q[axis as usize] - pos[axis as usize];
                let (near, far) = if delta < 0.0 { (2 * p, 2 * p + 1) } else { (2 * p + 1, 2 * p) };
                if near <= n {
                    self.locate(near, q, k, bound, out);
                }
                if far <= n && delta * delta <= *bound {
                    self.locate(far, q, k, bound, out);
                }
            }
            let (dx, dy, dz) = (pos[0] - q[0], pos[1] - q[1], pos[2] - q[2]);
            let d2 = dx * dx + dy * dy + dz * dz;
            if d2 <= *bound {
                if out.len() < k {
                    out.push((p as u32, d2));
                    if out.len() == k {
                        // Jensen's delayed heap construction.
                        for i in (0..k / 2).rev() {
                            sift_down(out, i);
                        }
                        *bound = out[0].1;
                    }
                } else if d2 < out[0].1 {
                    out[0] = (p as u32, d2);
                    sift_down(out, 0);
                    *bound = out[0].1;
                }
            }
        }
    }

    fn balance(items: &mut [[f32; 3]], nodes: &mut [([f32; 3], u32)], i: usize) {
        if items.is_empty() {
            return;
        }
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in items.iter() {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        let axis = (1..3).fold(0, |b, a| if hi[a] - lo[a] > hi[b] - lo[b] { a } else { b });
        let m = left_size(items.len());
        items.select_nth_unstable_by(m, |a, b| a[axis].total_cmp(&b[axis]));
        nodes[i] = (items[m], axis as u32);
        let (left, right) = items.split_at_mut(m);
        balance(left, nodes, 2 * i);
        balance(&mut right[1..], nodes, 2 * i + 1);
    }

    fn sift_down(h: &mut [(u32, f32)], mut i: usize) {
        let x = h[i];
        loop {
            let mut c = 2 * i + 1;
            if c >= h.len() {
                break;
            }
            if c + 1 < h.len() && h[c + 1].1 > h[c].1 {
                c += 1;
            }
            if h[c].1 <= x.1 {
                break;
            }
            h[i] = h[c];
            i = c;
        }
        h[i] = x;
    }
}
