//! The U.S. Standard Atmosphere 1976 from 0 to 86 km: seven layers in geopotential height with
//! constant lapse rates, the hydrostatic pressure of each, and the ideal-gas density.
//!
//! With geopotential height H = r₀z/(r₀ + z) (z geometric) and layer b starting at H_b with
//! molecular-scale temperature T_b, pressure P_b and lapse rate L_b:
//! - T(H) = T_b + L_b (H − H_b);
//! - P(H) = P_b [T_b / T(H)]^{g₀M₀/(R*L_b)} when L_b ≠ 0, and
//!   P(H) = P_b exp(−g₀M₀(H − H_b)/(R*T_b)) when L_b = 0 (both solve dP/dH = −ρg₀);
//! - ρ = PM₀/(R*T).
//!
//! T_b and P_b follow from the sea-level values 288.15 K and 101325 Pa by continuity.
//! Derivatives with respect to geometric height use dH/dz = (r₀/(r₀ + z))²:
//! dT/dz = L_b dH/dz and dP/dz = −(g₀M₀/(R*T)) P dH/dz.
//!
//! The temperature returned is the molecular-scale temperature T_M of the standard. Below 80 km it
//! equals the kinetic temperature; between 80 and 86 km the kinetic temperature is T_M·M/M₀ with
//! M/M₀ falling to 0.999579 at 86 km (so 186.87 K against T_M = 186.946 K). Density computed from
//! T_M and M₀ is exact there, which is what refraction needs. Outside −5 km (the standard's lowest
//! table entry) to 86 km the state is held at the nearer end's value with zero derivatives, so it
//! stays finite anywhere (atmospheres end at their top, at most 86 km).
//!
//! # References
//! - U.S. Standard Atmosphere, 1976, NOAA-S/T 76-1562 (U.S. Government Printing Office,
//!   Washington D.C.), §1.2: Eqs. 18 (geopotential), 23 (temperature), 33a/33b (pressure),
//!   42 (density); Table 4 (layers: H_b = 0, 11, 20, 32, 47, 51, 71 km; L_b = −6.5, 0, 1.0, 2.8,
//!   0, −2.8, −2.0 K/km); g₀ = 9.80665 m s⁻², r₀ = 6356.766 km.

use super::gas::{M0_KG_PER_MOL, R_STAR};
use std::sync::LazyLock;

/// Standard gravity, m s⁻².
pub const G0: f64 = 9.806_65;
/// Effective Earth radius of the geopotential conversion, m.
pub const R0_M: f64 = 6_356_766.0;
/// The top of the standard's lower atmosphere (geometric), m.
pub const TOP_GEOMETRIC_M: f64 = 86_000.0;
/// The lowest altitude of the standard's tables (geometric), m.
pub const BOTTOM_GEOMETRIC_M: f64 = -5_000.0;

const BASE_H_M: [f64; 7] = [0.0, 11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0];
const LAPSE_K_PER_M: [f64; 7] = [-6.5e-3, 0.0, 1.0e-3, 2.8e-3, 0.0, -2.8e-3, -2.0e-3];

/// One layer's base: geopotential height, temperature, pressure and lapse rate.
#[derive(Clone, Copy, Debug)]
struct Layer {
    h_m: f64,
    t_k: f64,
    p_pa: f64,
    lapse: f64,
}

static LAYERS: LazyLock<[Layer; 7]> = LazyLock::new(|| {
    let mut layers = [Layer { h_m: 0.0, t_k: 288.15, p_pa: 101_325.0, lapse: LAPSE_K_PER_M[0] }; 7];
    for b in 1..7 {
        let below = layers[b - 1];
        let (t, p) = within(&below, BASE_H_M[b]);
        layers[b] = Layer { h_m: BASE_H_M[b], t_k: t, p_pa: p, lapse: LAPSE_K_PER_M[b] };
    }
    layers
});

