//! Numerical robustness: the Earth as a sphere, rays leaving surfaces, watertight meshes.

use morgana::geometry::{Bvh, DVec3, Disk, Quad, Ray, Shape, Sphere, Triangle, spawn_origin};
use morgana::rng::{Rng, Stream};
use morgana::sampling::uniform_sphere;

const R_EARTH: f64 = 6.371e6;

fn earth() -> Shape {
    Shape::Sphere(Sphere { center: DVec3::new(0.0, -R_EARTH, 0.0), radius: R_EARTH })
}

/// A ray from height `h` above the north pole (0, h, 0) in the x–y plane, `below` radians
/// below the geometric horizon (negative: above it).
fn horizon_ray(h: f64, below: f64) -> Ray {
    let dip = (R_EARTH / (R_EARTH + h)).acos();
    let a = dip + below;
    Ray::new(DVec3::new(0.0, h, 0.0), DVec3::new(a.cos(), -a.sin(), 0.0))
}

/// Closed-form distance to the Earth along [`horizon_ray`] for `below` > 0. With
/// L = √((R+h)² − R²) the tangent length, the line passes the centre at D = (R+h) cos(dip+α),
/// and R − D = 2R sin²(α/2) + L sin α (no cancellation); t = (R+h) sin(dip+α) − √((R−D)(R+D)).
fn horizon_distance(h: f64, below: f64) -> f64 {
    let l = ((R_EARTH + h) * (R_EARTH + h) - R_EARTH * R_EARTH).sqrt();
    let dip = (R_EARTH / (R_EARTH + h)).acos();
    let r_minus_d = 2.0 * R_EARTH * (below / 2.0).sin().powi(2) + l * below.sin();
    let d = R_EARTH - r_minus_d;
    (R_EARTH + h) * (dip + below).sin() - (r_minus_d * (R_EARTH + d)).sqrt()
}

#[test]
fn earth_ray_from_two_metres_aimed_at_the_horizon() {
    let e = earth();
    let h = 2.0;
    let tangent_length = (2.0 * R_EARTH * h + h * h).sqrt(); // 5048.17 m
    // Aimed exactly at the horizon: found once, at the tangent point. Where along the ray a
    // grazing hit lies is ill-conditioned (a 1e-9 m change in the miss distance moves it by
    // √(2R·1e-9) ≈ 0.1 m), hence the 0.5 m tolerance.
    let ray = horizon_ray(h, 0.0);
    let (t, n) = e.intersect(&ray, f64::INFINITY).expect("horizon ray lost");
    assert!((t - tangent_length).abs() < 0.5, "t = {t}, want {tangent_length}");
    assert!(n.dot(ray.dir).abs() < 1e-4, "not tangent: n·d = {}", n.dot(ray.dir));
    assert_not_doubled(&e, &ray, t);
    // Slightly below the horizon: the closed form, to 1e-6 relative.
    for below in [1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let want = horizon_distance(h, below);
        let (t, _) = e
            .intersect(&horizon_ray(h, below), f64::INFINITY)
            .unwrap_or_else(|| panic!("lost {below} rad below the horizon"));
        assert!((t - want).abs() < 1e-6 * want, "{below}: t = {t}, want {want}");
    }
    // Slightly above: nothing (1e-7 rad above passes 5e-4 m over the ground).
    for above in [1e-7, 1e-6, 1e-3] {
        assert_eq!(e.intersect(&horizon_ray(h, -above), f64::INFINITY), None, "{above}");
    }
}

