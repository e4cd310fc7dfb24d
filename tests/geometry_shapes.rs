//! Shapes: intersections against closed forms and against independent algorithms on random
//! rays; areas; uniform area sampling by chi-square.

use morgana::geometry::{DVec3, Disk, Quad, Ray, Shape, Sphere, Triangle};
use morgana::rng::{Rng, Stream};
use morgana::sampling::uniform_sphere;
use morgana::testing::chi2::{chi2_discrete, chi2_sphere};
use std::f64::consts::PI;

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1.0)
}

fn assert_hit(shape: &Shape, ray: Ray, t_max: f64, t: f64, normal: DVec3) {
    let (got_t, got_n) = shape.intersect(&ray, t_max).unwrap_or_else(|| panic!("{shape:?}: missed {ray:?}"));
    assert!(close(got_t, t, 1e-14), "{shape:?}: t {got_t} != {t}");
    assert!((got_n - normal).length() < 1e-14, "{shape:?}: n {got_n} != {normal}");
}

fn assert_miss(shape: &Shape, ray: Ray, t_max: f64) {
    assert_eq!(shape.intersect(&ray, t_max), None, "{shape:?}: {ray:?}");
}

fn unit(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z).normalize()
}

#[test]
fn sphere_closed_forms() {
    let c = DVec3::new(1.0, 2.0, 3.0);
    let s = Shape::Sphere(Sphere { center: c, radius: 1.0 });
    let down_z = |x: f64, y: f64| Ray::new(c + DVec3::new(x, y, -5.0), DVec3::Z);
    assert_hit(&s, down_z(0.0, 0.0), f64::INFINITY, 4.0, -DVec3::Z);
    // Offset 0.6 from the axis: t = 5 − √(1 − 0.36) = 4.2, normal (0, 0.6, −0.8).
    assert_hit(&s, down_z(0.0, 0.6), f64::INFINITY, 4.2, DVec3::new(0.0, 0.6, -0.8));
    assert_hit(&s, down_z(0.0, 0.0), 4.0001, 4.0, -DVec3::Z);
    assert_miss(&s, down_z(0.0, 0.0), 3.9999);
    assert_miss(&s, down_z(1.2, 0.0), f64::INFINITY);
    assert_miss(&s, Ray::new(c + DVec3::new(0.0, 0.0, -5.0), -DVec3::Z), f64::INFINITY);
    // From the centre the outward normal faces along the ray.
    assert_hit(&s, Ray::new(c, DVec3::X), f64::INFINITY, 1.0, DVec3::X);
    // From inside, off centre: |(0.5,0,0) + t (0,1,0)| = 1 ⇒ t = √0.75.
    let inside = Ray::new(c + DVec3::new(0.5, 0.0, 0.0), DVec3::Y);
    assert_hit(&s, inside, f64::INFINITY, 0.75f64.sqrt(), DVec3::new(0.5, 0.75f64.sqrt(), 0.0));
    assert!((s.area() - 4.0 * PI).abs() < 1e-14);
    let b = s.bounds();
    assert!(b.min.cmple(c - 1.0).all() && b.max.cmpge(c + 1.0).all());
    assert!((b.max - c - 1.0).max_element() < 1e-12);
}

