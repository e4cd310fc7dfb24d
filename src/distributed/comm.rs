//! The processes a render runs on: a closed set of communicators with the few operations the
//! distributed render needs.
//!
//! [`Comm::Local`] is one process, rank 0 of 1: its collectives hand back the caller's own data
//! and its messages go to itself. `Comm::Mpi` (feature `mpi`) is `MPI_COMM_WORLD` under
//! `mpirun`. Everything above this file is written once against [`Comm`], so the single-process
//! render runs the same distribution code as an MPI job, with one rank.
//!
//! The primitives are byte-level: an all-gather that streams each rank's contribution in pieces
//! (so a photon map larger than MPI's 2³¹-element counts, or larger than a second copy in memory,
//! can be assembled), a broadcast from rank 0, and tagged point-to-point messages for the eye
//! pass's lease protocol. Typed helpers are built on them here, once for every comm.

#[cfg(feature = "mpi")]
use super::mpi_comm::MpiComm;
pub use super::wire::{PIECE_CAP, Tag, piece_bytes, round_parts, rounds};
use std::collections::VecDeque;
use std::sync::Mutex;

/// The processes of a render.
pub enum Comm {
    /// One process: rank 0 of 1.
    Local(LocalComm),
    /// `MPI_COMM_WORLD` of an MPI job (feature `mpi`).
    #[cfg(feature = "mpi")]
    Mpi(MpiComm),
}

/// One process: rank 0 of 1, with a mailbox for messages to itself.
#[derive(Default)]
pub struct LocalComm {
    mailbox: Mutex<VecDeque<(Tag, Vec<u8>)>>,
}

impl Comm {
    /// A single-process comm.
    pub fn local() -> Comm {
        Comm::Local(LocalComm::default())
    }

    /// The comm of this run: `MPI_COMM_WORLD` when built with the `mpi` feature (one rank when
    /// not started by `mpirun`), else [`Comm::local`]. Dropping an MPI comm finalises MPI.
    pub fn start() -> crate::error::Result<Comm> {
        #[cfg(feature = "mpi")]
        {
            MpiComm::start().map(Comm::Mpi)
        }
        #[cfg(not(feature = "mpi"))]
        {
            match launcher_ranks() {
                Some(n) if n > 1 => Err(crate::error::Error::input(
                    None,
                    format!(
                        "this morgana was built without MPI but was started as one of {n} MPI ranks, \
                         so each would render the whole image alone; build it with \
                         `cargo build --release --features mpi` (see README, \"Distributed rendering\")"
                    ),
                )),
                _ => Ok(Comm::local()),
            }
        }
    }

    /// This process's rank, `0..size()`.
    pub fn rank(&self) -> usize {
        match self {
            Comm::Local(_) => 0,
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.rank(),
        }
    }

    /// Number of ranks.
    pub fn size(&self) -> usize {
        match self {
            Comm::Local(_) => 1,
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.size(),
        }
    }

    /// Whether this is rank 0, the one that reads the scene and writes the outputs.
    pub fn is_root(&self) -> bool {
        self.rank() == 0
    }

    /// The name of the host this rank runs on.
    pub fn host(&self) -> String {
        match self {
            Comm::Local(_) => local_host_name(),
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.host(),
        }
    }

    /// What the comm is, for reports: "local" or the MPI library's version line.
    pub fn kind(&self) -> String {
        match self {
            Comm::Local(_) => "local".to_string(),
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.library(),
        }
    }

    /// Every rank's `local` bytes, delivered on every rank to `sink(rank, offset, piece)`: the
    /// piece is bytes `offset..offset + piece.len()` of that rank's contribution. Pieces hold
    /// whole `unit`-byte elements (each rank's length must be a multiple of `unit`) and at most
    /// [`PIECE_CAP`] bytes; each byte of each rank arrives exactly once, a rank's pieces in
    /// increasing offset. Collective. Returns the bytes received from other ranks.
    pub fn all_gather_pieces(&self, local: &[u8], unit: usize, sink: &mut dyn FnMut(usize, usize, &[u8])) -> u64 {
        match self {
            Comm::Local(_) => {
                debug_assert_eq!(local.len() % unit.max(1), 0, "contribution of whole units");
                if !local.is_empty() {
                    sink(0, 0, local);
                }
                0
            }
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.all_gather_pieces(local, unit, sink),
        }
    }

    /// Rank 0's `bytes` on every rank (other ranks pass anything, e.g. nothing). Collective.
    pub fn broadcast(&self, bytes: Vec<u8>) -> Vec<u8> {
        match self {
            Comm::Local(_) => bytes,
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.broadcast(bytes),
        }
    }

    /// Sends `bytes` to rank `to` (at most 2³¹ − 1 of them).
    pub fn send(&self, to: usize, tag: Tag, bytes: &[u8]) {
        match self {
            Comm::Local(l) => {
                debug_assert_eq!(to, 0, "a local comm has only rank 0");
                lock(&l.mailbox).push_back((tag, bytes.to_vec()));
            }
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.send(to, tag, bytes),
        }
    }

