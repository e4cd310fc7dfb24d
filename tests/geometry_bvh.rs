//! The BVH against brute force over all shapes, on random rays through random scenes.

use morgana::geometry::{Bvh, DVec3, Disk, Quad, Ray, Shape, Sphere, Triangle};
use morgana::rng::{Rng, Stream};
use morgana::sampling::uniform_sphere;

fn point(rng: &mut Rng, half: f64) -> DVec3 {
    DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * (2.0 * half) - half
}

/// A scene of `n` mixed shapes in a box of half-size `half`: a few large overlapping spheres,
/// quads and disks, and many small triangles (some in clusters, some coincident).
fn random_scene(rng: &mut Rng, n: usize, half: f64) -> Vec<Shape> {
    let mut shapes: Vec<Shape> = Vec::with_capacity(n);
    while shapes.len() < n {
        let c = point(rng, half);
        let size = half * 10f64.powf(-3.0 * rng.uniform());
        let shape = match rng.below(20) {
            0 => Shape::Sphere(Sphere { center: c, radius: 0.3 * size }),
            1 => Shape::Quad(Quad { origin: c, u: point(rng, size), v: point(rng, size) }),
            2 => Shape::Disk(Disk { center: c, normal: uniform_sphere(rng.uniform2()), radius: 0.5 * size }),
            3 if !shapes.is_empty() => {
                // An exact duplicate of an earlier shape: ties must resolve consistently.
                let i = rng.below(shapes.len() as u64) as usize;
                shapes[i].clone()
            }
            _ => {
                let s = 0.02 * half;
                Shape::Triangle(Triangle { p: [c, c + point(rng, s), c + point(rng, s)] })
            }
        };
        shapes.push(shape);
    }
    shapes
}

fn random_ray(rng: &mut Rng, half: f64) -> (Ray, f64) {
    let o = point(rng, 1.5 * half);
    // Half the rays are aimed at a point of the scene box, half go anywhere.
    let dir = if rng.uniform() < 0.5 { (point(rng, half) - o).normalize() } else { uniform_sphere(rng.uniform2()) };
    let t_max = if rng.uniform() < 0.3 { 3.0 * half * rng.uniform() } else { f64::INFINITY };
    (Ray::new(o, dir), t_max)
}

/// Nearest hit by testing every shape (lowest index wins ties).
fn brute_force(shapes: &[Shape], ray: &Ray, t_max: f64) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for (i, s) in shapes.iter().enumerate() {
        if let Some((t, _)) = s.intersect(ray, t_max)
            && best.is_none_or(|(_, tb)| t < tb)
        {
            best = Some((i, t));
        }
    }
    best
}

fn check_against_brute_force(shapes: &[Shape], rays: &[(Ray, f64)]) -> usize {
    let bvh = Bvh::build(shapes);
    let mut hits = 0;
    for (ray, t_max) in rays {
        let want = brute_force(shapes, ray, *t_max);
        let got = bvh.intersect(shapes, ray, *t_max);
        match (got, want) {
            (None, None) => {}
            (Some(h), Some((i, t))) => {
                assert_eq!(h.t, t, "{ray:?}: BVH t {} (prim {}) vs brute force {t} (prim {i})", h.t, h.prim);
                let shape = &shapes[h.prim as usize];
                // Another shape at exactly the same distance is a tie, not an error.
                assert_eq!(shape.intersect(ray, *t_max).map(|x| x.0), Some(t));
                assert_eq!(h.point, shape.hit_point(ray, t));
                assert_eq!(h.normal, shape.normal_at(h.point));
                hits += 1;
            }
            _ => panic!("{ray:?} t_max {t_max}: BVH {got:?} vs brute force {want:?}"),
        }
        assert_eq!(bvh.occluded(shapes, ray, *t_max), want.is_some(), "{ray:?}");
    }
    hits
}

