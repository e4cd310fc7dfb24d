//! How fixed work is divided among ranks: contiguous shares (photon batches) and blocks dealt
//! round-robin (irradiance points). Both depend only on (n, rank, size), so every rank computes
//! every rank's part without asking.

use std::ops::Range;

/// Rank `rank`'s contiguous share of tasks `0..n` among `size` ranks: shares differ by at most
/// one task (the first `n mod size` ranks get one more), and in rank order they tile `0..n`.
pub fn share(n: u64, rank: usize, size: usize) -> Range<u64> {
    let (size, rank) = (size.max(1) as u64, rank as u64);
    let (q, r) = (n / size, n % size);
    let start = rank * q + rank.min(r);
    start..start + q + u64::from(rank < r)
}

/// The blocks of `block` tasks (the last may be short) of `0..n` that rank `rank` owns when
/// blocks are dealt round-robin among `size` ranks: blocks `rank`, `rank + size`, …
pub fn dealt(n: u64, block: u64, rank: usize, size: usize) -> impl Iterator<Item = Range<u64>> {
    let block = block.max(1);
    (rank as u64..n.div_ceil(block)).step_by(size.max(1)).map(move |b| b * block..((b + 1) * block).min(n))
}

/// The task that rank `rank`'s `j`-th owned task (counting through its [`dealt`] blocks in
/// order) is. Every block but the last of all is full, so this is arithmetic.
pub fn dealt_index(j: u64, block: u64, rank: usize, size: usize) -> u64 {
    let block = block.max(1);
    (rank as u64 + (j / block) * size.max(1) as u64) * block + j % block
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_cover(n: u64, size: usize, parts: &dyn Fn(usize) -> Vec<Range<u64>>) {
        let mut hits = vec![0u8; n as usize];
        for r in 0..size {
            for range in parts(r) {
                for t in range {
                    hits[t as usize] += 1;
                }
            }
        }
        assert!(hits.iter().all(|&h| h == 1), "n {n}, {size} ranks: some task is missed or repeated");
    }

    #[test]
    fn shares_cover_every_batch_once_in_rank_order() {
        for n in [0u64, 1, 2, 5, 24, 25, 1000, 24_415] {
            for size in 1..=9 {
                check_cover(n, size, &|r| vec![share(n, r, size)]);
                let shares: Vec<_> = (0..size).map(|r| share(n, r, size)).collect();
                assert_eq!(shares[0].start, 0);
                assert_eq!(shares[size - 1].end, n);
                assert!(shares.windows(2).all(|w| w[0].end == w[1].start), "not in rank order");
                let lens: Vec<u64> = shares.iter().map(|s| s.end - s.start).collect();
                assert!(lens.iter().max().unwrap() - lens.iter().min().unwrap() <= 1, "{lens:?}");
            }
        }
    }

    #[test]
    fn dealt_blocks_cover_every_point_once() {
        for n in [0u64, 1, 7, 256, 257, 10_000] {
            for block in [1u64, 3, 256] {
                for size in 1..=5 {
                    check_cover(n, size, &|r| dealt(n, block, r, size).collect());
                }
            }
        }
        assert_eq!(dealt(10, 3, 1, 2).collect::<Vec<_>>(), vec![3..6, 9..10]);
    }

    #[test]
    fn dealt_index_counts_through_the_owned_blocks() {
        for (n, block, size) in [(10u64, 3u64, 2usize), (1000, 256, 3), (257, 256, 2), (5, 1, 4)] {
            for rank in 0..size {
                for (j, t) in dealt(n, block, rank, size).flatten().enumerate() {
                    assert_eq!(dealt_index(j as u64, block, rank, size), t);
                }
            }
        }
    }
}