#[test]
fn quad_closed_forms() {
    let q = Shape::Quad(Quad { origin: DVec3::ZERO, u: DVec3::new(2.0, 0.0, 0.0), v: DVec3::new(0.0, 3.0, 0.0) });
    assert_hit(&q, Ray::new(DVec3::new(1.0, 1.0, 5.0), -DVec3::Z), f64::INFINITY, 5.0, DVec3::Z);
    // From the back the front normal is still u × v.
    assert_hit(&q, Ray::new(DVec3::new(1.0, 1.0, -2.0), DVec3::Z), f64::INFINITY, 2.0, DVec3::Z);
    let oblique = Ray::new(DVec3::new(0.0, 0.0, 4.0), unit(1.0, 1.5, -4.0));
    assert_hit(&q, oblique, f64::INFINITY, 19.25f64.sqrt(), DVec3::Z);
    assert_miss(&q, Ray::new(DVec3::new(2.5, 1.0, 5.0), -DVec3::Z), f64::INFINITY);
    assert_miss(&q, Ray::new(DVec3::new(1.0, -0.1, 5.0), -DVec3::Z), f64::INFINITY);
    assert_miss(&q, Ray::new(DVec3::new(1.0, 1.0, 5.0), -DVec3::Z), 4.9);
    assert_miss(&q, Ray::new(DVec3::new(1.0, 1.0, 5.0), DVec3::X), f64::INFINITY);
    assert!((q.area() - 6.0).abs() < 1e-14);
    // A sheared quad: (2.8, 0.9) = 0.95 u + 0.9 v is inside, (0.5, 0.9) is not.
    let skew = Shape::Quad(Quad { origin: DVec3::ZERO, u: DVec3::new(2.0, 0.0, 0.0), v: DVec3::new(1.0, 1.0, 0.0) });
    assert_hit(&skew, Ray::new(DVec3::new(2.8, 0.9, 1.0), -DVec3::Z), f64::INFINITY, 1.0, DVec3::Z);
    assert_miss(&skew, Ray::new(DVec3::new(0.5, 0.9, 1.0), -DVec3::Z), f64::INFINITY);
    assert!((skew.area() - 2.0).abs() < 1e-14);
}

#[test]
fn disk_closed_forms() {
    let d = Shape::Disk(Disk { center: DVec3::new(0.0, 0.0, 1.0), normal: DVec3::new(0.0, 0.0, 2.0), radius: 2.0 });
    assert_hit(&d, Ray::new(DVec3::new(1.9, 0.0, 5.0), -DVec3::Z), f64::INFINITY, 4.0, DVec3::Z);
    assert_miss(&d, Ray::new(DVec3::new(1.5, 1.5, 5.0), -DVec3::Z), f64::INFINITY);
    assert_hit(&d, Ray::new(DVec3::new(0.0, 0.0, -1.0), DVec3::Z), f64::INFINITY, 2.0, DVec3::Z);
    assert!((d.area() - 4.0 * PI).abs() < 1e-13);
    // A tilted disk's box reaches r √(1 − n_i²) along each axis.
    let n = unit(1.0, 0.0, 1.0);
    let tilted = Shape::Disk(Disk { center: DVec3::ZERO, normal: n, radius: 1.0 });
    let b = tilted.bounds();
    let half = DVec3::new(0.5f64.sqrt(), 1.0, 0.5f64.sqrt());
    assert!((b.max - half).abs().max_element() < 1e-12 && b.max.cmpge(half).all());
}

#[test]
fn triangle_closed_forms() {
    let tri = Shape::Triangle(Triangle { p: [DVec3::ZERO, DVec3::X, DVec3::Y] });
    assert_hit(&tri, Ray::new(DVec3::new(0.25, 0.25, 1.0), -DVec3::Z), f64::INFINITY, 1.0, DVec3::Z);
    assert_hit(&tri, Ray::new(DVec3::new(0.25, 0.25, -3.0), DVec3::Z), f64::INFINITY, 3.0, DVec3::Z);
    assert_miss(&tri, Ray::new(DVec3::new(0.6, 0.6, 1.0), -DVec3::Z), f64::INFINITY);
    assert_miss(&tri, Ray::new(DVec3::new(-0.1, 0.5, 1.0), -DVec3::Z), f64::INFINITY);
    assert_miss(&tri, Ray::new(DVec3::new(0.25, 0.25, 1.0), DVec3::Z), f64::INFINITY);
    // Clockwise winding flips the front normal.
    let cw = Shape::Triangle(Triangle { p: [DVec3::ZERO, DVec3::Y, DVec3::X] });
    assert_hit(&cw, Ray::new(DVec3::new(0.25, 0.25, 1.0), -DVec3::Z), f64::INFINITY, 1.0, -DVec3::Z);
    let big = Shape::Triangle(Triangle { p: [DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0), DVec3::new(0.0, 0.0, 4.0)] });
    assert!((big.area() - 6.0).abs() < 1e-14);
}

