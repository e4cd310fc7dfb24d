//! The photon pass as the renderer runs it: shoot, build the maps the effect plan asks for, and
//! precompute irradiance for final gathering — on one rank or many ([`crate::distributed`]).

use super::progress;
use super::stats::{MapReport, Phases};
use crate::distributed::{self, Rank, assemble, photons::Shot};
use crate::error::Result;
use crate::photon::MapKind;
use crate::photon_map::{
    BeamMap, Estimator, IrradianceCache, Paths, PhotonBeamMap, PhotonMap, PhotonRecord, fold_record, tube_radii,
};
use crate::scene::VolumeEstimate;
use crate::scene::{IntegratorSettings, Scene};
use crate::timing::Span;
use rayon::prelude::*;

/// Every stride-th global photon gets a precomputed irradiance estimate (Christensen uses 4).
pub const IRRADIANCE_STRIDE: usize = 4;

/// The photon maps of a render.
#[derive(Default)]
pub struct Maps {
    /// Photons on diffuse surfaces (indirect light, or all light with `direct = "photon_map"`).
    pub global: Option<PhotonMap>,
    /// Photons that reached a diffuse surface through specular surfaces only.
    pub caustic: Option<PhotonMap>,
    /// Photons at interactions in participating media.
    pub volume: Option<PhotonMap>,
    /// The volume photons' gather discs, for the beam estimate (`volume_estimate = "beam"`).
    pub beam: Option<BeamMap>,
    /// The photons' flights through media as tubes (`volume_estimate = "photon_beams"`).
    pub photon_beams: Option<PhotonBeamMap>,
    /// Irradiance precomputed at global-map photons, for final gathering.
    pub irradiance: Option<IrradianceCache>,
}

/// Runs the photon passes the plan asks for with the settings `s` of one progressive pass (see
/// [`IntegratorSettings::for_pass`]), on every rank of `rank`'s comm: each rank shoots its
/// share of the batches and every rank assembles the whole maps (see [`crate::distributed`]).
/// Fails, on every rank, if a map would not fit in the rank's budget.
pub fn build(
    rank: &mut Rank,
    scene: &Scene,
    s: &IntegratorSettings,
    bars: progress::Bars,
    stop: crate::timing::Stop,
    phases: &mut Phases,
    reports: &mut Vec<MapReport>,
) -> Result<Maps> {
    let plan = &scene.plan;
    let mut maps = Maps::default();
    if plan.global_map.on || plan.volume_map.on {
        let mut shot = shoot(rank, scene, (MapKind::Global, s.seed), s.photons, "global", (bars, stop), phases);
        if plan.global_map.on {
            let (map, report) = build_map(rank, &shot.sink.surface, "global", s.photons, &shot, phases)?;
            reports.push(report);
            maps.global = Some(map);
        }
        if plan.volume_map.on {
            // Where the scene is symmetric about the sun's axis, every rank folds its own
            // photons (per photon, so the map is still independent of the rank count).
            let fold = crate::scene::symmetry::scene_fold(scene).ok();
            if let Some(f) = &fold {
                let t = Span::start();
                shot.sink.volume.par_iter_mut().for_each(|r| *r = fold_record(f, r));
                phases.add("volume photon folding", t);
            }
            let (map, report) = build_map(rank, &shot.sink.volume, "volume", s.photons, &shot, phases)?;
            let map = match fold {
                Some(f) => map.folded(f),
                None => map,
            };
            reports.push(report);
            if s.volume_estimate == VolumeEstimate::Beam {
                let t = Span::start();
                maps.beam = Some(BeamMap::build(&map, s.beam.k, s.beam.max_radius_m, s.beam.scale));
                phases.add("volume beam radii", t);
            }
            if s.volume_estimate == VolumeEstimate::PhotonBeams {
                // The camera's paths: under shadow rays without the light straight from the lights.
                let paths = if plan.shadow_rays.on { Paths::NotDirect } else { Paths::All };
                let beams = std::mem::take(&mut shot.sink.beams);
                let (beams, report) = photon_beams(rank, scene, paths, &map, beams, s, &shot, phases)?;
                reports.push(report);
                maps.photon_beams = Some(beams);
            }
            maps.volume = Some(map);
        }
    }
    if plan.caustic_map.on {
        let shot = shoot(rank, scene, (MapKind::Caustic, s.seed), s.caustic_photons, "caustic", (bars, stop), phases);
        let (map, report) = build_map(rank, &shot.sink.surface, "caustic", s.caustic_photons, &shot, phases)?;
        reports.push(report);
        maps.caustic = Some(map);
    }
    if plan.final_gather.on
        && let Some(global) = &maps.global
    {
        let est = Estimator {
            map: global,
            k: s.k,
            max_radius: s.max_radius_m,
            filter: s.filter,
            bands: scene.bands,
            paths: Paths::All,
            scatter_rows: None,
            disc_share: scene.disc_share(),
        };
        let (cache, gathered) = assemble::irradiance(rank.comm, &mut rank.budget, &est, IRRADIANCE_STRIDE)?;
        rank.report.irradiance_received_bytes += gathered.received_bytes;
        maps.irradiance = Some(cache);
        phases.push("irradiance precompute", gathered.compute);
        phases.push("irradiance gather", gathered.gather);
        phases.push("irradiance cache build", gathered.build);
    }
    Ok(maps)
}

