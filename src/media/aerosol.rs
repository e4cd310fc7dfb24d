//! Aerosols of the scattering atmosphere ([`super::constituents`]): an extinction that follows
//! Ångström's law in wavelength and falls off exponentially in height.
//!
//! # Optical depth (Ångström 1929)
//! The vertical optical depth of the whole column is τ(λ) = β (λ / 1 µm)^−α: β is the optical
//! depth at 1 µm (Ångström's turbidity coefficient), α the Ångström exponent (about 1.3 for
//! continental aerosol, near 0 for large particles).
//!
//! # Profile
//! The extinction coefficient at height h is σ(λ, h) = τ(λ) d(h) with
//! d(h) = e^{−h/H} / (H (1 − e^{−top/H})) (m⁻¹): an exponential of scale height H whose integral
//! from the ground to the atmosphere's top is exactly 1, so the column's optical depth is τ(λ).
//!
//! # Visibility (Koschmieder 1924)
//! A meteorological visibility V (the distance at which a black object's contrast against the
//! horizon sky falls to 2 %) gives the total extinction at 550 nm at the ground,
//! σ₅₅₀ = ln 50 / V = 3.912/V; the aerosols take what Rayleigh scattering of the air there leaves,
//! σ_a = 3.912/V − σ_R(550 nm, 0), so τ(550 nm) = σ_a H (1 − e^{−top/H}) and
//! β = τ(550 nm) × 0.55^α.
//!
//! # Scattering
//! A single-scattering albedo ω(λ) — one number, or a table in wavelength
//! ([`super::albedo::Albedo`]) — and a Henyey–Greenstein phase function, or a two-term
//! Henyey–Greenstein one (the scene chooses; [`super::phase::TwoTermHg`]).
//!
//! # References
//! - A. Ångström, "On the atmospheric transmission of Sun radiation and on dust in the air",
//!   Geografiska Annaler 11 (1929), 156–166.
//! - H. Koschmieder, "Theorie der horizontalen Sichtweite", Beitr. Phys. freien Atm. 12 (1924),
//!   33–55; WMO-No. 8 (meteorological optical range at a 5 % threshold is 3.0/σ; Koschmieder's
//!   2 % gives 3.912/σ).

/// Koschmieder's constant ln(1/0.02) = 3.912: extinction × visibility at a 2 % contrast
/// threshold.
pub const KOSCHMIEDER: f64 = 3.912_023_005_428_146;

/// τ(λ) = β (λ/1000 nm)^−α, the column's optical depth.
pub fn optical_depth(wavelength_nm: f64, alpha: f64, beta: f64) -> f64 {
    beta * (wavelength_nm / 1000.0).powf(-alpha)
}

/// The normalised exponential d(h) = e^{−h/H} / (H (1 − e^{−top/H})), m⁻¹, ∫₀^top d dh = 1.
pub fn profile(scale_height_m: f64, top_m: f64) -> impl Fn(f64) -> f64 {
    let norm = 1.0 / (scale_height_m * -(-top_m / scale_height_m).exp_m1());
    move |h| norm * (-h / scale_height_m).exp()
}

/// β from a visibility `visibility_m` (Koschmieder), the air's extinction at 550 nm at the ground
/// `rayleigh_550_per_m`, the exponent α and the profile; `None` when the air alone would already
/// limit the visibility to less than `visibility_m`.
pub fn beta_from_visibility(
    visibility_m: f64,
    rayleigh_550_per_m: f64,
    alpha: f64,
    scale_height_m: f64,
    top_m: f64,
) -> Option<f64> {
    let sigma = KOSCHMIEDER / visibility_m - rayleigh_550_per_m;
    if sigma <= 0.0 {
        return None;
    }
    let tau_550 = sigma * scale_height_m * -(-top_m / scale_height_m).exp_m1();
    Some(tau_550 * 0.55f64.powf(alpha))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profile_integrates_to_one() {
        let d = profile(1200.0, 86_000.0);
        let n = 86_000;
        let simpson: f64 = (0..n / 2)
            .map(|i| {
                let h = 2.0 * i as f64;
                (d(h) + 4.0 * d(h + 1.0) + d(h + 2.0)) / 3.0
            })
            .sum();
        assert!((simpson - 1.0).abs() < 1e-10, "{simpson}");
    }

    #[test]
    fn visibility_gives_koschmieder_extinction_at_the_ground() {
        // V = 23 km ("clear"), Rayleigh 1.16e-5 m⁻¹ at 550 nm: the aerosol extinction at the
        // ground is 3.912/23 km − 1.16e-5 = 1.585e-4 m⁻¹.
        let (alpha, h, top) = (1.3, 1200.0, 86_000.0);
        let beta = beta_from_visibility(23_000.0, 1.16e-5, alpha, h, top).unwrap();
        let ground = optical_depth(550.0, alpha, beta) * profile(h, top)(0.0);
        assert!((ground / (KOSCHMIEDER / 23_000.0 - 1.16e-5) - 1.0).abs() < 1e-12, "{ground}");
        assert!(beta_from_visibility(400_000.0, 1.16e-5, alpha, h, top).is_none());
    }
}