// ---- independent algorithms on random rays -------------------------------------------------

fn random_dir(rng: &mut Rng) -> DVec3 {
    uniform_sphere(rng.uniform2())
}

fn random_point(rng: &mut Rng, half: f64) -> DVec3 {
    DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * (2.0 * half) - half
}

/// Geometric ray–sphere test (closest approach; Glassner, *An Introduction to Ray Tracing*).
/// Returns the nearest positive root and the squared miss distance relative to r².
fn sphere_reference(s: &Sphere, ray: &Ray) -> (Option<f64>, f64) {
    let l = s.center - ray.origin;
    let tca = l.dot(ray.dir);
    let d2 = l.length_squared() - tca * tca;
    let r2 = s.radius * s.radius;
    if d2 > r2 {
        return (None, (d2 - r2) / r2);
    }
    let thc = (r2 - d2).sqrt();
    let t = [tca - thc, tca + thc].into_iter().find(|&t| t > 0.0);
    (t, (d2 - r2) / r2)
}

/// Solves o + t d = a + x e1 + y e2 by Cramer's rule: (x, y, t).
fn cramer(o: DVec3, d: DVec3, a: DVec3, e1: DVec3, e2: DVec3) -> Option<(f64, f64, f64)> {
    let det = e1.dot(e2.cross(-d));
    if det.abs() < 1e-12 {
        return None;
    }
    let rhs = o - a;
    let x = rhs.dot(e2.cross(-d)) / det;
    let y = e1.dot(rhs.cross(-d)) / det;
    let t = e1.dot(e2.cross(rhs)) / det;
    Some((x, y, t))
}

/// Möller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection": (b1, b2, t).
fn moller_trumbore(tri: &Triangle, ray: &Ray) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
    let pv = ray.dir.cross(e2);
    let det = e1.dot(pv);
    if det.abs() < 1e-12 {
        return None;
    }
    let tv = ray.origin - tri.p[0];
    let u = tv.dot(pv) / det;
    let qv = tv.cross(e1);
    let v = ray.dir.dot(qv) / det;
    let t = e2.dot(qv) / det;
    Some((u, v, t))
}

/// Counts agreements; panics on a disagreement that is not within `margin` of a boundary.
fn compare(kind: &str, got: Option<f64>, want: Option<f64>, ambiguous: bool) -> usize {
    match (got, want) {
        (Some(a), Some(b)) => {
            assert!(close(a, b, 1e-9), "{kind}: t {a} vs reference {b}");
            1
        }
        (None, None) => 1,
        _ if ambiguous => 0,
        _ => panic!("{kind}: got {got:?}, reference {want:?}"),
    }
}

const RAYS: usize = 20_000;

#[test]
fn sphere_matches_geometric_solution_on_random_rays() {
    let mut rng = Rng::for_task(1, Stream::Test, 100);
    let (mut agree, mut hits) = (0, 0);
    for _ in 0..RAYS {
        let s = Sphere { center: random_point(&mut rng, 5.0), radius: 0.1 + 3.0 * rng.uniform() };
        // Aim near the sphere so that about half the rays hit.
        let o = random_point(&mut rng, 10.0);
        let target = s.center + random_point(&mut rng, 1.5 * s.radius);
        let ray = Ray::new(o, (target - o).normalize());
        let t_max = if rng.uniform() < 0.3 { 20.0 * rng.uniform() } else { f64::INFINITY };
        let (want, miss) = sphere_reference(&s, &ray);
        let want = want.filter(|&t| t < t_max);
        let near_boundary =
            miss.abs() < 1e-9 || want.is_some_and(|t| t < 1e-9 || (t - t_max).abs() < 1e-9 * t_max.min(1e3));
        let got = Shape::Sphere(s.clone()).intersect(&ray, t_max);
        if let (Some((t, n)), Some(_)) = (got, want) {
            let expect_n = (ray.at(t) - s.center) / s.radius;
            assert!((n - expect_n).length() < 1e-9, "normal {n} vs {expect_n}");
            hits += 1;
        }
        agree += compare("sphere", got.map(|h| h.0), want, near_boundary);
    }
    assert!(agree >= RAYS - 10, "only {agree} of {RAYS} agree");
    assert!(hits > RAYS / 5, "too few hits ({hits}) to test anything");
}

