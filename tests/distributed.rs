//! The distribution logic without MPI: the parts P ranks compute, put together the way the
//! distributed render puts them together, equal what one process computes — bit for bit.
//! (`scripts/test_mpi.sh` runs the same renders under `mpirun` with 1, 2 and 3 ranks.)

mod common;

use common::render_with;
use morgana::distributed::split::{dealt, dealt_index, share};
use morgana::distributed::{self, Comm, Schedule, assemble::IRRADIANCE_BLOCK};
use morgana::photon::PassSettings;
use morgana::photon::{self, MapKind};
use morgana::photon_map::{Estimator, IrradianceCache, Paths, PhotonMap, PhotonRecord};
use morgana::render::{RenderOptions, render_on};
use morgana::scene::{Scene, default_scene};

fn small_scene(photons: u64) -> Scene {
    let mut s = default_scene().expect("default scene");
    s.camera =
        morgana::geometry::Camera::new(s.camera.position, s.camera.look_at, s.camera.up, s.camera.fov_deg, 24, 20);
    s.integrator.spp = 1;
    s.integrator.gather_rays = 2;
    s.apply_overrides(Some(photons), Some(11));
    s
}

fn bits(r: &PhotonRecord) -> [u64; 11] {
    let v = |d: glam::DVec3| [d.x.to_bits(), d.y.to_bits(), d.z.to_bits()];
    let [a, b, c] = v(r.position);
    let [d, e, f] = v(r.dir);
    let [g, h, i] = v(r.normal);
    [a, b, c, d, e, f, g, h, i, r.wavelength_nm.to_bits(), r.power_w.to_bits()]
}

#[test]
fn rank_shares_of_the_batches_give_the_single_process_photons_in_order() {
    // 10 full batches and a short one.
    let scene = small_scene(10 * photon::BATCH + 123);
    for kind in [MapKind::Global, MapKind::Caustic] {
        let emitted = match kind {
            MapKind::Global => scene.integrator.photons,
            MapKind::Caustic => scene.integrator.caustic_photons,
        };
        let (whole, whole_stats) = photon::shoot(&scene.world, &PassSettings::of(&scene), kind, emitted, 11, &|_| {});
        assert!(!whole.surface.is_empty(), "{kind:?}: no photons stored");
        for ranks in [1, 2, 3, 4, 12] {
            let mut surface = Vec::new();
            let mut stats = Vec::new();
            for r in 0..ranks {
                let range = share(photon::batch_count(emitted), r, ranks);
                let (sink, st) =
                    photon::shoot_batches(&scene.world, &PassSettings::of(&scene), kind, emitted, 11, range, &|_| {});
                surface.extend(sink.surface);
                stats.push(st);
            }
            assert_eq!(surface.len(), whole.surface.len(), "{kind:?}, {ranks} ranks");
            assert!(surface.iter().zip(&whole.surface).all(|(a, b)| bits(a) == bits(b) && a.path == b.path));
            let total = distributed::photons::sum(&stats);
            assert_eq!((total.emitted, total.stored, total.missed), (emitted, whole_stats.stored, whole_stats.missed));
            assert_eq!(total.power_per_photon_w, whole_stats.power_per_photon_w);
            // Powers are summed in another order: equal to rounding.
            let rel =
                (total.absorbed_surface_w - whole_stats.absorbed_surface_w).abs() / whole_stats.absorbed_surface_w;
            assert!(rel < 1e-12, "absorbed power differs by {rel:e}");
        }
    }
}

/// Photon beams (`volume_estimate = "photon_beams"`): the ranks' shares of the batches, put
/// one after the other in rank order (what `assemble::photon_beams` does with the all-gather),
/// are the single process's beams bit for bit, and so is each beam sent over the wire.
#[test]
fn rank_shares_of_the_batches_give_the_single_process_photon_beams_in_order() {
    let toml = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/volume_caustic.toml"))
        .expect("the example")
        .replace("[integrator]\n", "[integrator]\nvolume_estimate = \"photon_beams\"\n");
    let scene = common::scene(&toml);
    let pass = PassSettings::of(&scene);
    assert!(pass.photon_beams, "the pass keeps photon beams");
    let emitted = 5 * photon::BATCH + 77;
    let (whole, _) = photon::shoot(&scene.world, &pass, MapKind::Global, emitted, 11, &|_| {});
    assert!(whole.beams.len() > 1000, "{} beams", whole.beams.len());
    let bits = |b: &morgana::photon_map::PhotonBeam| b.to_le_bytes();
    for ranks in [2, 3, 7] {
        let mut beams = Vec::new();
        for r in 0..ranks {
            let range = share(photon::batch_count(emitted), r, ranks);
            let (sink, _) = photon::shoot_batches(&scene.world, &pass, MapKind::Global, emitted, 11, range, &|_| {});
            let wire: Vec<u8> = sink.beams.iter().flat_map(|b| b.to_le_bytes()).collect();
            beams.extend(
                wire.chunks_exact(morgana::photon_map::PhotonBeam::BYTES)
                    .map(morgana::photon_map::PhotonBeam::from_le_bytes),
            );
        }
        assert_eq!(beams.len(), whole.beams.len(), "{ranks} ranks");
        assert!(beams.iter().zip(&whole.beams).all(|(a, b)| bits(a) == bits(b)), "{ranks} ranks");
    }
}

