//! What crosses between ranks, independent of how it is sent: the tags of the eye pass's
//! point-to-point messages, and the schedule of a streamed all-gather (pieces per rank and
//! round) that both the single-process and the MPI communicators follow.

/// Tags of the point-to-point messages (the eye pass's lease protocol, see [`super::eye`]).
/// Tags of the point-to-point messages (the eye pass's lease protocol, see [`super::eye`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(i32)]
pub enum Tag {
    /// Worker → rank 0: the rows of the last lease (if any) and a request for the next.
    Request = 11,
    /// Rank 0 → worker: the next lease of rows, or none.
    Lease = 12,
}

/// Largest piece (bytes per rank and round) of a streamed all-gather
/// ([`super::Comm::all_gather_pieces`]): 64 MiB, so a round's receive buffer stays small next to
/// the maps being assembled.
pub const PIECE_CAP: u64 = 64 << 20;

/// The pieces of one round of a streamed all-gather: for each rank with `counts[rank]` bytes,
/// the byte range of its contribution that round `round` carries, when every rank sends at most
/// `piece` bytes per round. Rounds `0..rounds(counts, piece)` carry every byte exactly once.
pub fn round_parts(counts: &[u64], piece: u64, round: u64) -> Vec<std::ops::Range<u64>> {
    counts
        .iter()
        .map(|&c| {
            let start = (round * piece).min(c);
            start..(start + piece).min(c)
        })
        .collect()
}

/// Rounds a streamed all-gather takes: enough for the largest contribution.
pub fn rounds(counts: &[u64], piece: u64) -> u64 {
    counts.iter().max().map_or(0, |m| m.div_ceil(piece.max(1)))
}

/// Bytes per rank and round: whole `unit`s, at most [`PIECE_CAP`], and small enough that a
/// round's total over `size` ranks fits MPI's `int` counts and displacements.
pub fn piece_bytes(size: usize, unit: usize) -> u64 {
    let unit = unit.max(1) as u64;
    let limit = PIECE_CAP.min(i32::MAX as u64 / size.max(1) as u64);
    (limit / unit).max(1) * unit
}
