//! Ciddor 1996: the refractive index of air in the visible and near infrared (300–1690 nm), of
//! dry air and ([`Ciddor::refractivity_moist`]) of moist air.
//!
//! Standard air (dry, 15 °C, 101325 Pa, 450 µmol/mol CO₂), σ = 1/λ in μm⁻¹ (Ciddor Eq. 1):
//! (n_as − 1)·10⁸ = k₁/(k₀ − σ²) + k₃/(k₂ − σ²), k₀ = 238.0185 μm⁻², k₁ = 5 792 105 μm⁻²,
//! k₂ = 57.362 μm⁻², k₃ = 167 917 μm⁻².
//! With x_c µmol/mol CO₂ (Eq. 2): n_axs − 1 = (n_as − 1)(1 + 0.534 × 10⁻⁶ (x_c − 450)).
//! Molar mass (Eq. 4): M_a = 10⁻³ [28.9635 + 12.011 × 10⁻⁶ (x_c − 400)] kg/mol.
//! Density ρ = pM_a/(ZRT) with the BIPM compressibility (Eq. 12, dry air, t in °C):
//! Z = 1 − (p/T)(a₀ + a₁t + a₂t²) + (p/T)² d.
//! Dry air at (p, T) (Eq. 5): n − 1 = (ρ/ρ_axs)(n_axs − 1), ρ_axs the density of standard air —
//! Gladstone–Dale with K(λ) = (n_axs − 1)/ρ_axs.
//!
//! Moist air (Ciddor Eqs. 3, 5, 12 with water vapour): standard water vapour (20 °C, 1333 Pa)
//! has (n_ws − 1)·10⁸ = 1.022 (295.235 + 2.6422σ² − 0.032380σ⁴ + 0.004028σ⁶); with the water
//! vapour mole fraction x_w = p_w/p the densities are ρ_a = p M_a (1 − x_w)/(ZRT) and
//! ρ_w = p M_w x_w/(ZRT), M_w = 0.018015 kg/mol, Z = 1 − (p/T)[a₀ + a₁t + a₂t² + (b₀ + b₁t)x_w +
//! (c₀ + c₁t)x_w²] + (p/T)²(d + e x_w²), and n − 1 = (ρ_a/ρ_axs)(n_axs − 1) + (ρ_w/ρ_ws)(n_ws − 1),
//! ρ_ws the density of standard water vapour (x_w = 1).
//!
//! # References
//! - P. E. Ciddor 1996, "Refractive index of air: new equations for the visible and near
//!   infrared", Appl. Opt. 35:1566–1573.
//! - J. A. Stone & J. H. Zimmerman, "Index of refraction of air", NIST Engineering Metrology
//!   Toolbox, Appendix A-III (the same computation, step by step).
//! - R. S. Davis 1992, "Equation for the determination of the density of moist air (1981/91)",
//!   Metrologia 29:67–70 (the compressibility constants a₀…e).

use crate::atmosphere::dual::Dual;

const K0: f64 = 238.0185;
const K1: f64 = 5_792_105.0;
const K2: f64 = 57.362;
const K3: f64 = 167_917.0;
const A0: f64 = 1.581_23e-6;
const A1: f64 = -2.9331e-8;
const A2: f64 = 1.1043e-10;
const D: f64 = 1.83e-11;
const B0: f64 = 5.707e-6;
const B1: f64 = -2.051e-8;
const C0: f64 = 1.9898e-4;
const C1: f64 = -2.376e-6;
const E: f64 = -0.765e-8;
/// Molar mass of water vapour (Ciddor 1996), kg/mol.
const M_W: f64 = 0.018_015;
/// The gas constant Ciddor 1996 uses, J mol⁻¹ K⁻¹.
const R_CIDDOR: f64 = 8.314_510;

/// Ciddor's dry-air law at a CO₂ mole fraction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ciddor {
    /// CO₂ mole fraction x_c, µmol/mol.
    pub co2_ppm: f64,
    /// Density of standard air with this CO₂ content, kg m⁻³.
    rho_axs: f64,
}

impl Ciddor {
    /// The standard state: 15 °C, 101325 Pa.
    pub const STANDARD_TEMPERATURE_K: f64 = 288.15;
    /// Pressure of the standard state, Pa.
    pub const STANDARD_PRESSURE_PA: f64 = 101_325.0;

