//! Limb darkening of the sun's disc: how the radiance of a point of the disc falls from its
//! centre to its edge, per wavelength.
//!
//! A point of the disc at angular offset θ from its centre, on a disc of angular radius θ_m,
//! lies at r = sin θ / sin θ_m of the solar radius from the disc's centre (the line of sight
//! passes the sun's centre at D sin θ, and R = D sin θ_m), where it sees the solar surface at
//! μ = cos ϑ = √(1 − r²). Its radiance is I(λ, μ) = I(λ, 1) P(λ, μ) with the law
//!
//! P(λ, μ) = Σₖ₌₀⁵ Aₖ(λ) μᵏ,  P(λ, 1) = 1
//!
//! of Neckel & Labs (1994), Table: fifth-order polynomials fitted to the continuum intensities
//! measured across the disc at 30 wavelengths from 303 to 1099 nm. Between two tabulated
//! wavelengths the coefficients are interpolated linearly and renormalised to P(1) = 1.
//!
//! The disc's irradiance must stay the E(λ) the light is given: the projected solid angle of
//! the disc is a disk of radius sin θ_m in the plane normal to the axis, on which
//! dω cos θ = dx dy and r = ρ / sin θ_m, so
//!
//! E = ∫ I cos θ dω = I(λ, 1) π sin²θ_m F(λ),  F = ∫₀¹ P(μ(r)) 2r dr = 2 ∫₀¹ P(μ) μ dμ = Σ 2Aₖ/(k + 2)
//!
//! (2r dr = −2μ dμ), and the centre radiance is I(λ, 1) = E/(π sin²θ_m F). F is the disc's
//! mean radiance over its centre's, which Neckel & Labs print for each row; the tests check the
//! closed form against that column. Directions are drawn with the density P/F over the unit
//! disk: r from the radial CDF C(r) = [Σ 2Aₖ(1 − μᵏ⁺²)/(k + 2)]/F (μ = √(1 − r²)), inverted by
//! safeguarded Newton iteration on μ, and a uniform azimuth.
//!
//! # References
//! - H. Neckel, D. Labs (1994), "Solar limb darkening 1986–1990 (λλ 303 to 1099 nm)", Solar
//!   Physics 153, 91–114: the coefficients A₀…A₅ and the mean-to-centre ratio per wavelength,
//!   as reproduced in the Swedish Solar Telescope's reduction pipeline (ISP-SST `sstred`,
//!   `red_neckel_coefficients.pro`, 2021). That reproduction's row at 365.875 nm sums to 0.998
//!   (every other to 1 within 2 × 10⁻⁵) and misses its own printed mean by 10⁻³, so one of its
//!   digits is wrong; morgana leaves that row out and interpolates over 349.947–374.086 nm.

use std::f64::consts::PI;

/// How the radiance of a disc light varies across it (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimbDarkening {
    /// Uniformly bright: P = 1, F = 1.
    Uniform,
    /// The fifth-order law of Neckel & Labs (1994), wavelength by wavelength.
    NeckelLabs1994,
}