#[test]
fn bvh_matches_brute_force_in_random_scenes() {
    for (seed, n) in [(1u64, 3000usize), (2, 500), (3, 20_000)] {
        let mut rng = Rng::for_task(20, Stream::Test, seed);
        let half = 10f64.powf(4.0 * rng.uniform() - 1.0);
        let shapes = random_scene(&mut rng, n, half);
        let rays: Vec<(Ray, f64)> = (0..4000).map(|_| random_ray(&mut rng, half)).collect();
        let hits = check_against_brute_force(&shapes, &rays);
        assert!(hits > 400, "scene {seed}: only {hits} hits");
    }
}

#[test]
fn bvh_handles_tiny_scenes() {
    let mut rng = Rng::for_task(20, Stream::Test, 10);
    let empty = Bvh::build(&[]);
    let ray = Ray::new(DVec3::ZERO, DVec3::X);
    assert_eq!(empty.intersect(&[], &ray, f64::INFINITY), None);
    assert!(!empty.occluded(&[], &ray, f64::INFINITY));
    assert_eq!(Bvh::default().intersect(&[], &ray, f64::INFINITY), None);
    // Up to 40 shapes: trees of at most 33 nodes take the small stack, larger ones the full one.
    for n in 1..=40 {
        let shapes = random_scene(&mut rng, n, 1.0);
        let rays: Vec<(Ray, f64)> = (0..500).map(|_| random_ray(&mut rng, 1.0)).collect();
        check_against_brute_force(&shapes, &rays);
    }
}

#[test]
fn bvh_with_the_earth_and_a_road() {
    // The Earth, a road of triangles and quads at the origin, rays near the horizon.
    let r = 6.371e6;
    let mut shapes = vec![Shape::Sphere(Sphere { center: DVec3::new(0.0, -r, 0.0), radius: r })];
    let mut rng = Rng::for_task(20, Stream::Test, 11);
    for _ in 0..2000 {
        let c = DVec3::new(200.0 * rng.uniform() - 100.0, 0.5 * rng.uniform(), 20.0 * rng.uniform() - 10.0);
        shapes.push(Shape::Triangle(Triangle { p: [c, c + point(&mut rng, 0.5), c + point(&mut rng, 0.5)] }));
        if rng.uniform() < 0.1 {
            shapes.push(Shape::Quad(Quad { origin: c, u: point(&mut rng, 3.0), v: point(&mut rng, 3.0) }));
        }
    }
    let rays: Vec<(Ray, f64)> = (0..4000)
        .map(|_| {
            let o = DVec3::new(
                400.0 * rng.uniform() - 200.0,
                10f64.powf(4.0 * rng.uniform() - 2.0),
                40.0 * rng.uniform() - 20.0,
            );
            let azimuth = 2.0 * std::f64::consts::PI * rng.uniform();
            let elevation = -0.01 * rng.uniform().powi(3) + 1e-3 * (rng.uniform() - 0.5);
            let dir = DVec3::new(azimuth.cos() * elevation.cos(), elevation.sin(), azimuth.sin() * elevation.cos());
            (Ray::new(o, dir), f64::INFINITY)
        })
        .collect();
    let hits = check_against_brute_force(&shapes, &rays);
    assert!(hits > 1000, "{hits}");
}

#[test]
fn bvh_build_is_deterministic_across_thread_counts() {
    let mut rng = Rng::for_task(20, Stream::Test, 12);
    let shapes = random_scene(&mut rng, 50_000, 100.0);
    let build_with = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool")
            .install(|| Bvh::build(&shapes))
    };
    let one = build_with(1);
    assert_eq!(one, build_with(2));
    assert_eq!(one, build_with(3));
    assert_eq!(one, Bvh::build(&shapes));
}

