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

/// `MemAvailable` from `/proc/meminfo`, in bytes (None where there is no such file).
pub fn available_bytes() -> Option<u64> {
    crate::memory::mem_available()
}

/// Parses a byte count with an optional binary suffix: `512`, `64k`, `800M`, `8G`, `1T`
/// (k = 2¹⁰ … T = 2⁴⁰; a trailing `B` or `iB` is allowed: `8GiB`).
pub fn parse_bytes(s: &str) -> std::result::Result<u64, String> {
    let t = s.trim();
    let t = t.strip_suffix("iB").or_else(|| t.strip_suffix('B')).unwrap_or(t);
    let (digits, shift) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => {
            let shift = match c.to_ascii_uppercase() {
                'K' => 10,
                'M' => 20,
                'G' => 30,
                'T' => 40,
                _ => return Err(format!("unknown size suffix '{c}' in \"{s}\": use k, M, G or T")),
            };
            (&t[..i], shift)
        }
        _ => (t, 0),
    };
    let v: f64 = digits.trim().parse().map_err(|_| format!("expected a size such as 8G or 512M, found \"{s}\""))?;
    let bytes = v * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(format!("expected a positive size such as 8G or 512M, found \"{s}\""));
    }
    Ok(bytes as u64)
}

/// A byte count for messages: "3.20 GB (3200000000 bytes)".
pub fn human(bytes: u64) -> String {
    let b = bytes as f64;
    let (v, unit) = match b {
        b if b >= 1e12 => (b / 1e12, "TB"),
        b if b >= 1e9 => (b / 1e9, "GB"),
        b if b >= 1e6 => (b / 1e6, "MB"),
        b if b >= 1e3 => (b / 1e3, "kB"),
        _ => return format!("{bytes} bytes"),
    };
    format!("{v:.2} {unit} ({bytes} bytes)")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn budget(policy: MapMemory, ranks_on_host: usize) -> Budget {
        let hosts: Vec<String> = (0..ranks_on_host).map(|_| "h".to_string()).chain(["other".to_string()]).collect();
        Budget::new(policy, &hosts, "h")
    }

    #[test]
    fn sizes_parse_with_binary_suffixes() {
        assert_eq!(parse_bytes("512"), Ok(512));
        assert_eq!(parse_bytes("64k"), Ok(65_536));
        assert_eq!(parse_bytes("1.5M"), Ok(1_572_864));
        assert_eq!(parse_bytes("8G"), Ok(8 << 30));
        assert_eq!(parse_bytes("8GiB"), Ok(8 << 30));
        assert_eq!(parse_bytes("2TB"), Ok(2 << 40));
        for bad in ["", "G", "-1G", "0", "8X", "lots", "nan"] {
            assert!(parse_bytes(bad).is_err(), "{bad:?} accepted");
        }
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

    #[test]
    fn this_host_reports_available_memory() {
        if std::path::Path::new("/proc/meminfo").exists() {
            assert!(available_bytes().is_some_and(|b| b > 0));
        }
    }
}
