//! An independent reference for multiple scattering in a plane-parallel layer: a deterministic
//! adding–doubling solver of the scalar transfer equation for the phase function
//! p(cos Θ) = K (1 + c cos² Θ) (Rayleigh's with depolarisation, c = (1 − ρ)/(1 + ρ); c = 0 is
//! isotropic), sharing no code with morgana (its own Gauss–Legendre nodes, its own linear solver,
//! no photons, no media).
//!
//! # The problem
//! A homogeneous layer of optical depth τ and single-scattering albedo ω over a black surface, lit
//! at the top by a collimated beam of irradiance E (on a plane normal to the beam) at μ₀ = cos θ₀.
//! The diffuse radiance leaving the top, L↑(μ, φ), and the bottom, L↓(μ, φ), are wanted.
//!
//! # Azimuthal modes (Chandrasekhar 1950)
//! With μ, μ′ the signed direction cosines of travel and s = √(1 − μ²), cos Θ = μμ′ + s s′ cos Δφ,
//! so cos² Θ = (μμ′)² + s² s′²/2 + 2μμ′ s s′ cos Δφ + (s² s′²/2) cos 2Δφ and
//! p = Σ_{m=0}^{2} (2 − δ_{m0}) p_m(μ, μ′) cos mΔφ with
//! p₀ = K [1 + c((μμ′)² + s² s′²/2)], p₁ = K c μμ′ s s′, p₂ = K c s² s′²/4,
//! K = 3/(4π(3 + c)) (so that ∫ p dΩ = 1). A radiance L = Σ (2 − δ_{m0}) L_m cos mφ scatters into
//! the source ω · 2π ∫ p_m(μ, μ′) L_m(μ′) dμ′ of mode m; the three modes are independent.
//!
//! # Adding–doubling (van de Hulst 1980; Hansen & Travis 1974)
//! Directions per hemisphere: Gauss–Legendre nodes on (0, 1) with weights w, plus the cosines the
//! caller asks about (sun, views) as extra nodes with weight ε = 10⁻¹² (they take part as incident
//! and outgoing directions; their share as intermediate directions is ε-small). A layer is two
//! matrices per mode acting on the vector of downward (or upward) radiances at the nodes: R (back
//! out of the side it entered) and T (through, the direct beam e^{−t/μ} on the diagonal included);
//! the column j carries the weight 2π w_j. A layer of δτ = τ/2²⁰ starts with single scattering,
//! exact in δτ:
//!
//! R_ij = ω 2π w_j p_m(−μ_i, μ_j) μ_j/(μ_i + μ_j) [1 − e^{−δτ(1/μ_i + 1/μ_j)}],
//! T_ij = δ_ij e^{−δτ/μ_i} + ω 2π w_j p_m(μ_i, μ_j) μ_j/(μ_j − μ_i) [e^{−δτ/μ_j} − e^{−δτ/μ_i}]
//! (→ δτ/μ_i e^{−δτ/μ_i} · μ_j as μ_j → μ_i);
//!
//! two equal layers make one twice as thick (the layer is symmetric, so R and T are the same from
//! either side): R₂ = R + T (I − R R)⁻¹ R T, T₂ = T (I − R R)⁻¹ T, twenty times. The error of
//! starting from single scattering is of order δτ (5 × 10⁻⁷ at τ = 0.5).
//! The radiance leaving the top toward μ, with relative azimuth Δφ between the horizontal
//! directions of travel of the beam and the outgoing light, is
//! L↑ = E Σ_m (2 − δ_{m0}) R_m[μ, μ₀]/(2π ε) cos mΔφ, and L↓ likewise with T.
//!
//! # References
//! - S. Chandrasekhar, *Radiative Transfer* (1950): the phase function with depolarisation
//!   (§I.18), its azimuthal expansion.
//! - H. C. van de Hulst, *Multiple Light Scattering* (1980), the doubling method.
//! - J. E. Hansen, L. D. Travis, "Light scattering in planetary atmospheres", Space Sci. Rev. 16
//!   (1974), 527–610 (adding and doubling).

use std::f64::consts::PI;

/// Weight of the extra (asked-about) directions.
const EPS: f64 = 1e-12;

/// Doublings from the starting layer: δτ = τ/2^DOUBLINGS.
pub const DOUBLINGS: u32 = 20;

/// Reflection and transmission of a layer per azimuthal mode, on its nodes.
pub struct Layer {
    mu: Vec<f64>,
    w: Vec<f64>,
    /// Index of the first extra node.
    extra: usize,
    r: Vec<Matrix>,
    t: Vec<Matrix>,
}