    /// `co2_ppm` in 0–2000 µmol/mol.
    pub fn new(co2_ppm: f64) -> Result<Ciddor, String> {
        if !(0.0..=2000.0).contains(&co2_ppm) {
            return Err(format!("co2_ppm = {co2_ppm} is out of range: Ciddor 1996 covers 0 to 2000 µmol/mol"));
        }
        let rho_axs = dry_density(Self::STANDARD_PRESSURE_PA, Self::STANDARD_TEMPERATURE_K, co2_ppm);
        Ok(Ciddor { co2_ppm, rho_axs })
    }

    /// n_as − 1 of standard air with 450 µmol/mol CO₂ (Eq. 1).
    pub fn standard_refractivity(wavelength_nm: f64) -> f64 {
        let s2 = (1e3 / wavelength_nm).powi(2);
        1e-8 * (K1 / (K0 - s2) + K3 / (K2 - s2))
    }

    /// n_axs − 1: standard air with this CO₂ content (Eq. 2).
    pub fn refractivity_standard_state(&self, wavelength_nm: f64) -> f64 {
        Self::standard_refractivity(wavelength_nm) * (1.0 + 0.534e-6 * (self.co2_ppm - 450.0))
    }

    /// n − 1 of dry air at `temperature_k` and `pressure_pa` (Eq. 5 with the real-gas density).
    pub fn refractivity(&self, wavelength_nm: f64, temperature_k: f64, pressure_pa: f64) -> f64 {
        let rho = dry_density(pressure_pa, temperature_k, self.co2_ppm);
        rho / self.rho_axs * self.refractivity_standard_state(wavelength_nm)
    }

    /// [`Ciddor::refractivity`] N and its partial derivatives (N, ∂N/∂p in Pa⁻¹, ∂N/∂T in K⁻¹):
    /// with ρ = pM_a/(ZRT), ∂ln ρ/∂p = 1/p − (∂Z/∂p)/Z and ∂ln ρ/∂T = −1/T − (∂Z/∂T)/Z.
    pub fn refractivity_grad(&self, wavelength_nm: f64, temperature_k: f64, pressure_pa: f64) -> (f64, f64, f64) {
        let n = self.refractivity(wavelength_nm, temperature_k, pressure_pa);
        let (z, z_p, z_t) = compressibility(pressure_pa, temperature_k);
        (n, n * (1.0 / pressure_pa - z_p / z), n * (-1.0 / temperature_k - z_t / z))
    }

    /// The real-gas density ρ = pM_a/(ZRT) of the dry air and its partial derivatives
    /// (ρ, ∂ρ/∂p, ∂ρ/∂T): n − 1 = K(λ)·ρ ([`Ciddor::gladstone_dale_m3_per_kg`]).
    pub fn density_grad(&self, temperature_k: f64, pressure_pa: f64) -> (f64, f64, f64) {
        let rho = dry_density(pressure_pa, temperature_k, self.co2_ppm);
        let (z, z_p, z_t) = compressibility(pressure_pa, temperature_k);
        (rho, rho * (1.0 / pressure_pa - z_p / z), rho * (-1.0 / temperature_k - z_t / z))
    }

    /// K(λ) = (n_axs − 1)/ρ_axs, m³ kg⁻¹.
    pub fn gladstone_dale_m3_per_kg(&self, wavelength_nm: f64) -> f64 {
        self.refractivity_standard_state(wavelength_nm) / self.rho_axs
    }

    /// ρ_axs, kg m⁻³.
    pub fn standard_density_kg_m3(&self) -> f64 {
        self.rho_axs
    }

    /// n − 1 of moist air at `temperature_k` and total pressure `pressure_pa` holding water
    /// vapour of partial pressure `vapour_pa` (Ciddor Eq. 5 with water vapour; module notes).
    pub fn refractivity_moist(&self, wavelength_nm: f64, temperature_k: f64, pressure_pa: f64, vapour_pa: f64) -> f64 {
        let c = Dual::constant;
        self.refractivity_moist_dual(wavelength_nm, c(temperature_k), c(pressure_pa), c(vapour_pa)).v
    }

    /// [`Ciddor::refractivity_moist`] of dual numbers: n − 1 and its derivative with respect to
    /// whatever T, p and p_w are functions of (e.g. height).
    pub fn refractivity_moist_dual(
        &self,
        wavelength_nm: f64,
        temperature_k: Dual,
        pressure_pa: Dual,
        vapour_pa: Dual,
    ) -> Dual {
        let (t, p, pw) = (temperature_k, pressure_pa, vapour_pa);
        let xw = if p.v > 0.0 { pw / p } else { Dual::constant(0.0) };
        let z = compressibility_dual(p, t, xw);
        let ka = self.refractivity_standard_state(wavelength_nm) / self.rho_axs * molar_mass_dry(self.co2_ppm);
        let (tw, pws) = (293.15, 1333.0);
        let rho_ws = pws * M_W / (compressibility_moist(pws, tw, 1.0) * R_CIDDOR * tw);
        let kw = water_vapour_refractivity(wavelength_nm) / rho_ws * M_W;
        ((p - pw) * ka + pw * kw) / (z * t * R_CIDDOR)
    }
}