#[test]
fn quad_matches_cramer_on_random_rays() {
    let mut rng = Rng::for_task(1, Stream::Test, 101);
    let (mut agree, mut hits) = (0, 0);
    for _ in 0..RAYS {
        let q = Quad {
            origin: random_point(&mut rng, 3.0),
            u: random_point(&mut rng, 2.0),
            v: random_point(&mut rng, 2.0),
        };
        let o = random_point(&mut rng, 6.0);
        let target = q.origin + (1.4 * rng.uniform() - 0.2) * q.u + (1.4 * rng.uniform() - 0.2) * q.v;
        let ray = Ray::new(o, (target - o).normalize());
        let Some((a, b, t)) = cramer(o, ray.dir, q.origin, q.u, q.v) else {
            continue;
        };
        let inside = (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b);
        let want = (inside && t > 0.0).then_some(t);
        let edge = [a, b, 1.0 - a, 1.0 - b].iter().any(|x| x.abs() < 1e-9) || t.abs() < 1e-9;
        let got = Shape::Quad(q.clone()).intersect(&ray, f64::INFINITY);
        if let Some((_, n)) = got {
            assert!((n - q.u.cross(q.v).normalize()).length() < 1e-12);
            hits += 1;
        }
        agree += compare("quad", got.map(|h| h.0), want, edge);
    }
    assert!(agree >= RAYS - 50, "only {agree} of {RAYS} agree");
    assert!(hits > RAYS / 5, "too few hits ({hits})");
}

#[test]
fn disk_matches_in_plane_solution_on_random_rays() {
    let mut rng = Rng::for_task(1, Stream::Test, 102);
    let (mut agree, mut hits) = (0, 0);
    for _ in 0..RAYS {
        let n = random_dir(&mut rng);
        let disk = Disk {
            center: random_point(&mut rng, 3.0),
            normal: n * (0.5 + rng.uniform()),
            radius: 0.2 + 2.0 * rng.uniform(),
        };
        // Any two independent in-plane vectors: Cramer gives the in-plane coordinates.
        let helper = if n.x.abs() < 0.5 { DVec3::X } else { DVec3::Y };
        let e1 = n.cross(helper).normalize();
        let e2 = n.cross(e1);
        let o = random_point(&mut rng, 6.0);
        let target = disk.center + 1.3 * disk.radius * (rng.uniform() * e1 + rng.uniform() * e2);
        let ray = Ray::new(o, (target - o).normalize());
        let Some((x, y, t)) = cramer(o, ray.dir, disk.center, e1, e2) else {
            continue;
        };
        let rho = (x * x + y * y).sqrt();
        let want = (rho <= disk.radius && t > 0.0).then_some(t);
        let edge = (rho - disk.radius).abs() < 1e-9 || t.abs() < 1e-9;
        let got = Shape::Disk(disk.clone()).intersect(&ray, f64::INFINITY);
        if let Some((_, normal)) = got {
            assert!((normal - n).length() < 1e-12);
            hits += 1;
        }
        agree += compare("disk", got.map(|h| h.0), want, edge);
    }
    assert!(agree >= RAYS - 50, "only {agree} of {RAYS} agree");
    assert!(hits > RAYS / 5, "too few hits ({hits})");
}

