//! An independent reference for the Mobley et al. (1993) canonical problems: a deterministic
//! discrete-ordinates solver of the plane-parallel radiative transfer equation, sharing no code
//! with morgana (its own phase-function reader and interpolation, its own Fresnel law, no photons).
//!
//! # The equation it solves
//! A homogeneous, deep ocean (c = 1, so optical depth τ = depth in m) with single-scattering
//! albedo ω₀ under a flat surface of index n, a black sky and a sun at zenith angle θ_s giving
//! Ed(0+) above the surface. The sun's beam, refracted to μ_b = cos θ_w (Snell) with Fresnel's
//! transmittance T(θ_s), is kept apart (its irradiance on a plane normal to it is
//! E_b(τ) = Ed(0+) T e^{−τ/μ_b} / μ_b); the diffuse radiance obeys
//!
//! μ dL/dτ = −L + ω₀ ∫ p(ω′·ω) L(ω′) dω′ + ω₀ p(ω_b·ω) E_b(τ)   (μ = cos of travel from straight down)
//!
//! with L(0, μ > 0) = R(μ) L(0, −μ) (the surface's internal Fresnel reflection, total beyond the
//! critical angle) and no light from below τ_max.
//! Only the azimuthal mean of L (Fourier mode 0) is solved: a flat surface does not couple azimuthal
//! modes, and Ed, Eu, Eod, Eou and the radiance along the vertical (Lu, straight up; no azimuth there)
//! depend on that mode alone.
//!
//! # Discretisation
//! - Directions: N bins uniform in polar angle θ; the radiance is uniform in solid angle over a bin
//!   (finite volume). The bin-to-bin redistribution P(i | j), the probability that light uniform over
//!   bin j scatters into bin i, is integrated over the scattering angle Θ (cells with the phase
//!   function's mass, about 5,000 of them, log-spaced from 10⁻⁹ rad, at most 0.05° wide) and over the
//!   azimuth in closed form: for a direction at cos θ′ = μ′ scattered by Θ, the fraction of azimuths
//!   that leave it at a polar angle below t is arccos((cos t − μ′ cos Θ)/(sin θ′ sin Θ))/π.
//!   Mean of bin i's radiance source: ω₀ Σ_j (Δμ_j/Δμ_i) P(i | j) L_j.
//! - Depth: nodes every Δτ; each bin is carried along its mean μ (which makes the flux exact for
//!   uniform radiance in the bin) with the source linear between nodes, integrated exactly:
//!   L_{k+1} = L_k e^{−x} + w_far J_k + w_near J_{k+1}, x = Δτ/|μ|,
//!   w_far = (1 − e^{−x}(1 + x))/x, w_near = 1 − e^{−x} − w_far; the beam's source, an
//!   exponential in τ, is carried exactly (`sweep`).
//! - The scattering integral is iterated (source, then sweeps up and down, i.e. one more order of
//!   scattering each time) until no radiance changes by more than 10⁻¹² (≈ 190 sweeps at ω₀ = 0.9).
//!
//! Convergence (problem 2, ω₀ = 0.9, Ed, Eou and Lu at τ = 1, 5, 10): the setting used (90 bins,
//! Δτ = 0.05, 8 points per input bin) differs from 180 bins, from Δτ = 0.025 and from 16 points
//! by at most 0.25 % (`tests/ocean.rs::discrete_ordinates_reference_convergence_and_sensitivity`).
//!
//! # References
//! - Mobley, Gentili, Gordon et al., "Comparison of numerical models for computing underwater
//!   light fields", Applied Optics 32(36) (1993), 7484–7504: the problems.
//! - Mobley, *Light and Water* (1994): the transfer equation, Fresnel's law at a level surface,
//!   Gershun's law, the azimuthal decomposition of the radiance.

use std::f64::consts::PI;

