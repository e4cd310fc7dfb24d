//! The photon-beam estimate: the light a medium scatters toward the eye along a chord, from the
//! tubes of the photon beams it passes through (Jarosz et al. 2011).
//!
//! A photon of power Φ flying a straight stretch of a medium is a sample of the track-length
//! estimator of fluence: blurred across its direction with the kernel 1/(π r²), it adds
//! Φ/(π r²) to the fluence inside its tube of radius r. The radiance a chord gathers is the
//! in-scattered light integrated along it,
//!
//! ∫₀ˢ T(0→t) σ_s(x) ∫ f(ω'·ω) L(x, ω') dω' dt ≈ Σ_b T(0→t_b) σ_s(x_b) f(λ_b; ω_b·ω) Φ_b ℓ_b / (π r_b² Δλ)
//!
//! summed over the beams whose tube the chord passes through for a length ℓ_b about t_b: a
//! "beam × beam" estimate in the terms of Jarosz, Nowrouzezahrai, Sadeghi & Jensen (2011), with
//! a kernel blurring each beam across itself in two dimensions; their 1-D kernel would divide
//! by sin θ instead, which is unbounded for a chord along a beam. The
//! bias is that of the blur across the beam, O(r²) where the fluence is smooth; a tube crossed
//! at random holds a chord 2 r long on average, so its noise falls as 1/r and not 1/r² as a
//! disc's: progressive passes shrink r as rᵢ₊₁ = rᵢ (i + α)/(i + 1) ([`crate::scene`]'s
//! `tube_scale`, the rule of progressive photon beams).
//!
//! Each term is read as a photon stored at the chord's point with power Φ_b σ_t(x_b) ℓ_b, the
//! collisions the stretch ℓ_b makes on average, so the medium's albedo, phase function and
//! inelastic components weigh it as they weigh a stored photon ([`super::BeamEstimator`]):
//! σ_s = α σ_t elastically, and every beam (direct ones too) re-emits inelastically.
//!
//! # References
//! - W. Jarosz, D. Nowrouzezahrai, I. Sadeghi and H. W. Jensen (2011), "A comprehensive theory
//!   of volumetric radiance estimation using photon points and beams", ACM Transactions on
//!   Graphics 30(1), 5.
//! - W. Jarosz, D. Nowrouzezahrai, R. Thomas, P.-P. Sloan and M. Zwicker (2011), "Progressive
//!   photon beams", ACM Transactions on Graphics 30(6), 181.

use super::{ChordEstimate, Paths, PhotonBeamMap, SegmentEnds, TubeHit};
use crate::media::Medium;
use crate::spectrum::{BandValues, Bands};
use glam::DVec3;
use std::f64::consts::PI;

/// The photon-beam estimate on one pass's beams.
pub struct TubeEstimator<'a> {
    /// The beams and their tubes.
    pub beams: &'a PhotonBeamMap,
    /// The bands estimates are binned into.
    pub bands: Bands,
    /// Which beams count for elastic scattering (inelastic re-emission counts every beam).
    pub paths: Paths,
}

impl ChordEstimate for TubeEstimator<'_> {
    type Hit = TubeHit;

    /// The beams whose tube the chord passes through. The tubes end on the planes across their
    /// beams, so `ends` is not needed: a beam that ends on a wall stops there.
    fn gather(&self, o: DVec3, dir: DVec3, length: f64, _ends: SegmentEnds, hits: &mut Vec<TubeHit>) {
        self.beams.query(o, dir, length, hits);
    }

    fn t(hit: &TubeHit) -> f64 {
        hit.t
    }

    fn radiance(
        &self,
        hit: &TubeHit,
        x: DVec3,
        wo: DVec3,
        (id, medium): (u32, &Medium),
        tmp: &mut BandValues,
        add: &mut impl FnMut(usize, f64),
    ) {
        let b = self.beams.beam(hit.index);
        if b.medium != id || hit.r2.is_nan() || hit.r2 <= 0.0 {
            return;
        }
        let l = b.wavelength_nm;
        let at = medium.at(x);
        let collisions_w = b.power_w * at.density() * at.sigma_t(l) * hit.inside_m;
        let kernel = 1.0 / (PI * hit.r2 * self.bands.width_nm());
        let cos = b.dir.dot(wo);
        super::beam::add_reemitted(medium, self.bands, (l, cos, collisions_w), kernel, tmp, add);
        if !self.paths.accepts(b.path) {
            return;
        }
        if let Some(band) = self.bands.index_of(l) {
            add(band, at.albedo(l) * at.phase_eval(l, cos) * collisions_w * kernel);
        }
    }
}
