//! Map assembly: every rank's photons gathered onto every rank, built into the same kd-tree a
//! single process builds; and the irradiance cache, estimated in parts and gathered likewise.
//!
//! A photon map is built by [`PhotonMap::build`] as: bounding box of the records → origin (the
//! box centre) → encoding relative to it → kd-tree of the photons in record order. Assembly runs
//! the same steps across ranks:
//!
//! 1. each rank's box is gathered and combined by min and max (exact), giving the single-process
//!    origin;
//! 2. each rank encodes its records relative to it (encoding is per photon);
//! 3. the 32-byte photons are all-gathered ([`Comm::all_gather_pieces`], rounds of ≤ 64 MiB per
//!    rank) into rank order — which is batch order, since ranks shoot contiguous batch ranges;
//! 4. each rank builds the kd-tree from that identical sequence.
//!
//! So every rank holds, bit for bit, the map one process would build, and images do not depend
//! on the number of ranks. The memory check of [`super::budget`] runs between steps 2 and 3.
//!
//! # Seam for a distributed kd-tree
//! Maps are [`Placement::Replicated`] only. A partitioned map (each rank keeping the photons of
//! its kd-tree subtrees, queries forwarded to the owner of a cell) would be a second
//! [`Placement`], chosen when the budget check fails, with the eye pass's `knn` going through it;
//! steps 1–2 and the budget check stay as they are.

use super::Comm;
use super::budget::Budget;
use super::split::{dealt, dealt_index};
use crate::error::Result;
use crate::photon_map::{Estimator, IrradianceCache, KdTree, Photon, PhotonBeam, PhotonMap, PhotonRecord};
use crate::timing::{Span, Took};
use glam::DVec3;

/// Where a map's photons live.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// Every rank holds the whole map.
    Replicated,
}

/// Irradiance cache points are dealt to ranks in blocks of this many (round-robin, so ranks get
/// points from every part of the kd-tree order and a similar share of dense regions).
pub const IRRADIANCE_BLOCK: u64 = 256;

/// What an assembly step moved, and how long its parts took on this rank.
#[derive(Clone, Copy, Debug, Default)]
pub struct Gathered {
    /// Items over all ranks.
    pub items: u64,
    /// Bytes this rank received from the others.
    pub received_bytes: u64,
    /// Estimating this rank's share (irradiance cache; zero for photon maps).
    pub compute: Took,
    /// Combining bounds and counts and encoding (photon maps), the budget check, the all-gather.
    pub gather: Took,
    /// Building the kd-tree (the same on every rank).
    pub build: Took,
}

/// The photon map of every rank's `records` (this rank's, in batch order), the same on every
/// rank. Collective. Fails, on every rank, if the map would not fit in `budget`.
pub fn photon_map(
    comm: &Comm,
    budget: &mut Budget,
    name: &str,
    records: &[PhotonRecord],
) -> Result<(PhotonMap, Gathered)> {
    let t = Span::start();
    let (lo, hi) = global_bounds(comm, records);
    let origin = PhotonMap::origin_for(lo, hi);
    let encoded = PhotonMap::encode(records, origin);
    let counts = comm.all_gather_u64(&[encoded.len() as u64]);
    let offsets: Vec<u64> = counts.iter().scan(0, |acc, c| Some(std::mem::replace(acc, *acc + c[0]))).collect();
    let items: u64 = counts.iter().map(|c| c[0]).sum();
    let bytes = KdTree::<Photon>::bytes_for(items as usize) as u64;
    budget.reserve(comm, &format!("the {name} photon map ({items} photons)"), bytes)?;
    let (photons, received) = match comm.size() {
        // One rank's all-gather hands back its own photons.
        1 => (encoded, 0),
        _ => gather_photons(comm, encoded, &offsets, items as usize),
    };
    let gather = t.took();
    let t = Span::start();
    let map = PhotonMap::from_photons(origin, photons);
    let build = t.took();
    Ok((map, Gathered { items, received_bytes: received, compute: Took::default(), gather, build }))
}

/// Every rank's photon beams in rank order — the batches' order, so the single process's order
/// on any rank count — this rank's `beams` kept in place, the others' decoded from the
/// all-gather ([`PhotonBeam::to_le_bytes`]), with the time taken and the bytes received. The
/// gathered beams are checked against `budget` first. Collective.
pub fn photon_beams(comm: &Comm, budget: &mut Budget, beams: Vec<PhotonBeam>) -> Result<(Vec<PhotonBeam>, Took, u64)> {
    let t = Span::start();
    let counts = comm.all_gather_u64(&[beams.len() as u64]);
    let total: u64 = counts.iter().map(|c| c[0]).sum();
    let bytes = total * size_of::<PhotonBeam>() as u64;
    budget.reserve(comm, &format!("the photon beams ({total} flights)"), bytes)?;
    if comm.size() == 1 {
        return Ok((beams, t.took(), 0));
    }
    let wire: Vec<u8> = beams.iter().flat_map(|b| b.to_le_bytes()).collect();
    let parts = comm.all_gather(&wire);
    drop(wire);
    let me = comm.rank();
    let mut all = Vec::with_capacity(total as usize);
    let mut received = 0u64;
    let mut mine = Some(beams);
    for (rank, part) in parts.iter().enumerate() {
        if rank == me {
            all.extend(mine.take().unwrap_or_default());
        } else {
            received += part.len() as u64;
            all.extend(part.chunks_exact(PhotonBeam::BYTES).map(PhotonBeam::from_le_bytes));
        }
    }
    Ok((all, t.took(), received))
}