/// A phase function given at angles (degrees, increasing, ending at 180) in any unit, read and
/// interpolated here: a power law in θ between rows (log–log), the first segment's power law
/// continued to θ = 0 (integrable for exponents above −2) unless `forward` is false (then
/// nothing scatters below the first angle), normalised over the sphere here.
pub struct Phase {
    theta: Vec<f64>,
    beta: Vec<f64>,
    forward: bool,
    norm: f64,
}

impl Phase {
    pub fn from_rows(rows: &[(f64, f64)]) -> Phase {
        Phase::with_forward(rows, true)
    }

    /// With or without the extension below the first angle.
    pub fn with_forward(rows: &[(f64, f64)], forward: bool) -> Phase {
        let (theta, beta) = (rows.iter().map(|r| r.0.to_radians()).collect(), rows.iter().map(|r| r.1).collect());
        let mut p = Phase { theta, beta, forward, norm: 1.0 };
        p.norm = p.cells().iter().map(|c| c.2).sum();
        p
    }

    /// Rows `angle_deg,value` of a CSV (comment lines start with `#`; a header is skipped).
    pub fn csv_rows(path: &std::path::Path) -> Vec<(f64, f64)> {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        text.lines()
            .filter(|l| !l.starts_with('#'))
            .filter_map(|l| {
                let mut c = l.split(',');
                Some((c.next()?.trim().parse().ok()?, c.next()?.trim().parse().ok()?))
            })
            .collect()
    }

    /// The table of a CSV file ([`Phase::csv_rows`]), extended forward.
    pub fn from_csv(path: &std::path::Path) -> Phase {
        Phase::from_rows(&Phase::csv_rows(path))
    }

    /// The value as given (unnormalised) at θ in radians.
    fn raw(&self, t: f64) -> f64 {
        let (th, b) = (&self.theta, &self.beta);
        let j = if t <= th[1] { 0 } else { th.partition_point(|x| *x <= t).min(th.len() - 1) - 1 };
        let m = (b[j + 1] / b[j]).ln() / (th[j + 1] / th[j]).ln();
        b[j] * (t / th[j]).powf(m)
    }

    /// Cells (Θ_lo, Θ_hi, ∫ β dω over the cell, unnormalised): [0, 10⁻⁹ rad] in closed form,
    /// then Simpson's rule on cells growing by 1 % up to 0.05° wide, split at the table's angles.
    fn cells(&self) -> Vec<(f64, f64, f64)> {
        let mut edges = vec![0.0, 1e-9];
        let wide = 0.05f64.to_radians();
        while let Some(&t) = edges.last().filter(|t| **t < PI) {
            edges.push((t * 1.01).min(t + wide).min(PI));
        }
        edges.extend(&self.theta);
        edges.sort_by(f64::total_cmp);
        edges.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        let m0 = (self.beta[1] / self.beta[0]).ln() / (self.theta[1] / self.theta[0]).ln();
        let f = |x: f64| self.raw(x) * x.sin();
        edges
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let mass = if !self.forward && b <= self.theta[0] {
                    0.0
                } else if a == 0.0 {
                    // ∫₀ᵇ β₀ (θ/θ₀)^m 2π θ dθ
                    2.0 * PI * self.beta[0] * b * b * (b / self.theta[0]).powf(m0) / (2.0 + m0)
                } else {
                    2.0 * PI * (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b))
                };
                (a, b, mass)
            })
            .collect()
    }

    /// The mean cosine and the backscatter fraction of the normalised function.
    pub fn moments(&self) -> (f64, f64) {
        let q = self.quadrature();
        (q.iter().map(|(t, w)| t.cos() * w).sum(), q.iter().filter(|(t, _)| *t > 0.5 * PI).map(|(_, w)| w).sum())
    }

    /// (scattering angle, probability) of each cell: a quadrature of the normalised function.
    pub fn quadrature(&self) -> Vec<(f64, f64)> {
        self.cells().iter().map(|&(a, b, m)| (if a == 0.0 { 0.0 } else { 0.5 * (a + b) }, m / self.norm)).collect()
    }
}

