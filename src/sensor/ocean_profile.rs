//! Ocean-optics irradiance and radiance at depths, per wavelength band, from the volume photon
//! map: Ed, Eu (planar down- and upwelling irradiance), Eod, Eou (scalar), Lu (upwelling
//! radiance in the nadir-viewing direction) — the quantities HydroLight reports.
//!
//! # Estimator: collisions in the volume map
//! The global pass stores a photon at every interaction in a medium, so in a medium of
//! extinction σ_t the stored power per unit volume is σ_t times the fluence rate. For the photons
//! in a horizontal slab of area A and thickness Δz centred on depth z (V = A Δz) that arrived
//! travelling downward (↓) or upward (↑), with ΔΦ_p the photon's power, μ_p the cosine of its
//! direction with the vertical and σ_t at its own wavelength and position,
//!
//! - E_od = Σ_↓ ΔΦ_p / (σ_t V Δλ_b),  E_ou = Σ_↑ ΔΦ_p / (σ_t V Δλ_b);
//! - E_d = Σ_↓ |μ_p| ΔΦ_p / (σ_t V Δλ_b),  E_u = Σ_↑ |μ_p| ΔΦ_p / (σ_t V Δλ_b);
//!
//! This is the collision estimator of the fluence (Spanier & Gelbard 1969, §3.5; Mobley 1994,
//! §6.4): unbiased apart from averaging over the slab (an exponential decay K over Δz biases by
//! (KΔz)²/24). It reads the same map the eye pass reads, costs one pass over the stored photons,
//! and needs no change to photon tracing; its noise is that of the number of collisions in the
//! slab. (A plane-crossing tally during tracing would count crossings instead — lower noise
//! near the surface, but it would reach into the tracer.)
//!
//! # Slabs at the surface
//! A slab is clipped to the water, the side of the surface away from `up`: at a depth z below
//! Δz/2 (z = 0 included) it spans depths max(0, z − Δz/2) to z + Δz/2, counts only photons
//! there, and its volume is V = A × that clipped thickness (see [`OceanProfile::slab_depths_m`]).
//! (Unclipped, the half of the slab in the air holds no photons of the water and the reading
//! was half the irradiance.) The reading is then the mean over the clipped slab, which is
//! centred below z: for E ∝ e^{−Kz} the reading at z = 0 is E(0)(1 − e^{−KΔz/2})/(KΔz/2),
//! E(Δz/4) to first order — 1.6 % below E(0) for K = 0.66 m⁻¹ and Δz = 0.1 m; a thinner slab
//! lowers that bias at the cost of noise. The sensor does not know of a bottom: a slab reaching
//! through the sea floor is not clipped there.
//!
//! L_u, the nadir-viewing (zenith-travelling) radiance at depth z, is the light scattered
//! straight up by every collision below z and attenuated on the way (the expected-value, or
//! next-event, estimator for a horizontally homogeneous field, Spanier & Gelbard §3.6):
//!
//! L_u(z, b) = (1/(A Δλ_b)) Σ_{z_p > z} ΔΦ_p [α(λ_p) p(μ_p) 1_b(λ_p) e^{−σ_t(λ_p)(z_p − z)}
//!             + Σ_i p_i(μ_p) T_i(λ_p, b) e^{−σ_t(λ_b)(z_p − z)}],
//!
//! μ_p the cosine between the photon's direction and up (p averaged over a 5° cone about the
//! nadir-viewing direction for photons travelling near it, see `cone_mean_phase`, which keeps a
//! forward-peaked phase function from giving heavy-tailed weights), the second term the inelastic
//! re-emission into band b (see [`crate::media::inelastic::BandTransfer`], attenuated at the
//! band centre λ_b). It uses every collision below z, so it is far less noisy than counting
//! photons in a cone; it assumes the water column between
//! z_p and z is the medium at the photon (no surface in between) and the field horizontally
//! homogeneous over the measured square.
//!
//! Above the water, E_d(0+) is computed from the lights by shadow rays from the surface point
//! (`samples` per band, each at a jittered wavelength in the band).
//!
//! Derived: L_w = L_u(0−) (1 − R(0)) / n², with R(0) = ((n − 1)/(n + 1))² the Fresnel
//! reflectance at normal incidence and L_u(0−) the estimate at depth 0; R_rs = L_w / E_d(0+) (sr⁻¹); K_d between consecutive depths
//! = ln(E_d(z₁)/E_d(z₂)) / (z₂ − z₁) (Mobley 1994, §1.7 and §4.3 for the n² law).
//!
//! Units: irradiances W m⁻² nm⁻¹, radiances W m⁻² sr⁻¹ nm⁻¹, R_rs sr⁻¹, K_d m⁻¹.
//!
//! # References
//! - Mobley, *Light and Water* (1994), §1.7 (AOPs), §4.3 (the n² law of radiance), §6.4.
//! - Spanier & Gelbard, *Monte Carlo Principles and Neutron Transport Problems* (1969).

