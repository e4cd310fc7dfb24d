//! The column ∫ d ds of a height profile along a straight ray from a point inside a spherically
//! symmetric atmosphere to its top, tabulated over the point's radius r and the ray's zenith
//! cosine μ (Bruneton & Neyret 2008): a shadow ray to the sun reads it instead of integrating
//! the profile (~1 400 evaluations of the density) every time.
//!
//! # Parametrisation
//! With R the Earth's radius, R_t = R + top the atmosphere's and H = √(R_t² − R²) the distance
//! to the top along the horizontal ray from the ground, a point at radius r has ρ = √(r² − R²)
//! (its distance to the horizon) and a ray from it in direction μ reaches the top after
//! d(r, μ) = −rμ + √(r²(μ² − 1) + R_t²). The rays that miss the ground (μ ≥ −ρ/r) have d from
//! d_min = R_t − r (straight up) to d_max = ρ + H (grazing the ground), and the table's
//! coordinates are
//!
//! x_r = ρ/H,  x_μ = (d − d_min)/(d_max − d_min),
//!
//! both in [0, 1], on a uniform grid of nodes: x_r puts the nodes densest in height near the
//! ground, where the air is, and x_μ spreads the few degrees around the horizon, where the
//! column grows 40-fold, over the whole axis (Bruneton & Neyret 2008, §4; Bruneton 2017, the
//! functions `GetTransmittanceTextureUvFromRMu` and `GetRMuFromTransmittanceTextureUv`). The
//! inverse, for the nodes: ρ = H x_r, r = √(ρ² + R²), d = d_min + x_μ (d_max − d_min) and
//! μ = (H² − ρ² − d²)/(2rd) (μ = 1 at d = 0).
//!
//! # Values and their error
//! A node holds ln(C + C_floor), with C the column from the profile's own quadrature
//! ([`AirProfile::integrals`], good to 3 × 10⁻⁸) and C_floor = 10⁻⁹ of the vertical column from
//! the ground, so the logarithm stays finite where C vanishes (at the top); a lookup
//! interpolates the logarithms by Catmull–Rom splines in both coordinates (exact for
//! quadratics: near the ground ln C ≈ ln C₀ − h/H_s with h ≈ ρ²/2R is quadratic in x_r) and
//! returns exp(·) − C_floor. The grid is sized by the error it leaves (see
//! [`COLUMN_TOLERANCE`]). Rays from the top cell of x_r (the top 1.34 km of USA76's 86 km,
//! where the air is 10⁻⁵ of the ground's) are left to the quadrature: there the column of a
//! level ray falls as √(top − h) and no interpolation follows it. Only smooth profiles are tabulated (see
//! [`AirProfile::column_table`]); the nodes' columns are integrated on 4 km panels.
//!
//! # References
//! - E. Bruneton & F. Neyret, "Precomputed atmospheric scattering", Computer Graphics Forum
//!   27(4) (EGSR 2008), 1079–1086, §4 (the transmittance table and its parametrisation).
//! - E. Bruneton, "A qualitative and quantitative evaluation of 8 clear sky models", IEEE TVCG
//!   23(12) (2017), and its reference implementation `precomputed_atmospheric_scattering`
//!   (functions.glsl: the horizon-aware mapping of μ used here).

use super::air_profile::AirProfile;
use crate::atmosphere::Earth;
use glam::DVec3;

