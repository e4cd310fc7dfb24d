//! The model atmosphere of refraction tables: what SOFA `iauRefco` and SLALIB `slaRefro` take
//! (pressure, temperature and relative humidity at the observer, the observer's height and
//! latitude, the tropospheric lapse rate, the wavelength), made into n(r) as Hohenkerk &
//! Sinclair (1985) do.
//!
//! # The model (Hohenkerk & Sinclair 1985; the 1992 Explanatory Supplement, §3.281)
//! The Earth is a sphere of radius s = 6 378 120 m; the observer is at r₀ = s + h₀. Gravity
//! g = 9.784 (1 − 0.0026 cos 2φ − 2.8 × 10⁻⁷ h₀) m s⁻² at latitude φ; γ_a = g M_d/R
//! (M_d = 28.9644 g/mol, R = 8314.32 J kmol⁻¹ K⁻¹).
//! - *Troposphere* (r < r_t = s + 11 km): T = T₀τ, τ = 1 − α(r − r₀)/T₀ (lapse rate α); water
//!   vapour pressure p_w = p_w0 τ^δ (δ = 18.36); hydrostatic equilibrium of the moist air gives
//!   the total pressure p = (p₀ + w)τ^γ − wτ^δ, γ = γ_a/α, w = p_w0 (1 − M_w/M_d) γ/(δ − γ).
//! - *Stratosphere* (r ≥ r_t): isothermal at T_t, p and p_w both ∝ exp(−γ_a (r − r_t)/T_t).
//! - *Top*: r_s = s + 80 km, above which refraction is neglected (n taken as 1: a ray crossing
//!   r_s turns by asin(n_s sin z_s) − z_s, Snell's law at the top; [`super::quadrature`]).
//! - p_w0 from the relative humidity ϱ: p_w0 = ϱ p_s/(1 − (1 − ϱ)p_s/p₀) (ϱ as a ratio of
//!   mixing ratios), p_s = 10^((0.7859 + 0.03477t)/(1 + 0.00412t)) (1 + p₀(4.5 × 10⁻⁶ +
//!   6 × 10⁻¹⁰ t²)) hPa at t °C (Gill 1982, as slaRefro).
//!
//! The refractivity n − 1 at (p, T, p_w) is one of ([`Refractivity`]): Ciddor 1996 for moist air
//! ([`crate::atmosphere::dispersion::Ciddor::refractivity_moist`]), or the optical formula of
//! slaRefro (revision of 2005): n − 1 = (a p − b p_w)/T, a = (287.6155 + 1.62887/λ² +
//! 0.01360/λ⁴)(273.15/1013.25) × 10⁻⁶ hPa⁻¹ K (λ in μm; the dry-air group refractivity of
//! IAG Resolution 3, 1999), b = 11.2684 × 10⁻⁶ hPa⁻¹ K (Hohenkerk & Sinclair's water term).
//! n and r dn/dr come out of one evaluation in dual numbers ([`crate::atmosphere::dual`]).
//!
//! # References
//! - C. Y. Hohenkerk & A. T. Sinclair 1985, "The computation of angular atmospheric refraction
//!   at large zenith angles", HM Nautical Almanac Office Technical Note 63.
//! - P. T. Wallace, SLALIB `slaRefro` (1997), and IAU SOFA `iauRefco`.
//! - A. E. Gill, *Atmosphere–Ocean Dynamics*, Academic Press 1982 (saturation vapour pressure).

use crate::atmosphere::dispersion::Ciddor;
use crate::atmosphere::dual::Dual;

/// Earth radius of the model, m (Hohenkerk & Sinclair; slaRefro's `s`).
pub const MODEL_EARTH_RADIUS_M: f64 = 6_378_120.0;
/// Height of the tropopause above the sea, m.
pub const TROPOPAUSE_M: f64 = 11_000.0;
/// Height above which refraction is neglected, m.
pub const TOP_M: f64 = 80_000.0;
const GAS_CONSTANT: f64 = 8314.32;
const M_DRY: f64 = 28.9644;
const M_WATER: f64 = 18.0152;
const DELTA: f64 = 18.36;

/// The observer and the air at the observer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    /// Air pressure at the observer, hPa.
    pub pressure_hpa: f64,
    /// Air temperature at the observer, K.
    pub temperature_k: f64,
    /// Relative humidity at the observer, 0–1.
    pub humidity: f64,
    /// Height above the sea, m.
    pub height_m: f64,
    /// Latitude, degrees.
    pub latitude_deg: f64,
    /// Tropospheric lapse rate −dT/dh, K m⁻¹.
    pub lapse_k_per_m: f64,
    /// Wavelength, nm.
    pub wavelength_nm: f64,
}

