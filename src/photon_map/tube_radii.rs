//! The tube radius of each photon beam, from the density of the volume map's photons around it.
//!
//! A photon beam's estimate blurs the beam across itself into a tube of radius r_b (see
//! [`super::photon_beams`]); its noise is set by how many tubes an eye chord passes through, its
//! bias by r_b². The radius follows the beam estimate's discs ([`super::BeamMap::build`]): where
//! the point map's k nearest photons about the beam's middle lie within r_p, a chord of length s
//! crosses ρ π r_p² s discs of photons (ρ the photons' density). A chord meets the tubes of
//! beams of length density λ_L (m of beam per m³) of total length inside them
//! E[Σ inside] = λ_L π r_b² s, and a line through a long cylinder of radius r runs 4V/S = 2 r
//! inside it on average (Cauchy's mean chord), so it crosses λ_L π r_b s / 2 tubes. The same
//! count as the discs' gives
//!
//! r_b = 2 r_p² ρ / λ_L = 2 r_p² / ℓ̄,
//!
//! with ℓ̄ = λ_L/ρ the length of beam per stored photon over the whole pass. For r_p = 5 cm and
//! ℓ̄ = 1 m a tube's radius is 5 mm where the disc's was 5 cm: about as many hits a chord, the
//! light blurred over a tenth of the width.
//!
//! # References
//! - W. Jarosz, D. Nowrouzezahrai, I. Sadeghi and H. W. Jensen (2011), "A comprehensive theory
//!   of volumetric radiance estimation using photon points and beams", ACM Transactions on
//!   Graphics 30(1), 5.
//! - L. A. Santaló (1976), Integral Geometry and Geometric Probability, Addison-Wesley (the mean
//!   chord 4V/S of a convex body met by isotropic uniform lines, Cauchy's formula).

use super::{Neighbours, PhotonBeam, PhotonMap};
use rayon::prelude::*;

/// The tube radius of each of `beams`, m: 2 r_p²/ℓ̄ with r_p the radius of the sphere about the
/// beam's middle holding the `k` nearest photons of `points` (at most `max_radius`, which it is
/// also where fewer lie within it), ℓ̄ = `total_length_m` over the photons in `points` (the
/// pass's beams' total length, those not kept included), times `scale`; at most `max_radius`.
/// Each is `max_radius` × `scale` when there are no photons or no beam length. Computed in
/// parallel; the result does not depend on the thread count.
pub fn tube_radii(
    points: &PhotonMap,
    beams: &[PhotonBeam],
    total_length_m: f64,
    k: usize,
    max_radius: f64,
    scale: f64,
) -> Vec<f64> {
    if points.is_empty() || total_length_m.is_nan() || total_length_m <= 0.0 {
        return vec![max_radius * scale; beams.len()];
    }
    let per_photon = total_length_m / points.len() as f64;
    beams
        .par_iter()
        .map_init(Neighbours::default, |nb, b| {
            points.knn(b.origin + 0.5 * b.length * b.dir, k, max_radius, nb);
            let rp = if nb.len() < k { max_radius } else { f64::from(nb.max_dist2()).sqrt() };
            (2.0 * rp * rp / per_photon).min(max_radius) * scale
        })
        .collect()
}

/// The longest piece of a beam in the hierarchy of [`super::PhotonBeamMap`], in tube radii.
pub const PIECE_RADII: f64 = 8.0;

/// The most pieces per beam on average: where tubes are thin against their beams' length, the
/// pieces are made longer so that the map holds at most this many per beam.
pub const MAX_PIECES_PER_BEAM: f64 = 16.0;

/// `beams` cut into pieces at most [`PIECE_RADII`] tube radii long (each with its beam's
/// radius, power and path), for the hierarchy: a beam of a metre in a tube of 5 mm has a
/// bounding box 200 times wider than its tube, so a chord's query would test hundreds of beams
/// for each one it passes through. The pieces' tubes, flat-ended, tile their beam's tube, so the
/// estimate is the same sum over shorter stretches. No piece is shorter than the beams' total
/// length over [`MAX_PIECES_PER_BEAM`] times their number (the map's memory stays within that
/// many beams'; `render::memory` counts on it).
pub fn pieces(beams: Vec<PhotonBeam>, radii: Vec<f64>) -> (Vec<PhotonBeam>, Vec<f64>) {
    let shortest = shortest_piece(&beams);
    let total = piece_count(&beams, &radii);
    let (mut out, mut out_radii) = (Vec::with_capacity(total), Vec::with_capacity(total));
    for (b, r) in beams.into_iter().zip(radii) {
        let n = pieces_of(&b, r, shortest);
        let step = b.length / n as f64;
        for i in 0..n {
            out.push(PhotonBeam { origin: b.origin + (i as f64 * step) * b.dir, length: step, ..b });
            out_radii.push(r);
        }
    }
    (out, out_radii)
}

/// How many pieces [`pieces`] cuts `beams` (with tube radii `radii`) into.
pub fn piece_count(beams: &[PhotonBeam], radii: &[f64]) -> usize {
    let shortest = shortest_piece(beams);
    beams.iter().zip(radii).map(|(b, r)| pieces_of(b, *r, shortest)).sum()
}

/// The shortest piece [`pieces`] makes of `beams`, m.
fn shortest_piece(beams: &[PhotonBeam]) -> f64 {
    let total: f64 = beams.iter().map(|b| b.length).filter(|l| l.is_finite()).sum();
    total / (MAX_PIECES_PER_BEAM * beams.len().max(1) as f64)
}

/// The pieces of one beam of tube radius `r`: its length over the longer of [`PIECE_RADII`]
/// radii and `shortest`, rounded up (one for a beam that cannot be hit).
fn pieces_of(b: &PhotonBeam, r: f64, shortest: f64) -> usize {
    let n = (b.length / (PIECE_RADII * r).max(shortest)).ceil();
    if n.is_finite() && n > 1.0 { n as usize } else { 1 }
}