use glam::DVec3;
use std::io::{self, Write};
use std::path::Path;

/// Ocean irradiances and radiance at depths (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct OceanProfile {
    /// A point on the water surface: the centre of the measured square.
    pub origin: DVec3,
    /// First edge of the horizontal square (centred on `origin`), m.
    pub u: DVec3,
    /// Second edge of the horizontal square, m.
    pub v: DVec3,
    /// Unit vector up (toward the air).
    pub up: DVec3,
    /// Depths below the surface, m.
    pub depths_m: Vec<f64>,
    /// Thickness Δz of each measuring slab, centred on its depth and clipped to the water.
    pub slab_m: f64,
    /// Refractive index of the water for L_w.
    pub ior: f64,
    /// Shadow-ray samples per band for E_d(0+).
    pub samples: usize,
}

/// One row of the profile: a depth and a band.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ProfileRow {
    /// Depth below the surface, m.
    pub depth_m: f64,
    /// Band centre, nm.
    pub wavelength_nm: f64,
    /// Downwelling planar irradiance E_d, W m⁻² nm⁻¹.
    pub ed: f64,
    /// Upwelling planar irradiance E_u, W m⁻² nm⁻¹.
    pub eu: f64,
    /// Downwelling scalar irradiance E_od, W m⁻² nm⁻¹.
    pub eod: f64,
    /// Upwelling scalar irradiance E_ou, W m⁻² nm⁻¹.
    pub eou: f64,
    /// Upwelling radiance L_u in the nadir-viewing direction, W m⁻² sr⁻¹ nm⁻¹.
    pub lu: f64,
}

/// What the profile measured.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileReading {
    /// The sensor's name.
    pub name: String,
    /// One row per depth and band.
    pub rows: Vec<ProfileRow>,
    /// Per band: (wavelength, Ed(0+), Lu(0−), Lw, Rrs).
    pub surface: Vec<[f64; 5]>,
    /// The standard errors of the values, from the spread of progressive passes (two or
    /// more; `None` after one pass).
    pub std_error: Option<ProfileError>,
}

/// The standard errors of a [`ProfileReading`]'s values, in the same units.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ProfileError {
    /// Per row: Ed, Eu, Eod, Eou, Lu.
    pub rows: Vec<[f64; 5]>,
    /// Per band: Ed(0+), Lu(0−), Lw, Rrs.
    pub surface: Vec<[f64; 4]>,
}

/// Half-angle of the cone over which L_u is averaged (a narrow-field radiometer).
pub const LU_CONE_DEG: f64 = 5.0;

impl OceanProfile {
    /// The slab measured at `depth_m`, clipped to the water: (top, bottom) depths in m, top =
    /// max(0, z − Δz/2), bottom = z + Δz/2. Its volume is A × (bottom − top).
    pub fn slab_depths_m(&self, depth_m: f64) -> (f64, f64) {
        let half = 0.5 * self.slab_m;
        ((depth_m - half).max(0.0), depth_m + half)
    }

