//! The photon pass across ranks: each rank shoots a contiguous range of the pass's batches.
//!
//! A pass of `emitted` photons has `⌈emitted / BATCH⌉` batches, and batch `b` draws from the
//! random stream `(seed, map, b)` whoever shoots it ([`crate::photon::shoot_batches`]). Rank `r`
//! of `P` shoots [`share`]`(batches, r, P)`: shares differ by at most one batch and tile the
//! batches in rank order, so the ranks' photons, concatenated in rank order, are exactly the
//! single-process photon set in its order. Batches are statistically alike (every photon picks
//! its light and direction at random), so equal shares balance the pass without scheduling.

use super::Comm;
use super::split::share;
use crate::photon::inelastic::InelasticTally;
use crate::photon::{self, MapKind, PhotonSink, PhotonStats};
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// What one rank shot in one pass.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct RankPhotons {
    /// The pass ("global" or "caustic").
    pub pass: String,
    /// Batches `[first, end)` this rank shot.
    pub batches: [u64; 2],
    /// Photons this rank emitted.
    pub emitted: u64,
    /// Photons this rank stored on surfaces.
    pub stored_surface: u64,
    /// Photons this rank stored in media.
    pub stored_volume: u64,
    /// Wall time of this rank's tracing, s.
    pub trace_seconds: f64,
}

/// A pass as this rank sees it after shooting: its own photons, the statistics of all ranks.
pub struct Shot {
    /// This rank's stored photons, in batch order.
    pub sink: PhotonSink,
    /// The pass's statistics summed over ranks.
    pub stats: PhotonStats,
    /// This rank's share.
    pub mine: RankPhotons,
}

/// The batches of a pass of `emitted` photons that this rank shoots, and their photons.
pub fn my_share(comm: &Comm, emitted: u64) -> (std::ops::Range<u64>, u64) {
    let batches = share(photon::batch_count(emitted), comm.rank(), comm.size());
    let photons = batches.clone().map(|b| photon::batch_photons(emitted, b)).sum();
    (batches, photons)
}

/// Shoots this rank's share of a pass seeded with `seed` and sums the statistics over ranks.
/// Collective.
#[allow(clippy::too_many_arguments)]
pub fn shoot(
    comm: &Comm,
    scene: &Scene,
    seed: u64,
    deadline: crate::timing::Stop,
    kind: MapKind,
    emitted: u64,
    pass: &str,
    on_batch: &(dyn Fn(u64) + Sync),
) -> Shot {
    let t = std::time::Instant::now();
    let (batches, _) = my_share(comm, emitted);
    let (sink, local) = photon::shoot_batches(
        &scene.world,
        &photon::PassSettings { deadline, ..photon::PassSettings::of(scene) },
        kind,
        emitted,
        seed,
        batches.clone(),
        on_batch,
    );
    let mine = RankPhotons {
        pass: pass.to_string(),
        batches: [batches.start, batches.end],
        emitted: local.emitted,
        stored_surface: sink.surface.len() as u64,
        stored_volume: sink.volume.len() as u64,
        trace_seconds: t.elapsed().as_secs_f64(),
    };
    let stats = sum(&comm.all_gather_json(&local));
    Shot { sink, stats, mine }
}

/// The statistics of a pass from its ranks' parts (in rank order): counts and powers added,
/// the power per photon (the same on every rank that had lights) kept.
pub fn sum(parts: &[PhotonStats]) -> PhotonStats {
    let mut total = PhotonStats {
        emitted: parts.iter().map(|p| p.emitted).sum(),
        power_per_photon_w: parts.iter().map(|p| p.power_per_photon_w).fold(0.0, f64::max),
        inelastic: parts.first().map(|p| named_tallies(&p.inelastic)).unwrap_or_default(),
        ..PhotonStats::default()
    };
    for p in parts {
        total.add(p);
        total.curved.add(&p.curved);
    }
    total
}

/// Zeroed copies of a rank's inelastic tallies, keeping their medium and component names (every
/// rank has the same components: it validated the same scene).
fn named_tallies(t: &[InelasticTally]) -> Vec<InelasticTally> {
    t.iter()
        .map(|t| InelasticTally { medium: t.medium.clone(), component: t.component.clone(), ..Default::default() })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_add_counts_and_keep_the_photon_power() {
        let a = PhotonStats { emitted: 10, stored: 3, power_per_photon_w: 0.5, escaped_w: 1.0, ..Default::default() };
        let mut b =
            PhotonStats { emitted: 6, stored: 2, power_per_photon_w: 0.5, escaped_w: 2.5, ..Default::default() };
        b.curved.ode_steps = 7;
        let s = sum(&[a.clone(), b]);
        assert_eq!((s.emitted, s.stored, s.power_per_photon_w, s.escaped_w, s.curved.ode_steps), (16, 5, 0.5, 3.5, 7));
        // One rank: the statistics themselves.
        assert_eq!(sum(std::slice::from_ref(&a)), a);
    }

    #[test]
    fn sums_keep_the_inelastic_components_names() {
        let t = |events, w| InelasticTally {
            medium: "sea".into(),
            component: "chlorophyll".into(),
            events,
            emitted_w: w,
            ..Default::default()
        };
        let a = PhotonStats { inelastic: vec![t(2, 0.25)], ..Default::default() };
        let b = PhotonStats { inelastic: vec![t(3, 0.5)], ..Default::default() };
        assert_eq!(sum(&[a, b]).inelastic, vec![t(5, 0.75)]);
    }
}