impl Default for Observer {
    /// The sea level of the U.S. Standard Atmosphere 1976 (1013.25 hPa, 15 °C, its 6.5 K/km
    /// lapse rate), dry air, latitude 45°, 550 nm.
    fn default() -> Observer {
        Observer {
            pressure_hpa: 1013.25,
            temperature_k: 288.15,
            humidity: 0.0,
            height_m: 0.0,
            latitude_deg: 45.0,
            lapse_k_per_m: 0.0065,
            wavelength_nm: 550.0,
        }
    }
}

/// The law for n − 1 of moist air.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Refractivity {
    /// Ciddor 1996, moist air (CO₂ as given).
    Ciddor(Ciddor),
    /// The optical formula of slaRefro (IAG 1999 dry air, Hohenkerk & Sinclair's water term).
    HohenkerkSinclair,
}

/// The layer a point is in (the lapse rate jumps at the tropopause, so ∇n does).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layer {
    /// Below the tropopause.
    Troposphere,
    /// From the tropopause up.
    Stratosphere,
}

/// n(r) of one observer's model atmosphere at one wavelength (module notes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelAtmosphere {
    /// The inputs.
    pub observer: Observer,
    /// The refractivity law.
    pub law: Refractivity,
    /// r₀ = s + h₀, m.
    pub r_obs_m: f64,
    /// r_t, m.
    pub r_tropopause_m: f64,
    /// r_s, m.
    pub r_top_m: f64,
    gamma_a: f64,
    gamma: f64,
    w_hpa: f64,
    pw0_hpa: f64,
    t_tropopause_k: f64,
    p_tropopause_hpa: f64,
    pw_tropopause_hpa: f64,
}

impl ModelAtmosphere {
    /// The model for `observer` with `law`; checks the inputs (each message names the quantity).
    pub fn new(observer: Observer, law: Refractivity) -> Result<ModelAtmosphere, String> {
        check(&observer, &law)?;
        let o = observer;
        let g = 9.784 * (1.0 - 0.0026 * (2.0 * o.latitude_deg.to_radians()).cos() - 2.8e-7 * o.height_m);
        let gamma_a = g * M_DRY / GAS_CONSTANT;
        let gamma = gamma_a / o.lapse_k_per_m;
        let pw0 = vapour_pressure_hpa(o.humidity, o.temperature_k, o.pressure_hpa);
        let w = pw0 * (1.0 - M_WATER / M_DRY) * gamma / (DELTA - gamma);
        let r_obs = MODEL_EARTH_RADIUS_M + o.height_m;
        let r_t = MODEL_EARTH_RADIUS_M + TROPOPAUSE_M;
        let mut m = ModelAtmosphere {
            observer: o,
            law,
            r_obs_m: r_obs,
            r_tropopause_m: r_t,
            r_top_m: MODEL_EARTH_RADIUS_M + TOP_M,
            gamma_a,
            gamma,
            w_hpa: w,
            pw0_hpa: pw0,
            t_tropopause_k: 0.0,
            p_tropopause_hpa: 0.0,
            pw_tropopause_hpa: 0.0,
        };
        let (t, p, pw) = m.troposphere(Dual::constant(r_t));
        if !(t.v > 100.0 && p.v > 0.0) {
            return Err(format!(
                "the lapse rate {} K/m cools the air to {} K at the tropopause (11 km); expected a lapse rate that keeps it above 100 K",
                o.lapse_k_per_m, t.v
            ));
        }
        (m.t_tropopause_k, m.p_tropopause_hpa, m.pw_tropopause_hpa) = (t.v, p.v, pw.v);
        Ok(m)
    }

    /// The layer of radius `r_m`.
    pub fn layer_of(&self, r_m: f64) -> Layer {
        if r_m < self.r_tropopause_m { Layer::Troposphere } else { Layer::Stratosphere }
    }

    /// n and r·dn/dr at radius `r_m` by the formulas of `layer` (either may be evaluated a
    /// little beyond its layer, as the quadrature's root finder does).
    pub fn n_rdndr(&self, layer: Layer, r_m: f64) -> (f64, f64) {
        let r = Dual::variable(r_m);
        let (t, p, pw) = match layer {
            Layer::Troposphere => self.troposphere(r),
            Layer::Stratosphere => self.stratosphere(r),
        };
        let nr = self.refractivity(t, p, pw);
        (1.0 + nr.v, r_m * nr.d)
    }

    /// n and dn/dr at radius `r_m` (the layer by the radius; 1 and 0 from the top up).
    pub fn n_dndr(&self, r_m: f64) -> (f64, f64) {
        if r_m >= self.r_top_m {
            return (1.0, 0.0);
        }
        let (n, rd) = self.n_rdndr(self.layer_of(r_m), r_m);
        (n, rd / r_m)
    }

