//! BVH build time and ray throughput.
//!
//! `cargo bench --bench bvh` (add `-- --quick` for a short run). Scenes: a bumpy terrain height
//! field (a mesh as a scanner or DEM would give it) and a soup of random small triangles.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use morgana::geometry::{Bvh, DVec3, Ray, Shape, Triangle};
use morgana::rng::{Rng, Stream};
use morgana::sampling::uniform_sphere;
use std::hint::black_box;

/// A terrain of about `n` triangles over 1 km², heights of a few metres.
fn terrain(n: usize) -> Vec<Shape> {
    let k = ((n / 2) as f64).sqrt() as usize;
    let step = 1000.0 / k as f64;
    let height = |i: usize, j: usize| {
        let (x, z) = (i as f64 * step, j as f64 * step);
        3.0 * (x / 37.0).sin() * (z / 53.0).cos() + 0.5 * (x / 5.0 + z / 7.0).sin()
    };
    let v = |i: usize, j: usize| DVec3::new(i as f64 * step - 500.0, height(i, j), j as f64 * step - 500.0);
    let mut shapes = Vec::with_capacity(2 * k * k);
    for i in 0..k {
        for j in 0..k {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            shapes.push(Shape::Triangle(Triangle { p: [a, b, c] }));
            shapes.push(Shape::Triangle(Triangle { p: [a, c, d] }));
        }
    }
    shapes
}

/// `n` random triangles of ~1 m in a 100 m cube.
fn soup(n: usize) -> Vec<Shape> {
    let mut rng = Rng::for_task(1, Stream::Test, 0);
    let mut point = |h: f64| DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * (2.0 * h) - h;
    (0..n)
        .map(|_| {
            let c = point(50.0);
            Shape::Triangle(Triangle { p: [c, c + point(0.7), c + point(0.7)] })
        })
        .collect()
}

/// Rays from 1.5 m to 100 m above the terrain, mostly looking down at grazing to steep angles.
fn terrain_rays(n: usize) -> Vec<Ray> {
    let mut rng = Rng::for_task(2, Stream::Test, 0);
    (0..n)
        .map(|_| {
            let o =
                DVec3::new(800.0 * rng.uniform() - 400.0, 5.0 + 100.0 * rng.uniform(), 800.0 * rng.uniform() - 400.0);
            let mut d = uniform_sphere(rng.uniform2());
            d.y = -d.y.abs();
            Ray::new(o, d)
        })
        .collect()
}

fn soup_rays(n: usize) -> Vec<Ray> {
    let mut rng = Rng::for_task(3, Stream::Test, 0);
    (0..n)
        .map(|_| {
            let o = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 100.0 - 50.0;
            Ray::new(o, uniform_sphere(rng.uniform2()))
        })
        .collect()
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("bvh_build");
    group.sample_size(10);
    for (name, shapes) in
        [("terrain_100k", terrain(100_000)), ("terrain_1M", terrain(1_000_000)), ("soup_1M", soup(1_000_000))]
    {
        group.throughput(Throughput::Elements(shapes.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(name), &shapes, |b, s| b.iter(|| Bvh::build(black_box(s))));
    }
    group.finish();
}

fn trace(c: &mut Criterion) {
    let mut group = c.benchmark_group("bvh_rays");
    group.sample_size(10);
    const RAYS: usize = 100_000;
    for (name, shapes, rays) in
        [("terrain_1M", terrain(1_000_000), terrain_rays(RAYS)), ("soup_1M", soup(1_000_000), soup_rays(RAYS))]
    {
        let bvh = Bvh::build(&shapes);
        group.throughput(Throughput::Elements(RAYS as u64));
        group.bench_function(BenchmarkId::new("intersect", name), |b| {
            b.iter(|| rays.iter().filter(|r| bvh.intersect(&shapes, r, f64::INFINITY).is_some()).count())
        });
        group.bench_function(BenchmarkId::new("occluded", name), |b| {
            b.iter(|| rays.iter().filter(|r| bvh.occluded(&shapes, r, f64::INFINITY)).count())
        });
    }
    group.finish();
}

criterion_group!(benches, build, trace);
criterion_main!(benches);
