//! What a render measured: wall time per phase, photons per map, rays traced.

use crate::photon::PhotonStats;
pub use crate::raypath::RayCounts;
pub use crate::timing::{PhaseTime, Phases};
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct MapReport {
    pub map: String,
    pub emitted: u64,
    pub stored: u64,
    pub memory_bytes: u64,
    pub trace_seconds: f64,
    pub build_seconds: f64,
    pub stats: PhotonStats,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct RenderStats {
    /// Things the run found that the user should know (e.g. a photon map the plan asked for
    /// that stored no photon), printed on stderr and kept in `report.json`.
    #[serde(rename = "run_warnings", skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    pub phases: Phases,
    pub maps: Vec<MapReport>,
    pub rays: RayCounts,
    pub irradiance_points: u64,
    pub irradiance_memory_bytes: u64,
    /// Integrator work along the eye pass's curved paths.
    pub eye_curved: crate::raypath::CurvedWorkTotals,
    /// Ranks, per-rank photon counts and phase times, bytes moved (see [`crate::distributed`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distributed: Option<crate::distributed::DistributedReport>,
}