/// Nodes along x_r.
const NODES_R: usize = 128;
/// Nodes along x_μ.
const NODES_MU: usize = 384;
/// The height span of the quadrature panels of the nodes' columns, m: 16 Gauss–Legendre nodes
/// per 4 km of a smooth profile's height (the only kind tabulated), at a quarter of the cost
/// of the profile's own 1 km panels; their error is part of what the test measures against
/// those 1 km panels.
const BUILD_PANEL_M: f64 = 4_000.0;
/// C_floor relative to the vertical column from the ground (see the module docs).
const FLOOR_RELATIVE: f64 = 1e-9;
/// What the table may err by (the test draws 10⁵ random (r, μ) of USA76's air and of an
/// aerosol haze): |C_table − C| ≤ 5 × 10⁻⁴ C + 10⁻⁵ C_vertical, with C_vertical the column
/// straight up from the ground. The optical depth of every tabulated constituent then errs by
/// at most 5 × 10⁻⁴ of itself plus 10⁻⁵ of its vertical optical depth (4 × 10⁻⁶ for the air at
/// 400 nm), so the sun's transmittance e^−τ by a relative 5 × 10⁻⁴ τ: 0.04 % at solar zenith
/// 60° (τ ≤ 0.75 at 400 nm), at most 0.2 % wherever the sun still gives 2 % of its light
/// (τ ≤ 4) — ten times below the 2 % per-pixel noise the sky renders aim at. The grid of
/// 128 × 384 nodes keeps the worst error seen at half the bound; 128 × 256 nodes erred by
/// 5.6 × 10⁻⁴ (descending near-grazing rays from above 70 km).
pub const COLUMN_TOLERANCE: (f64, f64) = (5e-4, 1e-5);

/// ln(C + C_floor) of one profile at the grid's nodes over (x_r, x_μ) (see the module docs).
pub struct ColumnTable {
    radius_m: f64,
    top_radius_m: f64,
    horizon_m: f64,
    floor: f64,
    nodes: (usize, usize),
    r_max: f64,
    ln_values: Vec<f64>,
}

impl std::fmt::Debug for ColumnTable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ColumnTable({} × {} nodes, floor {:e})", self.nodes.0, self.nodes.1, self.floor)
    }
}

/// Where a ray sits in the table: the cell (i, j) and the fractions within it.
#[derive(Clone, Copy, Debug)]
pub struct Cell {
    i: usize,
    j: usize,
    fr: f64,
    fmu: f64,
}

/// The geometry of a spherical Earth's atmosphere: R, R_t and H = √(R_t² − R²).
#[derive(Clone, Copy, Debug)]
struct Shell {
    radius_m: f64,
    top_radius_m: f64,
    horizon_m: f64,
}

impl Shell {
    fn new(radius_m: f64, top_m: f64) -> Shell {
        let top_radius_m = radius_m + top_m;
        Shell { radius_m, top_radius_m, horizon_m: ((top_radius_m - radius_m) * (top_radius_m + radius_m)).sqrt() }
    }

    /// d(r, μ), the distance to the top.
    fn distance_to_top(&self, r: f64, mu: f64) -> f64 {
        let disc = r * r * (mu * mu - 1.0) + self.top_radius_m * self.top_radius_m;
        -r * mu + disc.max(0.0).sqrt()
    }

    /// (x_r, x_μ) of a point at radius r and a ray of zenith cosine μ that misses the ground.
    fn coordinates(&self, r: f64, mu: f64) -> (f64, f64) {
        let rho = ((r - self.radius_m) * (r + self.radius_m)).max(0.0).sqrt();
        let (d_min, d_max) = (self.top_radius_m - r, rho + self.horizon_m);
        let d = self.distance_to_top(r, mu);
        (rho / self.horizon_m, ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0))
    }

    /// (r, μ) of the coordinates (x_r, x_μ).
    fn point(&self, x_r: f64, x_mu: f64) -> (f64, f64) {
        let rho = self.horizon_m * x_r;
        let r = (rho * rho + self.radius_m * self.radius_m).sqrt();
        let (d_min, d_max) = (self.top_radius_m - r, rho + self.horizon_m);
        let d = d_min + x_mu * (d_max - d_min);
        let h2 = self.horizon_m * self.horizon_m;
        let mu = if d <= 0.0 { 1.0 } else { ((h2 - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0) };
        (r, mu)
    }
}

impl ColumnTable {
    /// The table of `profile`, whose Earth must be spherical (`None` for a flat one).
    /// `parallel`: on the rayon pool's threads (not from within a task of that pool).
    pub fn build(profile: &AirProfile, parallel: bool) -> Option<ColumnTable> {
        ColumnTable::build_on(profile, (NODES_R, NODES_MU), parallel)
    }