#[test]
fn maps_assembled_from_parts_equal_the_map_built_at_once() {
    let scene = small_scene(6 * photon::BATCH);
    let (sink, _) =
        photon::shoot(&scene.world, &PassSettings::of(&scene), MapKind::Global, scene.integrator.photons, 11, &|_| {});
    let whole = PhotonMap::build(&sink.surface);
    for ranks in [2, 3, 5] {
        // Split the records unevenly, as ranks' stored counts differ.
        let cut = |r: usize| sink.surface.len() * r * r / (ranks * ranks);
        let parts: Vec<&[PhotonRecord]> = (0..ranks).map(|r| &sink.surface[cut(r)..cut(r + 1)]).collect();
        let boxes: Vec<_> = parts.iter().map(|p| PhotonMap::bounds(p)).collect();
        let lo = boxes.iter().fold(glam::DVec3::INFINITY, |a, b| a.min(b.0));
        let hi = boxes.iter().fold(glam::DVec3::NEG_INFINITY, |a, b| a.max(b.1));
        let origin = PhotonMap::origin_for(lo, hi);
        assert_eq!(origin, whole.origin());
        let photons: Vec<_> = parts.iter().flat_map(|p| PhotonMap::encode(p, origin)).collect();
        let map = PhotonMap::from_photons(origin, photons);
        let bytes = |m: &PhotonMap| m.photons().iter().flat_map(|p| p.to_le_bytes()).collect::<Vec<u8>>();
        assert!(bytes(&map) == bytes(&whole), "{ranks} parts: kd-tree differs");
        assert_eq!(map.tree().depth(), whole.tree().depth());
    }
}

#[test]
fn irradiance_estimated_in_dealt_blocks_equals_the_whole_estimate() {
    let scene = small_scene(8 * photon::BATCH);
    let (sink, _) =
        photon::shoot(&scene.world, &PassSettings::of(&scene), MapKind::Global, scene.integrator.photons, 11, &|_| {});
    let map = PhotonMap::build(&sink.surface);
    let s = &scene.integrator;
    let est = Estimator {
        map: &map,
        k: s.k,
        max_radius: s.max_radius_m,
        filter: s.filter,
        bands: scene.bands,
        paths: Paths::All,
        scatter_rows: None,
        disc_share: None,
    };
    let stride = 4;
    let n = IrradianceCache::points(map.len(), stride) as u64;
    assert!(n > 2 * IRRADIANCE_BLOCK, "too few points ({n}) to deal blocks");
    let all: Vec<u32> = (0..n as u32).collect();
    let whole = IrradianceCache::estimate(&est, stride, &all);
    let nb = scene.bands.count;
    for ranks in [2, 3] {
        let mut values = vec![f32::NAN; whole.len()];
        for r in 0..ranks {
            let mine: Vec<u32> = dealt(n, IRRADIANCE_BLOCK, r, ranks).flatten().map(|i| i as u32).collect();
            let part = IrradianceCache::estimate(&est, stride, &mine);
            for (j, v) in part.chunks_exact(nb).enumerate() {
                let p = dealt_index(j as u64, IRRADIANCE_BLOCK, r, ranks) as usize;
                values[p * nb..][..nb].copy_from_slice(v);
            }
        }
        assert!(values.iter().zip(&whole).all(|(a, b)| a.to_bits() == b.to_bits()), "{ranks} ranks");
    }
    let cache = IrradianceCache::from_values(&est, stride, whole);
    assert_eq!(cache.len(), IrradianceCache::build(&est, stride).len());
}

#[test]
fn static_and_dynamic_schedules_give_the_same_image() {
    let scene = small_scene(20_000);
    let dynamic = render_with(&scene, 2);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("pool");
    let opts = distributed::Options { schedule: Schedule::Static, ..Default::default() };
    let stat = pool
        .install(|| {
            render_on(&Comm::local(), &scene, &RenderOptions { quiet: true, ..RenderOptions::default() }, &opts)
        })
        .expect("render")
        .expect("rank 0 has the image");
    let b = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert!(dynamic.image.data.iter().any(|v| *v > 0.0), "image is black");
    assert!(b(&dynamic.image.data) == b(&stat.image.data), "schedules give different images");
    assert_eq!(dynamic.stats.rays, stat.stats.rays);
    let d = stat.stats.distributed.as_ref().expect("distributed report");
    assert_eq!((d.ranks, d.per_rank[0].eye.rows), (1, 20));
}

#[test]
fn a_map_memory_limit_stops_the_render_with_a_clear_error() {
    let scene = small_scene(20_000);
    let opts = distributed::Options { map_memory: distributed::MapMemory::Limit(1000), ..Default::default() };
    let err = match render_on(&Comm::local(), &scene, &RenderOptions { quiet: true, ..RenderOptions::default() }, &opts)
    {
        Ok(_) => panic!("a 1000-byte budget was accepted"),
        Err(e) => e,
    };
    assert_eq!(err.exit_code(), 2);
    let msg = err.to_string();
    assert!(msg.contains("global photon map") && msg.contains("--max-map-memory"), "{msg}");
}
