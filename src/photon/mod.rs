//! The photon pass: emission, tracing with Russian roulette, and the storage rules of each map.
//!
//! Photons are emitted in proportion to light power, each with one wavelength drawn from its
//! light's spectrum; refraction with dispersion then separates colours by itself. Work is split
//! into fixed batches whose random streams derive from (seed, map, batch), so the photon set is
//! identical for any thread count.

mod emit;
pub mod inelastic;
mod targeting;
mod trace;

pub use emit::LightChooser;
pub use targeting::CausticTargets;
pub use trace::{MapKind, PhotonSink, PhotonStats};

use crate::ode::CurvedSettings;
use crate::raypath::Propagator;
use crate::rng::{Rng, Stream};
use crate::scene::Scene;
use crate::world::World;
use rayon::prelude::*;

/// What a photon pass needs besides the world: the effect plan's decisions and the run's
/// settings.
#[derive(Clone, Copy, Debug)]
pub struct PassSettings<'a> {
    /// How curved paths are followed (`None`: the plan keeps every path straight).
    pub curved: Option<&'a CurvedSettings>,
    /// Whether photons are stored in media (the plan's volume map).
    pub volume_map: bool,
    /// Whether sensors read photons from the volume map (then absorbing-only media keep them).
    pub photon_sensors: bool,
    /// Whether each photon's flights through media are kept as photon beams as well
    /// (`volume_estimate = "photon_beams"`, with the volume map).
    pub photon_beams: bool,
    /// The wavelengths simulated, nm; light re-emitted outside them is absorbed.
    pub range_nm: (f64, f64),
    /// Whether photons cross a layered upper air in one move ([`crate::raypath::shell`]) where
    /// the scene has one and no sensor counts photons (on unless a test compares the two).
    pub layered_shell: bool,
    /// When the run must stop (time budget, cancel flag): batches not started by then are
    /// skipped (and counted in [`PhotonStats::stopped_batches`]).
    pub deadline: crate::timing::Stop<'a>,
}

