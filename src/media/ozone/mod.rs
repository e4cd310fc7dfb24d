//! Ozone: its absorption cross-section σ(λ) and its number density in height, scaled to a
//! column in Dobson units — a constituent of the scattering atmosphere
//! ([`super::constituents`]) that only absorbs.
//!
//! # Cross-section
//! Bogumil et al. (2003) at 293 K, resampled to 1–2 nm (see [`data`]), interpolated linearly in
//! wavelength; 0 outside 230–1000 nm. The Chappuis band peaks at 603 nm with
//! σ = 5.307 × 10⁻²¹ cm²; the Huggins band rises through 310–350 nm toward the Hartley band.
//!
//! # Profile
//! The shape is AFGL mid-latitude summer's (Anderson et al. 1986): number density
//! n(h) = x(h) P(h)/(k_B T(h)) at the table's heights (x the volume mixing ratio), interpolated
//! linearly in ln n between them, so n decays exponentially between levels. The profile is scaled
//! so that its column from the ground to the atmosphere's top is the scene's
//! ∫₀^top n dh = D × 2.6867 × 10²⁰ m⁻² for D Dobson units (1 DU = 2.6867 × 10¹⁶ molecules cm⁻²,
//! the number of molecules in a layer of pure ozone 10 µm thick at 273.15 K and 1013.25 hPa).
//! The column is integrated by composite Simpson's rule on 1 m steps. AFGL's own column up to
//! 86 km, integrated the same way, is 300.4 DU.
//!
//! # References
//! - K. Bogumil et al., J. Photochem. Photobiol. A 157 (2003), 167–184.
//! - G. P. Anderson et al., "AFGL atmospheric constituent profiles (0–120 km)",
//!   AFGL-TR-86-0110 (1986), Table 1b.
//! - WMO, *Guide to Instruments and Methods of Observation* (WMO-No. 8), ch. on ozone: the
//!   Dobson unit.

pub mod data;
mod table;

pub use table::{Interpolation, NumberDensityTable};

use crate::spectrum::{Spectrum, Tabulated};

/// Molecules per square metre in one Dobson unit (2.6867 × 10¹⁶ cm⁻²).
pub const MOLECULES_PER_M2_PER_DU: f64 = 2.6867e20;

/// Boltzmann's constant, J/K (SI 2019, exact).
const BOLTZMANN_J_PER_K: f64 = 1.380_649e-23;

/// The absorption cross-section σ(λ) in m² per molecule (Bogumil et al. 2003, 293 K), linear
/// between the table's wavelengths and 0 outside them.
pub fn cross_section_m2() -> Spectrum {
    let (nm, cm2): (Vec<f64>, Vec<f64>) = data::BOGUMIL_293K.iter().map(|&(l, s)| (l, s * 1e-4)).unzip();
    Spectrum::Tabulated(Tabulated::new(nm, cm2).expect("the built-in ozone table is increasing in wavelength"))
}

/// AFGL mid-latitude summer ozone number density at height `h_m`, m⁻³ (log-linear between
/// the table's heights; the top level's value above it).
pub fn afgl_number_density_per_m3(h_m: f64) -> f64 {
    let rows = data::AFGL_MLS;
    let n = |i: usize| {
        let (_, p_mb, t_k, ppmv) = rows[i];
        ppmv * 1e-6 * p_mb * 100.0 / (BOLTZMANN_J_PER_K * t_k)
    };
    let h_km = h_m * 1e-3;
    if h_km <= rows[0].0 {
        return n(0);
    }
    let Some(i) = rows.windows(2).position(|w| h_km < w[1].0) else { return n(rows.len() - 1) };
    let f = (h_km - rows[i].0) / (rows[i + 1].0 - rows[i].0);
    (n(i).ln() * (1.0 - f) + n(i + 1).ln() * f).exp()
}

/// The ozone number density of a column of `dobson_units` up to `top_m` with the AFGL
/// mid-latitude summer shape: a function of height (m) giving m⁻³.
pub fn profile(dobson_units: f64, top_m: f64) -> impl Fn(f64) -> f64 {
    let scale = dobson_units * MOLECULES_PER_M2_PER_DU / afgl_column_per_m2(top_m);
    move |h| scale * afgl_number_density_per_m3(h)
}

/// ∫₀^top n dh of the AFGL profile, m⁻², by Simpson's rule on steps of about 1 m.
pub fn afgl_column_per_m2(top_m: f64) -> f64 {
    column_per_m2(top_m, afgl_number_density_per_m3)
}

/// ∫₀^top n dh of a number density `n` (m⁻³ at a height in m), m⁻², by composite Simpson's
/// rule on steps of about 1 m.
pub fn column_per_m2(top_m: f64, number_density_per_m3: impl Fn(f64) -> f64) -> f64 {
    let n = ((top_m.ceil() as usize).div_ceil(2) * 2).max(2);
    let dh = top_m / n as f64;
    let f = |i: usize| number_density_per_m3(i as f64 * dh);
    let inner: f64 = (1..n).map(|i| if i % 2 == 1 { 4.0 * f(i) } else { 2.0 * f(i) }).sum();
    (f(0) + inner + f(n)) * dh / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chappuis_peak_is_bogumils() {
        // Bogumil et al. (2003), 293 K, as published: 5.30671e-21 cm² at 603.0779 nm.
        let s = cross_section_m2();
        assert!((s.eval(603.0779) / 5.30671e-25 - 1.0).abs() < 1e-12);
        // Linear between the kept published points 601.9617 nm (5.30237e-21) and 603.0779 nm.
        let mid = 0.5 * (601.9617 + 603.0779);
        assert!((s.eval(mid) / (0.5 * (5.30237e-25 + 5.30671e-25)) - 1.0).abs() < 1e-12);
        assert_eq!(s.eval(1100.0), 0.0);
    }

    #[test]
    fn the_afgl_column_is_about_300_du() {
        // AFGL mid-latitude summer up to 86 km, log-linear in density between levels: 300.38 DU
        // by the exact integral of each exponential layer, Σ n_i H_i (1 − e^{−Δh_i/H_i}) with
        // H_i = Δh_i / ln(n_i/n_{i+1}) (evaluated apart from this code, in Python).
        let du = afgl_column_per_m2(86_000.0) / MOLECULES_PER_M2_PER_DU;
        assert!((du / 300.376_616_152_960_9 - 1.0).abs() < 1e-9, "{du}");
        // The peak number density lies near 22–25 km, about 4–5 × 10¹⁸ m⁻³ (Anderson Table 1b).
        let peak = (0..=60)
            .map(|k| (k, afgl_number_density_per_m3(k as f64 * 1000.0)))
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        assert!((20..=26).contains(&peak.0) && (4e18..5.5e18).contains(&peak.1), "{peak:?}");
    }

    #[test]
    fn the_profile_holds_the_column_it_is_given() {
        let f = profile(300.0, 86_000.0);
        let n = 86_000;
        let simpson: f64 = (0..n / 2)
            .map(|i| {
                let h = 2.0 * i as f64;
                (f(h) + 4.0 * f(h + 1.0) + f(h + 2.0)) / 3.0
            })
            .sum();
        assert!((simpson / (300.0 * MOLECULES_PER_M2_PER_DU) - 1.0).abs() < 1e-9, "{simpson}");
    }
}