/// Neckel & Labs (1994): wavelength (nm), A₀…A₅, and their printed mean-to-centre ratio F.
/// The row at 365.875 nm is left out (see the module docs).
pub const NECKEL_LABS_1994: [[f64; 8]; 29] = [
    [303.327, 0.08011, 0.70695, 0.49910, -0.31080, -0.02177, 0.04642, 0.6826],
    [310.843, 0.08160, 0.71609, 0.69685, -0.87703, 0.47008, -0.08760, 0.6883],
    [320.468, 0.08833, 0.77285, 0.65382, -1.04647, 0.72921, -0.19775, 0.6985],
    [329.897, 0.09188, 0.92459, 0.19604, -0.39546, 0.23599, -0.05303, 0.7116],
    [349.947, 0.11012, 1.02168, -0.10924, -0.00055, -0.08688, 0.06487, 0.7260],
    [374.086, 0.12579, 0.85402, 0.54601, -1.15048, 0.88928, -0.26462, 0.7288],
    [390.915, 0.12995, 0.91836, -0.07566, 0.19149, -0.28712, 0.12298, 0.7204],
    [401.970, 0.12323, 1.08648, -0.43974, 0.45912, -0.32759, 0.09850, 0.7303],
    [416.319, 0.12814, 1.19947, -0.84407, 1.07201, -0.79537, 0.23982, 0.7380],
    [427.930, 0.14249, 1.28796, -1.19564, 1.68603, -1.36658, 0.44572, 0.7495],
    [443.885, 0.16220, 1.24893, -0.92165, 0.89978, -0.50148, 0.11220, 0.7588],
    [445.125, 0.15248, 1.38517, -1.49615, 1.99886, -1.48155, 0.44119, 0.7596],
    [457.345, 0.16604, 1.38544, -1.52275, 2.00232, -1.45969, 0.42864, 0.7651],
    [477.427, 0.19571, 1.30551, -1.25845, 1.50626, -1.05472, 0.30570, 0.7751],
    [492.905, 0.20924, 1.30798, -1.20411, 1.21505, -0.67196, 0.14381, 0.7823],
    [519.930, 0.23695, 1.29927, -1.28034, 1.37760, -0.85054, 0.21706, 0.7925],
    [541.760, 0.26073, 1.27428, -1.30352, 1.47085, -0.96618, 0.26384, 0.8002],
    [559.950, 0.26892, 1.34319, -1.58427, 1.91271, -1.31350, 0.37295, 0.8061],
    [579.880, 0.28392, 1.36896, -1.75998, 2.22154, -1.56074, 0.44630, 0.8125],
    [610.975, 0.30854, 1.36620, -1.83572, 2.33221, -1.63082, 0.45959, 0.8221],
    [640.970, 0.33644, 1.30590, -1.79238, 2.45040, -1.89979, 0.59943, 0.8290],
    [669.400, 0.34685, 1.37539, -2.04425, 2.70493, -1.94290, 0.55999, 0.8360],
    [700.875, 0.37885, 1.25553, -1.70908, 2.19647, -1.59554, 0.47378, 0.8434],
    [748.710, 0.40627, 1.22842, -1.67877, 2.05535, -1.39972, 0.38845, 0.8524],
    [811.760, 0.42977, 1.25182, -1.85164, 2.31949, -1.59101, 0.44155, 0.8621],
    [869.600, 0.45396, 1.25101, -2.02958, 2.75410, -2.02287, 0.59338, 0.8701],
    [948.850, 0.47855, 1.19813, -1.86296, 2.36939, -1.64367, 0.46056, 0.8773],
    [1046.60, 0.49870, 1.21429, -2.06976, 2.80703, -2.05247, 0.60221, 0.8841],
    [1098.95, 0.51149, 1.19354, -2.00174, 2.66936, -1.94981, 0.57715, 0.8890],
];