/// This rank's share of a pass of `kind` seeded with `seed` (statistics summed over ranks), with
/// its time as "NAME photon tracing"; `(bars, stop)`: where progress shows, and when batches stop
/// being started.
fn shoot(
    rank: &mut Rank,
    scene: &Scene,
    (kind, seed): (MapKind, u64),
    emitted: u64,
    name: &str,
    (bars, stop): (progress::Bars, crate::timing::Stop),
    phases: &mut Phases,
) -> Shot {
    let batches = crate::photon::batch_count(emitted);
    progress::note(
        bars.quiet,
        rank.comm.size(),
        &format!("{name} photons: {batches} batches over {} ranks", rank.comm.size()),
    );
    let t = Span::start();
    let (_, mine) = distributed::photons::my_share(rank.comm, emitted);
    let pb = bars.bar(mine, &format!("{name} photons"));
    let shot = distributed::photons::shoot(rank.comm, scene, seed, stop, kind, emitted, name, &|n| pb.inc(n));
    pb.finish_and_clear();
    phases.add(&format!("{name} photon tracing"), t);
    rank.report.photons.push(shot.mine.clone());
    shot
}

/// The photon beams of this pass (`beams`, this rank's flights; every rank's gathered in batch
/// order, timed as "photon beam gather") with their tubes' radii from the volume map `points`
/// ([`tube_radii`]), timed as "photon beam radii" and "photon beam build". `paths`: which beams
/// camera paths read.
#[allow(clippy::too_many_arguments)]
fn photon_beams(
    rank: &mut Rank,
    scene: &Scene,
    paths: Paths,
    points: &PhotonMap,
    beams: Vec<crate::photon_map::PhotonBeam>,
    s: &IntegratorSettings,
    shot: &Shot,
    phases: &mut Phases,
) -> Result<(PhotonBeamMap, MapReport)> {
    let (beams, gather, received) = assemble::photon_beams(rank.comm, &mut rank.budget, beams)?;
    phases.push("photon beam gather", gather);
    rank.report.map_received_bytes += received;
    let t = Span::start();
    // Beams the camera's estimate never reads are not kept: straight from the light under
    // shadow rays, in a medium that re-emits nothing. The radii count them in the pass's length.
    let total_length_m: f64 = beams.iter().map(|b| b.length).sum();
    let beams: Vec<_> = beams
        .into_iter()
        .filter(|b| paths.accepts(b.path) || scene.world.media[b.medium as usize].inelastic.transfer.is_some())
        .collect();
    let radii = tube_radii(points, &beams, total_length_m, s.beam.k, s.beam.max_radius_m, s.beam.tube_scale);
    let n = crate::photon_map::piece_count(&beams, &radii);
    let bytes = (n * crate::photon_map::BYTES_PER_BEAM) as u64;
    rank.budget.reserve(rank.comm, &format!("the photon beams ({n} pieces of {} flights)", beams.len()), bytes)?;
    let (beams, radii) = crate::photon_map::pieces(beams, radii);
    phases.add("photon beam radii", t);
    let t = Span::start();
    let map = PhotonBeamMap::new(beams, radii);
    let build_s = phases.add("photon beam build", t);
    let report = map_report("photon beams", s.photons, (map.len(), map.memory_bytes()), shot, build_s);
    Ok((map, report))
}

/// The map of every rank's `records`, timed as "NAME map gather" (bounds, encoding, budget check
/// and all-gather) and "NAME map build" (the kd-tree).
fn build_map(
    rank: &mut Rank,
    records: &[PhotonRecord],
    name: &str,
    emitted: u64,
    shot: &Shot,
    phases: &mut Phases,
) -> Result<(PhotonMap, MapReport)> {
    let (map, gathered) = assemble::photon_map(rank.comm, &mut rank.budget, name, records)?;
    phases.push(&format!("{name} map gather"), gathered.gather);
    let build_s = phases.push(&format!("{name} map build"), gathered.build);
    rank.report.map_received_bytes += gathered.received_bytes;
    let report = map_report(name, emitted, (map.len(), map.memory_bytes()), shot, build_s);
    Ok((map, report))
}

/// The report of map `name` of `emitted` photons holding `(stored, memory_bytes)`, traced by
/// `shot` and built in `build_s` seconds.
fn map_report(
    name: &str,
    emitted: u64,
    (stored, memory_bytes): (usize, usize),
    shot: &Shot,
    build_s: f64,
) -> MapReport {
    MapReport {
        map: name.to_string(),
        emitted,
        stored: stored as u64,
        memory_bytes: memory_bytes as u64,
        trace_seconds: shot.mine.trace_seconds,
        build_seconds: build_s,
        stats: shot.stats.clone(),
    }
}