    /// The clipped slab's thickness, m: Δz where the slab lies in the water, less near the
    /// surface.
    pub fn slab_thickness_m(&self, depth_m: f64) -> f64 {
        if depth_m >= 0.5 * self.slab_m {
            self.slab_m
        } else {
            let (top, bottom) = self.slab_depths_m(depth_m);
            bottom - top
        }
    }
}

impl ProfileReading {
    /// `sensor,depth_m,wavelength_nm,Ed,Eu,Eod,Eou,Lu` (W m⁻² nm⁻¹; Lu W m⁻² sr⁻¹ nm⁻¹).
    pub fn write_csv(&self, path: &Path) -> io::Result<()> {
        let mut f = io::BufWriter::new(std::fs::File::create(path)?);
        let se_header = if self.std_error.is_some() { ",Ed_se,Eu_se,Eod_se,Eou_se,Lu_se" } else { "" };
        writeln!(f, "sensor,depth_m,wavelength_nm,Ed,Eu,Eod,Eou,Lu{se_header}")?;
        for (i, r) in self.rows.iter().enumerate() {
            write!(
                f,
                "{},{},{},{:e},{:e},{:e},{:e},{:e}",
                self.name, r.depth_m, r.wavelength_nm, r.ed, r.eu, r.eod, r.eou, r.lu
            )?;
            if let Some(e) = self.std_error.as_ref().and_then(|e| e.rows.get(i)) {
                write!(f, ",{:e},{:e},{:e},{:e},{:e}", e[0], e[1], e[2], e[3], e[4])?;
            }
            writeln!(f)?;
        }
        f.flush()
    }

    /// `sensor,wavelength_nm,Ed_0plus,Lu_0minus,Lw,Rrs_per_sr` (and `Ed_0plus_se,Lu_0minus_se,
    /// Lw_se,Rrs_per_sr_se` after two passes or more), then K_d rows in a second table
    /// `sensor,depth_from_m,depth_to_m,wavelength_nm,Kd_per_m` after a blank line.
    pub fn write_derived_csv(&self, path: &Path) -> io::Result<()> {
        let mut f = io::BufWriter::new(std::fs::File::create(path)?);
        let se_header = if self.std_error.is_some() { ",Ed_0plus_se,Lu_0minus_se,Lw_se,Rrs_per_sr_se" } else { "" };
        writeln!(f, "sensor,wavelength_nm,Ed_0plus,Lu_0minus,Lw,Rrs_per_sr{se_header}")?;
        for (i, s) in self.surface.iter().enumerate() {
            write!(f, "{},{},{:e},{:e},{:e},{:e}", self.name, s[0], s[1], s[2], s[3], s[4])?;
            if let Some(e) = self.std_error.as_ref().and_then(|e| e.surface.get(i)) {
                write!(f, ",{:e},{:e},{:e},{:e}", e[0], e[1], e[2], e[3])?;
            }
            writeln!(f)?;
        }
        writeln!(f)?;
        writeln!(f, "sensor,depth_from_m,depth_to_m,wavelength_nm,Kd_per_m")?;
        for (z1, z2, l, k) in self.kd() {
            writeln!(f, "{},{z1},{z2},{l},{k:e}", self.name)?;
        }
        f.flush()
    }

    /// K_d between consecutive depths, per band: (z₁, z₂, λ, K_d); skipped where E_d is zero.
    pub fn kd(&self) -> Vec<(f64, f64, f64, f64)> {
        let mut out = Vec::new();
        for a in &self.rows {
            let next = self
                .rows
                .iter()
                .filter(|b| b.wavelength_nm == a.wavelength_nm && b.depth_m > a.depth_m)
                .min_by(|x, y| x.depth_m.total_cmp(&y.depth_m));
            if let Some(b) = next
                && a.ed > 0.0
                && b.ed > 0.0
            {
                out.push((a.depth_m, b.depth_m, a.wavelength_nm, (a.ed / b.ed).ln() / (b.depth_m - a.depth_m)));
            }
        }
        out
    }
}