impl LimbDarkening {
    /// The scene name of the law.
    pub fn name(&self) -> &'static str {
        match self {
            LimbDarkening::Uniform => "none",
            LimbDarkening::NeckelLabs1994 => "neckel_labs_1994",
        }
    }

    /// The wavelengths (nm) the law covers: everything for a uniform disc, Neckel & Labs's
    /// 303.327–1098.95 nm.
    pub fn range_nm(&self) -> (f64, f64) {
        match self {
            LimbDarkening::Uniform => (0.0, f64::INFINITY),
            LimbDarkening::NeckelLabs1994 => (NECKEL_LABS_1994[0][0], NECKEL_LABS_1994[NECKEL_LABS_1994.len() - 1][0]),
        }
    }

    /// A₀…A₅ at `wavelength_nm`, normalised to P(1) = Σ Aₖ = 1 (wavelengths outside the table,
    /// which the scene reader refuses, take the nearest row).
    pub fn coefficients(&self, wavelength_nm: f64) -> [f64; 6] {
        match self {
            LimbDarkening::Uniform => [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            LimbDarkening::NeckelLabs1994 => interpolate_row(wavelength_nm),
        }
    }

    /// P(λ, μ) = I(λ, μ)/I(λ, 1).
    pub fn profile(&self, wavelength_nm: f64, mu: f64) -> f64 {
        let a = self.coefficients(wavelength_nm);
        a.iter().rev().fold(0.0, |acc, c| acc * mu + c)
    }

    /// F(λ) = 2 ∫₀¹ P μ dμ = Σ 2Aₖ/(k + 2): the disc's mean radiance over its centre's.
    pub fn mean_over_centre(&self, wavelength_nm: f64) -> f64 {
        let a = self.coefficients(wavelength_nm);
        a.iter().enumerate().map(|(k, c)| 2.0 * c / (k as f64 + 2.0)).sum()
    }

    /// P/F at the disc's fractional radius `r` (0 at the centre, 1 at the limb): the radiance
    /// there over the disc's mean radiance; 0 outside the disc.
    pub fn relative_radiance(&self, wavelength_nm: f64, r: f64) -> f64 {
        if !(0.0..=1.0).contains(&r) {
            return 0.0;
        }
        match self {
            LimbDarkening::Uniform => 1.0,
            LimbDarkening::NeckelLabs1994 => {
                // profile / mean_over_centre, from one interpolation of the coefficients.
                let a = self.coefficients(wavelength_nm);
                let mu = (1.0 - r * r).max(0.0).sqrt();
                let p = a.iter().rev().fold(0.0, |acc, c| acc * mu + c);
                let f: f64 = a.iter().enumerate().map(|(k, c)| 2.0 * c / (k as f64 + 2.0)).sum();
                p / f
            }
        }
    }

    /// A point (x, y) of the unit disk drawn with density P(μ(r))/(π F) from `u`.
    pub fn sample_disk(&self, wavelength_nm: f64, u: [f64; 2]) -> [f64; 2] {
        let r = match self {
            LimbDarkening::Uniform => u[0].sqrt(),
            LimbDarkening::NeckelLabs1994 => self.sample_radius(wavelength_nm, u[0]),
        };
        let (s, c) = (2.0 * PI * u[1]).sin_cos();
        [r * c, r * s]
    }

    /// C(r): the share of the disc's flux within fractional radius `r` at `wavelength_nm`,
    /// G(μ)/F with G(μ) = Σ 2Aₖ(1 − μᵏ⁺²)/(k + 2) and μ = √(1 − r²) (module docs).
    pub fn cumulative(&self, wavelength_nm: f64, r: f64) -> f64 {
        let a = self.coefficients(wavelength_nm);
        let mu = (1.0 - r * r).max(0.0).sqrt();
        let g: f64 =
            a.iter().enumerate().map(|(k, c)| 2.0 * c * (1.0 - mu.powi(k as i32 + 2)) / (k as f64 + 2.0)).sum();
        g / self.mean_over_centre(wavelength_nm)
    }

    /// The fractional radius r with C(r) = u (module docs): solves G(μ) = u F for μ, where
    /// G(μ) = Σ 2Aₖ(1 − μᵏ⁺²)/(k + 2) falls from F at μ = 0 to 0 at μ = 1 with G′ = −2μP.
    fn sample_radius(&self, wavelength_nm: f64, u: f64) -> f64 {
        let a = self.coefficients(wavelength_nm);
        let big_f: f64 = a.iter().enumerate().map(|(k, c)| 2.0 * c / (k as f64 + 2.0)).sum();
        let g = |mu: f64| -> f64 {
            a.iter().enumerate().map(|(k, c)| 2.0 * c * (1.0 - mu.powi(k as i32 + 2)) / (k as f64 + 2.0)).sum()
        };
        let target = u * big_f;
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        let mut mu = (1.0 - u).sqrt(); // exact for a uniform disc
        for _ in 0..60 {
            let residual = g(mu) - target;
            if residual.abs() <= 1e-15 {
                break;
            }
            if residual > 0.0 {
                lo = mu
            } else {
                hi = mu
            }
            if hi - lo < 1e-15 {
                break;
            }
            let slope = -2.0 * mu * a.iter().rev().fold(0.0, |acc, c| acc * mu + c);
            let newton = mu - residual / slope;
            mu = if slope < 0.0 && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        }
        (1.0 - mu * mu).max(0.0).sqrt()
    }
}

/// Equal cells of s = r² in a [`DiskTable`].
pub const DISK_TABLE_CELLS: usize = 64;