#[test]
fn earth_tangent_rays_are_found_once() {
    let e = earth();
    // Exactly representable: tangent at the pole from 1 km and 100 km away.
    for d in [1e3, 1e5] {
        let ray = Ray::new(DVec3::new(-d, 0.0, 0.0), DVec3::X);
        let (t, n) = e.intersect(&ray, f64::INFINITY).expect("tangent ray lost");
        assert!((t - d).abs() < 1e-9 * d, "t = {t}");
        assert!((n - DVec3::Y).length() < 1e-12);
        let p = e.hit_point(&ray, t);
        let on = Ray::new(e.spawn_origin(p, n, DVec3::X), DVec3::X);
        assert_eq!(e.intersect(&on, f64::INFINITY), None, "tangent hit doubled");
    }
    // Tangent at random points of the globe, 1 km before the tangent point: never lost, and
    // found within the conditioning of a grazing hit.
    let mut rng = Rng::for_task(7, Stream::Test, 1);
    let centre = DVec3::new(0.0, -R_EARTH, 0.0);
    for _ in 0..10_000 {
        let n = uniform_sphere(rng.uniform2());
        let tangent = n.cross(uniform_sphere(rng.uniform2())).normalize();
        let p = centre + R_EARTH * n;
        let ray = Ray::new(p - 1e3 * tangent, tangent);
        let (t, normal) = e.intersect(&ray, f64::INFINITY).unwrap_or_else(|| panic!("tangent ray at {n} lost"));
        assert!((t - 1e3).abs() < 0.5, "t = {t}");
        assert!((normal - n).length() < 1e-6);
        assert_not_doubled(&e, &ray, t);
    }
}

/// A grazing ray meets the sphere along at most the chord its rounding allows: a line passing
/// δ ≈ 1e-9 m inside the Earth runs 2√(2Rδ) ≈ 0.2 m inside. One metre past the reported hit,
/// the same line finds nothing more.
fn assert_not_doubled(e: &Shape, ray: &Ray, t: f64) {
    let beyond = Ray::new(ray.at(t + 1.0), ray.dir);
    assert_eq!(e.intersect(&beyond, f64::INFINITY), None, "grazing hit doubled: {ray:?}");
}

#[test]
fn earth_from_100_km() {
    let e = earth();
    let h = 1e5;
    let down = Ray::new(DVec3::new(0.0, h, 0.0), -DVec3::Y);
    let (t, n) = e.intersect(&down, f64::INFINITY).expect("nadir ray lost");
    assert!((t - h).abs() < 1e-6 * h, "t = {t}");
    assert!((n - DVec3::Y).length() < 1e-12);
    assert!(e.hit_point(&down, t).length() < 1e-6);
    // Oblique, at angle θ from the nadir: t = (R+h) cos θ − √(R² − (R+h)² sin² θ).
    for theta in [0.1f64, 0.5, 1.0, 1.2] {
        let dir = DVec3::new(theta.sin(), -theta.cos(), 0.0);
        let rh = R_EARTH + h;
        let want = rh * theta.cos() - (R_EARTH * R_EARTH - rh * rh * theta.sin().powi(2)).sqrt();
        let (t, _) = e.intersect(&Ray::new(DVec3::new(0.0, h, 0.0), dir), f64::INFINITY).expect("oblique ray lost");
        assert!((t - want).abs() < 1e-6 * want, "θ = {theta}: t = {t}, want {want}");
    }
    // To random ground points within 300 km of the pole (the horizon from 100 km is 1130 km).
    let mut rng = Rng::for_task(7, Stream::Test, 2);
    let centre = DVec3::new(0.0, -R_EARTH, 0.0);
    for _ in 0..10_000 {
        let phi = 2.0 * std::f64::consts::PI * rng.uniform();
        let angle = 3e5 / R_EARTH * rng.uniform().sqrt();
        let n = DVec3::new(angle.sin() * phi.cos(), angle.cos(), angle.sin() * phi.sin());
        let target = centre + R_EARTH * n;
        let o = DVec3::new(0.0, h, 0.0);
        let want = (target - o).length();
        let (t, _) = e.intersect(&Ray::new(o, (target - o) / want), f64::INFINITY).expect("lost");
        assert!((t - want).abs() < 1e-6 * want, "t = {t}, want {want}");
    }
}

#[test]
fn earth_just_above_the_surface() {
    let e = earth();
    let mut rng = Rng::for_task(7, Stream::Test, 3);
    for h in [1e-6, 1e-3, 1.0, 2.0] {
        let o = DVec3::new(0.0, h, 0.0);
        assert_eq!(e.intersect(&Ray::new(o, DVec3::Y), f64::INFINITY), None, "h = {h}");
        // Straight down: the height itself (f64 resolves heights to ~1e-9 m at this radius).
        let (t, _) = e.intersect(&Ray::new(o, -DVec3::Y), f64::INFINITY).expect("lost");
        assert!((t - h).abs() < 2e-9 + 1e-12 * h, "h = {h}: t = {t}");
        // Rising directions, down to grazing ones: no false hit.
        for k in 0..2000 {
            let horizontal = DVec3::new(rng.uniform() - 0.5, 0.0, rng.uniform() - 0.5).normalize();
            let rise = if k % 2 == 0 { rng.uniform() } else { 10f64.powf(-12.0 * rng.uniform()) };
            let dir = (horizontal + rise * DVec3::Y).normalize();
            let hit = e.intersect(&Ray::new(o, dir), f64::INFINITY);
            assert_eq!(hit, None, "h = {h}, rise {rise}: false hit");
        }
    }
}