#[test]
fn triangle_matches_moller_trumbore_on_random_rays() {
    let mut rng = Rng::for_task(1, Stream::Test, 103);
    let (mut agree, mut hits) = (0, 0);
    for _ in 0..RAYS {
        let tri = Triangle { p: [0, 1, 2].map(|_| random_point(&mut rng, 3.0)) };
        let o = random_point(&mut rng, 6.0);
        let (b1, b2) = (1.2 * rng.uniform() - 0.1, 1.2 * rng.uniform() - 0.1);
        let target = tri.p[0] + b1 * (tri.p[1] - tri.p[0]) + b2 * (tri.p[2] - tri.p[0]);
        let ray = Ray::new(o, (target - o).normalize());
        let Some((u, v, t)) = moller_trumbore(&tri, &ray) else {
            continue;
        };
        let inside = u >= 0.0 && v >= 0.0 && u + v <= 1.0;
        let want = (inside && t > 0.0).then_some(t);
        let edge = [u, v, 1.0 - u - v].iter().any(|x| x.abs() < 1e-9) || t.abs() < 1e-9;
        let got = Shape::Triangle(tri.clone()).intersect(&ray, f64::INFINITY);
        if let Some((_, n)) = got {
            let want_n = (tri.p[1] - tri.p[0]).cross(tri.p[2] - tri.p[0]).normalize();
            assert!((n - want_n).length() < 1e-9);
            hits += 1;
        }
        agree += compare("triangle", got.map(|h| h.0), want, edge);
    }
    assert!(agree >= RAYS - 50, "only {agree} of {RAYS} agree");
    assert!(hits > RAYS / 5, "too few hits ({hits})");
}

#[test]
fn hit_points_lie_on_the_surface() {
    let mut rng = Rng::for_task(1, Stream::Test, 104);
    let shapes = [
        Shape::Sphere(Sphere { center: DVec3::new(0.3, -1.0, 2.0), radius: 1.7 }),
        Shape::Quad(Quad {
            origin: DVec3::new(-1.0, 0.5, 0.2),
            u: DVec3::new(2.0, 0.3, -0.4),
            v: DVec3::new(0.1, 1.5, 0.9),
        }),
        Shape::Disk(Disk { center: DVec3::new(0.5, 0.5, -0.5), normal: DVec3::new(1.0, 2.0, 3.0), radius: 1.5 }),
        Shape::Triangle(Triangle {
            p: [DVec3::new(-1.0, -1.0, 0.3), DVec3::new(2.0, -0.5, 0.1), DVec3::new(0.0, 2.0, -0.7)],
        }),
    ];
    for shape in &shapes {
        let mut hits = 0;
        for _ in 0..2000 {
            let target = shape.sample(rng.uniform2()).point;
            let o = target + 50.0 * random_dir(&mut rng);
            let ray = Ray::new(o, (target - o).normalize());
            let Some((t, n)) = shape.intersect(&ray, f64::INFINITY) else {
                continue;
            };
            hits += 1;
            let p = shape.hit_point(&ray, t);
            let off = match shape {
                Shape::Sphere(s) => (p - s.center).length() - s.radius,
                _ => n.dot(p - shape.sample([0.5, 0.5]).point),
            };
            assert!(off.abs() < 1e-13, "{shape:?}: hit point {off} off the surface");
        }
        assert!(hits > 1000, "{shape:?}: {hits} hits");
    }
}

// ---- uniform area sampling -------------------------------------------------------------------

const SAMPLES: usize = 200_000;

#[test]
fn sphere_samples_are_uniform_by_area() {
    let s = Sphere { center: DVec3::new(2.0, -3.0, 1.0), radius: 2.5 };
    let shape = Shape::Sphere(s.clone());
    let mut rng = Rng::for_task(2, Stream::Test, 0);
    let p = chi2_sphere(
        20,
        40,
        SAMPLES,
        || {
            let x = shape.sample(rng.uniform2());
            assert!(((x.point - s.center).length() - s.radius).abs() < 1e-12);
            assert!((x.normal - (x.point - s.center) / s.radius).length() < 1e-12);
            Some((x.point - s.center).normalize())
        },
        |_| 1.0 / (4.0 * PI),
    );
    assert!(p > 1e-3, "p = {p}");
}