/// Shadow-ray directions for a limb-darkened disc: s = r² drawn from a density constant on each
/// of [`DISK_TABLE_CELLS`] equal cells of s, with each cell's probability the law's share of the
/// disc's flux in it at one reference wavelength (the exact C(r) at the cell edges), and a
/// uniform azimuth. A uniform disc is uniform in s, so the density relative to uniform sampling
/// of the projected solid angle is q = N (C(rⱼ₊₁) − C(rⱼ)) in cell j, and a sample weighted by
/// (P/F)(λ, r)/q estimates the same irradiance at every λ as uniform sampling weighted by P/F
/// did. At the reference wavelength (P/F)/q is within the cell's spread of P of 1, so the
/// 0.3–1.2 spread of P/F across the sun's disc at 400 nm no longer reaches each shadow ray;
/// other wavelengths keep only the ratio of their law to the reference's.
#[derive(Clone, Debug, PartialEq)]
pub struct DiskTable {
    /// C at the cell edges s = j/N: 0 at the centre, 1 at the limb.
    cdf: Vec<f64>,
}

impl DiskTable {
    /// The table of `law` at `wavelength_nm`.
    pub fn new(law: LimbDarkening, wavelength_nm: f64) -> DiskTable {
        let n = DISK_TABLE_CELLS;
        let mut cdf: Vec<f64> = (0..=n).map(|j| law.cumulative(wavelength_nm, (j as f64 / n as f64).sqrt())).collect();
        cdf[0] = 0.0;
        cdf[n] = 1.0;
        DiskTable { cdf }
    }

    /// A point (x, y) of the unit disk from `u`, and its density relative to uniform, q.
    pub fn sample(&self, u: [f64; 2]) -> ([f64; 2], f64) {
        let n = self.cdf.len() - 1;
        let j = (self.cdf.partition_point(|c| *c <= u[0]).max(1) - 1).min(n - 1);
        let width = self.cdf[j + 1] - self.cdf[j];
        let within = if width > 0.0 { ((u[0] - self.cdf[j]) / width).clamp(0.0, 1.0) } else { 0.5 };
        let r = ((j as f64 + within) / n as f64).min(1.0).sqrt();
        let (sin, cos) = (2.0 * PI * u[1]).sin_cos();
        ([r * cos, r * sin], n as f64 * width)
    }
}

