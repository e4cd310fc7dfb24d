//! The memory a render will need, estimated before it allocates its photon maps, and checked
//! against a limit (`--max-memory`, default: what the machine has available).
//!
//! The photons a pass stores are not known before it runs; a pilot of the pass's first batch
//! ([`crate::photon::pilot`]) measures how many each emitted photon leaves on surfaces and in
//! media, and the estimate scales that to the whole pass. With `N` photons a pass stores (on this
//! rank: its share of the batches), `n` those of one map over all ranks, `B` bands and a `W × H`
//! image, the resident memory at each phase's peak is modelled as
//!
//! ```text
//!   scene        the process's resident memory after loading the scene and the pilot
//!   tracing      96·N (the traced records) + 96·N_later (the largest group of batches after
//!                the first, 8 per thread; see `photon::shoot_batches`; one batch if the pass
//!                is one group) + 2 · 96·N_batch per thread (each worker's scratch, grown by
//!                doubling)
//!   map build    96·N (records still held) + the maps built so far, each 32·n + 8·(2^depth − 1)
//!                (photons, kd-tree nodes with leaves of ≤ 32 photons); under MPI also 2 · 32·N
//!                (this rank's encoded photons and their wire bytes); with photon beams
//!                (`volume_estimate = "photon_beams"`) 80 bytes per traced beam, and at most
//!                160 per piece of the built map (the piece, its radius and indices, two nodes
//!                of the hierarchy: `photon_map::BYTES_PER_BEAM`; at most 16 pieces per beam,
//!                `photon_map::MAX_PIECES_PER_BEAM`)
//!   irradiance   the maps + max(2 · 4·B·n_irr (the values, and their bytes for the gather),
//!                4·B·n_irr + 76·n_irr + nodes (the values, the points' sites and the kd-tree)),
//!                n_irr = n_global/4; the cache then holds (28 + 4·B)·n_irr + nodes
//!   eye pass     the maps + 2 · 4·W·H·B (rows, then the image) + 12·W·H (linear sRGB)
//!                + 8·n_vol·Σ_m s_m (each volume photon's scattering row in each medium m that
//!                reads the volume map, s_m values: `photon_map::scatter_rows`; every medium
//!                counted)
//!   outputs      4·W·H·(B + 3) (EXR channels) + 3·W·H (PNG bytes) + the image
//! ```
//!
//! A run that may make several progressive passes also holds, through every phase of its
//! passes after the first, the running mean and spread of each band value (2 · 8·W·H·B), and
//! writes their standard errors (4·W·H·B, and as many EXR channels): the maps of one pass are
//! dropped before the next builds its own, so the rest stays that of one pass.
//!
//! The tracing phase's model follows the allocator: a group's records are copied into the pass's
//! records and freed. The first group's blocks are fresh and larger than glibc's mmap threshold,
//! so freeing them unmaps them; that raises the threshold, so later groups' blocks come from the
//! heap and stay resident after they are freed (and are reused by the next group). Counting the
//! first group as well over-estimated passes of two groups by 23–28 % (prism_dispersion,
//! sunset_sea at a quarter of their image size).
//!
//! The estimate is the scene's memory plus the largest of the phases (with the maps held
//! from earlier phases). The constants are the sizes of `PhotonRecord` (96 bytes) and `Photon`
//! (32), and the layouts of the irradiance cache and the image; `scripts/memory_check.sh`
//! compares the estimate with the measured peak (`VmHWM`) on the shipped examples.

use crate::error::{Error, Result};
use crate::memory::{available_bytes, current_rss_bytes, human};
use crate::photon::{MapKind, PassSettings, pilot};
use crate::scene::Scene;
use serde::Serialize;

