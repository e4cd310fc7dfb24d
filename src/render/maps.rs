//! The photon pass as the renderer runs it: shoot, build the maps the effect plan asks for, and
//! precompute irradiance for final gathering.

use super::progress;
use super::stats::{MapReport, Phases};
use crate::photon::{self, MapKind};
use crate::photon_map::{Estimator, IrradianceCache, PhotonMap};
use crate::scene::{DirectLighting, Scene};
use std::time::Instant;

/// Every stride-th global photon gets a precomputed irradiance estimate (Christensen uses 4).
pub const IRRADIANCE_STRIDE: usize = 4;

/// The photon maps of a render.
#[derive(Default)]
pub struct Maps {
    pub global: Option<PhotonMap>,
    pub caustic: Option<PhotonMap>,
    pub irradiance: Option<IrradianceCache>,
}

/// Runs the photon passes the plan asks for.
pub fn build(scene: &Scene, quiet: bool, phases: &mut Phases, reports: &mut Vec<MapReport>) -> Maps {
    let s = &scene.integrator;
    let mut maps = Maps::default();
    if scene.plan.global_map.on {
        let store_direct = s.direct == DirectLighting::PhotonMap || s.final_gather;
        let kind = MapKind::Global { store_direct };
        let (map, report) = one_map(scene, kind, s.photons, "global", quiet, phases);
        reports.push(report);
        maps.global = Some(map);
    }
    if scene.plan.caustic_map.on {
        let (map, report) = one_map(scene, MapKind::Caustic, s.caustic_photons, "caustic", quiet, phases);
        reports.push(report);
        maps.caustic = Some(map);
    }
    if scene.plan.final_gather.on
        && let Some(global) = &maps.global
    {
        let t = Instant::now();
        let est = Estimator { map: global, k: s.k, max_radius: s.max_radius_m, filter: s.filter, bands: scene.bands };
        maps.irradiance = Some(IrradianceCache::build(&est, IRRADIANCE_STRIDE));
        phases.add("irradiance precompute", t);
    }
    maps
}

fn one_map(
    scene: &Scene,
    kind: MapKind,
    emitted: u64,
    name: &str,
    quiet: bool,
    phases: &mut Phases,
) -> (PhotonMap, MapReport) {
    let t = Instant::now();
    let pb = progress::bar(quiet, emitted, &format!("{name} photons"));
    let (records, stats) = photon::shoot(scene, kind, emitted, scene.integrator.seed, &|n| pb.inc(n));
    pb.finish_and_clear();
    let trace_s = phases.add(&format!("{name} photon tracing"), t);
    let t = Instant::now();
    let map = PhotonMap::build(&records);
    let build_s = phases.add(&format!("{name} map build"), t);
    let report = MapReport {
        map: name.to_string(),
        emitted,
        stored: map.len() as u64,
        memory_bytes: map.memory_bytes() as u64,
        trace_seconds: trace_s,
        build_seconds: build_s,
        stats,
    };
    (map, report)
}