/// Fresnel reflectance of unpolarised light from index n1 into n2 at incidence cosine `cos_i`
/// (1 beyond the critical angle).
pub fn fresnel(n1: f64, n2: f64, cos_i: f64) -> f64 {
    let s2 = (n1 / n2).powi(2) * (1.0 - cos_i * cos_i);
    if s2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - s2).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// Direction bins uniform in the polar angle θ of travel, measured from straight down.
struct Bins {
    edges: Vec<f64>,
}

impl Bins {
    fn new(n: usize) -> Bins {
        Bins { edges: (0..=n).map(|i| PI * i as f64 / n as f64).collect() }
    }
    fn n(&self) -> usize {
        self.edges.len() - 1
    }
    fn dmu(&self, i: usize) -> f64 {
        self.edges[i].cos() - self.edges[i + 1].cos()
    }
    fn mu_mean(&self, i: usize) -> f64 {
        0.5 * (self.edges[i].cos() + self.edges[i + 1].cos())
    }
    fn bin_of(&self, t: f64) -> usize {
        ((t / PI * self.n() as f64) as usize).min(self.n() - 1)
    }

    /// Adds `w` times the distribution over bins of a direction at cos θ′ = `mu` scattered by Θ
    /// at a uniformly random azimuth.
    fn redistribute(&self, mu: f64, big_theta: f64, w: f64, out: &mut [f64]) {
        let tp = mu.clamp(-1.0, 1.0).acos();
        let (lo, hi) = ((tp - big_theta).abs(), (tp + big_theta).min(2.0 * PI - tp - big_theta));
        let s = (1.0 - mu * mu).max(0.0).sqrt() * big_theta.sin();
        let (ilo, ihi) = (self.bin_of(lo), self.bin_of(hi));
        if ilo == ihi || s < 1e-14 {
            out[self.bin_of(0.5 * (lo + hi))] += w;
            return;
        }
        let c = mu * big_theta.cos();
        let below = |t: f64| ((t.cos() - c) / s).clamp(-1.0, 1.0).acos() / PI;
        let mut prev = 0.0;
        for (i, slot) in out.iter_mut().enumerate().take(ihi).skip(ilo) {
            let g = below(self.edges[i + 1]);
            *slot += w * (g - prev);
            prev = g;
        }
        out[ihi] += w * (1.0 - prev);
    }
}

/// A canonical problem and the resolution to solve it at.
#[derive(Clone, Copy)]
pub struct Problem {
    pub albedo: f64,
    pub n_water: f64,
    pub sun_zenith_deg: f64,
    /// Ed(0+), the sun's irradiance on the surface from above.
    pub ed_above: f64,
    pub tau_max: f64,
    pub dtau: f64,
    pub bins: usize,
    /// Points per input bin (midpoints of equal steps in μ) for P(i | j).
    pub mu_points: usize,
    /// Whether the surface reflects upwelling light back down (Fresnel, total beyond 48.3°).
    pub surface_reflection: bool,
}

impl Problem {
    /// Mobley et al. (1993) problems 1 and 2: n = 1.34, sun at 60°, Ed(0+) = 0.5, 60 optical
    /// depths (as `examples/mobley1993_problem{1,2}.toml`); 90 bins, Δτ = 0.05, 8 points per bin.
    pub fn mobley1993(albedo: f64) -> Problem {
        Problem {
            albedo,
            n_water: 1.34,
            sun_zenith_deg: 60.0,
            ed_above: 0.5,
            tau_max: 60.0,
            dtau: 0.05,
            bins: 90,
            mu_points: 8,
            surface_reflection: true,
        }
    }
}