// ---- rays leaving a surface ------------------------------------------------------------------

/// Double-double arithmetic (Dekker 1971) for reference roots.
#[derive(Clone, Copy, Debug)]
struct Dd(f64, f64);

impl Dd {
    fn from(x: f64) -> Dd {
        Dd(x, 0.0)
    }
    fn sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        let bb = s - a;
        Dd(s, (a - (s - bb)) + (b - bb))
    }
    fn add(self, o: Dd) -> Dd {
        let s = Dd::sum(self.0, o.0);
        let e = s.1 + self.1 + o.1;
        let hi = s.0 + e;
        Dd(hi, e - (hi - s.0))
    }
    fn neg(self) -> Dd {
        Dd(-self.0, -self.1)
    }
    fn mul(self, o: Dd) -> Dd {
        let p = self.0 * o.0;
        let e = self.0.mul_add(o.0, -p) + self.0 * o.1 + self.1 * o.0;
        let hi = p + e;
        Dd(hi, e - (hi - p))
    }
    fn sqrt(self) -> Dd {
        if self.0 <= 0.0 {
            return Dd::from(0.0);
        }
        let s = self.0.sqrt();
        let r = self.add(Dd::from(s).mul(Dd::from(s)).neg());
        Dd::sum(s, r.0 / (2.0 * s))
    }
    fn div(self, o: Dd) -> f64 {
        (self.0 + self.1) / (o.0 + o.1)
    }
}