/// Bytes of one traced photon record (`photon_map::PhotonRecord`).
const RECORD_BYTES: f64 = 96.0;
/// Bytes of one stored photon (`photon_map::Photon`).
const PHOTON_BYTES: f64 = 32.0;
/// Bytes of one traced photon beam (`photon_map::PhotonBeam`).
const BEAM_BYTES: f64 = size_of::<crate::photon_map::PhotonBeam>() as f64;
/// Bytes of one piece of a beam in a built `photon_map::PhotonBeamMap` at most.
const BEAM_MAP_BYTES: f64 = crate::photon_map::BYTES_PER_BEAM as f64;

/// How much memory a run may use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MemoryLimit {
    /// No check (the library's default).
    #[default]
    Unlimited,
    /// At most this many bytes (`--max-memory`).
    Limit(u64),
    /// What the OS reports available when the run starts, plus what the process already holds
    /// (the command line's default). No check where that is unknown.
    Available,
}

/// The estimate of a run's peak memory, and its parts, as `report.json` records them.
#[derive(Clone, Debug, Default, Serialize)]
pub struct MemoryEstimate {
    /// Resident memory after loading the scene (and the pilot), bytes.
    pub scene_bytes: u64,
    /// Photons the global pass is expected to store (surface + volume, all ranks).
    pub expected_global_photons: u64,
    /// Photons the caustic pass is expected to store (all ranks).
    pub expected_caustic_photons: u64,
    /// The largest phase's memory on top of the scene's, bytes.
    pub largest_phase_bytes: u64,
    /// Which phase that is.
    pub largest_phase: String,
    /// The estimated peak resident memory, bytes.
    pub estimated_peak_bytes: u64,
    /// The limit checked against, bytes (`None`: unlimited or unknown).
    pub limit_bytes: Option<u64>,
    /// The measured peak resident memory at the end of the run (`VmHWM`), bytes.
    pub measured_peak_bytes: Option<u64>,
}

/// Kd-tree node bytes for `n` photons: 8 bytes per node of a tree with leaves of ≤ 32.
fn nodes_bytes(n: f64) -> f64 {
    if n <= 32.0 {
        return 0.0;
    }
    let depth = (n / 32.0).log2().ceil();
    8.0 * (2f64.powf(depth) - 1.0)
}

/// A map of `n` photons as held after its build.
fn map_bytes(n: f64) -> f64 {
    PHOTON_BYTES * n + nodes_bytes(n)
}

