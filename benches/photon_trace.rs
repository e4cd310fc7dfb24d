//! Photon tracing and a small end-to-end render of a scene with a participating medium and no
//! inelastic component (examples/fog_box.toml), on one thread: the cost the inelastic machinery
//! must not add when no medium is inelastic (goal ≤ 5%).
//!
//! `cargo bench --bench photon_trace`; `scripts/bench_overhead.sh` runs it on the
//! commit before the inelastic code and on this one and prints criterion's change.

use criterion::{Criterion, criterion_group, criterion_main};
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::render::{RenderOptions, render};
use morgana::scene::load_scene_file;
use std::hint::black_box;
use std::path::Path;

fn fog_box() -> morgana::scene::Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/fog_box.toml");
    match load_scene_file(&path) {
        Ok(s) => s,
        Err(e) => panic!("{}: {e}", path.display()),
    }
}

fn photon_pass(c: &mut Criterion) {
    let scene = fog_box();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("one-thread pool");
    let mut group = c.benchmark_group("no_inelastic");
    group.sample_size(20);
    group.bench_function("fog_box_photons_100k", |b| {
        b.iter(|| {
            pool.install(|| {
                black_box(
                    shoot(&scene.world, &PassSettings::of(&scene), MapKind::Global, 100_000, 1, &|_| {})
                        .1
                        .stored_volume,
                )
            })
        })
    });
    let mut small = fog_box();
    small.camera.width = 32;
    small.camera.height = 32;
    small.integrator.spp = 1;
    small.integrator.gather_rays = 4;
    small.apply_overrides(Some(50_000), None);
    group.bench_function("fog_box_render_32px_50k", |b| {
        b.iter(|| {
            pool.install(|| {
                black_box(render(&small, &RenderOptions { quiet: true, ..RenderOptions::default() }).image.data[0])
            })
        })
    });
    group.finish();
}

criterion_group!(benches, photon_pass);
criterion_main!(benches);
