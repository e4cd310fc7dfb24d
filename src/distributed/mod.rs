//! Distributed rendering: the photon passes and the eye pass split across the ranks of a
//! [`Comm`] — one process ([`Comm::Local`]) or an MPI job (`Comm::Mpi`, feature `mpi`).
//!
//! The render runs the same code on every comm ([`crate::render::render_on`]); with one rank
//! every collective hands back the rank's own data, so the single-process render *is* the
//! distributed render with one rank, and the output does not depend on the number of ranks:
//!
//! 1. **Scene** ([`scene`]): rank 0 reads the file and broadcasts its text; every rank validates
//!    it and the ranks compare fingerprints of the files it names.
//! 2. **Photon passes** ([`photons`]): rank `r` shoots a contiguous range of each pass's batches;
//!    batch `b` has the random stream (seed, pass, b) wherever it runs.
//! 3. **Maps** ([`assemble`]): photons are all-gathered in batch order and every rank builds the
//!    kd-tree one process would build; the irradiance cache is estimated in dealt blocks and
//!    gathered. Memory per rank is checked first ([`budget`]): every rank holds every map.
//! 4. **Eye pass** ([`eye`], [`tiles`]): rank 0 leases rows to ranks as they ask (guided
//!    self-scheduling) and gathers the rendered rows into the image in pixel order.
//! 5. **Report** ([`report`]): per-rank photon counts, phase times, eye-pass work and bytes moved
//!    are gathered for `report.json`; only rank 0 writes outputs, staged and renamed last
//!    ([`fault`] for what happens when a rank fails).

pub mod assemble;
pub mod budget;
pub mod comm;
pub mod eye;
pub mod fault;
pub mod fingerprint;
#[cfg(feature = "mpi")]
mod mpi_comm;
pub mod photons;
pub mod report;
pub mod scene;
pub mod split;
pub mod tiles;
pub mod wire;

pub use assemble::Placement;
pub use budget::{Budget, MapMemory};
pub use comm::Comm;
pub use report::{DistributedReport, RankReport};
pub use tiles::Schedule;

/// How to distribute a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// Map memory each rank may use.
    pub map_memory: MapMemory,
    /// How rank 0 hands out eye-pass rows.
    pub schedule: Schedule,
}

/// One rank's state through a render: its comm, map budget and report.
pub struct Rank<'w> {
    /// The processes of the render.
    pub comm: &'w Comm,
    /// The map memory limit and the eye-pass schedule.
    pub options: Options,
    /// The map memory this rank has used and may use, checked before each map is assembled.
    pub budget: Budget,
    /// What this rank did, for `report.json`.
    pub report: RankReport,
}

impl<'w> Rank<'w> {
    /// This rank of `comm`, on the current rayon pool. Collective (the ranks' hosts are
    /// gathered, to share a host's memory among its ranks).
    pub fn new(comm: &'w Comm, options: Options) -> Rank<'w> {
        let host = comm.host();
        let hosts = comm.all_gather_json(&host);
        let budget = Budget::new(options.map_memory, &hosts, &host);
        let report =
            RankReport { rank: comm.rank(), host, threads: rayon::current_num_threads(), ..RankReport::default() };
        Rank { comm, options, budget, report }
    }

    /// Every rank's report, in rank order, on every rank, after this rank's `phases`. Collective.
    pub fn gather_reports(&mut self, phases: &crate::timing::Phases) -> Vec<RankReport> {
        self.report.phases = phases.0.clone();
        self.report.map_memory_bytes = self.budget.held();
        self.comm.all_gather_json(&self.report)
    }
}