/// Every rank's photons in rank order: this rank's copied in place, the others' decoded from
/// the all-gather. Returns them and the bytes received.
fn gather_photons(comm: &Comm, encoded: Vec<Photon>, offsets: &[u64], items: usize) -> (Vec<Photon>, u64) {
    let me = comm.rank();
    let wire: Vec<u8> = encoded.iter().flat_map(|p| p.to_le_bytes()).collect();
    let mut photons = vec![Photon::from_le_bytes(&[0; Photon::BYTES]); items];
    photons[offsets[me] as usize..][..encoded.len()].copy_from_slice(&encoded);
    drop(encoded);
    let received = comm.all_gather_pieces(&wire, Photon::BYTES, &mut |rank, offset, piece| {
        if rank == me {
            return;
        }
        let first = offsets[rank] as usize + offset / Photon::BYTES;
        for (slot, b) in photons[first..].iter_mut().zip(piece.chunks_exact(Photon::BYTES)) {
            *slot = Photon::from_le_bytes(b.try_into().unwrap_or(&[0; Photon::BYTES]));
        }
    });
    (photons, received)
}

/// The bounding box of every rank's finite record positions.
fn global_bounds(comm: &Comm, records: &[PhotonRecord]) -> (DVec3, DVec3) {
    let (lo, hi) = PhotonMap::bounds(records);
    let mine: Vec<u64> = lo.to_array().iter().chain(hi.to_array().iter()).map(|v| v.to_bits()).collect();
    let f = |b: u64| f64::from_bits(b);
    comm.all_gather_u64(&mine).iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(DVec3::new(f(v[0]), f(v[1]), f(v[2]))), hi.max(DVec3::new(f(v[3]), f(v[4]), f(v[5]))))
    })
}

/// The irradiance cache of `est`'s map (which every rank holds), each rank estimating the blocks
/// of points dealt to it, the values gathered into point order on every rank: the cache
/// [`IrradianceCache::build`] computes. Collective; fails on every rank if it would not fit.
pub fn irradiance(
    comm: &Comm,
    budget: &mut Budget,
    est: &Estimator,
    stride: usize,
) -> Result<(IrradianceCache, Gathered)> {
    let n = IrradianceCache::points(est.map.len(), stride) as u64;
    let bands = est.bands.count;
    let bytes = IrradianceCache::bytes_for(n as usize, bands) as u64;
    let t = Span::start();
    budget.reserve(comm, &format!("the irradiance cache ({n} points, {bands} bands)"), bytes)?;
    let reserve = t.took();
    let t = Span::start();
    let size = comm.size();
    let mine: Vec<u32> = dealt(n, IRRADIANCE_BLOCK, comm.rank(), size).flatten().map(|i| i as u32).collect();
    let estimated = IrradianceCache::estimate(est, stride, &mine);
    let mut local: Vec<u8> = Vec::with_capacity(4 * estimated.len());
    for v in estimated {
        local.extend_from_slice(&v.to_le_bytes());
    }
    let compute = t.took();
    let t = Span::start();
    let point_bytes = (4 * bands).max(1);
    let mut values = vec![0f32; n as usize * bands];
    let received = comm.all_gather_pieces(&local, point_bytes, &mut |rank, offset, piece| {
        for (j, chunk) in (offset / point_bytes..).zip(piece.chunks_exact(point_bytes)) {
            let point = dealt_index(j as u64, IRRADIANCE_BLOCK, rank, size) as usize;
            for (d, b) in values[point * bands..][..bands].iter_mut().zip(chunk.chunks_exact(4)) {
                *d = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            }
        }
    });
    let gathered = t.took();
    let gather =
        Took { seconds: reserve.seconds + gathered.seconds, cpu_seconds: reserve.cpu_seconds + gathered.cpu_seconds };
    drop(local);
    let t = Span::start();
    let cache = IrradianceCache::from_values(est, stride, values);
    let build = t.took();
    let g = Gathered { items: n, received_bytes: received, compute, gather, build };
    Ok((cache, g))
}
