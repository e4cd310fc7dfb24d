//! The photon map: round trip of stored photons, queries against brute force, determinism.

use glam::DVec3;
use morgana::photon_map::{KdPoint, Neighbours, Photon, PhotonMap, PhotonPath, PhotonRecord};
use morgana::rng::{Rng, Stream};

fn angle_deg(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

fn uniform_dir(rng: &mut Rng) -> DVec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Photons in a box far from the world origin: half on its floor (with normals), half in the
/// volume. `power_w` is the record's index + 1 (exact in f32), to recognise it after reordering.
fn records(n: usize, seed: u64) -> (Vec<PhotonRecord>, DVec3, DVec3) {
    let mut rng = Rng::for_task(seed, Stream::Test, 0);
    let lo = DVec3::new(6.4e6, -2.0e3, 120.0);
    let size = DVec3::new(800.0, 300.0, 50.0);
    let recs = (0..n)
        .map(|i| {
            let u = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform());
            let surface = i % 2 == 0;
            let mut position = lo + u * size;
            if surface {
                position.z = lo.z;
            }
            PhotonRecord {
                position,
                dir: uniform_dir(&mut rng),
                normal: if surface { DVec3::Z } else { DVec3::ZERO },
                wavelength_nm: 360.0 + 470.0 * rng.uniform(),
                power_w: (i + 1) as f64,
                path: if i % 2 == 0 { PhotonPath::Direct } else { PhotonPath::Diffuse },
            }
        })
        .collect();
    (recs, lo, size)
}

#[test]
fn records_round_trip_within_stated_precision() {
    let (recs, _, size) = records(50_000, 1);
    let map = PhotonMap::build(&recs);
    assert_eq!(map.len(), recs.len());
    let mut seen = vec![false; recs.len()];
    for i in 0..map.len() as u32 {
        let got = map.record(i);
        let id = got.power_w as usize - 1;
        assert!(!seen[id], "record {id} stored twice");
        seen[id] = true;
        let want = &recs[id];
        let err = (got.position - want.position).abs();
        // Resolution ≈ extent × 6e-8; rounding errs by half of it.
        assert!(err.cmple(size * 3e-8).all(), "position error {err} for extent {size}");
        assert!(angle_deg(got.dir, want.dir) < 0.01);
        if want.normal == DVec3::ZERO {
            assert_eq!(got.normal, DVec3::ZERO);
        } else {
            assert!(angle_deg(got.normal, want.normal) < 0.01);
        }
        assert!((got.wavelength_nm - want.wavelength_nm).abs() < want.wavelength_nm * 6e-8);
        assert_eq!(got.power_w, want.power_w);
    }
    assert!(seen.iter().all(|&s| s));
}

#[test]
fn origin_is_the_centre_of_the_bounding_box() {
    let recs = [-3.0, 5.0, 1.0].map(|x| PhotonRecord {
        position: DVec3::new(x, 10.0 * x, -x),
        dir: DVec3::X,
        normal: DVec3::ZERO,
        wavelength_nm: 500.0,
        power_w: 1.0,
        path: PhotonPath::Diffuse,
    });
    let map = PhotonMap::build(&recs);
    assert_eq!(map.origin(), DVec3::new(1.0, 10.0, -1.0));
}

#[test]
fn knn_matches_brute_force_over_stored_photons() {
    let (recs, lo, size) = records(40_000, 2);
    let map = PhotonMap::build(&recs);
    let photons: Vec<Photon> = map.photons().to_vec();
    let mut rng = Rng::for_task(3, Stream::Test, 0);
    let mut out = Neighbours::default();
    for _ in 0..200 {
        let mut x = lo + DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * size;
        if rng.uniform() < 0.5 {
            x.z = lo.z + 0.01;
        }
        for (k, r) in [(1, 10.0), (50, 3.0), (100, 8.0), (100, 1e9), (500, 20.0)] {
            map.knn(x, k, r, &mut out);
            // Brute force in the map's f32 frame, as the tree computes it.
            let rel = x - map.origin();
            let q = [rel.x as f32, rel.y as f32, rel.z as f32];
            let r2 = (r * r) as f32;
            let mut d: Vec<f32> = photons
                .iter()
                .map(|p| {
                    let s = p.position();
                    let (dx, dy, dz) = (s[0] - q[0], s[1] - q[1], s[2] - q[2]);
                    dx * dx + dy * dy + dz * dz
                })
                .filter(|&d2| d2 <= r2)
                .collect();
            d.sort_by(f32::total_cmp);
            d.truncate(k);
            let mut got: Vec<f32> = out.items.iter().map(|e| e.1).collect();
            got.sort_by(f32::total_cmp);
            assert_eq!(got, d);
            // And the distances agree with the decoded f64 positions: photon and query are each
            // within extent × 3e-8 per axis of their f32 form.
            let tol = 2.0 * 3f64.sqrt() * size.max_element() * 3e-8;
            for &(i, d2) in &out.items {
                let exact = (map.record(i).position - x).length();
                let d = f64::from(d2).sqrt();
                assert!((d - exact).abs() <= tol + 1e-6 * exact, "{d} vs {exact}");
            }
        }
    }
}

#[test]
fn bad_queries_and_empty_maps_give_nothing() {
    let (recs, lo, _) = records(1000, 4);
    let map = PhotonMap::build(&recs);
    let mut out = Neighbours::default();
    map.knn(DVec3::new(f64::NAN, lo.y, lo.z), 10, 100.0, &mut out);
    assert!(out.is_empty());
    map.knn(lo, 10, f64::NAN, &mut out);
    assert!(out.is_empty());
    map.knn(lo, 10, -1.0, &mut out);
    assert!(out.is_empty());
    map.knn(lo, 0, 100.0, &mut out);
    assert!(out.is_empty());
    let empty = PhotonMap::build(&[]);
    assert!(empty.is_empty());
    assert_eq!(empty.origin(), DVec3::ZERO);
    empty.knn(lo, 10, f64::INFINITY, &mut out);
    assert!(out.is_empty());
}

#[test]
fn non_finite_records_are_dropped() {
    let (mut recs, _, _) = records(100, 5);
    recs[3].position.x = f64::NAN;
    recs[7].position.y = f64::INFINITY;
    let map = PhotonMap::build(&recs);
    assert_eq!(map.len(), 98);
    assert!(map.origin().is_finite());
}

#[test]
fn memory_is_32_bytes_per_photon_plus_nodes() {
    let (recs, _, _) = records(100_000, 6);
    let map = PhotonMap::build(&recs);
    let per_photon = map.memory_bytes() as f64 / map.len() as f64;
    assert!((32.0..33.0).contains(&per_photon), "{per_photon} bytes per photon");
}

#[test]
fn build_is_identical_for_one_and_two_threads() {
    let (recs, _, _) = records(200_000, 7);
    let build = |threads| {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| PhotonMap::build(&recs))
    };
    let (a, b) = (build(1), build(2));
    assert_eq!(a.origin(), b.origin());
    assert!(a.photons() == b.photons());
}