/// Chi-square of points classified into `cells` against `weights`, via `classify`.
fn grid_chi2(weights: &[f64], seed: u64, mut classify: impl FnMut([f64; 2]) -> usize) -> f64 {
    let mut rng = Rng::for_task(3, Stream::Test, seed);
    chi2_discrete(weights, SAMPLES, || classify(rng.uniform2()))
}

fn cell(x: f64, y: f64, nx: usize, ny: usize) -> usize {
    let i = ((x * nx as f64) as usize).min(nx - 1);
    let j = ((y * ny as f64) as usize).min(ny - 1);
    i * ny + j
}

#[test]
fn quad_samples_are_uniform_by_area() {
    let q = Quad { origin: DVec3::new(1.0, 2.0, 3.0), u: DVec3::new(2.0, 0.5, 0.0), v: DVec3::new(-0.3, 1.0, 1.0) };
    let shape = Shape::Quad(q.clone());
    let n = q.u.cross(q.v).normalize();
    let p = grid_chi2(&[1.0; 100], 1, |u| {
        let s = shape.sample(u);
        assert!((s.normal - n).length() < 1e-12);
        // (a, b) from the point: o + 0·d = origin + a u + b v with d = n.
        let (a, b, h) = cramer(s.point, n, q.origin, q.u, q.v).expect("solvable");
        assert!(h.abs() < 1e-12, "off the plane by {h}");
        cell(a, b, 10, 10)
    });
    assert!(p > 1e-3, "p = {p}");
}

#[test]
fn disk_samples_are_uniform_by_area_and_a_wrong_sampler_is_rejected() {
    let d = Disk { center: DVec3::new(-1.0, 0.5, 2.0), normal: DVec3::new(0.3, -1.0, 0.2), radius: 1.5 };
    let n = d.normal.normalize();
    let e1 = n.cross(DVec3::X).normalize();
    let e2 = n.cross(e1);
    let shape = Shape::Disk(d.clone());
    // Uniform on the disk ⇔ (ρ²/R², φ/2π) uniform on the unit square.
    let classify = |p: DVec3| {
        let w = p - d.center;
        assert!(w.dot(n).abs() < 1e-12);
        let (x, y) = (w.dot(e1), w.dot(e2));
        let rho2 = (x * x + y * y) / (d.radius * d.radius);
        assert!(rho2 <= 1.0 + 1e-12);
        cell(rho2, y.atan2(x).rem_euclid(2.0 * PI) / (2.0 * PI), 10, 12)
    };
    let p = grid_chi2(&[1.0; 120], 2, |u| classify(shape.sample(u).point));
    assert!(p > 1e-3, "p = {p}");
    // Power check: radius uniform in [0, R] (not √u) must be rejected.
    let p_bad = grid_chi2(&[1.0; 120], 3, |u| {
        let (r, phi) = (d.radius * u[0], 2.0 * PI * u[1]);
        classify(d.center + r * (phi.cos() * e1 + phi.sin() * e2))
    });
    assert!(p_bad < 1e-6, "wrong sampler accepted: p = {p_bad}");
}

