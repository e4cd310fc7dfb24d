//! What a render measured: wall time per phase, photons per map, rays traced.

use crate::distributed::clock::{Span, Took};
use crate::photon::PhotonStats;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PhaseTime {
    pub phase: String,
    /// Wall time.
    pub seconds: f64,
    /// CPU time of this process over the phase (see [`crate::distributed::clock`]).
    #[serde(default)]
    pub cpu_seconds: f64,
}

/// Wall (and CPU) time per phase, in the order the phases ran.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Phases(pub Vec<PhaseTime>);

impl Phases {
    /// Records the time since `start` under `phase` and returns its wall time in seconds.
    pub fn add(&mut self, phase: &str, start: Span) -> f64 {
        self.push(phase, start.took())
    }

    /// Records `took` under `phase` and returns its wall time in seconds.
    pub fn push(&mut self, phase: &str, took: Took) -> f64 {
        self.0.push(PhaseTime { phase: phase.to_string(), seconds: took.seconds, cpu_seconds: took.cpu_seconds });
        took.seconds
    }
}

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

/// Rays traced in the eye pass, by purpose.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RayCounts {
    /// Camera rays and the specular continuations of eye paths.
    pub eye: u64,
    pub shadow: u64,
    pub gather: u64,
}

impl RayCounts {
    pub fn add(&mut self, o: &RayCounts) {
        self.eye += o.eye;
        self.shadow += o.shadow;
        self.gather += o.gather;
    }
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct RenderStats {
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
