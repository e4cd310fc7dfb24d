//! Eye-pass tiles: which rows of the image a rank renders next.
//!
//! A tile is a run of whole image rows, so its pixels are contiguous in the row-major image and
//! rank 0 puts a finished tile in place with one copy. Rank 0 keeps a [`Dispenser`] and hands out
//! *leases* (one tile each) on request. Two policies:
//!
//! - [`Schedule::Dynamic`], guided self-scheduling (Polychronopoulos & Kuck 1987) with smaller
//!   chunks as in "factoring" (Hummel, Schonberg & Flynn 1992): each lease is `⌈R / 4P⌉` rows of
//!   the `R` still unassigned, among `P` ranks. Early leases are large (few messages), late ones
//!   small, so ranks that drew expensive rows (glass, media, curved paths) are not waited for at
//!   the end. The divisor is 4P rather than factoring's 2P because rows differ a lot in cost: in
//!   the default scene at 192×160 (2 ranks) rows 40–70 took one rank 3.0 s while the other
//!   rendered the remaining 130 rows in 2.6 s — with as many rays per row, so it is the cost per
//!   ray (k-nearest searches where photons are sparse) — and a first lease of R/2P rows could
//!   outlast all the other work.
//! - [`Schedule::Static`], blocks of rows dealt round-robin ([`super::split::dealt`]), about
//!   eight per rank: each rank's share is fixed in advance; it balances only as well as the rows'
//!   costs are spread.
//!
//! Pixels keep their own random streams, so the image is the same for either policy, any rank
//! count and any lease sizes.
//!
//! # References
//! - Polychronopoulos & Kuck 1987, "Guided self-scheduling: a practical scheduling scheme for
//!   parallel supercomputers", IEEE Trans. Computers C-36(12).
//! - Hummel, Schonberg & Flynn 1992, "Factoring: a method for scheduling parallel loops",
//!   CACM 35(8).

use super::split::dealt;
use std::ops::Range;

/// How rank 0 hands out rows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Schedule {
    /// Guided self-scheduling: leases of ⌈remaining / 4·ranks⌉ rows, to whoever asks.
    #[default]
    Dynamic,
    /// Fixed blocks of rows dealt round-robin, about eight per rank.
    Static,
}

/// A dynamic lease is the remaining rows over this many times the ranks.
pub const LEASE_DIVISOR: usize = 4;

/// Static blocks per rank.
pub const STATIC_BLOCKS_PER_RANK: usize = 8;

/// The rows still to hand out.
pub struct Dispenser {
    rows: usize,
    ranks: usize,
    /// Most rows in a lease (so a tile's message stays within MPI's counts).
    max_rows: usize,
    state: State,
}

enum State {
    Dynamic {
        next: usize,
    },
    /// Each rank's remaining blocks, in order.
    Static {
        queues: Vec<std::collections::VecDeque<Range<usize>>>,
    },
}

impl Dispenser {
    /// A dispenser of `rows` rows among `ranks` ranks, leases of at most `max_rows` rows.
    pub fn new(schedule: Schedule, rows: usize, ranks: usize, max_rows: usize) -> Dispenser {
        let ranks = ranks.max(1);
        let max_rows = max_rows.max(1);
        let state = match schedule {
            Schedule::Dynamic => State::Dynamic { next: 0 },
            Schedule::Static => {
                let block = rows.div_ceil(ranks * STATIC_BLOCKS_PER_RANK).clamp(1, max_rows) as u64;
                let queues = (0..ranks)
                    .map(|r| dealt(rows as u64, block, r, ranks).map(|b| b.start as usize..b.end as usize).collect())
                    .collect();
                State::Static { queues }
            }
        };
        Dispenser { rows, ranks, max_rows, state }
    }

    /// The next lease for `rank`, or `None` when it has nothing more to do.
    pub fn next(&mut self, rank: usize) -> Option<Range<usize>> {
        match &mut self.state {
            State::Dynamic { next } => {
                let remaining = self.rows - *next;
                if remaining == 0 {
                    return None;
                }
                let n = remaining.div_ceil(LEASE_DIVISOR * self.ranks).min(self.max_rows);
                let lease = *next..*next + n;
                *next += n;
                Some(lease)
            }
            State::Static { queues } => queues.get_mut(rank)?.pop_front(),
        }
    }
}

/// The most rows per lease for rows of `row_bytes` bytes: a lease's message stays under 256 MiB.
pub fn max_rows_for(row_bytes: usize) -> usize {
    ((256usize << 20) / row_bytes.max(1)).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Drains a dispenser with ranks asking in turn (rank `order[i % len]`), and checks that
    /// every row is handed out exactly once.
    fn drain(
        schedule: Schedule,
        rows: usize,
        ranks: usize,
        max_rows: usize,
        order: &[usize],
    ) -> Vec<(usize, Range<usize>)> {
        let mut d = Dispenser::new(schedule, rows, ranks, max_rows);
        let mut out = Vec::new();
        let mut finished = vec![false; ranks];
        let mut i = 0;
        while finished.iter().any(|f| !f) {
            let r = order[i % order.len()] % ranks;
            i += 1;
            match d.next(r) {
                Some(l) => {
                    assert!(!l.is_empty() && l.len() <= max_rows);
                    out.push((r, l));
                }
                None => finished[r] = true,
            }
            assert!(i < 100_000, "dispenser does not run dry");
        }
        let mut hits = vec![0u32; rows];
        for (_, l) in &out {
            for y in l.clone() {
                hits[y] += 1;
            }
        }
        assert!(hits.iter().all(|&h| h == 1), "{schedule:?}, {rows} rows, {ranks} ranks: a row is missed or repeated");
        out
    }

    #[test]
    fn every_row_is_leased_exactly_once() {
        for schedule in [Schedule::Dynamic, Schedule::Static] {
            for rows in [0, 1, 2, 7, 48, 144, 1080] {
                for ranks in 1..=6 {
                    for max_rows in [1, 5, usize::MAX] {
                        drain(schedule, rows, ranks, max_rows, &[0, 1, 2, 3, 4, 5]);
                        drain(schedule, rows, ranks, max_rows, &[1, 1, 0, 2, 1, 3, 5, 4]);
                    }
                }
            }
        }
    }

    #[test]
    fn dynamic_leases_shrink_to_single_rows() {
        let leases = drain(Schedule::Dynamic, 1080, 4, usize::MAX, &[0, 1, 2, 3]);
        let lens: Vec<usize> = leases.iter().map(|(_, l)| l.len()).collect();
        assert_eq!(lens[0], 68, "first lease is rows / (4 ranks)");
        assert!(lens.windows(2).all(|w| w[1] <= w[0]), "{lens:?}");
        assert_eq!(*lens.last().unwrap(), 1);
        // O(P log(R/P)) leases, far fewer than rows.
        assert!(lens.len() < 150, "{} leases", lens.len());
    }

    #[test]
    fn static_blocks_are_fixed_per_rank() {
        let leases = drain(Schedule::Static, 100, 3, usize::MAX, &[2, 0, 1]);
        for (r, l) in &leases {
            // Blocks of ⌈100 / 24⌉ = 5 rows dealt round-robin.
            assert_eq!((l.start / 5) % 3, *r, "block {l:?} went to rank {r}");
        }
    }

    #[test]
    fn lease_size_respects_the_message_limit() {
        assert_eq!(max_rows_for(usize::MAX), 1);
        assert_eq!(max_rows_for(1 << 20), 256);
    }
}
