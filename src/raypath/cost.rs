//! What curved propagation cost: integrator steps and field samples, counted across threads.
//!
//! Each event adds its integrator's counters once (one atomic add per counter per event, not per
//! step), so counting does not slow the stepping.

use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// Running totals shared by the threads of one pass.
#[derive(Debug, Default)]
pub struct CurvedWork {
    events: AtomicU64,
    accepted: AtomicU64,
    rejected: AtomicU64,
    rhs_evals: AtomicU64,
    chords: AtomicU64,
    lost: AtomicU64,
    trapped: AtomicU64,
    ascents: AtomicU64,
}

/// A snapshot of [`CurvedWork`], as `report.json` records it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CurvedWorkTotals {
    /// Events (surface, medium interaction, escape) reached along curved paths.
    pub curved_events: u64,
    /// Accepted integrator steps.
    pub ode_steps: u64,
    /// Rejected integrator steps.
    pub ode_rejected: u64,
    /// Samples of n and ∇n.
    pub rhs_evals: u64,
    /// Straight chords handed to geometry and media.
    pub chords: u64,
    /// Paths ended because the integrator failed (a field that gave a non-finite value).
    pub lost: u64,
    /// Paths taken to escape because they were trapped in a duct past all finite geometry
    /// ([`super::far`]).
    #[serde(default)]
    pub trapped: u64,
    /// Paths that left the layered upper air upward in one move, by Bouguer's invariant
    /// ([`super::shell::LayeredShell::ascend`]).
    #[serde(default)]
    pub shell_ascents: u64,
}

impl CurvedWork {
    /// Adds one curved event's integrator counters and its number of chords.
    pub fn add(&self, accepted: u64, rejected: u64, rhs_evals: u64, chords: u64) {
        self.events.fetch_add(1, Relaxed);
        self.accepted.fetch_add(accepted, Relaxed);
        self.rejected.fetch_add(rejected, Relaxed);
        self.rhs_evals.fetch_add(rhs_evals, Relaxed);
        self.chords.fetch_add(chords, Relaxed);
    }

    /// Counts a path ended because the integrator failed.
    pub fn lose(&self) {
        self.lost.fetch_add(1, Relaxed);
    }

    /// Counts a path taken to escape because it is trapped in a duct ([`super::far`]).
    pub fn trap(&self) {
        self.trapped.fetch_add(1, Relaxed);
    }

    /// Counts a path that left the layered upper air upward in one move.
    pub fn ascent(&self) {
        self.ascents.fetch_add(1, Relaxed);
    }

    /// The counts so far.
    pub fn totals(&self) -> CurvedWorkTotals {
        CurvedWorkTotals {
            curved_events: self.events.load(Relaxed),
            ode_steps: self.accepted.load(Relaxed),
            ode_rejected: self.rejected.load(Relaxed),
            rhs_evals: self.rhs_evals.load(Relaxed),
            chords: self.chords.load(Relaxed),
            lost: self.lost.load(Relaxed),
            trapped: self.trapped.load(Relaxed),
            shell_ascents: self.ascents.load(Relaxed),
        }
    }
}

impl CurvedWorkTotals {
    /// Adds another snapshot (e.g. another rank's) to this one.
    pub fn add(&mut self, o: &CurvedWorkTotals) {
        self.curved_events += o.curved_events;
        self.ode_steps += o.ode_steps;
        self.ode_rejected += o.ode_rejected;
        self.rhs_evals += o.rhs_evals;
        self.chords += o.chords;
        self.lost += o.lost;
        self.trapped += o.trapped;
        self.shell_ascents += o.shell_ascents;
    }
}

/// Rays traced and other work done in the eye pass, by purpose: each effect of the plan that
/// runs in the eye pass has a counter here, so `report.json` shows that an effect the plan
/// turned off did no work.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RayCounts {
    /// Camera rays and the specular continuations of eye paths.
    pub eye: u64,
    /// Shadow rays (direct light and single scattering by next-event estimation).
    pub shadow: u64,
    /// Final-gathering rays.
    pub gather: u64,
    /// Eye paths split into one path per wavelength (dispersion), or narrowed to one chosen
    /// wavelength (gather paths).
    #[serde(default)]
    pub splits: u64,
    /// Work in participating media: ray-marching steps of the photon-map eye pass, collisions
    /// of the path tracer.
    #[serde(default)]
    pub medium_steps: u64,
    /// Lanes of split eye paths whose ends were interpolated from a dispersion bundle's guides
    /// instead of traced.
    #[serde(default)]
    pub bundled: u64,
    /// Image rows not rendered because the run's time budget (`--max-seconds`) ran out.
    #[serde(default)]
    pub stopped_rows: u64,
}

impl RayCounts {
    /// Adds `o`'s counts.
    pub fn add(&mut self, o: &RayCounts) {
        self.eye += o.eye;
        self.shadow += o.shadow;
        self.gather += o.gather;
        self.splits += o.splits;
        self.medium_steps += o.medium_steps;
        self.bundled += o.bundled;
        self.stopped_rows += o.stopped_rows;
    }

    /// The counts added since `before` (taken from the same running counter).
    pub fn since(&self, before: &RayCounts) -> RayCounts {
        RayCounts {
            eye: self.eye - before.eye,
            shadow: self.shadow - before.shadow,
            gather: self.gather - before.gather,
            splits: self.splits - before.splits,
            medium_steps: self.medium_steps - before.medium_steps,
            bundled: self.bundled - before.bundled,
            stopped_rows: self.stopped_rows - before.stopped_rows,
        }
    }
}