    /// The table of `profile` on `nodes` = (along x_r, along x_μ) nodes.
    fn build_on(profile: &AirProfile, nodes: (usize, usize), parallel: bool) -> Option<ColumnTable> {
        use rayon::prelude::*;
        let Earth::Spherical(s) = profile.earth() else { return None };
        let shell = Shell::new(s.radius_m, profile.top_m());
        let column = |r: f64, mu: f64| {
            let o = s.centre + r * DVec3::Y;
            let dir = DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), mu, 0.0);
            profile.integral_in_panels(o, dir, f64::INFINITY, BUILD_PANEL_M)
        };
        let floor = FLOOR_RELATIVE * column(s.radius_m, 1.0);
        let mut ln_values = vec![0.0; nodes.0 * nodes.1];
        let row = |(i, out): (usize, &mut [f64])| {
            for (j, v) in out.iter_mut().enumerate() {
                let (r, mu) = shell.point(node(i, nodes.0), node(j, nodes.1));
                *v = (column(r, mu) + floor).ln();
            }
        };
        if parallel {
            ln_values.par_chunks_mut(nodes.1).enumerate().for_each(row);
        } else {
            ln_values.chunks_mut(nodes.1).enumerate().for_each(row);
        }
        let Shell { radius_m, top_radius_m, horizon_m } = shell;
        // Within the top cell the column of a level ray falls as √(top − h) to 0 and the cell
        // of a fixed direction sweeps x_μ as fast, which no interpolation follows: rays from
        // there (where the air is 10⁻⁵ of the ground's) are integrated.
        let r_max = shell.point(node(nodes.0 - 2, nodes.0), 0.0).0;
        Some(ColumnTable { radius_m, top_radius_m, horizon_m, floor, nodes, r_max, ln_values })
    }

    fn shell(&self) -> Shell {
        Shell { radius_m: self.radius_m, top_radius_m: self.top_radius_m, horizon_m: self.horizon_m }
    }

    /// The cell of the ray `o + t·dir` (`dir` a unit vector) when the table gives its column
    /// over [0, t]: `o` at or above the ground and below the top, the ray missing the ground and
    /// reaching the top within `t`. `None` otherwise: the caller integrates.
    pub fn cell(&self, centre: DVec3, o: DVec3, dir: DVec3, t: f64) -> Option<Cell> {
        let shell = self.shell();
        let q = o - centre;
        let r = q.length();
        if !(r >= shell.radius_m && r < self.r_max) {
            return None;
        }
        let mu = q.dot(dir) / r;
        // The ray misses the ground when it rises or its lowest point, at radius r√(1 − μ²),
        // is at or above it.
        if mu < 0.0 && r * r * (1.0 - mu * mu) < shell.radius_m * shell.radius_m {
            return None;
        }
        if t < shell.distance_to_top(r, mu) {
            return None;
        }
        let (x_r, x_mu) = shell.coordinates(r, mu);
        let (i, fr) = split(x_r, self.nodes.0);
        let (j, fmu) = split(x_mu, self.nodes.1);
        Some(Cell { i, j, fr, fmu })
    }

    /// The column at `cell`: Catmull–Rom interpolation of the logarithms over the 4 × 4 nodes
    /// around it (exact for quadratics; a missing node beyond an edge is extrapolated by the
    /// parabola through the three nodes inside, so the edge cells stay exact for quadratics).
    pub fn column(&self, cell: Cell) -> f64 {
        let Cell { i, j, fr, fmu } = cell;
        let (wr, wmu) = (catmull_rom_weights(fr), catmull_rom_weights(fmu));
        let (n_r, n_mu) = (self.nodes.0 as isize, self.nodes.1 as isize);
        let v = |a: isize, b: isize| self.ln_values[(a * n_mu + b) as usize];
        // The value at node (a, b) of the grid extended by linear extrapolation.
        let at = |a: isize, b: isize| {
            let along_mu = |a: isize| match b {
                -1 => 3.0 * (v(a, 0) - v(a, 1)) + v(a, 2),
                b if b == n_mu => 3.0 * (v(a, n_mu - 1) - v(a, n_mu - 2)) + v(a, n_mu - 3),
                b => v(a, b),
            };
            match a {
                -1 => 3.0 * (along_mu(0) - along_mu(1)) + along_mu(2),
                a if a == n_r => 3.0 * (along_mu(n_r - 1) - along_mu(n_r - 2)) + along_mu(n_r - 3),
                a => along_mu(a),
            }
        };
        let mut ln = 0.0;
        for (da, w_a) in wr.iter().enumerate() {
            let a = i as isize + da as isize - 1;
            let row: f64 = wmu.iter().enumerate().map(|(db, w_b)| w_b * at(a, j as isize + db as isize - 1)).sum();
            ln += w_a * row;
        }
        (ln.exp() - self.floor).max(0.0)
    }
}

