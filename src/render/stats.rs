//! What a render measured: wall time per phase, photons per map, rays traced.

use crate::photon::PhotonStats;
pub use crate::raypath::RayCounts;
pub use crate::timing::{PhaseTime, Phases};
use serde::Serialize;

/// One photon map's counts and costs, as `report.json` records them.
#[derive(Clone, Debug, Serialize)]
pub struct MapReport {
    /// Which map: "global", "caustic" or "volume".
    pub map: String,
    /// Photons emitted for it.
    pub emitted: u64,
    /// Photons stored in it.
    pub stored: u64,
    /// Memory of the map, bytes.
    pub memory_bytes: u64,
    /// Wall time of photon tracing on this rank, s.
    pub trace_seconds: f64,
    /// Wall time of building the kd-tree, s.
    pub build_seconds: f64,
    /// What became of the photons traced (stored, absorbed, escaped, ...).
    pub stats: PhotonStats,
}

/// What a render measured, as `report.json` records it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RenderStats {
    /// Things the run found that the user should know (e.g. a photon map the plan asked for
    /// that stored no photon), printed on stderr and kept in `report.json`.
    #[serde(rename = "run_warnings", skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// Wall time per phase.
    pub phases: Phases,
    /// The memory the run was estimated to need before it allocated its maps, the limit, and
    /// the peak measured at its end.
    pub memory: crate::render::MemoryEstimate,
    /// One entry per photon map built.
    pub maps: Vec<MapReport>,
    /// Rays traced, by kind.
    pub rays: RayCounts,
    /// Points with precomputed irradiance for final gathering.
    pub irradiance_points: u64,
    /// Memory of the irradiance cache, bytes.
    pub irradiance_memory_bytes: u64,
    /// Integrator work along the eye pass's curved paths.
    pub eye_curved: crate::raypath::CurvedWorkTotals,
    /// Ranks, per-rank photon counts and phase times, bytes moved (see [`crate::distributed`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distributed: Option<crate::distributed::DistributedReport>,
}