    /// A message with `tag` from any rank (`from` = None) or from rank `from`, if one has
    /// arrived: (sender, bytes). Does not wait.
    pub fn try_receive(&self, from: Option<usize>, tag: Tag) -> Option<(usize, Vec<u8>)> {
        match self {
            Comm::Local(l) => {
                debug_assert!(from.is_none_or(|f| f == 0), "a local comm has only rank 0");
                let mut q = lock(&l.mailbox);
                let i = q.iter().position(|(t, _)| *t == tag)?;
                q.remove(i).map(|(_, b)| (0, b))
            }
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.try_receive(from, tag),
        }
    }

    /// Ends the whole job after a broken protocol invariant (a bug, not bad input): prints
    /// `message` and aborts every rank (`MPI_Abort`), so no rank is left waiting.
    pub fn abort(&self, message: &str) -> ! {
        eprintln!("morgana: rank {} of {}: internal error: {message}", self.rank(), self.size());
        match self {
            Comm::Local(_) => std::process::exit(1),
            #[cfg(feature = "mpi")]
            Comm::Mpi(w) => w.abort(1),
        }
    }

    /// Every rank's `local` bytes, in rank order, on every rank. Collective.
    pub fn all_gather(&self, local: &[u8]) -> Vec<Vec<u8>> {
        let mut out = vec![Vec::new(); self.size()];
        self.all_gather_pieces(local, 1, &mut |rank, _, piece| out[rank].extend_from_slice(piece));
        out
    }

    /// Every rank's `values`, in rank order, on every rank. Collective.
    pub fn all_gather_u64(&self, values: &[u64]) -> Vec<Vec<u64>> {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.all_gather(&bytes)
            .iter()
            .map(|b| b.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8]))).collect())
            .collect()
    }

    /// Every rank's value serialised as JSON, in rank order, on every rank. Collective. A value
    /// that does not decode (a bug, or ranks running different morgana builds) aborts the job.
    pub fn all_gather_json<T: serde::Serialize + serde::de::DeserializeOwned>(&self, value: &T) -> Vec<T> {
        let bytes = match serde_json::to_vec(value) {
            Ok(b) => b,
            Err(e) => self.abort(&format!("cannot encode a message: {e}")),
        };
        self.all_gather(&bytes)
            .iter()
            .enumerate()
            .map(|(r, b)| match serde_json::from_slice(b) {
                Ok(v) => v,
                Err(e) => {
                    self.abort(&format!("cannot decode rank {r}'s message (do all ranks run the same build?): {e}"))
                }
            })
            .collect()
    }
}

/// The rank count an MPI launcher announced in the environment (Open MPI's
/// `OMPI_COMM_WORLD_SIZE`, MPICH's and Intel MPI's `PMI_SIZE`), if any.
pub fn launcher_ranks() -> Option<usize> {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"].iter().find_map(|v| std::env::var(v).ok()?.trim().parse().ok())
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// The host name (Linux: the kernel's; elsewhere `$HOSTNAME`, or "localhost").
pub fn local_host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "localhost".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_carry_every_byte_once() {
        for counts in [vec![0u64], vec![5, 0, 17], vec![64, 64], vec![1, 100, 33, 0, 99]] {
            for piece in [1u64, 7, 16, 64, 1000] {
                let mut seen: Vec<Vec<u32>> = counts.iter().map(|&c| vec![0; c as usize]).collect();
                for k in 0..rounds(&counts, piece) {
                    for (r, part) in round_parts(&counts, piece, k).into_iter().enumerate() {
                        assert!(part.end - part.start <= piece);
                        for b in part {
                            seen[r][b as usize] += 1;
                        }
                    }
                }
                assert!(seen.iter().flatten().all(|&n| n == 1), "counts {counts:?} piece {piece}");
            }
        }
    }

    #[test]
    fn pieces_are_whole_units_within_mpi_counts() {
        for size in [1, 2, 3, 64, 1000] {
            for unit in [1, 32, 68] {
                let p = piece_bytes(size, unit);
                assert_eq!(p % unit as u64, 0);
                assert!(p <= PIECE_CAP && p * size as u64 <= i32::MAX as u64, "size {size} unit {unit}: {p}");
            }
        }
    }

    #[test]
    fn local_world_is_rank_0_of_1_and_hands_back_its_data() {
        let w = Comm::local();
        assert_eq!((w.rank(), w.size(), w.is_root()), (0, 1, true));
        assert_eq!(w.all_gather(b"abc"), vec![b"abc".to_vec()]);
        assert_eq!(w.all_gather_u64(&[7, u64::MAX]), vec![vec![7, u64::MAX]]);
        assert_eq!(w.broadcast(vec![1, 2]), vec![1, 2]);
        assert_eq!(w.try_receive(None, Tag::Lease), None);
        w.send(0, Tag::Request, b"x");
        assert_eq!(w.try_receive(None, Tag::Lease), None);
        assert_eq!(w.try_receive(Some(0), Tag::Request), Some((0, b"x".to_vec())));
        assert_eq!(w.try_receive(None, Tag::Request), None);
    }
}