/// n_ws − 1 of standard water vapour (20 °C, 1333 Pa; Ciddor Eq. 3).
fn water_vapour_refractivity(wavelength_nm: f64) -> f64 {
    let s2 = (1e3 / wavelength_nm).powi(2);
    1.022e-8 * (295.235 + s2 * (2.6422 + s2 * (-0.032_380 + s2 * 0.004_028)))
}

/// M_a of dry air with `co2_ppm` CO₂ (Ciddor Eq. 4), kg/mol.
fn molar_mass_dry(co2_ppm: f64) -> f64 {
    1e-3 * (28.9635 + 12.011e-6 * (co2_ppm - 400.0))
}

/// Z of moist air of water vapour mole fraction `xw` (Ciddor Eq. 12).
fn compressibility_moist(pressure_pa: f64, temperature_k: f64, xw: f64) -> f64 {
    let c = Dual::constant;
    compressibility_dual(c(pressure_pa), c(temperature_k), c(xw)).v
}

/// [`compressibility_moist`] of dual numbers.
fn compressibility_dual(p: Dual, temperature_k: Dual, xw: Dual) -> Dual {
    let t = temperature_k + -273.15;
    let pt = p / temperature_k;
    let a = t * (t * A2 + A1) + A0 + xw * (t * B1 + B0) + xw * xw * (t * C1 + C0);
    let one = Dual::constant(1.0);
    one - pt * a + pt * pt * (xw * xw * E + D)
}

/// ρ = pM_a/(ZRT) of dry air (Eqs. 4 and 12).
fn dry_density(pressure_pa: f64, temperature_k: f64, co2_ppm: f64) -> f64 {
    let ma = molar_mass_dry(co2_ppm);
    let (z, _, _) = compressibility(pressure_pa, temperature_k);
    pressure_pa * ma / (z * R_CIDDOR * temperature_k)
}

/// The compressibility of dry air (Eq. 12) and its partial derivatives: (Z, ∂Z/∂p, ∂Z/∂T).
fn compressibility(pressure_pa: f64, temperature_k: f64) -> (f64, f64, f64) {
    let t = temperature_k - 273.15;
    let pt = pressure_pa / temperature_k;
    let a = A0 + A1 * t + A2 * t * t;
    let z = 1.0 - pt * a + pt * pt * D;
    let z_p = (-a + 2.0 * pt * D) / temperature_k;
    let z_t = pt / temperature_k * a - pt * (A1 + 2.0 * A2 * t) - 2.0 * pt * pt * D / temperature_k;
    (z, z_p, z_t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moist_air_without_vapour_is_dry_air() {
        let c = Ciddor::new(450.0).expect("co2");
        for (l, t, p) in [(400.0, 250.0, 60_000.0), (550.0, 288.15, 101_325.0), (800.0, 310.0, 105_000.0)] {
            let (dry, moist) = (c.refractivity(l, t, p), c.refractivity_moist(l, t, p, 0.0));
            assert!((moist / dry - 1.0).abs() < 1e-14, "{dry} vs {moist}");
        }
    }

    #[test]
    fn water_vapour_lowers_the_optical_refractivity_by_its_published_amount() {
        // Replacing dry air by water vapour at the same total pressure lowers n − 1 in the
        // visible. Edlén's water term (Birch & Downs 1993, as in Stone & Zimmerman, NIST, A-IV)
        // is −p_w(3.7345 − 0.0401σ²)·10⁻¹⁰, p_w in Pa: at 633 nm (σ² = 2.496 μm⁻²) and
        // p_w = 1333 Pa, 4.84 × 10⁻⁷. Expected: Ciddor's drop within ±20 % of that (a guard
        // against a lost, mis-signed or mis-scaled water term, not a comparison of the laws).
        let c = Ciddor::new(450.0).expect("co2");
        let drop = c.refractivity_moist(633.0, 293.15, 101_325.0, 0.0)
            - c.refractivity_moist(633.0, 293.15, 101_325.0, 1333.0);
        assert!((3.87e-7..5.81e-7).contains(&drop), "{drop}");
    }
}