/// Temperature, pressure and their rates of change with height at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    /// Molecular-scale temperature, K.
    pub temperature_k: f64,
    /// Pressure, Pa.
    pub pressure_pa: f64,
    /// dT/dz, K m⁻¹ (per metre of the height the state was asked at).
    pub dt_dz: f64,
    /// dP/dz, Pa m⁻¹.
    pub dp_dz: f64,
}

impl State {
    /// ρ = PM₀/(R*T).
    pub fn density_kg_m3(&self) -> f64 {
        super::gas::density_kg_m3(self.pressure_pa, self.temperature_k)
    }
}

/// The geometric heights where the lapse rate jumps (the bases of layers 1–6) and where the
/// model ends (its bottom and top, beyond which the state is held): there dT/dz, so ∇n, is
/// discontinuous, m.
pub fn kink_heights_geometric_m() -> impl Iterator<Item = f64> {
    BASE_H_M[1..].iter().map(|&h| geometric_m(h)).chain([BOTTOM_GEOMETRIC_M, TOP_GEOMETRIC_M])
}

/// Geopotential height H = r₀z/(r₀ + z) of geometric height z, m.
pub fn geopotential_m(z_m: f64) -> f64 {
    R0_M * z_m / (R0_M + z_m)
}

/// Geometric height z = r₀H/(r₀ − H) of geopotential height H, m.
pub fn geometric_m(h_m: f64) -> f64 {
    R0_M * h_m / (R0_M - h_m)
}

/// The state at geopotential height `h_m`, derivatives per geopotential metre.
pub fn at_geopotential(h_m: f64) -> State {
    let (h_min, h_max) = (geopotential_m(BOTTOM_GEOMETRIC_M), geopotential_m(TOP_GEOMETRIC_M));
    let clamped = !(h_min..=h_max).contains(&h_m);
    let h = h_m.clamp(h_min, h_max);
    let layer = &LAYERS[BASE_H_M.partition_point(|&b| b <= h).saturating_sub(1)];
    let (t, p) = within(layer, h);
    if clamped {
        return State { temperature_k: t, pressure_pa: p, dt_dz: 0.0, dp_dz: 0.0 };
    }
    State { temperature_k: t, pressure_pa: p, dt_dz: layer.lapse, dp_dz: -G0 * M0_KG_PER_MOL / (R_STAR * t) * p }
}

/// The state at geometric height `z_m`, derivatives per geometric metre.
pub fn at_geometric(z_m: f64) -> State {
    let inside = (BOTTOM_GEOMETRIC_M..=TOP_GEOMETRIC_M).contains(&z_m);
    let z = z_m.clamp(BOTTOM_GEOMETRIC_M, TOP_GEOMETRIC_M);
    let s = at_geopotential(geopotential_m(z));
    let dh_dz = if inside { (R0_M / (R0_M + z)).powi(2) } else { 0.0 };
    State { dt_dz: s.dt_dz * dh_dz, dp_dz: s.dp_dz * dh_dz, ..s }
}

/// The lowest temperature between `BOTTOM_GEOMETRIC_M` and geometric height `top_m`: it is at a
/// layer base or at the top, since T is linear within each layer.
pub fn min_temperature_below(top_m: f64) -> f64 {
    let top = at_geometric(top_m).temperature_k;
    LAYERS.iter().filter(|l| l.h_m <= geopotential_m(top_m)).map(|l| l.t_k).fold(top, f64::min)
}

/// Temperature and pressure at geopotential `h` within `layer` (Eqs. 23, 33a, 33b).
fn within(layer: &Layer, h: f64) -> (f64, f64) {
    let k = G0 * M0_KG_PER_MOL / R_STAR;
    let t = layer.t_k + layer.lapse * (h - layer.h_m);
    let p = if layer.lapse == 0.0 {
        layer.p_pa * (-k * (h - layer.h_m) / layer.t_k).exp()
    } else {
        layer.p_pa * (layer.t_k / t).powf(k / layer.lapse)
    };
    (t, p)
}