#[test]
fn triangle_samples_are_uniform_by_area_and_a_wrong_sampler_is_rejected() {
    let tri = Triangle { p: [DVec3::new(0.0, 1.0, 0.0), DVec3::new(3.0, 0.0, 1.0), DVec3::new(1.0, 2.0, -1.0)] };
    let (e1, e2) = (tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
    let n = e1.cross(e2).normalize();
    const N: usize = 12;
    // Cells of the (b1, b2) square: inside the triangle b1 + b2 ≤ 1 (weight 1), cut by the
    // diagonal (weight 1/2) or outside (0).
    let weights: Vec<f64> = (0..N * N)
        .map(|k| match (k / N + k % N + 1).cmp(&N) {
            std::cmp::Ordering::Less => 1.0,
            std::cmp::Ordering::Equal => 0.5,
            std::cmp::Ordering::Greater => 0.0,
        })
        .collect();
    let classify = |p: DVec3| {
        let (b1, b2, h) = cramer(p, n, tri.p[0], e1, e2).expect("solvable");
        assert!(h.abs() < 1e-12 && b1 >= -1e-12 && b2 >= -1e-12 && b1 + b2 <= 1.0 + 1e-12);
        cell(b1, b2, N, N)
    };
    let shape = Shape::Triangle(tri.clone());
    let p = grid_chi2(&weights, 4, |u| classify(shape.sample(u).point));
    assert!(p > 1e-3, "p = {p}");
    // Power check: b1 = u, b2 = v (1 − u) crowds the b1 → 1 corner.
    let p_bad = grid_chi2(&weights, 5, |u| classify(tri.p[0] + u[0] * e1 + u[1] * (1.0 - u[0]) * e2));
    assert!(p_bad < 1e-6, "wrong sampler accepted: p = {p_bad}");
}

#[test]
fn check_rejects_degenerate_shapes() {
    let bad = [
        Shape::Sphere(Sphere { center: DVec3::ZERO, radius: 0.0 }),
        Shape::Sphere(Sphere { center: DVec3::new(f64::NAN, 0.0, 0.0), radius: 1.0 }),
        Shape::Quad(Quad { origin: DVec3::ZERO, u: DVec3::X, v: 2.0 * DVec3::X }),
        Shape::Disk(Disk { center: DVec3::ZERO, normal: DVec3::ZERO, radius: 1.0 }),
        Shape::Disk(Disk { center: DVec3::ZERO, normal: DVec3::Z, radius: -1.0 }),
        Shape::Triangle(Triangle { p: [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X] }),
        Shape::Triangle(Triangle { p: [DVec3::ZERO, DVec3::X, DVec3::INFINITY] }),
    ];
    for s in &bad {
        assert!(s.check().is_err(), "{s:?} accepted");
        // Degenerate shapes never panic and never report hits with bad numbers.
        let hit = s.intersect(&Ray::new(DVec3::new(0.1, 0.1, 1.0), -DVec3::Z), f64::INFINITY);
        assert!(hit.is_none_or(|(t, _)| t.is_finite() && t > 0.0));
    }
    let good = Shape::Triangle(Triangle { p: [DVec3::ZERO, DVec3::X, DVec3::Y] });
    assert!(good.check().is_ok());
}

#[test]
fn a_sphere_touches_a_box_only_where_its_surface_passes_through() {
    use morgana::geometry::{Aabb, Sphere};
    let earth = Shape::Sphere(Sphere { center: DVec3::new(0.0, -6_371_000.0, 0.0), radius: 6_371_000.0 });
    let cube = |c: DVec3, h: f64| Aabb { min: c - DVec3::splat(h), max: c + DVec3::splat(h) };
    // Straddling the ground, wholly above it (10 km up), wholly inside (100 km down), and a
    // box beside the horizon 100 km away whose bottom (y = −700 m) stays above the ground there
    // (the surface is 785 m below y = 0 at that distance).
    assert!(earth.may_touch_box(&cube(DVec3::ZERO, 1.0)));
    assert!(!earth.may_touch_box(&cube(DVec3::new(0.0, 10_000.0, 0.0), 100.0)));
    assert!(!earth.may_touch_box(&cube(DVec3::new(0.0, -100_000.0, 0.0), 1000.0)));
    assert!(!earth.may_touch_box(&cube(DVec3::new(100_000.0, -650.0, 0.0), 50.0)));
    assert!(earth.may_touch_box(&cube(DVec3::new(100_000.0, -785.0, 0.0), 50.0)));
}
