//! Raman scattering by water: a shift of the wavenumber by the O–H stretch band.
//!
//! The emitted wavenumber is κ = κ' − Δκ (κ = 10⁷/λ in cm⁻¹ for λ in nm), Δκ drawn from the
//! band g(Δκ), a sum of Gaussians Σ_j w_j N(Δκ; Δκ_j, s_j) with Σ w_j = 1, s_j = FWHM_j/(2√(2 ln 2)).
//! In wavelength the redistribution is
//!
//! f_R(λ' → λ) = g(10⁷/λ' − 10⁷/λ) · 10⁷/λ²  (nm⁻¹),
//!
//! which integrates to one over λ (Mobley, *Light and Water* 1994, §5.13, Eq. 5.89–5.93).
//! Two band shapes are offered:
//! - `single`: one Gaussian at Δκ = 3357 cm⁻¹ with a given FWHM (the centre usually quoted for
//!   the water Raman band, e.g. Bartlett et al. 1998);
//! - `walrafen`: Walrafen's (1967) four-Gaussian decomposition as tabulated by Mobley (1994,
//!   Table 5.x): w = (0.41, 0.39, 0.10, 0.10), Δκ = (3250, 3425, 3530, 3625) cm⁻¹,
//!   FWHM = (210, 175, 140, 140) cm⁻¹.
//!
//! Sampling is exact: a Gaussian j by its weight, then a Box–Muller deviate. Sampling the
//! excitation for a given emission (the path tracer's adjoint) uses the same band: κ' = κ + Δκ.
//!
//! # References
//! - Walrafen, "Raman spectral studies of the effects of temperature on water structure",
//!   J. Chem. Phys. 47 (1967), 114–126.
//! - Mobley, *Light and Water* (1994), §5.13.
//! - Bartlett, Voss, Sathyendranath & Vodacek, "Raman scattering by pure water and seawater",
//!   Appl. Opt. 37 (1998), 3324–3332.

use super::gaussian::normal;
use crate::rng::Rng;
use std::f64::consts::PI;

/// 10⁷ nm cm⁻¹: κ (cm⁻¹) = 10⁷ / λ (nm).
pub const NM_CM: f64 = 1e7;

/// FWHM = 2√(2 ln 2) σ.
const FWHM_PER_SIGMA: f64 = 2.354_820_045_030_949;

/// The Raman shift band g(Δκ): a mixture of Gaussians in wavenumber shift, cm⁻¹ (see the module
/// docs).
#[derive(Clone, Debug, PartialEq)]
pub struct RamanShift {
    /// (weight, centre shift cm⁻¹, σ cm⁻¹), weights summing to one.
    lines: Vec<(f64, f64, f64)>,
}

impl RamanShift {
    /// One Gaussian band at `shift_cm` with full width at half maximum `fwhm_cm`.
    pub fn single(shift_cm: f64, fwhm_cm: f64) -> Result<RamanShift, String> {
        RamanShift::lines(&[(1.0, shift_cm, fwhm_cm)])
    }

    /// Walrafen's four-Gaussian band of liquid water (Mobley 1994).
    pub fn walrafen() -> RamanShift {
        RamanShift {
            lines: [(0.41, 3250.0, 210.0), (0.39, 3425.0, 175.0), (0.10, 3530.0, 140.0), (0.10, 3625.0, 140.0)]
                .iter()
                .map(|&(w, c, f)| (w, c, f / FWHM_PER_SIGMA))
                .collect(),
        }
    }

    /// Gaussians given as (weight, centre cm⁻¹, FWHM cm⁻¹); weights are normalised.
    pub fn lines(lines: &[(f64, f64, f64)]) -> Result<RamanShift, String> {
        let total: f64 = lines.iter().map(|l| l.0).sum();
        let ok = !lines.is_empty()
            && total > 0.0
            && lines.iter().all(|&(w, c, f)| w >= 0.0 && c.is_finite() && f.is_finite() && f > 0.0);
        if !ok {
            return Err("raman band: each line needs a weight ≥ 0, a finite shift and a FWHM > 0 (cm⁻¹)".into());
        }
        Ok(RamanShift { lines: lines.iter().map(|&(w, c, f)| (w / total, c, f / FWHM_PER_SIGMA)).collect() })
    }

    /// g(Δκ) per cm⁻¹.
    pub fn band(&self, shift_cm: f64) -> f64 {
        self.lines
            .iter()
            .map(|&(w, c, s)| w * (-0.5 * ((shift_cm - c) / s).powi(2)).exp() / (s * (2.0 * PI).sqrt()))
            .sum()
    }

    /// f_R(λ' → λ) per nm of λ.
    pub fn density(&self, excitation_nm: f64, emission_nm: f64) -> f64 {
        self.band(NM_CM / excitation_nm - NM_CM / emission_nm) * NM_CM / (emission_nm * emission_nm)
    }

    /// A shift Δκ drawn from g.
    pub fn sample_shift(&self, rng: &mut Rng) -> f64 {
        let mut u = rng.uniform();
        for &(w, c, s) in &self.lines {
            if u < w {
                return c + s * normal(rng);
            }
            u -= w;
        }
        let &(_, c, s) = self.lines.last().unwrap_or(&(1.0, 3357.0, 150.0));
        c + s * normal(rng)
    }

    /// An emission wavelength for excitation λ' (None when the shift leaves no positive
    /// wavenumber, which needs λ' beyond 2.5 μm).
    pub fn sample(&self, excitation_nm: f64, rng: &mut Rng) -> Option<f64> {
        let k = NM_CM / excitation_nm - self.sample_shift(rng);
        (k > 0.0).then(|| NM_CM / k)
    }

    /// The emission wavelengths outside which [`RamanShift::density`] is exactly zero in f64,
    /// nm: shifts beyond ±40σ of every line, whose Gaussian factor exp(−800) underflows to 0
    /// (exp underflows below −745). The upper end is infinite when the largest such shift
    /// exceeds the excitation's wavenumber.
    pub fn nonzero_nm(&self, excitation_nm: f64) -> (f64, f64) {
        let lo = self.lines.iter().map(|l| l.1 - 40.0 * l.2).fold(f64::INFINITY, f64::min);
        let hi = self.lines.iter().map(|l| l.1 + 40.0 * l.2).fold(f64::NEG_INFINITY, f64::max);
        let k = NM_CM / excitation_nm;
        let shortest = if k - lo > 0.0 { NM_CM / (k - lo) } else { f64::INFINITY };
        let longest = if k - hi > 0.0 { NM_CM / (k - hi) } else { f64::INFINITY };
        (shortest, longest)
    }

    /// The range of shifts holding all but 10⁻¹⁴ of the band (±8σ of each line), cm⁻¹.
    pub fn shift_range_cm(&self) -> (f64, f64) {
        let lo = self.lines.iter().map(|l| l.1 - 8.0 * l.2).fold(f64::INFINITY, f64::min);
        let hi = self.lines.iter().map(|l| l.1 + 8.0 * l.2).fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    }
}
