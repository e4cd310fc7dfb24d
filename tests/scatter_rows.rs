//! A volume photon's scattering row (`photon_map::scatter_rows`) stands for the albedo and the
//! phase function a volume estimate would compute at the photon's place and wavelength: it must
//! give the very same numbers, so that caching it changes no output.
//!
//! `cargo test --release --test scatter_rows`

mod common;

use glam::DVec3;
use morgana::photon::{MapKind, PassSettings, shoot};
use morgana::photon_map::{Estimator, Neighbours, Paths, PhotonMap, ScatterRows};
use morgana::rng::{Rng, Stream};
use morgana::scene::{Scene, load_scene_str};
use std::path::Path;
use std::sync::Arc;

/// An example scene as shipped (its relative paths resolved from `examples/`).
fn example(name: &str) -> Scene {
    let path = format!("examples/{name}.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    load_scene_str(&text, Path::new(&path), Path::new("examples"), name).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Every kind of medium the examples hold: an ocean (a phase-function mixture of water and
/// particles, Raman and fluorescence), an atmosphere of constituents (air, ozone, haze), plain
/// Rayleigh air, a Henyey–Greenstein fog, a fluorescent glass. At random places (0–120 km up,
/// where the constituents' densities change), wavelengths over each scene's range and angles,
/// the row's albedo × phase equals the medium's own to the last bit.
#[test]
fn a_row_gives_the_albedo_and_phase_the_medium_gives() {
    let mut rng = Rng::for_task(7, Stream::Test, 0);
    let mut uniform = move || rng.uniform();
    let mut checked = 0;
    for name in ["underwater_luminaire", "sky_haze", "sky_noon", "fog_box", "fluorescent_glass_block", "sunset_fog"] {
        let s = example(name);
        let (lo, hi) = (s.bands.min_nm, s.bands.max_nm);
        for m in &s.world.media {
            let mut row = vec![f64::NAN; m.scatter_row_len()];
            for _ in 0..4000 {
                let p = DVec3::new(2e4 * (uniform() - 0.5), 1.2e5 * uniform() - 50.0, 2e4 * (uniform() - 0.5));
                let (l, cos) = (lo + (hi - lo) * uniform(), 2.0 * uniform() - 1.0);
                let at = m.at(p);
                at.write_scatter_row(l, &mut row);
                let own = at.albedo(l) * at.phase_eval(l, cos);
                let from_row = m.scattered_from_row(&row, l, cos);
                assert_eq!(from_row.to_bits(), own.to_bits(), "{name}, medium {}: at {p}, {l} nm, cos {cos}", m.name);
                checked += 1;
            }
        }
    }
    assert!(checked >= 6 * 4000);
}

/// The ocean's volume estimate with rows equals the one without, band for band and bit for
/// bit, at points across the lit water (the rows filled once, read by every query).
#[test]
fn an_estimate_with_rows_is_the_estimate_without() {
    let s = example("underwater_luminaire");
    let (sink, _) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 20_000, 1, &|_| {});
    let map = PhotonMap::build(&sink.volume);
    assert!(map.len() > 1000, "{} volume photons", map.len());
    let estimator = |scatter_rows| Estimator {
        map: &map,
        k: 50,
        max_radius: 0.5,
        filter: s.integrator.filter,
        bands: s.bands,
        paths: Paths::All,
        scatter_rows,
        disc_share: None,
    };
    let plain = estimator(None);
    let with_rows = estimator(Some(Arc::new(ScatterRows::new(s.world.media.len()))));
    let mut nb = Neighbours::default();
    let mut nonzero = 0;
    for i in 0..200 {
        let x = sink.volume[i * (sink.volume.len() / 200)].position + DVec3::new(0.01, -0.02, 0.03);
        let wo = DVec3::new(0.3, -0.8, 0.5).normalize();
        let (a, ra) = plain.volume_scattered(x, wo, (0, &s.world.media[0]), &mut nb);
        let (b, rb) = with_rows.volume_scattered(x, wo, (0, &s.world.media[0]), &mut nb);
        assert_eq!(ra.to_bits(), rb.to_bits());
        for (va, vb) in a.iter().zip(&b) {
            assert_eq!(va.to_bits(), vb.to_bits(), "at {x}: {a:?} against {b:?}");
        }
        nonzero += usize::from(a.iter().any(|v| *v > 0.0));
    }
    assert!(nonzero > 150, "only {nonzero} of 200 estimates saw light");
}