/// The layer's optical properties.
#[derive(Clone, Copy)]
pub struct Slab {
    pub tau: f64,
    pub omega: f64,
    /// c of p = K(1 + c cos² Θ).
    pub c: f64,
}

impl Layer {
    /// Solves `slab` with `gauss` nodes per hemisphere and `extra` direction cosines (each in (0, 1]).
    pub fn solve(slab: Slab, gauss: usize, extra: &[f64]) -> Layer {
        Layer::solve_with(slab, gauss, extra, DOUBLINGS)
    }

    /// As `solve`, with `doublings` of a layer τ/2^doublings.
    pub fn solve_with(slab: Slab, gauss: usize, extra: &[f64], doublings: u32) -> Layer {
        let (mut mu, mut w) = gauss_legendre_01(gauss);
        let first_extra = mu.len();
        for &m in extra {
            assert!(m > 0.0 && m <= 1.0, "direction cosine {m}");
            mu.push(m);
            w.push(EPS);
        }
        let dtau = slab.tau / 2f64.powi(doublings as i32);
        let (mut r, mut t) = (Vec::new(), Vec::new());
        for m in 0..3 {
            let (mut rm, mut tm) = thin_layer(&mu, &w, slab, m, dtau);
            for _ in 0..doublings {
                (rm, tm) = double(&rm, &tm);
            }
            r.push(rm);
            t.push(tm);
        }
        Layer { mu, w, extra: first_extra, r, t }
    }

    /// Diffuse radiance leaving the top toward extra node `view` (upward at its cosine), for the
    /// beam of irradiance 1 at extra node `sun`, `dphi` (rad) the relative azimuth of travel.
    pub fn reflected(&self, view: usize, sun: usize, dphi: f64) -> f64 {
        self.sum_modes(&self.r, view, sun, dphi)
    }

    /// Diffuse radiance leaving the bottom toward extra node `view` (downward at its cosine).
    pub fn transmitted(&self, view: usize, sun: usize, dphi: f64) -> f64 {
        assert_ne!(view, sun, "the direct beam sits on the diagonal");
        self.sum_modes(&self.t, view, sun, dphi)
    }

    fn sum_modes(&self, ops: &[Matrix], view: usize, sun: usize, dphi: f64) -> f64 {
        let (i, j) = (self.extra + view, self.extra + sun);
        (0..3)
            .map(
                |m| if m == 0 { 1.0 } else { 2.0 } * ops[m].at(i, j) / (2.0 * PI * self.w[j]) * (m as f64 * dphi).cos(),
            )
            .sum()
    }

    /// Fluxes per unit incident flux for the beam at extra node `sun`: (reflected, transmitted
    /// diffuse, transmitted direct), the fluxes from mode 0 by the Gauss nodes,
    /// F = 2π Σ w_i μ_i L₀(μ_i).
    pub fn fluxes(&self, sun: usize) -> (f64, f64, f64) {
        let j = self.extra + sun;
        let mu0 = self.mu[j];
        let flux = |op: &Matrix| {
            (0..self.extra)
                .map(|i| 2.0 * PI * self.w[i] * self.mu[i] * op.at(i, j) / (2.0 * PI * self.w[j]))
                .sum::<f64>()
                / mu0
        };
        let direct = self.t[0].at(j, j);
        // The direct part of T at (j, j) is e^{−τ/μ₀} (radiance per radiance): the flux it carries is
        // that fraction of the incident flux.
        (flux(&self.r[0]), flux(&self.t[0]), direct)
    }
}

/// Single scattering in a layer of optical depth `dtau`, mode `m`.
fn thin_layer(mu: &[f64], w: &[f64], slab: Slab, m: usize, dtau: f64) -> (Matrix, Matrix) {
    let n = mu.len();
    let (mut r, mut t) = (Matrix::zero(n), Matrix::zero(n));
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (mu[i], mu[j]);
            let scale = slab.omega * 2.0 * PI * w[j];
            let refl = b / (a + b) * (1.0 - (-dtau * (1.0 / a + 1.0 / b)).exp());
            let trans = if (a - b).abs() < 1e-9 * a {
                dtau / a * (-dtau / a).exp()
            } else {
                b / (b - a) * ((-dtau / b).exp() - (-dtau / a).exp())
            };
            r.set(i, j, scale * phase_mode(slab.c, m, -a, b) * refl);
            let direct = if i == j { (-dtau / a).exp() } else { 0.0 };
            t.set(i, j, direct + scale * phase_mode(slab.c, m, a, b) * trans);
        }
    }
    (r, t)
}

