//! Memory per rank for the photon maps, checked before each map is gathered.
//!
//! Every rank holds every map (they are replicated, see [`super::assemble`]), so a rank needs
//!
//! ```text
//!   bytes = Σ_maps [ 32·n_map + 8·(2^depth(n_map) − 1) ]          (photons, kd-tree nodes)
//!         + n_irr · (28 + 4·bands) + 8·(2^depth(n_irr) − 1)        (irradiance cache)
//! ```
//!
//! with `n_map` the photons stored in a map over all ranks, `depth(n)` the kd-tree's height
//! (leaves of ≤ 32 photons, so the nodes cost 0.25–0.5 bytes per photon) and `n_irr = n_global/4`
//! cache points. That is about 32.4 bytes per stored photon: 3.2 GB per rank for 10⁸ stored
//! photons, 32 GB for 10⁹. Transiently a rank also holds its own traced records (96 bytes each,
//! a 1/ranks share), their encoded copy (32 bytes each) and one gather round (≤ 64 MiB per rank).
//!
//! Before gathering, each rank compares the bytes of the next map with its budget
//! ([`MapMemory`]); the verdict is [`super::fault::agree`]d, so a map that would not fit stops
//! every rank with a message, before anything is allocated. A distributed kd-tree, where each
//! rank holds a part of each map, is the later step that lifts this limit.

use super::Comm;
use super::fault::agree;
use crate::error::{Error, Result};
pub use crate::memory::{available_bytes, human, parse_bytes};

/// How much map memory a rank may use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MapMemory {
    /// No check (the library's single-process [`crate::render::render`]).
    #[default]
    Unlimited,
    /// At most this many bytes of maps per rank (`--max-map-memory`).
    Limit(u64),
    /// The next map must fit in the memory the OS reports available (`MemAvailable` in
    /// `/proc/meminfo`), shared with the other ranks on the same host. No check where that is
    /// unknown.
    Available,
}

/// The map memory a rank has used so far and may use.
pub struct Budget {
    policy: MapMemory,
    /// Bytes of the maps assembled so far.
    held: u64,
    /// Ranks running on this rank's host (they allocate the same maps at the same time).
    ranks_on_host: u64,
}

impl Budget {
    /// A budget under `policy`; `hosts` are the host names of all ranks.
    pub fn new(policy: MapMemory, hosts: &[String], my_host: &str) -> Budget {
        let ranks_on_host = hosts.iter().filter(|h| *h == my_host).count().max(1) as u64;
        Budget { policy, held: 0, ranks_on_host }
    }

    /// Bytes of the maps assembled so far on this rank.
    pub fn held(&self) -> u64 {
        self.held
    }

    /// Forgets every map held (a progressive pass dropped its maps before the next builds its own).
    pub fn release_all(&mut self) {
        self.held = 0;
    }

    /// Checks that `what` (`bytes` on every rank) fits, on every rank; records it as held.
    /// Collective: if it does not fit on some rank, every rank returns that rank's error.
    pub fn reserve(&mut self, comm: &Comm, what: &str, bytes: u64) -> Result<()> {
        let verdict = self.verdict(what, bytes, available_bytes());
        agree(comm, verdict)?;
        self.held += bytes;
        Ok(())
    }

    /// Whether `bytes` more fit when the OS has `available` bytes free (if known).
    fn verdict(&self, what: &str, bytes: u64, available: Option<u64>) -> Result<()> {
        let seam = "every rank holds every photon map; use fewer photons, fewer ranks per host or \
                    hosts with more memory (a distributed kd-tree that splits the maps between \
                    ranks is not implemented yet)";
        match self.policy {
            MapMemory::Unlimited => Ok(()),
            MapMemory::Limit(limit) if self.held + bytes > limit => Err(Error::input(
                None,
                format!(
                    "{what} needs {} on every rank, and the maps before it hold {}: {} in all, more \
                     than --max-map-memory {}; {seam}",
                    human(bytes),
                    human(self.held),
                    human(self.held + bytes),
                    human(limit)
                ),
            )),
            MapMemory::Available => match available {
                Some(avail) if bytes.saturating_mul(self.ranks_on_host) > avail => Err(Error::input(
                    None,
                    format!(
                        "{what} needs {} on every rank ({} ranks on this host: {}), but the host \
                         has only {} available; {seam}",
                        human(bytes),
                        self.ranks_on_host,
                        human(bytes.saturating_mul(self.ranks_on_host)),
                        human(avail)
                    ),
                )),
                _ => Ok(()),
            },
            MapMemory::Limit(_) => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn budget(policy: MapMemory, ranks_on_host: usize) -> Budget {
        let hosts: Vec<String> = (0..ranks_on_host).map(|_| "h".to_string()).chain(["other".to_string()]).collect();
        Budget::new(policy, &hosts, "h")
    }

    #[test]
    fn a_limit_counts_the_maps_already_held() {
        let mut b = budget(MapMemory::Limit(1000), 1);
        assert!(b.verdict("global", 600, None).is_ok());
        b.held = 600;
        let e = b.verdict("caustic", 600, None).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let msg = e.to_string();
        assert!(
            msg.contains("caustic") && msg.contains("--max-map-memory") && msg.contains("distributed kd-tree"),
            "{msg}"
        );
        assert!(b.verdict("caustic", 400, None).is_ok());
    }

    #[test]
    fn available_memory_is_shared_by_the_ranks_on_a_host() {
        let b = budget(MapMemory::Available, 3);
        assert!(b.verdict("global", 300, Some(900)).is_ok());
        let msg = b.verdict("global", 301, Some(900)).unwrap_err().to_string();
        assert!(msg.contains("3 ranks on this host"), "{msg}");
        assert!(b.verdict("global", u64::MAX, None).is_ok(), "unknown memory is not checked");
        assert!(budget(MapMemory::Unlimited, 1).verdict("global", u64::MAX, Some(0)).is_ok());
    }
}