/// The irradiances and the nadir radiance at one depth (names as in morgana's profile).
#[derive(Clone, Copy, Debug)]
pub struct Row {
    pub ed: f64,
    pub eu: f64,
    pub eod: f64,
    pub eou: f64,
    /// Upwelling radiance: the mean over the bin about straight up (half-angle 180°/N).
    pub lu: f64,
}

pub struct Solution {
    dtau: f64,
    /// Diffuse radiance `l[node][bin]`.
    l: Vec<Vec<f64>>,
    bins: Bins,
    mu_b: f64,
    beam_ed0: f64,
    pub sweeps: usize,
}

impl Solution {
    /// The row at a depth on the grid.
    pub fn at(&self, tau: f64) -> Row {
        let k = (tau / self.dtau).round() as usize;
        assert!((k as f64 * self.dtau - tau).abs() < 1e-9, "τ = {tau} is not a node");
        let b = &self.bins;
        let mut r = Row { ed: 0.0, eu: 0.0, eod: 0.0, eou: 0.0, lu: self.l[k][b.n() - 1] };
        for i in 0..b.n() {
            let e0 = 2.0 * PI * self.l[k][i] * b.dmu(i); // ∫ L dω over the bin
            let mu = b.mu_mean(i);
            if mu > 0.0 {
                (r.ed, r.eod) = (r.ed + e0 * mu, r.eod + e0);
            } else {
                (r.eu, r.eou) = (r.eu - e0 * mu, r.eou + e0);
            }
        }
        let beam = self.beam_ed0 * (-tau / self.mu_b).exp();
        r.ed += beam;
        r.eod += beam / self.mu_b;
        r
    }
}

/// Solves the problem (module documentation).
pub fn solve(pb: &Problem, phase: &Phase) -> Solution {
    let bins = Bins::new(pb.bins);
    let n = bins.n();
    let quad = phase.quadrature();
    let g = source_matrix(&bins, &quad, pb.mu_points);
    let cos_i = pb.sun_zenith_deg.to_radians().cos();
    let mu_b = (1.0 - (1.0 - cos_i * cos_i) / pb.n_water.powi(2)).sqrt();
    let beam_ed0 = pb.ed_above * (1.0 - fresnel(1.0, pb.n_water, cos_i));
    let mut from_beam = vec![0.0; n];
    for &(t, w) in &quad {
        bins.redistribute(mu_b, t, w, &mut from_beam);
    }
    let reflectance = |mu: f64| if pb.surface_reflection { fresnel(pb.n_water, 1.0, mu.abs()) } else { 0.0 };
    let refl: Vec<f64> = (0..n).map(|i| bin_mean(&bins, i, &reflectance)).collect();
    let nodes = (pb.tau_max / pb.dtau).round() as usize + 1;
    // The beam's source in bin i is A_i e^{−τ/μ_b}, carried exactly (`sweep`).
    let beam_source: Vec<f64> =
        (0..n).map(|i| pb.albedo * from_beam[i] / (2.0 * PI * bins.dmu(i)) * beam_ed0 / mu_b).collect();
    let mut l = vec![vec![0.0; n]; nodes];
    let mut sweeps = 0;
    loop {
        sweeps += 1;
        let source: Vec<Vec<f64>> = (0..nodes)
            .map(|k| (0..n).map(|i| pb.albedo * g[i].iter().zip(&l[k]).map(|(a, b)| a * b).sum::<f64>()).collect())
            .collect();
        let mut change = 0.0f64;
        // Upward bins from the bottom, then downward ones from the surface's reflection of them.
        for (i, &beam) in beam_source.iter().enumerate().skip(n / 2) {
            change = change.max(sweep(&bins, i, (pb.dtau, mu_b), (&source, beam), &mut l, 0.0));
        }
        for (i, &beam) in beam_source.iter().enumerate().take(n / 2) {
            let top = refl[n - 1 - i] * l[0][n - 1 - i];
            change = change.max(sweep(&bins, i, (pb.dtau, mu_b), (&source, beam), &mut l, top));
        }
        if change < 1e-12 {
            break;
        }
        assert!(sweeps < 5000, "the source iteration does not converge");
    }
    Solution { dtau: pb.dtau, l, bins, mu_b, beam_ed0, sweeps }
}

