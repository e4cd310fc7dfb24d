//! The `distributed` section of `report.json`: the ranks, what each one shot and rendered, how
//! long each of its phases took, and what crossed the network.

use super::assemble::Placement;
use super::eye::EyeWork;
use super::photons::RankPhotons;
use super::tiles::Schedule;
use crate::raypath::CurvedWorkTotals;
use crate::timing::PhaseTime;
use serde::{Deserialize, Serialize};

/// One rank's part of a render.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct RankReport {
    /// The rank's number.
    pub rank: usize,
    /// The host it ran on.
    pub host: String,
    /// Worker threads of this rank.
    pub threads: usize,
    /// Each photon pass: the batches this rank shot and the photons it stored.
    pub photons: Vec<RankPhotons>,
    /// Wall time per phase on this rank (the same phases as the top-level `phases`).
    pub phases: Vec<PhaseTime>,
    /// What the rank did in the eye pass.
    pub eye: EyeWork,
    /// Integrator work along this rank's curved eye paths.
    pub eye_curved: CurvedWorkTotals,
    /// Bytes this rank received assembling the photon maps.
    pub map_received_bytes: u64,
    /// Bytes this rank received assembling the irradiance cache.
    pub irradiance_received_bytes: u64,
    /// Bytes of photon maps and irradiance cache this rank holds.
    pub map_memory_bytes: u64,
}

/// The whole run.
#[derive(Clone, Debug, Serialize)]
pub struct DistributedReport {
    /// "local", or the MPI library's version line.
    pub comm: String,
    /// Number of ranks.
    pub ranks: usize,
    /// Each rank's host, in rank order.
    pub hosts: Vec<String>,
    /// How rank 0 handed out the eye pass's rows.
    pub schedule: Schedule,
    /// Where the photon maps live (every rank holds them all).
    pub placement: Placement,
    /// Bytes received over all ranks in the photon-map all-gathers.
    pub map_allgather_bytes: u64,
    /// Bytes received over all ranks in the irradiance-cache all-gathers.
    pub irradiance_allgather_bytes: u64,
    /// Bytes of eye-pass tiles received over all ranks.
    pub tile_bytes: u64,
    /// Each rank's report, in rank order.
    pub per_rank: Vec<RankReport>,
}

impl DistributedReport {
    /// The report from each rank's part, in rank order; totals are summed from them.
    pub fn new(comm: String, schedule: Schedule, per_rank: Vec<RankReport>) -> DistributedReport {
        DistributedReport {
            comm,
            ranks: per_rank.len(),
            hosts: per_rank.iter().map(|r| r.host.clone()).collect(),
            schedule,
            placement: Placement::Replicated,
            map_allgather_bytes: per_rank.iter().map(|r| r.map_received_bytes).sum(),
            irradiance_allgather_bytes: per_rank.iter().map(|r| r.irradiance_received_bytes).sum(),
            tile_bytes: per_rank.iter().map(|r| r.eye.received_bytes).sum(),
            per_rank,
        }
    }
}
