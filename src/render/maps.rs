//! The photon pass as the renderer runs it: shoot, build the maps the effect plan asks for, and
//! precompute irradiance for final gathering.

use super::progress;
use super::stats::{MapReport, Phases};
use crate::photon::{self, MapKind, PhotonStats};
use crate::photon_map::{Estimator, IrradianceCache, Paths, PhotonMap, PhotonRecord};
use crate::scene::Scene;
use std::time::Instant;

/// Every stride-th global photon gets a precomputed irradiance estimate (Christensen uses 4).
pub const IRRADIANCE_STRIDE: usize = 4;

/// The photon maps of a render.
#[derive(Default)]
pub struct Maps {
    pub global: Option<PhotonMap>,
    pub caustic: Option<PhotonMap>,
    pub volume: Option<PhotonMap>,
    pub irradiance: Option<IrradianceCache>,
}

/// Runs the photon passes the plan asks for.
pub fn build(scene: &Scene, quiet: bool, phases: &mut Phases, reports: &mut Vec<MapReport>) -> Maps {
    let s = &scene.integrator;
    let plan = &scene.plan;
    let mut maps = Maps::default();
    if plan.global_map.on || plan.volume_map.on {
        let (sink, stats, trace_s) = shoot(scene, MapKind::Global, s.photons, "global", quiet, phases);
        if plan.global_map.on {
            let (map, report) = build_map(&sink.surface, "global", s.photons, trace_s, &stats, phases);
            reports.push(report);
            maps.global = Some(map);
        }
        if plan.volume_map.on {
            let (map, report) = build_map(&sink.volume, "volume", s.photons, trace_s, &stats, phases);
            reports.push(report);
            maps.volume = Some(map);
        }
    }
    if plan.caustic_map.on {
        let (sink, stats, trace_s) = shoot(scene, MapKind::Caustic, s.caustic_photons, "caustic", quiet, phases);
        let (map, report) = build_map(&sink.surface, "caustic", s.caustic_photons, trace_s, &stats, phases);
        reports.push(report);
        maps.caustic = Some(map);
    }
    if plan.final_gather.on
        && let Some(global) = &maps.global
    {
        let t = Instant::now();
        let est = Estimator {
            map: global,
            k: s.k,
            max_radius: s.max_radius_m,
            filter: s.filter,
            bands: scene.bands,
            paths: Paths::All,
        };
        maps.irradiance = Some(IrradianceCache::build(&est, IRRADIANCE_STRIDE));
        phases.add("irradiance precompute", t);
    }
    maps
}

fn shoot(
    scene: &Scene,
    kind: MapKind,
    emitted: u64,
    name: &str,
    quiet: bool,
    phases: &mut Phases,
) -> (photon::PhotonSink, PhotonStats, f64) {
    let t = Instant::now();
    let pb = progress::bar(quiet, emitted, &format!("{name} photons"));
    let (sink, stats) = photon::shoot(scene, kind, emitted, scene.integrator.seed, &|n| pb.inc(n));
    pb.finish_and_clear();
    let seconds = phases.add(&format!("{name} photon tracing"), t);
    (sink, stats, seconds)
}

fn build_map(
    records: &[PhotonRecord],
    name: &str,
    emitted: u64,
    trace_s: f64,
    stats: &PhotonStats,
    phases: &mut Phases,
) -> (PhotonMap, MapReport) {
    let t = Instant::now();
    let map = PhotonMap::build(records);
    let build_s = phases.add(&format!("{name} map build"), t);
    let report = MapReport {
        map: name.to_string(),
        emitted,
        stored: map.len() as u64,
        memory_bytes: map.memory_bytes() as u64,
        trace_seconds: trace_s,
        build_seconds: build_s,
        stats: stats.clone(),
    };
    (map, report)
}
