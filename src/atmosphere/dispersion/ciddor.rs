//! Ciddor 1996: the refractive index of air in the visible and near infrared (300–1690 nm),
//! dry air here (no water vapour).
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
//! # References
//! - P. E. Ciddor 1996, "Refractive index of air: new equations for the visible and near
//!   infrared", Appl. Opt. 35:1566–1573.
//! - J. A. Stone & J. H. Zimmerman, "Index of refraction of air", NIST Engineering Metrology
//!   Toolbox, Appendix A-III (the same computation, step by step).
//! - R. S. Davis 1992, "Equation for the determination of the density of moist air (1981/91)",
//!   Metrologia 29:67–70 (the compressibility constants a₀…e).

const K0: f64 = 238.0185;
const K1: f64 = 5_792_105.0;
const K2: f64 = 57.362;
const K3: f64 = 167_917.0;
const A0: f64 = 1.581_23e-6;
const A1: f64 = -2.9331e-8;
const A2: f64 = 1.1043e-10;
const D: f64 = 1.83e-11;
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

    /// K(λ) = (n_axs − 1)/ρ_axs, m³ kg⁻¹.
    pub fn gladstone_dale_m3_per_kg(&self, wavelength_nm: f64) -> f64 {
        self.refractivity_standard_state(wavelength_nm) / self.rho_axs
    }

    /// ρ_axs, kg m⁻³.
    pub fn standard_density_kg_m3(&self) -> f64 {
        self.rho_axs
    }
}

/// ρ = pM_a/(ZRT) of dry air (Eqs. 4 and 12).
fn dry_density(pressure_pa: f64, temperature_k: f64, co2_ppm: f64) -> f64 {
    let ma = 1e-3 * (28.9635 + 12.011e-6 * (co2_ppm - 400.0));
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