/// G[i][j] = (Δμ_j/Δμ_i) P(i | j); P for the downward half, the upward half by symmetry.
fn source_matrix(bins: &Bins, quad: &[(f64, f64)], mu_points: usize) -> Vec<Vec<f64>> {
    let n = bins.n();
    let mut p = vec![vec![0.0; n]; n]; // p[j][i] = P(i | j)
    for j in 0..n / 2 {
        let (a, b) = (bins.edges[j + 1].cos(), bins.edges[j].cos());
        let mut out = vec![0.0; n];
        for q in 0..mu_points {
            let mu = a + (b - a) * (q as f64 + 0.5) / mu_points as f64;
            for &(t, w) in quad {
                bins.redistribute(mu, t, w / mu_points as f64, &mut out);
            }
        }
        for i in 0..n {
            p[j][i] = out[i];
            p[n - 1 - j][n - 1 - i] = out[i];
        }
    }
    (0..n).map(|i| (0..n).map(|j| bins.dmu(j) / bins.dmu(i) * p[j][i]).collect()).collect()
}

/// The mean of f(μ) over bin i (2000 midpoints in μ).
fn bin_mean(bins: &Bins, i: usize, f: &dyn Fn(f64) -> f64) -> f64 {
    let (a, b) = (bins.edges[i + 1].cos(), bins.edges[i].cos());
    let m = 2000;
    (0..m).map(|q| f(a + (b - a) * (q as f64 + 0.5) / m as f64)).sum::<f64>() / m as f64
}

/// Carries bin i from its boundary value `start` through the nodes (down from τ = 0 for a
/// downward bin, up from τ_max otherwise) with the diffuse source (`source[node][bin]`, linear
/// between nodes) and the beam's A e^{−τ/μ_b} (exact: over a step of length Δτ starting at τ₀,
/// ∫₀^Δτ A e^{−τ(s)/μ_b} e^{−(Δτ−s)/m} ds/m = A e^{−τ₀/μ_b} (e^{aΔτ} − e^{−Δτ/m}) / (m b), with
/// m = |μ|, a = ∓1/μ_b going down or up, b = a + 1/m); returns the largest change of a value.
fn sweep(
    bins: &Bins,
    i: usize,
    (dtau, mu_b): (f64, f64),
    (source, beam): (&[Vec<f64>], f64),
    l: &mut [Vec<f64>],
    start: f64,
) -> f64 {
    let nodes = l.len();
    let mu = bins.mu_mean(i);
    let m = mu.abs();
    let x = dtau / m;
    let e = (-x).exp();
    let w_far = if x < 1e-4 { x / 2.0 - x * x / 3.0 } else { (1.0 - e * (1.0 + x)) / x };
    let w_near = 1.0 - e - w_far;
    let a = if mu > 0.0 { -1.0 / mu_b } else { 1.0 / mu_b };
    let b = a + 1.0 / m;
    let beam_step = beam * if (b * dtau).abs() > 1e-9 { ((a * dtau).exp() - e) / (m * b) } else { x * e };
    let order: Vec<usize> = if mu > 0.0 { (0..nodes).collect() } else { (0..nodes).rev().collect() };
    let mut v = start;
    let mut change = (l[order[0]][i] - v).abs();
    l[order[0]][i] = v;
    for w in order.windows(2) {
        let (from, to) = (w[0], w[1]);
        let beam_here = beam_step * (-(from as f64) * dtau / mu_b).exp();
        v = v * e + w_far * source[from][i] + w_near * source[to][i] + beam_here;
        change = change.max((l[to][i] - v).abs());
        l[to][i] = v;
    }
    change
}