/// Neckel & Labs's coefficients at `wavelength_nm`, linear between rows, normalised to Σ = 1.
fn interpolate_row(wavelength_nm: f64) -> [f64; 6] {
    let t = &NECKEL_LABS_1994;
    let i = t.partition_point(|row| row[0] <= wavelength_nm).clamp(1, t.len() - 1);
    let (r0, r1) = (&t[i - 1], &t[i]);
    let w = ((wavelength_nm - r0[0]) / (r1[0] - r0[0])).clamp(0.0, 1.0);
    let mut a = [0.0; 6];
    for k in 0..6 {
        a[k] = (1.0 - w) * r0[k + 1] + w * r1[k + 1];
    }
    let sum: f64 = a.iter().sum();
    a.map(|c| c / sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quadrature::gauss_legendre;
    use crate::rng::{Rng, Stream};
    use crate::testing::chi2::chi2_1d;

    const LAW: LimbDarkening = LimbDarkening::NeckelLabs1994;

    #[test]
    fn every_row_sums_to_one_and_gives_its_printed_mean() {
        // Each row's Σ Aₖ is P(1) = 1 up to the rounding of six 5-decimal numbers (3 × 10⁻⁵),
        // and the closed form Σ 2Aₖ/(k + 2) matches the mean-to-centre ratio Neckel & Labs
        // print beside it (4 decimals: ± 5 × 10⁻⁵, plus the coefficients' rounding).
        for row in &NECKEL_LABS_1994 {
            let sum: f64 = row[1..7].iter().sum();
            assert!((sum - 1.0).abs() < 3e-5, "{} nm: Σ A = {sum}", row[0]);
            let f = LAW.mean_over_centre(row[0]);
            assert!((f - row[7]).abs() < 1e-4, "{} nm: F = {f}, printed {}", row[0], row[7]);
        }
    }

    #[test]
    fn the_profile_is_positive_and_falls_to_the_limb() {
        // A radiance: positive everywhere on the disc, and darker at the limb than at the centre.
        for l in [303.327, 365.0, 450.0, 550.0, 700.0, 1000.0, 1098.95] {
            for i in 0..=1000 {
                let mu = i as f64 / 1000.0;
                assert!(LAW.profile(l, mu) > 0.05, "{l} nm, μ = {mu}");
            }
            assert!((LAW.profile(l, 1.0) - 1.0).abs() < 1e-12);
            assert!(LAW.profile(l, 0.0) < 0.6 * LAW.profile(l, 1.0));
        }
    }

    #[test]
    fn the_mean_is_the_integral_of_the_profile_over_the_disk() {
        // F = ∫₀¹ P(√(1 − r²)) 2r dr, integrated numerically over r (16-point Gauss–Legendre on
        // 256 panels; the integrand has a square-root edge at r = 1, whence 1e-6), at a
        // tabulated and at two interpolated wavelengths.
        for l in [541.76, 600.0, 380.0] {
            let f = |r: f64| LAW.profile(l, (1.0 - r * r).max(0.0).sqrt()) * 2.0 * r;
            let numeric = gauss_legendre(&f, 0.0, 1.0, 256);
            assert!((numeric - LAW.mean_over_centre(l)).abs() < 1e-6, "{l} nm: {numeric}");
        }
    }

    #[test]
    fn radii_are_drawn_with_the_law() {
        // Radii on the unit disk: density p(r) = 2r P(μ(r))/F (module docs), chi-square at three
        // wavelengths; and the uniform disc's p(r) = 2r.
        for (law, l) in [(LAW, 320.0), (LAW, 550.0), (LAW, 1000.0), (LimbDarkening::Uniform, 550.0)] {
            let mut rng = Rng::for_task(19, Stream::Test, l as u64);
            let p = chi2_1d(
                (0.0, 1.0),
                40,
                200_000,
                || {
                    let [x, y] = law.sample_disk(l, rng.uniform2());
                    Some((x * x + y * y).sqrt())
                },
                |r| 2.0 * r * law.relative_radiance(l, r),
            );
            assert!(p > 1e-3, "{law:?} at {l} nm: p = {p}");
        }
    }

    #[test]
    fn the_disk_tables_weights_keep_each_wavelengths_irradiance_and_spread_little() {
        // The irradiance of a disc over its uniform mean is E[(P/F)(λ, r)/q] = 1 at every λ for
        // samples from the table at 550 nm (a wrong q or a sample outside its cell moves the
        // mean); at 550 nm the weight spreads by the cells' variation of P alone, where uniform
        // samples weighted by P/F spread by the whole disc's.
        let table = DiskTable::new(LAW, 550.0);
        let mut rng = Rng::for_task(23, Stream::Test, 0);
        let samples: Vec<(f64, f64)> = (0..200_000)
            .map(|_| {
                let ([x, y], q) = table.sample(rng.uniform2());
                ((x * x + y * y).sqrt(), q)
            })
            .collect();
        let stats = |w: &dyn Fn(f64, f64) -> f64| {
            let v: Vec<f64> = samples.iter().map(|(r, q)| w(*r, *q)).collect();
            let n = v.len() as f64;
            let mean = v.iter().sum::<f64>() / n;
            let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
            (mean, sd, sd / n.sqrt())
        };
        for l in [320.0, 400.0, 550.0, 700.0, 1000.0] {
            let (mean, sd, se) = stats(&|r, q| LAW.relative_radiance(l, r) / q);
            assert!((mean - 1.0).abs() < 4.0 * se + 1e-12, "{l} nm: mean weight {mean} ± {se}");
            if l == 550.0 {
                assert!(sd < 0.02, "550 nm: the weight spreads by {sd}");
            }
        }
        let mut rng = Rng::for_task(23, Stream::Test, 1);
        let uniform: Vec<f64> = (0..20_000).map(|_| LAW.relative_radiance(550.0, rng.uniform().sqrt())).collect();
        let mean = uniform.iter().sum::<f64>() / uniform.len() as f64;
        let sd = (uniform.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / uniform.len() as f64).sqrt();
        assert!(sd > 0.15, "uniform samples spread by {sd} only");
    }

    #[test]
    fn azimuths_are_uniform() {
        let mut rng = Rng::for_task(19, Stream::Test, 7);
        let p = chi2_1d(
            (-PI, PI),
            36,
            100_000,
            || {
                let [x, y] = LAW.sample_disk(550.0, rng.uniform2());
                Some(y.atan2(x))
            },
            |_| 1.0 / (2.0 * PI),
        );
        assert!(p > 1e-3, "p = {p}");
    }
}