impl<'a> PassSettings<'a> {
    /// The settings of `scene`'s photon passes.
    pub fn of(scene: &'a Scene) -> PassSettings<'a> {
        PassSettings {
            curved: scene.curved(),
            volume_map: scene.plan.volume_map.on,
            photon_sensors: !scene.sensors.is_empty(),
            photon_beams: scene.plan.volume_map.on
                && scene.integrator.volume_estimate == crate::scene::VolumeEstimate::PhotonBeams,
            range_nm: (scene.bands.min_nm, scene.bands.max_nm),
            layered_shell: true,
            deadline: crate::timing::Stop::default(),
        }
    }
}

/// Photons per batch (one random stream each).
pub const BATCH: u64 = 4096;

/// Batches traced together per worker thread before their photons are appended to the pass's.
pub const GROUP_BATCHES_PER_THREAD: usize = 8;

/// Emits `emitted` photons for a map of `kind` and returns the stored photons (surface and
/// volume, in batch order) and the pass's statistics. `on_batch` is called after each batch
/// with its photon count.
pub fn shoot(
    world: &World,
    pass: &PassSettings,
    kind: MapKind,
    emitted: u64,
    seed: u64,
    on_batch: &(dyn Fn(u64) + Sync),
) -> (PhotonSink, PhotonStats) {
    shoot_batches(world, pass, kind, emitted, seed, 0..batch_count(emitted), on_batch)
}

/// Photons stored per photon emitted in a pass of `kind`, on surfaces and in media, and photon
/// beams kept per photon (where the pass keeps them): measured by tracing the pass's first batch
/// (its first [`BATCH`] photons, the same ones the pass itself traces), for estimating a run's
/// memory before it allocates its maps.
pub fn pilot(world: &World, pass: &PassSettings, kind: MapKind, emitted: u64, seed: u64) -> (f64, f64, f64) {
    let n = batch_photons(emitted, 0);
    if n == 0 {
        return (0.0, 0.0, 0.0);
    }
    let (sink, _) = shoot_batches(world, pass, kind, emitted, seed, 0..1, &|_| {});
    let per = |len: usize| len as f64 / n as f64;
    (per(sink.surface.len()), per(sink.volume.len()), per(sink.beams.len()))
}

/// How many batches a pass of `emitted` photons has (the last one may be short).
pub fn batch_count(emitted: u64) -> u64 {
    emitted.div_ceil(BATCH)
}

/// Photons in batch `b` of a pass of `emitted` photons.
pub fn batch_photons(emitted: u64, b: u64) -> u64 {
    BATCH.min(emitted.saturating_sub(b * BATCH))
}

/// Shoots only batches `batches` (within `0..batch_count(emitted)`) of a pass of `emitted`
/// photons: each photon carries the power of the whole pass's share and each batch its own
/// random stream, so the union of the photons of disjoint ranges covering every batch, in batch
/// order, is what [`shoot`] returns. `stats.emitted` counts the photons of these batches.
#[allow(clippy::too_many_arguments)]
pub fn shoot_batches(
    world: &World,
    pass: &PassSettings,
    kind: MapKind,
    emitted: u64,
    seed: u64,
    batches: std::ops::Range<u64>,
    on_batch: &(dyn Fn(u64) + Sync),
) -> (PhotonSink, PhotonStats) {
    let batches = batches.start.min(batch_count(emitted))..batches.end.min(batch_count(emitted));
    let here = batches.clone().map(|b| batch_photons(emitted, b)).sum();
    let mut stats = PhotonStats { emitted: here, inelastic: inelastic::tallies(world), ..PhotonStats::default() };
    let Some(chooser) = LightChooser::new(&world.lights) else { return (PhotonSink::default(), stats) };
    let targets = match kind {
        MapKind::Caustic => match CausticTargets::new(world) {
            Some(t) => Some(t),
            None => return (PhotonSink::default(), stats),
        },
        MapKind::Global => None,
    };
    let power = chooser.total_power_w() / emitted.max(1) as f64;
    stats.power_per_photon_w = power;
    let prop = Propagator::new(world, pass.curved);
    // A sensor that counts photons keeps those absorbed in media: none may skip the air.
    let prop = if pass.layered_shell && !pass.photon_sensors { prop.with_layered_shell(pass.range_nm) } else { prop };
    let stream = match kind {
        MapKind::Caustic => Stream::CausticPhotons,
        MapKind::Global => Stream::GlobalPhotons,
    };
    // Each batch traces into a reused scratch sink (its vectors grow once per worker, not once
    // per batch) and returns an exact-size copy.
    let trace_batch = |out: &mut PhotonSink, b: u64| {
        if pass.deadline.reached() {
            return (PhotonSink::default(), PhotonStats { stopped_batches: 1, ..PhotonStats::default() });
        }
        let mut rng = Rng::for_task(seed, stream, b);
        let n = batch_photons(emitted, b);
        out.surface.clear();
        out.volume.clear();
        out.beams.clear();
        let mut st = PhotonStats::default();
        for _ in 0..n {
            let (l, _) = chooser.choose(rng.uniform());
            let (em, factor) = match &targets {
                Some(t) => t.emit(&world.lights[l], &mut rng),
                None => (world.lights[l].emit(&mut rng), 1.0),
            };
            if factor > 0.0 {
                let medium = world.light_media[l];
                trace::trace(world, pass, &prop, &em, medium, power * factor, kind, &mut rng, out, &mut st);
            } else {
                st.missed += 1;
            }
        }
        on_batch(n);
        (PhotonSink { surface: out.surface.clone(), volume: out.volume.clone(), beams: out.beams.clone() }, st)
    };
    // Batches are traced a group at a time and their photons appended in batch order, so the
    // pass holds its records once plus one group's and the workers' scratch (not every batch's
    // records and their concatenation), as the memory estimate (render::memory) assumes.
    let group = (GROUP_BATCHES_PER_THREAD * rayon::current_num_threads()) as u64;
    let mut sink = PhotonSink::default();
    let mut start = batches.start;
    while start < batches.end {
        let end = batches.end.min(start + group);
        let results: Vec<(PhotonSink, PhotonStats)> =
            (start..end).into_par_iter().map_init(PhotonSink::default, trace_batch).collect();
        let (surface, volume) =
            (results.iter().map(|r| r.0.surface.len()).sum(), results.iter().map(|r| r.0.volume.len()).sum());
        let beams: usize = results.iter().map(|r| r.0.beams.len()).sum();
        if start == batches.start {
            // Room for the whole pass as its first group predicts it (5 % over), in one
            // allocation: growing by each group reallocated the records as often as there were
            // groups, and a reallocation that copies holds the old and new buffers at once (the
            // measured peak of glass_caustic_hero varied by 12 MB from run to run).
            let scale = (batches.end - batches.start) as f64 / (end - start) as f64 * 1.05;
            sink.surface.reserve_exact((surface as f64 * scale).ceil() as usize);
            sink.volume.reserve_exact((volume as f64 * scale).ceil() as usize);
            sink.beams.reserve_exact((beams as f64 * scale).ceil() as usize);
        } else {
            sink.surface.reserve(surface);
            sink.volume.reserve(volume);
            sink.beams.reserve(beams);
        }
        for (p, s) in results {
            sink.surface.extend(p.surface);
            sink.volume.extend(p.volume);
            sink.beams.extend(p.beams);
            stats.add(&s);
        }
        start = end;
    }
    stats.curved = prop.work.totals();
    (sink, stats)
}