#[test]
fn bvh_depth_stays_bounded_for_pathological_inputs() {
    // Sizes and positions in geometric progression defeat a balanced split, and 5000 identical
    // triangles cannot be separated at all.
    let mut shapes: Vec<Shape> = (0..3000)
        .map(|k| {
            let s = 0.99f64.powi(k);
            Shape::Sphere(Sphere { center: DVec3::new(s, 0.0, 0.0), radius: 0.1 * s })
        })
        .collect();
    let tri = Triangle { p: [DVec3::ZERO, DVec3::X, DVec3::Y] };
    shapes.extend((0..5000).map(|_| Shape::Triangle(tri.clone())));
    let bvh = Bvh::build(&shapes);
    assert!(bvh.depth() <= 48 + 36, "depth {}", bvh.depth());
    let mut rng = Rng::for_task(20, Stream::Test, 13);
    let rays: Vec<(Ray, f64)> = (0..1000).map(|_| random_ray(&mut rng, 1.0)).collect();
    check_against_brute_force(&shapes, &rays);
}

#[test]
fn bvh_is_a_real_hierarchy() {
    // 10 000 small separated triangles: a good tree has ~n/2..2n nodes and depth ≈ log2 n.
    let mut rng = Rng::for_task(20, Stream::Test, 14);
    let shapes: Vec<Shape> = (0..10_000)
        .map(|_| {
            let c = point(&mut rng, 100.0);
            Shape::Triangle(Triangle { p: [c, c + point(&mut rng, 0.5), c + point(&mut rng, 0.5)] })
        })
        .collect();
    let bvh = Bvh::build(&shapes);
    assert!(bvh.node_count() > 1000 && bvh.node_count() < 20_000, "{} nodes", bvh.node_count());
    assert!(bvh.depth() < 40, "depth {}", bvh.depth());
    let b = bvh.bounds();
    for s in &shapes {
        let sb = s.bounds();
        assert!(b.contains(sb.min) && b.contains(sb.max));
    }
}

#[test]
fn the_sole_shape_touching_a_box_is_found_only_when_it_is_alone() {
    use morgana::geometry::Aabb;
    // A floor y = 0 over [−1, 1]² and a wall x = 0.5 standing on it, among many small spheres
    // far above (so that the tree has depth).
    let mut shapes = vec![
        Shape::Quad(Quad {
            origin: DVec3::new(-1.0, 0.0, -1.0),
            u: DVec3::new(0.0, 0.0, 2.0),
            v: DVec3::new(2.0, 0.0, 0.0),
        }),
        Shape::Quad(Quad {
            origin: DVec3::new(0.5, 0.0, -1.0),
            u: DVec3::new(0.0, 1.0, 0.0),
            v: DVec3::new(0.0, 0.0, 2.0),
        }),
    ];
    shapes.extend(
        (0..40).map(|i| Shape::Sphere(Sphere { center: DVec3::new(-1.0 + 0.05 * i as f64, 5.0, 0.0), radius: 0.01 })),
    );
    let bvh = Bvh::build(&shapes);
    let ball = |x: DVec3, r: f64| Aabb { min: x - DVec3::splat(r), max: x + DVec3::splat(r) };
    assert_eq!(bvh.sole_shape_touching_box(&shapes, &ball(DVec3::new(-0.5, 0.0, 0.0), 0.1)), Some(0));
    assert_eq!(bvh.sole_shape_touching_box(&shapes, &ball(DVec3::new(0.45, 0.0, 0.0), 0.1)), None);
    assert_eq!(bvh.sole_shape_touching_box(&shapes, &ball(DVec3::new(0.5, 0.5, 0.0), 0.1)), Some(1));
    assert_eq!(bvh.sole_shape_touching_box(&shapes, &ball(DVec3::new(0.0, 3.0, 0.0), 0.1)), None);
    assert!(bvh.may_touch_box(&shapes, &ball(DVec3::new(0.45, 0.0, 0.0), 0.1)));
    assert!(!bvh.may_touch_box(&shapes, &ball(DVec3::new(0.0, 3.0, 0.0), 0.1)));
}