/// Estimates the peak memory of rendering `scene` on one of `ranks` ranks, tracing pilots of
/// the photon passes the plan runs.
pub fn estimate(scene: &Scene, pass: &PassSettings, ranks: usize) -> MemoryEstimate {
    let s = &scene.integrator;
    let plan = &scene.plan;
    let share = 1.0 / ranks.max(1) as f64;
    let seed = s.seed;
    let (mut g_surface, mut g_volume, mut c_surface, mut g_beams) = (0.0, 0.0, 0.0, 0.0);
    if plan.global_map.on || plan.volume_map.on {
        let (a, b, c) = pilot(&scene.world, pass, MapKind::Global, s.photons, seed);
        g_surface = if plan.global_map.on { a * s.photons as f64 } else { 0.0 };
        g_volume = if plan.volume_map.on { b * s.photons as f64 } else { 0.0 };
        g_beams = c * s.photons as f64;
    }
    if plan.caustic_map.on {
        c_surface = pilot(&scene.world, pass, MapKind::Caustic, s.caustic_photons, seed).0 * s.caustic_photons as f64;
    }
    let scene_bytes = current_rss_bytes().unwrap_or(0);
    let records = |n: f64| RECORD_BYTES * n * share;
    // The largest group of batches after the first, still resident once copied (one batch for a
    // pass of a single group), and each worker's scratch sink, grown by doubling to hold a batch.
    let group = |n: f64, emitted: u64| {
        let threads = rayon::current_num_threads() as f64;
        let batches = crate::photon::GROUP_BATCHES_PER_THREAD as f64 * threads;
        let mine = n * share;
        let per_batch = (n / crate::photon::batch_count(emitted).max(1) as f64).min(mine);
        let first = (per_batch * batches).min(mine);
        let later = (mine - first).min(first).max(per_batch);
        RECORD_BYTES * (later + 2.0 * threads * per_batch)
    };
    // Photon beams: traced as records, then held with their radii and hierarchy.
    let global_records = records(g_surface + g_volume) + BEAM_BYTES * g_beams * share;
    let global_maps =
        map_bytes(g_surface) + map_bytes(g_volume) + BEAM_MAP_BYTES * crate::photon_map::MAX_PIECES_PER_BEAM * g_beams;
    let wire = |n: f64| if ranks > 1 { 2.0 * PHOTON_BYTES * n * share } else { 0.0 };
    let n_irr = if plan.final_gather.on { g_surface / 4.0 } else { 0.0 };
    let bands = scene.bands.count as f64;
    let irradiance = (28.0 + 4.0 * bands) * n_irr + nodes_bytes(n_irr);
    let irradiance_build = (8.0 * bands * n_irr).max(4.0 * bands * n_irr + 76.0 * n_irr + nodes_bytes(n_irr));
    let row_values: usize = scene.world.media.iter().map(|m| m.scatter_row_len()).sum();
    let scatter_rows = 8.0 * g_volume * row_values as f64;
    let pixels = (scene.camera.width * scene.camera.height) as f64;
    let image = 4.0 * pixels * bands;
    let (acc, se) = if s.progressive.pass_limit() > 1 { (16.0 * pixels * bands, 2.0 * image) } else { (0.0, 0.0) };
    let phases = [
        ("global photon tracing", acc + global_records + group(g_surface + g_volume, s.photons)),
        ("global map build", acc + global_records + global_maps + wire(g_surface.max(g_volume))),
        ("caustic photon tracing", acc + global_maps + records(c_surface) + group(c_surface, s.caustic_photons)),
        ("caustic map build", acc + global_maps + records(c_surface) + map_bytes(c_surface) + wire(c_surface)),
        ("irradiance cache", acc + global_maps + map_bytes(c_surface) + irradiance_build),
        (
            "eye pass",
            acc + global_maps + map_bytes(c_surface) + irradiance + scatter_rows + 2.0 * image + 12.0 * pixels,
        ),
        // The maps are gone by now (the render returns its image, then the outputs are written).
        ("outputs", image + se + 12.0 * pixels + 4.0 * pixels * (bands + 3.0) + 3.0 * pixels),
    ];
    let (name, largest) = phases.iter().fold(("", 0.0f64), |best, p| if p.1 > best.1 { (p.0, p.1) } else { best });
    MemoryEstimate {
        scene_bytes,
        expected_global_photons: (g_surface + g_volume).round() as u64,
        expected_caustic_photons: c_surface.round() as u64,
        largest_phase_bytes: largest.round() as u64,
        largest_phase: name.to_string(),
        estimated_peak_bytes: scene_bytes + largest.round() as u64,
        limit_bytes: None,
        measured_peak_bytes: None,
    }
}

/// Checks `est` against `limit` (recording the limit in it); an estimate over the limit is an
/// input error with the numbers.
pub fn check(est: &mut MemoryEstimate, limit: MemoryLimit) -> Result<()> {
    let (bytes, source) = match limit {
        MemoryLimit::Unlimited => return Ok(()),
        MemoryLimit::Limit(b) => (b, "--max-memory"),
        MemoryLimit::Available => match available_bytes() {
            Some(a) => (a + est.scene_bytes, "the memory this machine has available"),
            None => return Ok(()),
        },
    };
    est.limit_bytes = Some(bytes);
    if est.estimated_peak_bytes <= bytes {
        return Ok(());
    }
    Err(Error::input(
        None,
        format!(
            "this run would need about {} (the scene {}, then {} at its peak: {} global and {} caustic photons expected), more than {source} ({}); use fewer photons or pixels, or allow more with --max-memory",
            human(est.estimated_peak_bytes),
            human(est.scene_bytes),
            est.largest_phase,
            est.expected_global_photons,
            est.expected_caustic_photons,
            human(bytes)
        ),
    ))
}