/// The Catmull–Rom weights of the nodes k − 1, k, k + 1, k + 2 at fraction `t` of cell k:
/// p(t) = ½[2p₁ + (p₂ − p₀)t + (2p₀ − 5p₁ + 4p₂ − p₃)t² + (3p₁ − p₀ − 3p₂ + p₃)t³]
/// (Catmull & Rom 1974; exact for quadratics).
fn catmull_rom_weights(t: f64) -> [f64; 4] {
    let (t2, t3) = (t * t, t * t * t);
    [0.5 * (-t + 2.0 * t2 - t3), 0.5 * (2.0 - 5.0 * t2 + 3.0 * t3), 0.5 * (t + 4.0 * t2 - 3.0 * t3), 0.5 * (-t2 + t3)]
}

/// The coordinate of node `k` of `n`.
fn node(k: usize, n: usize) -> f64 {
    k as f64 / (n - 1) as f64
}

/// The cell of `x` ∈ [0, 1] on `n` nodes and the fraction within it.
fn split(x: f64, n: usize) -> (usize, f64) {
    let s = x * (n - 1) as f64;
    let k = (s as usize).min(n - 2);
    (k, s - k as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::rng::{Rng, Stream};

    #[test]
    fn coordinates_and_points_are_inverse() {
        let shell = Shell::new(6_371_000.0, 86_000.0);
        for (x_r, x_mu) in [(0.0, 0.0), (0.0, 1.0), (0.3, 0.999), (0.7, 0.2), (1.0, 0.5), (0.01, 0.5)] {
            let (r, mu) = shell.point(x_r, x_mu);
            let (a, b) = shell.coordinates(r, mu);
            assert!((a - x_r).abs() < 1e-9 && (b - x_mu).abs() < 1e-7, "({x_r}, {x_mu}) -> ({a}, {b})");
        }
        // x_μ = 1 from the ground is the horizontal ray, and 0 is straight up.
        assert!(shell.point(0.0, 1.0).1.abs() < 1e-12);
        assert!((shell.point(0.5, 0.0).1 - 1.0).abs() < 1e-12);
    }

    /// The worst of |C_table − C| / (5 × 10⁻⁴ C + 10⁻⁵ C_vertical) of the table of `profile`
    /// against its own quadrature ([`AirProfile::integral`]) over `n` random rays, and how many
    /// rays the table answered.
    fn worst_error(profile: &AirProfile, n: usize, seed: u64) -> (f64, usize) {
        let table = ColumnTable::build(profile, false).unwrap();
        let Earth::Spherical(s) = profile.earth() else { unreachable!() };
        let shell = table.shell();
        let vertical = profile.integral(s.centre + s.radius_m * DVec3::Y, DVec3::Y, f64::INFINITY);
        let mut rng = Rng::for_task(seed, Stream::Test, 0);
        let (mut worst, mut answered) = (0.0f64, 0);
        for k in 0..n {
            let (u, v) = (rng.uniform(), rng.uniform());
            // A third of the draws within 200 m of the ground, a third within 3 km of the top, a
            // third anywhere; every other one within 1° of the horizon (or of the ground's
            // tangent, below it), the rest anywhere above that.
            let h = match k % 3 {
                0 => 200.0 * u * u,
                1 => profile.top_m() - 3000.0 * u,
                _ => profile.top_m() * u,
            };
            let r = shell.radius_m + h;
            let mu_h = -((r - shell.radius_m) * (r + shell.radius_m)).sqrt() / r;
            let mu = if k % 2 == 0 { mu_h + (1.0 - mu_h) * v } else { (mu_h + 0.0175 * v * v).min(1.0) };
            let dir = DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), mu, 0.0);
            let o = s.centre + r * DVec3::Y;
            let Some(cell) = table.cell(s.centre, o, dir, f64::INFINITY) else { continue };
            answered += 1;
            let exact = profile.integral(o, dir, f64::INFINITY);
            let err = (table.column(cell) - exact).abs();
            worst = worst.max(err / (COLUMN_TOLERANCE.0 * exact + COLUMN_TOLERANCE.1 * vertical));
        }
        (worst, answered)
    }

    #[test]
    fn the_table_gives_the_columns_of_random_rays_within_its_bound() {
        // USA76's air and a 1.2 km aerosol haze, 10⁵ rays each (release build: ~10 s in all).
        let air = AirProfile::new(&Atmosphere::usa76(), Earth::standard(), 2.5e25).unwrap();
        let haze =
            AirProfile::from_heights(Earth::standard(), 86_000.0, crate::media::aerosol::profile(1200.0, 86_000.0));
        for (name, p, seed) in [("air", &air, 1), ("aerosol", &haze, 2)] {
            let (worst, answered) = worst_error(p, 100_000, seed);
            // The table answers every ray below its top cell (1.34 km), which holds about half
            // of the third drawn within 3 km of the top: ≥ 80 % of them.
            assert!(answered >= 80_000, "{name}: the table answered only {answered} rays");
            assert!(worst <= 1.0, "{name}: the worst error is {worst} × the bound");
        }
    }

    /// The benchmark atmosphere of Zawada et al. (2021), `tests/data/zawada2021/`: rows of
    /// altitude (m), air and ozone number density (cm⁻³) at 1 km levels.
    fn benchmark_levels() -> Vec<Vec<f64>> {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/zawada2021/number_density.csv"))
                .expect("the benchmark's profile");
        text.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().expect("a number")).collect()).collect()
    }

    #[test]
    fn a_tabulated_atmospheres_air_keeps_the_bound() {
        // An atmosphere file's `profile` (T, P at 1 km levels, ln P by monotone cubics: C¹, so
        // no slope breaks): the benchmark air of Zawada et al. (2021) at 250 K keeps a table,
        // and it keeps its bound (measured: 0.036 of it).
        let rows = benchmark_levels();
        let t_k = 250.0;
        let (h, p): (Vec<f64>, Vec<f64>) = rows
            .iter()
            .map(|r| {
                (r[0], r[1] * 1e6 * crate::atmosphere::gas::R_STAR * t_k / crate::atmosphere::gas::AVOGADRO_PER_MOL)
            })
            .unzip();
        let table = crate::atmosphere::TableProfile::new(h.clone(), vec![t_k; h.len()], p).unwrap();
        let atmosphere = Atmosphere::new(
            "benchmark",
            Earth::standard(),
            crate::atmosphere::BaseProfile::Table(table),
            Vec::new(),
            crate::atmosphere::AirDispersion::CauchyBornWolf,
            100_000.0,
        )
        .unwrap();
        let air = AirProfile::new(&atmosphere, Earth::standard(), 2.5e25).unwrap();
        assert!(air.column_table().0.is_some(), "a smooth profile keeps its table");
        let (worst, answered) = worst_error(&air, 20_000, 4);
        assert!(answered >= 16_000 && worst <= 1.0, "worst {worst} × the bound over {answered} rays");
    }

    #[test]
    fn rays_that_meet_the_ground_or_end_in_the_air_are_not_tabulated() {
        let air = AirProfile::new(&Atmosphere::usa76(), Earth::standard(), 2.5e25).unwrap();
        let table = ColumnTable::build(&air, false).unwrap();
        let Earth::Spherical(s) = air.earth() else { unreachable!() };
        let o = s.centre + (s.radius_m + 1000.0) * DVec3::Y;
        let down = DVec3::new(1.0, -0.02, 0.0).normalize(); // below the horizon from 1 km
        assert!(table.cell(s.centre, o, down, f64::INFINITY).is_none());
        assert!(table.cell(s.centre, o, DVec3::Y, 50_000.0).is_none(), "ends below the top");
        assert!(table.cell(s.centre, o, DVec3::Y, 90_000.0).is_some());
        let below = s.centre + (s.radius_m - 1.0) * DVec3::Y;
        assert!(table.cell(s.centre, below, DVec3::Y, f64::INFINITY).is_none(), "starts under the ground");
        // A flat Earth has no table.
        assert!(
            ColumnTable::build(&AirProfile::new(&Atmosphere::usa76(), Earth::flat_y(), 2.5e25).unwrap(), false)
                .is_none()
        );
    }

    #[test]
    fn a_table_read_between_levels_keeps_no_column_table() {
        // The benchmark ozone of Zawada et al. (2021), 1 km levels read linearly: its slope
        // breaks sit on the 1 km panels' edges, so it keeps those panels, but a column table of
        // it errs by 2.4 × the bound; marked, it has none and shadow rays integrate it.
        let rows = benchmark_levels();
        let (h, n): (Vec<f64>, Vec<f64>) = rows.iter().map(|r| (r[0], r[2] * 1e6)).unzip();
        let levels = crate::media::ozone::NumberDensityTable::new(h, n)
            .unwrap()
            .with_interpolation(crate::media::ozone::Interpolation::Linear);
        let read = move |x| levels.at(x);
        let unmarked = AirProfile::from_heights(Earth::standard(), 100_000.0, read.clone());
        let (worst, _) = worst_error(&unmarked, 20_000, 3);
        assert!(worst > 1.0, "the table kept its bound ({worst}): the mark would not be needed");
        let marked = AirProfile::from_heights(Earth::standard(), 100_000.0, read).with_slope_breaks();
        assert!(marked.column_table().0.is_none());
    }

    #[test]
    fn ozone_is_integrated_beside_a_tabulated_air() {
        // The AFGL ozone shape keeps no table (its finer panels mark its kinks); read together
        // with the air, its column is the quadrature's to the bit and the air's the table's.
        let air = AirProfile::new(&Atmosphere::usa76(), Earth::standard(), 2.5e25).unwrap();
        let ozone =
            AirProfile::from_heights(Earth::standard(), 86_000.0, crate::media::ozone::profile(300.0, 86_000.0));
        let (o, dir) = (DVec3::new(0.0, 500.0, 0.0), DVec3::new(0.3, 1.0, 0.0).normalize());
        let mut got = [0.0; 2];
        assert!(AirProfile::columns_to_top(&[&air, &ozone], o, dir, f64::INFINITY, &mut got));
        assert!(ozone.column_table().0.is_none());
        assert_eq!(got[1], ozone.integral(o, dir, f64::INFINITY));
        let exact = air.integral(o, dir, f64::INFINITY);
        assert!((got[0] / exact - 1.0).abs() <= COLUMN_TOLERANCE.0, "{} vs {exact}", got[0]);
        assert_ne!(got[0], exact, "the air's column comes from its table");
    }

    #[test]
    fn a_medium_builds_its_tables_once_and_other_media_build_none() {
        use crate::media::{Coefficients, Medium, density::Density, inelastic::Inelastic, phase::PhaseFunction};
        let air = AirProfile::new(&Atmosphere::usa76(), Earth::standard(), 2.5e25).unwrap();
        let medium = |density: Density| Medium {
            name: "m".into(),
            coefficients: Coefficients::RayleighAir(crate::media::rayleigh_air::CrossSection::Bodhaine {
                co2_ppm: 400.0,
            }),
            phase: PhaseFunction::isotropic(),
            density,
            index: None,
            inelastic: Inelastic::none(),
        };
        let atmosphere = medium(Density::AirProfile(air.clone()));
        assert!(atmosphere.build_column_tables(), "the first call builds the air's table");
        assert!(!atmosphere.build_column_tables(), "and the second finds it built");
        assert!(air.column_table().0.is_some(), "clones of the profile share it");
        assert!(!medium(Density::Uniform).build_column_tables(), "a homogeneous medium has none to build");
    }
}