fn dd_dot(a: [Dd; 3], b: [Dd; 3]) -> Dd {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

/// The far root of the ray with the sphere, in double-double: the exit point of a ray that
/// leaves the surface inward.
fn sphere_far_root(s: &Sphere, ray: &Ray) -> f64 {
    let f = [0, 1, 2].map(|i| Dd::sum(ray.origin[i], -s.center[i]));
    let d = [0, 1, 2].map(|i| Dd::from(ray.dir[i]));
    let a = dd_dot(d, d);
    let b = dd_dot(f, d);
    let c = dd_dot(f, f).add(Dd::from(s.radius).mul(Dd::from(s.radius)).neg());
    let disc = b.mul(b).add(a.mul(c).neg());
    b.neg().add(disc.sqrt()).div(a)
}

/// A direction leaving a surface with normal `n`: uniform on the sphere, or grazing at angle
/// 10^-k above or below the tangent plane, or exactly in it.
fn leaving_direction(rng: &mut Rng, n: DVec3) -> DVec3 {
    let tangent = n.cross(uniform_sphere(rng.uniform2())).normalize();
    match rng.below(4) {
        0 => uniform_sphere(rng.uniform2()),
        1 => tangent,
        k => {
            let angle = 10f64.powf(-16.0 * rng.uniform());
            let side = if k == 2 { 1.0 } else { -1.0 };
            (tangent * angle.cos() + n * side * angle.sin()).normalize()
        }
    }
}

fn spawn_shapes() -> Vec<Shape> {
    let big = 1e6;
    vec![
        Shape::Sphere(Sphere { center: DVec3::new(0.2, -0.3, 0.1), radius: 1.3 }),
        Shape::Sphere(Sphere { center: DVec3::new(3e-2, 1e-2, -2e-2), radius: 1e-2 }),
        earth(),
        Shape::Sphere(Sphere { center: DVec3::new(big, -2.0 * big, 0.5 * big), radius: 30.0 }),
        Shape::Quad(Quad {
            origin: DVec3::new(-1.0, -0.2, -1.0),
            u: DVec3::new(2.0, 0.3, 0.1),
            v: DVec3::new(0.2, 0.1, 2.0),
        }),
        // A tilted 10 km road around the origin.
        Shape::Quad(Quad {
            origin: DVec3::new(-5e3, -40.0, -5e3),
            u: DVec3::new(1e4, 30.0, 0.0),
            v: DVec3::new(0.0, 50.0, 1e4),
        }),
        Shape::Disk(Disk { center: DVec3::new(0.5, 0.2, -0.3), normal: DVec3::new(1.0, 2.0, -0.5), radius: 2.0 }),
        Shape::Disk(Disk { center: DVec3::new(big, 3.0, -big), normal: DVec3::new(0.1, 1.0, 0.3), radius: 5e3 }),
        Shape::Triangle(Triangle {
            p: [DVec3::new(-1.0, 0.1, -1.0), DVec3::new(2.0, -0.3, 0.0), DVec3::new(0.0, 0.4, 1.5)],
        }),
        Shape::Triangle(Triangle {
            p: [DVec3::new(-3e4, -20.0, -2e4), DVec3::new(4e4, 35.0, -1e4), DVec3::new(-1e4, 5.0, 5e4)],
        }),
        // A sliver: 1 m wide, 1 km long.
        Shape::Triangle(Triangle {
            p: [DVec3::new(-500.0, 0.0, 0.0), DVec3::new(500.0, 0.3, 0.2), DVec3::new(0.0, 1.0, 0.7)],
        }),
    ]
}

/// Rays spawned from surface points never find the surface they leave.
fn check_spawn(shape: &Shape, rays: usize, seed: u64, spawn: impl Fn(&Shape, DVec3, DVec3, DVec3) -> DVec3) {
    let mut rng = Rng::for_task(8, Stream::Test, seed);
    let mut far_hits = 0;
    for k in 0..rays {
        // Surface points from area samples and from hits of rays from afar.
        let (p, n) = if k % 2 == 0 {
            let s = shape.sample(rng.uniform2());
            (s.point, s.normal)
        } else {
            let target = shape.sample(rng.uniform2()).point;
            let from = target + 3.0 * shape.bounds().diagonal().length() * uniform_sphere(rng.uniform2());
            let ray = Ray::new(from, (target - from).normalize());
            let Some((t, n)) = shape.intersect(&ray, f64::INFINITY) else {
                continue;
            };
            (shape.hit_point(&ray, t), n)
        };
        let dir = leaving_direction(&mut rng, n);
        let ray = Ray::new(spawn(shape, p, n, dir), dir);
        let hit = shape.intersect(&ray, f64::INFINITY);
        match (shape, hit) {
            (_, None) => {}
            // Leaving a sphere inward, the ray must reach the far side, not the near one.
            (Shape::Sphere(s), Some((t, _))) if n.dot(dir) < 0.0 => {
                let want = sphere_far_root(s, &ray);
                assert!(
                    (t - want).abs() <= 0.05 * want,
                    "{shape:?}: re-hit at t = {t}, far side at {want} (n·d = {})",
                    n.dot(dir)
                );
                far_hits += 1;
            }
            (_, Some((t, _))) => panic!("{shape:?}: re-hit at t = {t} from {p}, n·d = {}", n.dot(dir)),
        }
    }
    if matches!(shape, Shape::Sphere(_)) {
        assert!(far_hits > rays / 8, "{shape:?}: only {far_hits} inward rays");
    }
}

#[test]
fn spawned_rays_never_hit_the_surface_they_leave() {
    for (i, shape) in spawn_shapes().iter().enumerate() {
        check_spawn(shape, 20_000, i as u64, |s, p, n, d| s.spawn_origin(p, n, d));
    }
}

#[test]
fn free_spawn_origin_suffices_for_shapes_away_from_the_origin() {
    // spawn_origin(p, n, dir) offsets by 128 ε |p|; that covers shapes whose coordinates are not
    // much larger than the points on them.
    let away = DVec3::new(7.0, -5.0, 6.0);
    let shapes = spawn_shapes().into_iter().filter(|s| s.error_scale() < 10.0).map(|s| match s {
        Shape::Sphere(x) => Shape::Sphere(Sphere { center: x.center + away, ..x }),
        Shape::Quad(x) => Shape::Quad(Quad { origin: x.origin + away, ..x }),
        Shape::Disk(x) => Shape::Disk(Disk { center: x.center + away, ..x }),
        Shape::Triangle(x) => Shape::Triangle(Triangle { p: x.p.map(|p| p + away) }),
    });
    for (i, shape) in shapes.enumerate() {
        check_spawn(&shape, 20_000, 100 + i as u64, |_, p, n, d| spawn_origin(p, n, d));
    }
}

// ---- watertightness --------------------------------------------------------------------------

/// An n × n grid of squares, each split into two triangles along alternating diagonals,
/// mapped by `to_world`; the triangles share edges and vertices exactly.
fn grid_mesh(n: usize, to_world: impl Fn(f64, f64) -> DVec3) -> (Vec<Triangle>, Vec<Vec<DVec3>>) {
    let v: Vec<Vec<DVec3>> =
        (0..=n).map(|i| (0..=n).map(|j| to_world(i as f64 / n as f64, j as f64 / n as f64)).collect()).collect();
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (v[i][j], v[i + 1][j], v[i + 1][j + 1], v[i][j + 1]);
            if (i + j) % 2 == 0 {
                tris.push(Triangle { p: [a, b, c] });
                tris.push(Triangle { p: [a, c, d] });
            } else {
                tris.push(Triangle { p: [a, b, d] });
                tris.push(Triangle { p: [b, c, d] });
            }
        }
    }
    (tris, v)
}

