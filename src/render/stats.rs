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
    /// Ranks, per-rank photon counts and phase times, bytes moved (see [`crate::distributed`];
    /// of the last progressive pass).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distributed: Option<crate::distributed::DistributedReport>,
    /// The progressive passes: how many, why they stopped, the error after each.
    pub progressive: crate::render::progressive::ProgressiveReport,
}

impl RenderStats {
    /// Adds one progressive pass's statistics: phase times summed by name, maps' photon counts
    /// and times summed (memory: the largest), rays and work added, warnings kept once.
    pub fn merge(&mut self, pass: RenderStats) {
        for ph in pass.phases.0 {
            match self.phases.0.iter_mut().find(|p| p.phase == ph.phase) {
                Some(p) => {
                    p.seconds += ph.seconds;
                    p.cpu_seconds += ph.cpu_seconds;
                }
                None => self.phases.0.push(ph),
            }
        }
        for m in pass.maps {
            match self.maps.iter_mut().find(|x| x.map == m.map) {
                Some(x) => {
                    x.emitted += m.emitted;
                    x.stored += m.stored;
                    x.memory_bytes = x.memory_bytes.max(m.memory_bytes);
                    x.trace_seconds += m.trace_seconds;
                    x.build_seconds += m.build_seconds;
                    x.stats.add(&m.stats);
                    x.stats.emitted += m.stats.emitted;
                }
                None => self.maps.push(m),
            }
        }
        for w in pass.warnings {
            if !self.warnings.contains(&w) {
                self.warnings.push(w);
            }
        }
        self.rays.add(&pass.rays);
        self.irradiance_points = self.irradiance_points.max(pass.irradiance_points);
        self.irradiance_memory_bytes = self.irradiance_memory_bytes.max(pass.irradiance_memory_bytes);
        self.eye_curved.add(&pass.eye_curved);
    }
}