/// p_m(μ, μ′) of K(1 + c cos² Θ), signed cosines of travel.
fn phase_mode(c: f64, m: usize, mu: f64, mu_p: f64) -> f64 {
    let k = 3.0 / (4.0 * PI * (3.0 + c));
    let (s2, sp2) = (1.0 - mu * mu, 1.0 - mu_p * mu_p);
    match m {
        0 => k * (1.0 + c * ((mu * mu_p).powi(2) + s2 * sp2 / 2.0)),
        1 => k * c * mu * mu_p * (s2 * sp2).sqrt(),
        _ => k * c * s2 * sp2 / 4.0,
    }
}

/// Two equal symmetric layers: R₂ = R + T G R T, T₂ = T G T, G = (I − R R)⁻¹.
fn double(r: &Matrix, t: &Matrix) -> (Matrix, Matrix) {
    let n = r.n;
    let i_minus_rr = Matrix::identity(n).sub(&r.mul(r));
    let gt = i_minus_rr.solve(t); // G T
    let t2 = t.mul(&gt);
    let r2 = r.add(&t.mul(&r.mul(&gt)));
    (r2, t2)
}

/// Gauss–Legendre nodes and weights on (0, 1): roots of P_n by Newton's method from
/// cos(π(k − 1/4)/(n + 1/2)) (Abramowitz & Stegun 22.16.6 start), mapped from (−1, 1).
pub fn gauss_legendre_01(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut w) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for k in 1..=n {
        let mut z = (PI * (k as f64 - 0.25) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, d) = legendre(n, z);
            let step = p / d;
            z -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let (_, dp) = legendre(n, z);
        x.push(0.5 * (1.0 + z));
        w.push(1.0 / ((1.0 - z * z) * dp * dp));
    }
    (x, w)
}

/// P_n(z) and P_n′(z) by the three-term recurrence.
fn legendre(n: usize, z: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, z);
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    (p1, n as f64 * (z * p1 - p0) / (z * z - 1.0))
}

/// A dense square matrix, row-major.
#[derive(Clone)]
pub struct Matrix {
    n: usize,
    a: Vec<f64>,
}

impl Matrix {
    fn zero(n: usize) -> Matrix {
        Matrix { n, a: vec![0.0; n * n] }
    }

    fn identity(n: usize) -> Matrix {
        let mut m = Matrix::zero(n);
        for i in 0..n {
            m.set(i, i, 1.0);
        }
        m
    }

    fn at(&self, i: usize, j: usize) -> f64 {
        self.a[i * self.n + j]
    }

    fn set(&mut self, i: usize, j: usize, v: f64) {
        self.a[i * self.n + j] = v;
    }

    fn mul(&self, b: &Matrix) -> Matrix {
        let n = self.n;
        let mut c = Matrix::zero(n);
        for i in 0..n {
            for k in 0..n {
                let aik = self.at(i, k);
                for j in 0..n {
                    c.a[i * n + j] += aik * b.a[k * n + j];
                }
            }
        }
        c
    }

    fn add(&self, b: &Matrix) -> Matrix {
        Matrix { n: self.n, a: self.a.iter().zip(&b.a).map(|(x, y)| x + y).collect() }
    }

    fn sub(&self, b: &Matrix) -> Matrix {
        Matrix { n: self.n, a: self.a.iter().zip(&b.a).map(|(x, y)| x - y).collect() }
    }

    /// X with self · X = b, by Gaussian elimination with partial pivoting.
    fn solve(&self, b: &Matrix) -> Matrix {
        let n = self.n;
        let (mut a, mut x) = (self.clone(), b.clone());
        for col in 0..n {
            let piv = (col..n).max_by(|&p, &q| a.at(p, col).abs().total_cmp(&a.at(q, col).abs())).unwrap();
            if piv != col {
                for j in 0..n {
                    a.a.swap(col * n + j, piv * n + j);
                    x.a.swap(col * n + j, piv * n + j);
                }
            }
            let d = a.at(col, col);
            for row in col + 1..n {
                let f = a.at(row, col) / d;
                if f == 0.0 {
                    continue;
                }
                for j in col..n {
                    a.a[row * n + j] -= f * a.a[col * n + j];
                }
                for j in 0..n {
                    x.a[row * n + j] -= f * x.a[col * n + j];
                }
            }
        }
        for col in (0..n).rev() {
            let d = a.at(col, col);
            for j in 0..n {
                x.a[col * n + j] /= d;
            }
            for row in 0..col {
                let f = a.at(row, col);
                if f == 0.0 {
                    continue;
                }
                for j in 0..n {
                    x.a[row * n + j] -= f * x.a[col * n + j];
                }
            }
        }
        x
    }
}