/// Interior targets of the grid: vertices exactly, and points on interior edges.
fn edge_and_vertex_targets(rng: &mut Rng, v: &[Vec<DVec3>], count: usize) -> Vec<DVec3> {
    let n = v.len() - 1;
    (0..count)
        .map(|k| {
            let (i, j) = (1 + rng.below(n as u64 - 1) as usize, 1 + rng.below(n as u64 - 1) as usize);
            let s = rng.uniform();
            match k % 4 {
                0 => v[i][j],
                1 => v[i][j] + s * (v[i + 1][j] - v[i][j]),
                2 => v[i][j] + s * (v[i][j + 1] - v[i][j]),
                // The diagonals of squares (i, j) and (i − 1, j − 1) alternate; both are edges.
                _ if (i + j) % 2 == 0 => v[i][j] + s * (v[i + 1][j + 1] - v[i][j]),
                _ => v[i + 1][j] + s * (v[i][j + 1] - v[i + 1][j]),
            }
        })
        .collect()
}

/// Rays from `distance` away through interior edges and vertices, in directions with
/// |d·axis| ≥ `min_cos` (keeping rays off silhouettes of a curved mesh, where a ray passing just
/// outside a fold rightly misses).
fn watertight_case(seed: u64, to_world: impl Fn(f64, f64) -> DVec3, distance: f64, axis: DVec3, min_cos: f64) {
    let (tris, v) = grid_mesh(6, to_world);
    let shapes: Vec<Shape> = tris.into_iter().map(Shape::Triangle).collect();
    let bvh = Bvh::build(&shapes);
    let mut rng = Rng::for_task(9, Stream::Test, seed);
    let n = (v[1][0] - v[0][0]).cross(v[0][1] - v[0][0]).normalize();
    for target in edge_and_vertex_targets(&mut rng, &v, 20_000) {
        // From either side, at any angle down to grazing (10⁻⁶ rad).
        let mut dir = uniform_sphere(rng.uniform2());
        while dir.dot(axis).abs() < min_cos {
            dir = uniform_sphere(rng.uniform2());
        }
        if dir.dot(n).abs() < 1e-6 {
            dir = (dir + 1e-6 * n).normalize();
        }
        let o = target - distance * dir;
        let ray = Ray::new(o, dir);
        let found = shapes.iter().any(|s| s.intersect(&ray, f64::INFINITY).is_some());
        assert!(found, "ray through {target} lost by every triangle");
        assert!(bvh.intersect(&shapes, &ray, f64::INFINITY).is_some(), "BVH lost ray through {target}");
        assert!(bvh.occluded(&shapes, &ray, f64::INFINITY), "BVH occlusion lost ray through {target}");
    }
}