    /// n − 1 and dn/dr at radius `r_m` (the layer by the radius; 0 and 0 from the top up), with
    /// n − 1 to its own relative precision (not through 1 + (n − 1)).
    pub fn refractivity_dndr(&self, r_m: f64) -> (f64, f64) {
        if r_m >= self.r_top_m {
            return (0.0, 0.0);
        }
        let r = Dual::variable(r_m);
        let (t, p, pw) = match self.layer_of(r_m) {
            Layer::Troposphere => self.troposphere(r),
            Layer::Stratosphere => self.stratosphere(r),
        };
        let nr = self.refractivity(t, p, pw);
        (nr.v, nr.d)
    }

    /// T (K), p and p_w (hPa) in the troposphere.
    fn troposphere(&self, r: Dual) -> (Dual, Dual, Dual) {
        let o = &self.observer;
        let tau = (r + -self.r_obs_m) * (-o.lapse_k_per_m / o.temperature_k) + 1.0;
        let (tg, td) = (tau.powf(self.gamma), tau.powf(DELTA));
        let p = tg * (o.pressure_hpa + self.w_hpa) - td * self.w_hpa;
        (tau * o.temperature_k, p, td * self.pw0_hpa)
    }

    /// T (K), p and p_w (hPa) in the stratosphere.
    fn stratosphere(&self, r: Dual) -> (Dual, Dual, Dual) {
        let f = ((r + -self.r_tropopause_m) * (-self.gamma_a / self.t_tropopause_k)).exp();
        (Dual::constant(self.t_tropopause_k), f * self.p_tropopause_hpa, f * self.pw_tropopause_hpa)
    }

    /// n − 1 at T (K), p and p_w (hPa).
    fn refractivity(&self, t: Dual, p: Dual, pw: Dual) -> Dual {
        match &self.law {
            Refractivity::Ciddor(c) => c.refractivity_moist_dual(self.observer.wavelength_nm, t, p * 100.0, pw * 100.0),
            Refractivity::HohenkerkSinclair => {
                let l2 = (self.observer.wavelength_nm * 1e-3).powi(2);
                let a = (287.6155 + 1.62887 / l2 + 0.01360 / (l2 * l2)) * (273.15 / 1013.25) * 1e-6;
                (p * a - pw * 11.2684e-6) / t
            }
        }
    }
}

/// Heights above the model's sea level ([`MODEL_EARTH_RADIUS_M`]).
impl super::terrestrial::RadialIndex for ModelAtmosphere {
    fn refractivity_slope(&self, h_m: f64) -> (f64, f64) {
        self.refractivity_dndr(MODEL_EARTH_RADIUS_M + h_m)
    }
}

/// p_w0 from relative humidity (module notes), hPa.
fn vapour_pressure_hpa(humidity: f64, temperature_k: f64, pressure_hpa: f64) -> f64 {
    if humidity <= 0.0 {
        return 0.0;
    }
    let t = temperature_k - 273.15;
    let ps = 10f64.powf((0.7859 + 0.03477 * t) / (1.0 + 0.00412 * t)) * (1.0 + pressure_hpa * (4.5e-6 + 6e-10 * t * t));
    humidity * ps / (1.0 - (1.0 - humidity) * ps / pressure_hpa)
}

/// The inputs' ranges: each message names the quantity (and the `morgana refraction` option
/// that sets it), its value and what is expected.
fn check(o: &Observer, law: &Refractivity) -> Result<(), String> {
    let range = |name: &str, v: f64, lo: f64, hi: f64, unit: &str| {
        if v.is_finite() && (lo..=hi).contains(&v) {
            Ok(())
        } else {
            Err(format!("{name} = {v}{unit} is out of range; expected {lo} … {hi}{unit}"))
        }
    };
    range("pressure (--pressure-hpa)", o.pressure_hpa, 1.0, 1200.0, " hPa")?;
    range("temperature (--temperature-c)", o.temperature_k - 273.15, -70.0, 55.0, " °C")?;
    range("relative humidity (--humidity)", o.humidity, 0.0, 1.0, "")?;
    range("observer height (--observer-height-m)", o.height_m, -1000.0, 10_000.0, " m")?;
    range("latitude (--latitude-deg)", o.latitude_deg, -90.0, 90.0, "°")?;
    range("lapse rate (--lapse-rate-k-per-m)", o.lapse_k_per_m, 0.001, 0.01, " K/m")?;
    match law {
        Refractivity::Ciddor(_) => range("wavelength (--wavelength-nm)", o.wavelength_nm, 300.0, 1690.0, " nm"),
        Refractivity::HohenkerkSinclair => range("wavelength (--wavelength-nm)", o.wavelength_nm, 300.0, 2000.0, " nm"),
    }
}
