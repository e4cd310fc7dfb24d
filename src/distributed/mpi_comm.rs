//! [`super::Comm::Mpi`]: `MPI_COMM_WORLD` through rsmpi (the `mpi` crate) over the system MPI.
//!
//! MPI is initialised with `MPI_THREAD_SERIALIZED`: the render calls MPI from its rayon worker
//! thread, and during the eye pass rank 0's lease server calls it from a second thread while the
//! first only computes, so calls never overlap. The default error handler
//! (`MPI_ERRORS_ARE_FATAL`) stays: if a rank dies, `mpirun` ends the job (see [`super::fault`]).
//!
//! Only `MPI_COMM_WORLD` is used, fetched afresh for each call (a handle, not a pointer), so the
//! comm can be shared with the server thread.

use super::wire::{Tag, piece_bytes, round_parts, rounds};
use crate::error::{Error, Result};
use mpi::Count;
use mpi::datatype::PartitionMut;
use mpi::environment::{Threading, Universe};
use mpi::point_to_point::MatchedReceiveVec;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// An initialised MPI environment; dropping it calls `MPI_Finalize`.
pub struct MpiComm {
    _universe: Universe,
    rank: usize,
    size: usize,
    host: String,
}

impl MpiComm {
    /// Initialises MPI (`MPI_Init_thread` asking for `MPI_THREAD_SERIALIZED`).
    pub fn start() -> Result<MpiComm> {
        let (universe, threading) = mpi::initialize_with_threading(Threading::Serialized)
            .ok_or_else(|| Error::internal("MPI is already initialised"))?;
        if !matches!(threading, Threading::Serialized | Threading::Multiple) {
            return Err(Error::internal(format!(
                "the MPI library offers only {threading:?} threading; morgana needs MPI_THREAD_SERIALIZED"
            )));
        }
        let comm = universe.world();
        let host = mpi::environment::processor_name().unwrap_or_else(|_| super::comm::local_host_name());
        Ok(MpiComm { rank: comm.rank() as usize, size: comm.size() as usize, host, _universe: universe })
    }

    fn comm(&self) -> SimpleCommunicator {
        SimpleCommunicator::world()
    }

    /// This process's rank in `MPI_COMM_WORLD`.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// Number of ranks in `MPI_COMM_WORLD`.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The processor name MPI reports for this rank (else the local host name).
    pub fn host(&self) -> String {
        self.host.clone()
    }

    /// The MPI library's version line (e.g. "Open MPI v4.1.4, ...").
    pub fn library(&self) -> String {
        let v = mpi::environment::library_version().unwrap_or_default();
        let line = v.lines().next().unwrap_or("MPI");
        line.trim_matches(|c: char| c == '\0' || c.is_whitespace()).to_string()
    }

    /// See [`super::Comm::all_gather_pieces`]: counts first, then rounds of `MPI_Allgatherv`.
    pub fn all_gather_pieces(&self, local: &[u8], unit: usize, sink: &mut dyn FnMut(usize, usize, &[u8])) -> u64 {
        let comm = self.comm();
        let mut counts = vec![0u64; self.size];
        comm.all_gather_into(&(local.len() as u64), &mut counts[..]);
        let piece = piece_bytes(self.size, unit);
        let mut buf: Vec<u8> = Vec::new();
        let mut received = 0u64;
        for k in 0..rounds(&counts, piece) {
            let parts = round_parts(&counts, piece, k);
            let lens: Vec<Count> = parts.iter().map(|p| (p.end - p.start) as Count).collect();
            let displs: Vec<Count> = lens.iter().scan(0, |acc, &c| Some(std::mem::replace(acc, *acc + c))).collect();
            buf.resize(lens.iter().map(|&c| c as usize).sum(), 0);
            let mine = &parts[self.rank];
            let send = &local[mine.start as usize..mine.end as usize];
            {
                let mut partition = PartitionMut::new(&mut buf[..], &lens[..], &displs[..]);
                comm.all_gather_varcount_into(send, &mut partition);
            }
            for (r, part) in parts.iter().enumerate() {
                let (d, n) = (displs[r] as usize, lens[r] as usize);
                if n > 0 {
                    if r != self.rank {
                        received += n as u64;
                    }
                    sink(r, part.start as usize, &buf[d..d + n]);
                }
            }
        }
        received
    }

    /// See [`super::Comm::broadcast`]: the length, then the bytes in pieces of MPI's `int` counts.
    pub fn broadcast(&self, mut bytes: Vec<u8>) -> Vec<u8> {
        let comm = self.comm();
        let root = comm.process_at_rank(0);
        let mut len = bytes.len() as u64;
        root.broadcast_into(&mut len);
        bytes.resize(len as usize, 0);
        for chunk in bytes.chunks_mut(i32::MAX as usize) {
            root.broadcast_into(chunk);
        }
        bytes
    }

    /// See [`super::Comm::send`]: a blocking standard-mode send.
    pub fn send(&self, to: usize, tag: Tag, bytes: &[u8]) {
        self.comm().process_at_rank(to as i32).send_with_tag(bytes, tag as i32);
    }

    /// See [`super::Comm::try_receive`]: a matched probe, then the receive.
    pub fn try_receive(&self, from: Option<usize>, tag: Tag) -> Option<(usize, Vec<u8>)> {
        let comm = self.comm();
        let probe = match from {
            Some(r) => comm.process_at_rank(r as i32).immediate_matched_probe_with_tag(tag as i32),
            None => comm.any_process().immediate_matched_probe_with_tag(tag as i32),
        }?;
        let (bytes, status) = probe.matched_receive_vec::<u8>();
        Some((status.source_rank() as usize, bytes))
    }

    /// `MPI_Abort` on `MPI_COMM_WORLD` with `code`.
    pub fn abort(&self, code: i32) -> ! {
        self.comm().abort(code)
    }
}