#[test]
fn rays_through_shared_edges_and_vertices_are_never_lost() {
    // The unit square in the x–y plane.
    watertight_case(1, |a, b| DVec3::new(a, b, 0.0), 3.0, DVec3::Z, 0.0);
    // Tilted and far from the origin, seen from 10 km.
    let (u, v) = (DVec3::new(3.0, 1.0, -2.0), DVec3::new(-1.0, 2.5, 0.7));
    watertight_case(2, move |a, b| DVec3::new(4e5, 1e3, -7e5) + a * u + b * v, 1e4, DVec3::Z, 0.0);
    // A curved height field y = 10 (a² − b²) over 100 m (slopes ≤ 0.2), seen from 1 m along
    // directions steeper than its slopes.
    let bent = |a: f64, b: f64| DVec3::new(100.0 * a, 10.0 * (a * a - b * b), 100.0 * b);
    watertight_case(3, bent, 1.0, DVec3::Y, 0.5);
}

#[test]
fn sphere_origins_on_the_surface_need_no_offset() {
    // The root within rounding error of t = 0 is refused, so from c + r n (rounded) an outward
    // ray finds nothing and an inward one finds the far side, at Earth scale and at 1 m.
    let mut rng = Rng::for_task(10, Stream::Test, 0);
    for (centre, r) in [(DVec3::new(0.0, -R_EARTH, 0.0), R_EARTH), (DVec3::new(0.3, 0.2, -0.1), 1.0)] {
        let s = Sphere { center: centre, radius: r };
        let shape = Shape::Sphere(s.clone());
        for _ in 0..20_000 {
            let n = uniform_sphere(rng.uniform2());
            let p = centre + r * n;
            let mut d = uniform_sphere(rng.uniform2());
            if d.dot(n).abs() < 1e-3 {
                continue;
            }
            if rng.uniform() < 0.5 {
                d = -d;
            }
            let ray = Ray::new(p, d);
            match shape.intersect(&ray, f64::INFINITY) {
                None => assert!(d.dot(n) > 0.0, "inward ray from {p} found nothing"),
                Some((t, _)) => {
                    assert!(d.dot(n) < 0.0, "outward ray from the surface hit it at t = {t}");
                    let chord = -2.0 * r * d.dot(n);
                    assert!((t - chord).abs() < 1e-6 * chord, "t = {t}, chord {chord}");
                }
            }
        }
    }
}

#[test]
fn small_sphere_seen_from_afar() {
    // r = 1 mm from 100 km: the textbook discriminant b² − 4ac cancels completely here
    // (b² ≈ 4e10, 4ac differs from it by 4e-6). Reference: closest approach in double-double.
    let mut rng = Rng::for_task(10, Stream::Test, 1);
    let s = Sphere { center: DVec3::new(3.0, 2.0, -1.0), radius: 1e-3 };
    let shape = Shape::Sphere(s.clone());
    let (mut hits, mut misses) = (0, 0);
    for _ in 0..20_000 {
        let o = s.center + 1e5 * uniform_sphere(rng.uniform2());
        let aim = s.center + 2.0 * s.radius * (uniform_sphere(rng.uniform2()) * rng.uniform());
        let ray = Ray::new(o, (aim - o).normalize());
        let l = [0, 1, 2].map(|i| Dd::sum(s.center[i], -o[i]));
        let d = [0, 1, 2].map(|i| Dd::from(ray.dir[i]));
        let (a, tca) = (dd_dot(d, d), dd_dot(l, d));
        // d² = |l|² − (l·d)²/a; the hit is at (l·d − √(r² a − (|l|² a − (l·d)²)))/a.
        let miss2 = dd_dot(l, l).mul(a).add(tca.mul(tca).neg());
        let r2a = Dd::from(s.radius).mul(Dd::from(s.radius)).mul(a);
        let gap = r2a.add(miss2.neg());
        let got = shape.intersect(&ray, f64::INFINITY).map(|h| h.0);
        if gap.0.abs() < 1e-6 * r2a.0 {
            continue; // within 1e-6 of tangency: either answer
        }
        if gap.0 < 0.0 {
            assert_eq!(got, None, "false hit");
            misses += 1;
        } else {
            let want = tca.add(gap.sqrt().neg()).div(a);
            let t = got.unwrap_or_else(|| panic!("lost a hit at {want}"));
            assert!((t - want).abs() < 1e-12 * want, "t = {t}, want {want}");
            hits += 1;
        }
    }
    assert!(hits > 1000 && misses > 1000, "{hits} hits, {misses} misses");
}
